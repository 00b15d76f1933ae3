//! Integration speed: one full loop of a Gödel light ray from the origin (perpendicular to
//! the axis, back on the axis after 2πa(√2 − 1)) at the default tolerance, and the same
//! loop without dense output (what a renderer's inner loop pays per step).
//! Run: cargo bench -p spacetime --bench geodesic

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use spacetime::*;

fn loop_geodesic(m: &Metric, dir: [f64; 3]) -> Geodesic {
    let o = Event::default();
    Geodesic::launch(m, o, &m.static_frame(o), dir, 1.0, TimeDirection::Past).unwrap()
}

fn bench(c: &mut Criterion) {
    let m = Metric::Godel(Godel::new(1.0));
    let g = loop_geodesic(&m, [1.0, 0.0, 0.0]);
    let limits = TraceLimits::one_loop(1.0);
    let probe = trace(m, &g, &limits);
    let steps = probe.steps.len() as u64;
    eprintln!(
        "one loop: {} accepted steps, {} rejected, {} evaluations, stop = {:?}",
        steps, probe.rejected_steps, probe.evaluations, probe.stop
    );

    let mut group = c.benchmark_group("godel_light_loop");
    group.throughput(Throughput::Elements(1));
    group.bench_function("trace_one_loop_with_dense_output", |b| {
        b.iter(|| trace(m, black_box(&g), &limits))
    });
    // Bare stepping: the integrator alone over the same loop, no dense output, no events.
    group.bench_function("step_one_loop_bare", |b| {
        b.iter(|| {
            let (sys, y0) = GeodesicSystem::new(m, black_box(&g.start));
            let mut ode = Dop853::new(sys, 0.0, y0, Tolerances::default(), None);
            while ode.lambda() < probe.lambda_end {
                ode.step();
            }
            ode.accepted
        })
    });
    group.finish();

    let mut group = c.benchmark_group("godel_steps");
    group.throughput(Throughput::Elements(steps));
    group.bench_function("accepted_steps", |b| {
        b.iter(|| {
            let (sys, y0) = GeodesicSystem::new(m, black_box(&g.start));
            let mut ode = Dop853::new(sys, 0.0, y0, Tolerances::default(), None);
            for _ in 0..steps {
                ode.step();
            }
            ode.lambda()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
