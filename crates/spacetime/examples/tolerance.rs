//! Worst drift of the constants of motion over one loop, and steps per loop, for several
//! tolerances, over many random light rays (from the origin and from random events):
//! `cargo run --release -p spacetime --example tolerance`.
use spacetime::*;

fn main() {
    let m = Metric::Godel(Godel::new(1.0));
    let mut seed: u64 = 0x9E3779B97F4A7C15;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let rays: Vec<(Event, [f64; 3])> = (0..400)
        .map(|i| {
            let at = if i % 2 == 0 {
                Event::default()
            } else {
                Event::new(0.0, 4.0 * rnd() - 2.0, 4.0 * rnd() - 2.0, 0.0)
            };
            (
                at,
                [2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0],
            )
        })
        .collect();
    for tol in [1e-11, 2e-11, 3e-11, 5e-11, 1e-10] {
        let (mut worst, mut steps) = (0.0f64, 0usize);
        for (at, dir) in &rays {
            let g = Geodesic::launch(
                &m,
                *at,
                &m.static_frame(*at),
                *dir,
                1.0,
                TimeDirection::Past,
            )
            .unwrap();
            let limits = TraceLimits {
                tolerances: Tolerances {
                    rtol: tol,
                    atol: tol,
                    ..Default::default()
                },
                ..TraceLimits::one_loop(1.0)
            };
            let tr = trace(m, &g, &limits);
            worst = worst.max(Drift::along(&m, &tr, 1.0).max());
            steps += tr.steps.len();
        }
        println!(
            "tol {tol:e}: worst drift {worst:.2e}, mean steps per loop {:.1}",
            steps as f64 / rays.len() as f64
        );
    }
}
