//! Whether data files hold the same records, lights and header, bit for bit (NaN fields of
//! missed pixels included), whatever their EXR compression: exit 0 if so, 1 (naming the
//! first difference) otherwise. Used by `scripts/same-outputs.sh --records`.
//! `cargo run --release -p datafile --example same_records -- A.exr B.exr [C.exr …]`

use datafile::DataFile;
use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let paths: Vec<String> = std::env::args().skip(1).collect();
    if paths.len() < 2 {
        eprintln!("usage: same_records A.exr B.exr [C.exr …]");
        return ExitCode::from(2);
    }
    let read = |p: &str| DataFile::read(Path::new(p)).map_err(|e| e.to_string());
    let first = match read(&paths[0]) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    let bits = |d: &DataFile| {
        let records: Vec<String> = d.records.iter().map(|r| format!("{r:?}")).collect();
        let lights: Vec<Vec<u32>> = d
            .lights
            .iter()
            .map(|l| l.iter().map(|x| x.to_bits()).collect())
            .collect();
        (
            d.width,
            d.height,
            format!("{:?}", d.header),
            records,
            lights,
        )
    };
    let want = bits(&first);
    for p in &paths[1..] {
        match read(p) {
            Ok(d) if bits(&d) == want => {}
            Ok(_) => {
                eprintln!("{p} differs from {}", paths[0]);
                return ExitCode::from(1);
            }
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::from(2);
            }
        }
    }
    ExitCode::SUCCESS
}
