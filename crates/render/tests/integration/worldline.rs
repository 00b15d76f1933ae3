//! Worldlines: transported frames stay orthonormal, and a ray point whose simultaneous
//! worldline point lies outside the integrated range still gets a finite distance.

use render::worldline::Worldline;
use scene::Motion;
use spacetime::{Event, Godel, LocalVelocity, Metric, Minkowski, Spacetime};

#[test]
fn free_fall_frames_stay_orthonormal_along_the_worldline() {
    let m = Metric::Godel(Godel::new(1.0));
    let motion = Motion::Geodesic {
        start: Event::new(0.0, -1.0, 0.3, 0.0),
        velocity: LocalVelocity::new(0.7, [1.0, 0.2, 0.1]).unwrap(),
    };
    let wl = Worldline::new(m, &motion, -12.0, 1.0).unwrap();
    for i in 0..=100 {
        let tau = -5.0 + 0.05 * i as f64;
        let p = wl.at(&m, tau).expect("inside the integrated range");
        // Orthonormal: g(e_a, e_b) = η_ab, the flat metric's components.
        let eta = Minkowski.metric(p.event);
        for (a, eta_a) in eta.iter().enumerate() {
            for (b, &want) in eta_a.iter().enumerate() {
                let got = m.dot(p.event, p.frame.e[a], p.frame.e[b]);
                assert!(
                    (got - want).abs() < 1e-9,
                    "τ = {tau}: g(e{a}, e{b}) = {got}"
                );
            }
        }
    }
}

#[test]
fn regression_far_point_beyond_the_integrated_range_is_not_skipped() {
    // A fast sphere in flat spacetime: a ray point whose rest-frame "now" lies beyond the
    // worldline's integrated range used to give no distance at all (an infinite probe), and
    // the tracer then skipped the whole step holding the hit.
    let m = Metric::Minkowski(Minkowski);
    let motion = Motion::Geodesic {
        start: Event::new(0.0, -2.0, 3.0, 0.0),
        velocity: LocalVelocity::new(0.9, [1.0, 0.0, 0.0]).unwrap(),
    };
    let wl = Worldline::new(m, &motion, -2.0, 0.5).unwrap();
    let x = Event::new(-1.9, 30.0, 3.0, 0.0);
    // The previous match on the ray (the seed) lies far beyond the integrated range.
    let far = wl
        .localize(&m, x, 100.0, 1.0)
        .expect("a distance, not None");
    let d = far.distance();
    assert!(d.is_finite() && d > 1.0, "distance {d}");
}

/// What the tracer assumes of a probe (to skip spans and exclude steps): its distance is a
/// lower bound of the true one, and the true one falls no faster than a near probe's rate.
/// Checked along many rays against the converged second-order distance, taken as the truth
/// where it is reliable (within 0.6a of the ball's centre). (A far probe's smaller rate
/// bounds only how fast its estimate may approach an entry: `far.rs`.)
#[test]
fn regression_probes_are_lower_bounds_and_the_distance_obeys_the_rate() {
    use render::target::Target;
    use render::worldline::Worldline as W;
    use spacetime::{trace, Geodesic, GeodesicKind, GeodesicState, TraceLimits};
    // Broken once when the second-order distance was used out to ~1a (where it overshoots),
    // and when first-order estimates at the switch were not shrunk (5 % too large there).
    let m = Metric::Godel(Godel::new(1.0));
    let objects = [
        Motion::Geodesic {
            start: Event::new(0.0, -1.0, 0.3, 0.0),
            velocity: LocalVelocity::new(0.7, [1.0, 0.0, 0.0]).unwrap(),
        },
        Motion::Rest {
            position: Event::new(0.0, 1.0, 0.2, 0.1),
        },
    ];
    let o = Event::default();
    let frame = m.static_frame(o);
    let radius = 0.2;
    for motion in objects {
        let target = crate::common::local_ball(m, radius, motion, (-12.0, 1.0));
        let Target::LocalSphere { worldline, .. } = &target else {
            unreachable!()
        };
        let truth = |s: &GeodesicState, wl: &W| {
            let lp = wl
                .localize(&m, s.x, wl.tau_guess(s.x.t), f64::INFINITY)?
                .near()?;
            let d = (lp.xi[0].powi(2) + lp.xi[1].powi(2) + lp.xi[2].powi(2)).sqrt();
            (d < 0.6).then_some(d - radius)
        };
        let (mut checked, mut rates, mut worst_bound, mut worst_rate): (usize, usize, f64, f64) =
            (0, 0, f64::NEG_INFINITY, 0.0);
        for i in 0..60 {
            let az = std::f64::consts::TAU * i as f64 / 60.0;
            let el = 0.05 * ((i % 5) as f64 - 2.0);
            let n = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
            let k = frame.vector([-1.0, n[0], n[1], n[2]]);
            let g = Geodesic::from_tangent(&m, GeodesicKind::Null, o, k);
            let tr = trace(
                m,
                &g,
                &TraceLimits {
                    until_time: Some(10.0),
                    ..Default::default()
                },
            );
            let dl = 0.005;
            let mut prev: Option<(f64, f64)> = None; // (true f, rate) at the previous point
            let mut l = 0.0;
            let mut seed = f64::NAN;
            while l < tr.lambda_end {
                let s = tr.state_at(l);
                let p = target.probe(&m, &s, seed);
                seed = p.tau;
                let t = truth(&s, worldline);
                if let Some(ft) = t {
                    checked += 1;
                    worst_bound = worst_bound.max(p.f - ft);
                    if let Some((fp, rate)) = prev {
                        rates += 1;
                        worst_rate = worst_rate.max((fp - ft) / dl / rate);
                    }
                }
                let near = p.xi[0].is_finite();
                prev = t.filter(|_| near).map(|ft| (ft, p.rate));
                l += dl;
            }
        }
        assert!(
            checked > 1000 && rates > 1000,
            "{motion:?}: only {checked} points near the ball, {rates} after a near probe"
        );
        // 1e-3: the second-order match itself depends on its Newton seed at the 1e-4 level.
        assert!(
            worst_bound <= 1e-3,
            "{motion:?}: a probe exceeded the true distance by {worst_bound}"
        );
        assert!(
            worst_rate <= 1.0,
            "{motion:?}: the distance fell {worst_rate} times faster than the bound"
        );
    }
}

/// Regression (fuzzing): falling balls at a small `a` took up to 2 × 200,000 stored steps
/// each (8 s and 580 MiB for one ball at a = 1e-6), with no bound on their number. Each
/// worldline now holds at most `MAX_WORLDLINE_STEPS` per direction, and all of a scene's
/// together at most `MAX_TOTAL_WORLDLINE_STEPS`, checked before any pixel is traced.
#[test]
fn regression_worldlines_beyond_their_budget_are_refused_before_tracing() {
    use render::driver::{render, NoProgress, RenderError, MAX_TOTAL_WORLDLINE_STEPS};
    use render::worldline::MAX_WORLDLINE_STEPS;
    let ball = |i: usize| {
        format!("[[object]]\nname = \"b{i}\"\nradius = 1e-4\nmotion = {{ kind = \"geodesic\", time = 0.0, position = {{ x = {}, y = 0.0, z = 0.0 }}, speed = 0.5, direction = [0, 1, 0] }}\n", 1e-4 * i as f64)
    };
    let balls = MAX_TOTAL_WORLDLINE_STEPS / MAX_WORLDLINE_STEPS + 1;
    let text = format!(
        "name = \"many\"\n[spacetime]\na = 1e-3\n[camera]\nkind = \"sphere\"\nwidth = 4\nheight = 2\n[trace]\nmax_past = 200.0\n{}",
        (0..balls).map(ball).collect::<String>()
    );
    let s = scene::Scene::from_str(&text, "many.toml").unwrap();
    match render(&s, &NoProgress) {
        Err(e @ RenderError::WorldlinesTooLong { steps }) => {
            assert!(steps > MAX_TOTAL_WORLDLINE_STEPS, "{e}");
            assert!(e.to_string().contains("max_past"), "{e}");
        }
        other => panic!(
            "expected the worldline budget error, got {:?}",
            other.map(|r| r.1)
        ),
    }
    // One such ball alone stays within its own bound.
    let one = scene::Scene::from_str(
        &text.replace(&(1..balls).map(ball).collect::<String>(), ""),
        "one.toml",
    )
    .unwrap();
    let (_, stats) = render(&one, &NoProgress).expect("a single ball is within budget");
    assert_eq!(stats.pixels, 8);
}
