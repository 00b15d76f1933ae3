//! Renderer speed on the benchmark scenes of the renderer issue:
//! (1) `scenes/bench-static.toml`: 440×50 panorama (220°×25°) of a sphere of radius 0.2 at
//!     rest at (1, 0, 0), observer at rest at the origin looking along +y, rays followed
//!     10 time units into the past; the whole render plus encoding the data file.
//! (2) the reference scene at a reduced 440×50 (its full 2200×250 wall time is measured
//!     with the CLI, see BENCHMARKS.md).
//! Each with the numeric tracer on 1 and 2 threads, and the exact tracer on 1.
//! (3) samples per pixel: the reference scene at 220×25 pixels with 1, 4 and 16 samples
//!     (numeric, 2 threads, data file included); throughput in picture pixels.
//! Run: cargo bench -p render --bench render (only (3): `-- samples_per_pixel`)

mod common;

use common::{sampled_scene, scene};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::driver::{render, NoProgress};

fn bench(c: &mut Criterion) {
    let threads = [1usize, 2];
    for (label, path) in [
        ("bench_static_440x50", "scenes/bench-static.toml"),
        ("reference_440x50", "scenes/reference.toml"),
    ] {
        let sc = scene(path, 440, 50, "numeric");
        let mut group = c.benchmark_group(label);
        group.sample_size(10);
        group.throughput(Throughput::Elements(440 * 50));
        let exact = scene(path, 440, 50, "exact");
        group.bench_function("exact_1_thread_with_datafile", |b| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .build()
                .unwrap();
            b.iter(|| {
                pool.install(|| {
                    render(&exact, &NoProgress)
                        .unwrap()
                        .0
                        .to_bytes()
                        .unwrap()
                        .len()
                })
            })
        });
        for &n in &threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap();
            group.bench_function(format!("numeric_{n}_threads_with_datafile"), |b| {
                b.iter(|| {
                    pool.install(|| {
                        let (data, _) = render(&sc, &NoProgress).unwrap();
                        data.to_bytes().unwrap().len()
                    })
                })
            });
        }
        group.finish();
    }
}

/// (3): the cost of N samples per pixel against one.
fn samples(c: &mut Criterion) {
    let (w, h) = (220, 25);
    let mut group = c.benchmark_group("samples_per_pixel");
    group.sample_size(10);
    group.throughput(Throughput::Elements(u64::from(w * h)));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    for n in [1, 4, 16] {
        let sc = sampled_scene("scenes/reference.toml", w, h, "numeric", n);
        group.bench_function(format!("reference_220x25_{n}_samples"), |b| {
            b.iter(|| {
                pool.install(|| {
                    let (data, _) = render(&sc, &NoProgress).unwrap();
                    data.to_bytes().unwrap().len()
                })
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench, samples);
criterion_main!(benches);
