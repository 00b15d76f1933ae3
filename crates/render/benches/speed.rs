//! The speed issue's rows, measured in process CPU time (all threads, EXR encoding
//! included) rather than wall time, so that figures taken while other builds share the
//! machine stay comparable: on idle cores a one-thread render's wall time is about its CPU
//! time, a two-thread one's about half.
//! (1) `scenes/bench-static.toml` 440×50, exact, one thread, with the data file
//!     (and tracing only, to tell tracing from encoding);
//! (2) the same, numeric;
//! (3) the reference scene at 440×50, exact, one thread;
//! (4) the reference scene at 2200×250, exact, two threads;
//! (5) `scenes/floor-grid.toml` (plane, ball, light: shadow rays) at 160×90, a sixteenth
//!     of its pixels, two threads, numeric (as the file) and exact.
//! Run: cargo bench -p render --bench speed [-- FILTER]

mod common;

use common::scene;
use criterion::{criterion_group, criterion_main, Bencher, Criterion, Throughput};
use render::driver::{render, NoProgress};
use std::time::Duration;

/// CPU time of the whole process so far (every thread).
fn cpu_now() -> Duration {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec through a valid pointer.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    assert_eq!(rc, 0, "clock_gettime");
    Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

/// Times `f` in process CPU time.
fn cpu(b: &mut Bencher, f: impl Fn() -> usize) {
    b.iter_custom(|iters| {
        let start = cpu_now();
        for _ in 0..iters {
            std::hint::black_box(f());
        }
        cpu_now() - start
    });
}

fn bench(c: &mut Criterion) {
    let pool = |n: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
    };
    let (one, two) = (pool(1), pool(2));
    // (label, scene file, width, height, method, threads, with the data file)
    let (bench, reference, floor) = (
        "scenes/bench-static.toml",
        "scenes/reference.toml",
        "scenes/floor-grid.toml",
    );
    #[rustfmt::skip] // one case a line, as a table
    let cases = [
        ("bench_static_440x50", bench, 440, 50, "exact", &one, true),
        ("bench_static_440x50", bench, 440, 50, "exact", &one, false),
        ("bench_static_440x50", bench, 440, 50, "numeric", &one, true),
        ("reference_440x50", reference, 440, 50, "exact", &one, true),
        ("reference_440x50", reference, 440, 50, "numeric", &one, true),
        ("reference_2200x250", reference, 2200, 250, "exact", &two, true),
        ("floor_grid_160x90", floor, 160, 90, "numeric", &two, true),
        ("floor_grid_160x90", floor, 160, 90, "exact", &two, true),
    ];
    for (label, path, w, h, method, pool, datafile) in cases {
        let sc = scene(path, w, h, method);
        let mut group = c.benchmark_group(format!("cpu_{label}"));
        group.sample_size(10);
        group.throughput(Throughput::Elements(u64::from(w) * u64::from(h)));
        let threads = pool.current_num_threads();
        let name = if datafile {
            format!("{method}_{threads}_threads_with_datafile")
        } else {
            format!("{method}_{threads}_threads_trace_only")
        };
        group.bench_function(name, |b| {
            cpu(b, || {
                pool.install(|| {
                    let (data, _) = render(&sc, &NoProgress).unwrap();
                    if datafile {
                        data.to_bytes().unwrap().len()
                    } else {
                        data.records.len()
                    }
                })
            })
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
