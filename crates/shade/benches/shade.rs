//! Re-shading a synthetic 1920×1080 data file with each shader (and two combinations): the
//! post-render stage's speed target is 8 ms per frame on 2 cores (BENCHMARKS.md, issue 13
//! row (6)). Group `shade 1920x1080`: from the file's [`shade::Channels`] (made once per
//! file, as the viewer and `godel sequence` do); group `shade 1920x1080 records`: from the
//! records (`Shading::image_into`).
//! `cargo bench -p shade --bench shade -- --measurement-time 3 --warm-up-time 1`

mod common;

use criterion::{criterion_group, criterion_main, Criterion};
use shade::{Channels, Shading};

fn bench(c: &mut Criterion) {
    let data = common::data();
    let cases = common::cases(&data);
    let mut buffer = Vec::new();
    let mut group = c.benchmark_group("shade 1920x1080");
    group.sample_size(20);
    for (_, name, settings) in &cases {
        let shading = Shading::new(&data, settings).expect("valid settings");
        let channels = Channels::new(&data, shading.needs());
        group.bench_function(*name, |b| {
            b.iter(|| shading.image_into_with(&channels, &mut buffer))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("shade 1920x1080 records");
    group.sample_size(20);
    for (_, name, settings) in &cases {
        let shading = Shading::new(&data, settings).expect("valid settings");
        group.bench_function(*name, |b| b.iter(|| shading.image_into(&data, &mut buffer)));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
