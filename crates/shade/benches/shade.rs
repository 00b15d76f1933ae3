//! Re-shading a synthetic 1920×1080 data file with each shader (and two combinations): the
//! post-render stage's speed target is under 20 ms per frame on 2 cores (BENCHMARKS.md).
//! `cargo bench -p shade --bench shade -- --measurement-time 3 --warm-up-time 1`

mod common;

use criterion::{criterion_group, criterion_main, Criterion};
use shade::Shading;

fn bench(c: &mut Criterion) {
    let data = common::data();
    let cases = common::cases(&data);
    let mut group = c.benchmark_group("shade 1920x1080");
    group.sample_size(20);
    let mut buffer = Vec::new();
    for (_, name, settings) in cases {
        let shading = Shading::new(&data, &settings).expect("valid settings");
        group.bench_function(name, |b| b.iter(|| shading.image_into(&data, &mut buffer)));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
