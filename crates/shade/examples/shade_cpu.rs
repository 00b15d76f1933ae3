//! CPU time of re-shading the benchmark's synthetic 1920×1080 data file, one shader per run:
//! wall-clock benchmarks on a shared, loaded machine are noisy, CPU time is not.
//! `RAYON_NUM_THREADS=1 cargo run --release -p shade --example shade_cpu -- frequency 20`
//! prints CPU milliseconds per frame (process user + system time / frames), shading from the
//! file's [`shade::Channels`] (made once, outside the timing); a third argument `records`
//! shades from the records instead (`Shading::image_into`).

#[path = "../benches/common/mod.rs"]
mod common;

use shade::{Channels, Shading};

fn cpu_seconds() -> f64 {
    // utime and stime, fields 14 and 15 of /proc/self/stat, in clock ticks (100 per second).
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<&str> = after.split_whitespace().collect();
    let tick = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    (tick(11) + tick(12)) / 100.0
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("frequency", String::as_str);
    let frames: u32 = args.get(2).and_then(|n| n.parse().ok()).unwrap_or(20);
    let data = common::data();
    let Some((_, _, s)) = common::cases(&data)
        .into_iter()
        .find(|(key, _, _)| *key == which)
    else {
        eprintln!("unknown case {which}");
        std::process::exit(2);
    };
    let records = args.get(3).is_some_and(|a| a == "records");
    let shading = Shading::new(&data, &s).expect("valid settings");
    let channels = Channels::new(&data, shading.needs());
    let mut buffer = Vec::new();
    let shade = |buffer: &mut Vec<u8>| match records {
        true => shading.image_into(&data, buffer),
        false => shading.image_into_with(&channels, buffer),
    };
    shade(&mut buffer); // warm-up: tables, pages
    let start = cpu_seconds();
    for _ in 0..frames {
        shade(&mut buffer);
    }
    let ms = (cpu_seconds() - start) * 1000.0 / f64::from(frames);
    println!("{which}: {ms:.1} ms CPU per 1920x1080 frame");
}
