//! Lists the pixels where two data files differ in object or status, or in t_emit by more
//! than 0.01 (column, row, and the object, status, λ and t_emit of each), at most 100.
//! `cargo run -p render --example differ -- A.exr B.exr`

use datafile::DataFile;
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() != 2 {
        eprintln!("usage: differ A.exr B.exr");
        std::process::exit(2);
    }
    let [a, b] = [&args[0], &args[1]].map(|p| {
        DataFile::read(Path::new(p)).unwrap_or_else(|e| {
            eprintln!("{e}");
            std::process::exit(1)
        })
    });
    if (a.width, a.height) != (b.width, b.height) {
        eprintln!("sizes differ");
        std::process::exit(1);
    }
    let differ = (a.records.iter().zip(&b.records).enumerate()).filter(|(_, (x, y))| {
        x.object != y.object || x.status != y.status || (x.t_emit - y.t_emit).abs() > 0.01
    });
    for (i, (x, y)) in differ.take(100) {
        println!(
            "({}, {}): {} {:?} λ {} t_emit {}  vs  {} {:?} λ {} t_emit {}",
            i % a.width,
            i / a.width,
            x.object,
            x.status,
            x.lambda,
            x.t_emit,
            y.object,
            y.status,
            y.lambda,
            y.t_emit
        );
    }
}
