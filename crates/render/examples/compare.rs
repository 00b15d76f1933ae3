//! Compares two data files pixel by pixel: how many pixels differ in object or status, and
//! the largest differences of g, t_emit, u, v where both hit the same object.
//! `cargo run -p render --example compare -- A.exr B.exr`

use datafile::DataFile;
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [a, b] = [&args[0], &args[1]]
        .map(|p| DataFile::read(Path::new(p)).unwrap_or_else(|e| panic!("{e}")));
    assert_eq!((a.width, a.height), (b.width, b.height), "sizes differ");
    let (mut object, mut status, mut both) = (0, 0, 0);
    let mut dmax = [0f32; 4];
    let mut worst = (0.0f32, 0usize);
    for (i, (x, y)) in a.records.iter().zip(&b.records).enumerate() {
        if x.is_hit() && y.is_hit() && (x.u - y.u).abs() > worst.0 {
            worst = ((x.u - y.u).abs(), i);
        }
        object += (x.object != y.object) as usize;
        status += (x.status != y.status) as usize;
        if x.is_hit() && y.is_hit() && x.object == y.object {
            both += 1;
            for (m, d) in
                dmax.iter_mut()
                    .zip([x.g - y.g, x.t_emit - y.t_emit, x.u - y.u, x.v - y.v])
            {
                *m = m.max(d.abs());
            }
        }
    }
    let (i, w) = (worst.1, a.width);
    println!(
        "largest |Δu| at pixel ({}, {}): {:?} vs {:?}",
        i % w,
        i / w,
        a.records[i],
        b.records[i]
    );
    println!(
        "{} pixels: {object} differ in object, {status} in status; {both} hit the same object, max |Δg| {:e}, |Δt_emit| {:e}, |Δu| {:e}, |Δv| {:e}",
        a.records.len(),
        dmax[0],
        dmax[1],
        dmax[2],
        dmax[3]
    );
}
