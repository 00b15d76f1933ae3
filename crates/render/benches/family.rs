//! Renderer speed in the Gödel-type family (issue 34): `scenes/godel-type.toml` (an earth
//! falling past an observer on the axis, a ball at rest) at 220×25 in the members
//! m²/Ω² = 0, 2 (Gödel's universe) and 4, traced by the exact tracer and (not in the causal
//! member 4, where the numeric tracer cannot follow the long loops of nearly in-plane rays)
//! the numeric one, on 2 threads, data file included; throughput in rays.
//! Run: cargo bench -p render --bench family

mod common;

use common::scene;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::driver::{render, NoProgress};
use scene::TraceMethod;
use spacetime::{GodelType, Metric};

fn bench(c: &mut Criterion) {
    let base = scene("scenes/godel-type.toml", 220, 25, "numeric");
    let omega = base.metric.godel_type().expect("a Gödel-type scene").omega;
    let mut group = c.benchmark_group("godel_type_220x25");
    group.sample_size(10);
    group.throughput(Throughput::Elements(220 * 25));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    for (ratio, methods) in [
        (0.0, &[TraceMethod::Exact, TraceMethod::Numeric][..]),
        (2.0, &[TraceMethod::Exact, TraceMethod::Numeric][..]),
        (4.0, &[TraceMethod::Exact][..]),
    ] {
        for &method in methods {
            let mut member = base.clone();
            member.metric = Metric::GodelType(GodelType::new(ratio * omega * omega, omega));
            member.trace.method = method;
            let name = format!("m2_{ratio}_omega2_{method:?}_2_threads").to_lowercase();
            group.bench_function(name, |b| {
                b.iter(|| {
                    pool.install(|| {
                        let (data, _) = render(&member, &NoProgress).unwrap();
                        data.to_bytes().unwrap().len()
                    })
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
