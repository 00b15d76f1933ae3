//! Which OpenEXR compression for the data file: encodes a data file written by `godel
//! render` with each lossless codec the `exr` crate writes, and reports the size, the
//! encoding time (median of N runs, sequential and with exr's parallel block compression)
//! and the decoding time. The records must come back identical (checked).
//! `cargo run --release -p datafile --example codecs -- FILE.exr [N]`

use exr::prelude::*;
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("usage: codecs FILE.exr [N]");
    let n: usize = args.next().map_or(9, |s| s.parse().expect("N"));
    let image = read_all_data_from_file(&path).expect("readable EXR");
    let original = datafile::DataFile::read(std::path::Path::new(&path)).expect("data file");
    println!("{path}: {}×{}", original.width, original.height);
    println!("codec      bytes      encode 1 thread   encode parallel   decode");
    for (name, c) in [
        ("NONE", Compression::Uncompressed),
        ("RLE", Compression::RLE),
        ("ZIPS", Compression::ZIP1),
        ("ZIP", Compression::ZIP16),
        ("PIZ", Compression::PIZ),
    ] {
        let mut img = image.clone();
        img.layer_data[0].encoding.compression = c;
        let encode = |parallel: bool| {
            let mut bytes = Vec::new();
            let w = img.write();
            let w = if parallel { w } else { w.non_parallel() };
            w.to_buffered(std::io::Cursor::new(&mut bytes))
                .expect("encodes");
            bytes
        };
        let bytes = encode(false);
        let time = |f: &dyn Fn()| {
            median(
                (0..n)
                    .map(|_| {
                        let t = Instant::now();
                        f();
                        t.elapsed().as_secs_f64() * 1e3
                    })
                    .collect(),
            )
        };
        let seq = time(&|| {
            encode(false);
        });
        let par = time(&|| {
            encode(true);
        });
        let dec = time(&|| {
            datafile::DataFile::from_bytes(&bytes).expect("decodes");
        });
        let back = datafile::DataFile::from_bytes(&bytes).expect("decodes");
        assert!(
            back.records
                .iter()
                .zip(&original.records)
                .all(|(a, b)| format!("{a:?}") == format!("{b:?}")),
            "{name}: records differ"
        );
        println!(
            "{name:<6} {:>11}   {seq:>9.2} ms      {par:>9.2} ms     {dec:>7.2} ms",
            bytes.len()
        );
    }
}
