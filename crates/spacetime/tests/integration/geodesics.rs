//! Geodesics: the integrator against the closed forms through the origin (docs/physics.md,
//! "Closed forms"; written out independently in this file), known facts of Gödel light rays
//! (horizon at 2a, return time, sense of rotation), conservation of E, L, p_z and the null
//! condition, rays through the axis, and straight lines in Minkowski spacetime.

use crate::common::Rng;
use spacetime::*;
use std::f64::consts::{PI, SQRT_2};

fn origin() -> Event {
    Event::default()
}

/// The closed-form geodesic through the origin with initial coordinate tangent `k`
/// (κ = 0 light, 1 particle with proper time), evaluated at parameter λ.
fn closed_form(a: f64, k: FourVector, kappa: f64, lambda: f64) -> Event {
    let e = k.t;
    let pz = k.z;
    let kperp = k.x.hypot(k.y);
    let chi = k.y.atan2(k.x);
    let omega = (e * e + kappa + pz * pz).sqrt() / (2.0 * a);
    let r_max = kperp / omega;
    let q = e.abs() / (SQRT_2 * a * omega);
    let th = omega * lambda;
    let phi_big =
        th + ((q - 1.0) * th.sin() * th.cos()).atan2(th.cos().powi(2) + q * th.sin().powi(2));
    let sg = e.signum();
    let r = r_max * th.sin();
    let phi = chi + sg * phi_big;
    Event::new(
        sg * 2.0 * SQRT_2 * a * phi_big - e * lambda,
        r * phi.cos(),
        r * phi.sin(),
        pz * lambda,
    )
}

fn launch(m: &Metric, at: Event, dir: [f64; 3], speed: f64, time: TimeDirection) -> Geodesic {
    Geodesic::launch(m, at, &m.static_frame(at), dir, speed, time).expect("valid launch")
}

#[test]
fn integrated_geodesics_match_the_closed_forms_through_the_origin() {
    let mut rng = Rng::new(11);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.7, 1.8] {
        let m = Metric::Godel(Godel::new(a));
        for i in 0..24 {
            let dir = rng.direction();
            let speed = if i % 2 == 0 {
                1.0
            } else {
                rng.uniform(0.05, 0.95)
            };
            let time = if i % 3 == 0 {
                TimeDirection::Past
            } else {
                TimeDirection::Future
            };
            let g = launch(&m, origin(), dir, speed, time);
            let kappa = if speed == 1.0 { 0.0 } else { 1.0 };
            let k = g.start.tangent(&m);
            // Two full loops of coordinate time.
            let limits = TraceLimits {
                until_time: Some(2.0 * 2.0 * SQRT_2 * PI * a),
                ..Default::default()
            };
            let tr = trace(m, &g, &limits);
            assert_eq!(tr.stop, StopReason::TimeReached);
            for (l, s) in tr.samples(400) {
                let want = closed_form(a, k, kappa, l);
                let d = (s.x - want)
                    .to_array()
                    .iter()
                    .fold(0.0f64, |m, v| m.max(v.abs()));
                worst = worst.max(d);
                assert!(
                    d < 1e-8,
                    "a={a} dir={dir:?} v={speed} λ={l}: {:?} vs {want:?}",
                    s.x
                );
            }
        }
    }
    eprintln!("worst deviation from the closed forms: {worst:e}");
}

#[test]
fn perpendicular_light_reaches_the_horizon_at_half_loop_and_returns_after_the_known_time() {
    for a in [1.0, 0.5, 2.0] {
        let m = Metric::Godel(Godel::new(a));
        let g = launch(&m, origin(), [1.0, 0.0, 0.0], 1.0, TimeDirection::Future);
        let tr = trace(m, &g, &TraceLimits::one_loop(a));
        assert_eq!(tr.stop, StopReason::AxisReturn);
        let t_ret = 2.0 * PI * a * (SQRT_2 - 1.0);
        assert!(
            (tr.end.x.t - t_ret).abs() < 1e-6 * a,
            "return time {} vs {t_ret}",
            tr.end.x.t
        );
        assert!(
            tr.end.x.r() < 1e-6 * a,
            "not back on the axis: r = {}",
            tr.end.x.r()
        );
        assert!(
            (tr.lambda_end - 2.0 * PI * a).abs() < 1e-6 * a,
            "λ_ret = {}",
            tr.lambda_end
        );
        let half = tr.state_at(0.5 * tr.lambda_end);
        assert!(
            (half.x.r() - 2.0 * a).abs() < 1e-6 * a,
            "r at half loop = {}",
            half.x.r()
        );
        assert!((half.x.t - 0.5 * t_ret).abs() < 1e-6 * a);
    }
}

#[test]
fn future_rays_turn_counter_clockwise_and_past_rays_clockwise() {
    let m = Metric::Godel(Godel::new(1.0));
    for (time, sign) in [(TimeDirection::Future, 1.0), (TimeDirection::Past, -1.0)] {
        let g = launch(&m, origin(), [1.0, 0.0, 0.0], 1.0, time);
        let tr = trace(m, &g, &TraceLimits::one_loop(1.0));
        assert_eq!(tr.stop, StopReason::AxisReturn);
        for (l, s) in tr.samples(50).into_iter().skip(1).take(48) {
            assert!(sign * s.x.y > 0.0, "{time:?} at λ={l}: y = {}", s.x.y);
        }
        // Time runs the way the ray was launched.
        assert!(sign * tr.end.x.t > 0.0);
    }
}

#[test]
fn no_light_ray_from_the_origin_crosses_the_horizon_and_tilted_rays_stay_inside() {
    let mut rng = Rng::new(12);
    for a in [1.0, 0.6] {
        let m = Metric::Godel(Godel::new(a));
        for i in 0..60 {
            let dir = if i == 0 {
                [0.0, 1.0, 0.0]
            } else {
                rng.direction()
            };
            let time = if i % 2 == 0 {
                TimeDirection::Future
            } else {
                TimeDirection::Past
            };
            let g = launch(&m, origin(), dir, 1.0, time);
            let tr = trace(m, &g, &TraceLimits::one_loop(a));
            let r_max = tr
                .samples(2001)
                .iter()
                .map(|(_, s)| s.x.r())
                .fold(0.0, f64::max);
            let cos_psi = dir[2];
            let sin_psi = (1.0 - cos_psi * cos_psi).sqrt();
            let want = 2.0 * a * sin_psi / (1.0 + cos_psi * cos_psi).sqrt();
            assert!(
                r_max <= 2.0 * a * (1.0 + 1e-9),
                "ray {dir:?} reached r = {r_max}"
            );
            assert!(
                (r_max - want).abs() < 1e-6 * a,
                "r_max {r_max} vs closed form {want} for ψ = {}",
                cos_psi.acos()
            );
        }
    }
}

#[test]
fn constants_of_motion_and_null_condition_are_conserved_over_a_full_loop() {
    let mut rng = Rng::new(13);
    for a in [1.0, 0.8] {
        let m = Metric::Godel(Godel::new(a));
        for i in 0..40 {
            // From the origin and from random events inside and beyond the horizon (L ≠ 0).
            let at = if i < 10 { origin() } else { rng.event(3.0 * a) };
            let speed = if i % 4 == 3 { 0.6 } else { 1.0 };
            let time = if i % 2 == 0 {
                TimeDirection::Past
            } else {
                TimeDirection::Future
            };
            let g = launch(&m, at, rng.direction(), speed, time);
            let tr = trace(m, &g, &TraceLimits::one_loop(a));
            assert!(!tr.stop.is_failure(), "{:?}", tr.stop);
            let d = Drift::along(&m, &tr, a);
            assert!(d.max() < 1e-9, "drift {d:?} from {at:?}");
            let c = ConstantsOfMotion::of(&m, &tr.start);
            let want_norm = if speed == 1.0 { 0.0 } else { -1.0 };
            assert!((c.normalization - want_norm).abs() < 1e-12);
        }
    }
}

#[test]
fn every_light_ray_from_any_event_returns_to_its_axis() {
    // Homogeneity: the isometry moving P to the origin maps the loop through the origin to
    // a loop through P's axis, so the axis-return stop is met from everywhere.
    let mut rng = Rng::new(14);
    let m = Metric::Godel(Godel::new(1.0));
    for _ in 0..30 {
        let at = rng.event(4.0);
        let mut dir = rng.direction();
        dir[2] *= 0.5;
        let g = launch(&m, at, dir, 1.0, TimeDirection::Past);
        let tr = trace(m, &g, &TraceLimits::one_loop(1.0));
        assert_eq!(tr.stop, StopReason::AxisReturn, "from {at:?}");
        let d = (tr.end.x.x - at.x).hypot(tr.end.x.y - at.y);
        assert!(d < 1e-6, "returned {d} away from the axis");
    }
}

#[test]
fn rays_through_the_axis_integrate_without_nan_or_stalls() {
    let mut rng = Rng::new(15);
    let m = Metric::Godel(Godel::new(1.0));
    for _ in 0..30 {
        // Start at the far point of a loop through the origin: the ray then crosses the axis.
        let g0 = launch(&m, origin(), rng.direction(), 1.0, TimeDirection::Future);
        let tr0 = trace(m, &g0, &TraceLimits::one_loop(1.0));
        let mid = tr0.state_at(0.5 * tr0.lambda_end);
        let g = Geodesic {
            kind: GeodesicKind::Null,
            start: mid,
        };
        let tr = trace(
            m,
            &g,
            &TraceLimits {
                until_time: Some(10.0),
                ..Default::default()
            },
        );
        assert_eq!(tr.stop, StopReason::TimeReached);
        assert!(tr.end.x.is_finite() && tr.end.p.is_finite());
        assert!(
            tr.rejected_steps * 5 <= tr.steps.len() as u64 + 5,
            "many rejected steps: {}",
            tr.rejected_steps
        );
        // The ray really went through the axis: the minimum distance is ~0.
        let rmin = tr
            .samples(4001)
            .iter()
            .map(|(_, s)| s.x.r())
            .fold(f64::INFINITY, f64::min);
        assert!(rmin < 1e-2);
        assert!(Drift::along(&m, &tr, 1.0).max() < 1e-9);
    }
    // A ray launched along the axis itself stays on it.
    let g = launch(&m, origin(), [0.0, 0.0, 1.0], 1.0, TimeDirection::Past);
    let tr = trace(m, &g, &TraceLimits::one_loop(1.0));
    assert_eq!(tr.stop, StopReason::TimeReached);
    assert!(tr.end.x.r() < 1e-12 && (tr.end.x.z - tr.lambda_end).abs() < 1e-9);
}

#[test]
fn until_time_stops_exactly_on_the_bound_in_both_directions() {
    let m = Metric::Godel(Godel::new(1.0));
    let mut rng = Rng::new(16);
    for i in 0..20 {
        let at = rng.event(1.5);
        let time = if i % 2 == 0 {
            TimeDirection::Past
        } else {
            TimeDirection::Future
        };
        let speed = if i % 3 == 0 { 0.5 } else { 1.0 };
        let g = launch(&m, at, rng.direction(), speed, time);
        let dt = rng.uniform(0.1, 2.0);
        let tr = trace(
            m,
            &g,
            &TraceLimits {
                until_time: Some(dt),
                ..Default::default()
            },
        );
        assert_eq!(tr.stop, StopReason::TimeReached);
        assert!(((tr.end.x.t - at.t).abs() - dt).abs() < 1e-12);
        // The end state is the dense output there: its other coordinates are consistent.
        let s = tr.state_at(tr.lambda_end * (1.0 - 1e-12));
        assert!((s.x.x - tr.end.x.x).abs() < 1e-9 && (s.x.t - tr.end.x.t).abs() < 1e-9);
    }
}

#[test]
fn timelike_in_plane_return_time_matches_the_closed_form() {
    let a = 1.0;
    let m = Metric::Godel(Godel::new(a));
    for v in [0.1, 0.5, 0.9] {
        let g = launch(&m, origin(), [0.0, 1.0, 0.0], v, TimeDirection::Future);
        let tr = trace(m, &g, &TraceLimits::one_loop(a));
        assert_eq!(tr.stop, StopReason::AxisReturn);
        let t_ret = 2.0 * PI * a * (SQRT_2 - 1.0 / (2.0 - v * v).sqrt());
        assert!(
            (tr.end.x.t - t_ret).abs() < 1e-6,
            "v={v}: {} vs {t_ret}",
            tr.end.x.t
        );
        let r_max = tr
            .samples(2001)
            .iter()
            .map(|(_, s)| s.x.r())
            .fold(0.0, f64::max);
        assert!((r_max - 2.0 * a * v / (2.0 - v * v).sqrt()).abs() < 1e-6);
    }
}

#[test]
fn minkowski_rays_are_straight() {
    let m = Metric::Minkowski(Minkowski);
    let mut rng = Rng::new(17);
    for i in 0..30 {
        let at = rng.event(5.0);
        let speed = if i % 2 == 0 { 1.0 } else { 0.7 };
        let g = launch(&m, at, rng.direction(), speed, TimeDirection::Past);
        let k = g.start.tangent(&m);
        let tr = trace(
            m,
            &g,
            &TraceLimits {
                until_time: Some(10.0),
                ..Default::default()
            },
        );
        for (l, s) in tr.samples(100) {
            let want = at.offset(k, l);
            let d = (s.x - want)
                .to_array()
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(
                d < 1e-12 * (1.0 + l),
                "λ={l}: off the straight line by {d:e}"
            );
        }
    }
}

#[test]
fn dense_output_is_accurate_between_steps() {
    // Harmonic oscillator y'' = −y: exact solution cos, sin; the 7th-order interpolant
    // must stay within the tolerance's order of magnitude inside every step.
    struct Osc;
    impl OdeSystem<2> for Osc {
        fn rhs(&self, y: &[f64; 2]) -> [f64; 2] {
            [y[1], -y[0]]
        }
    }
    let tol = Tolerances {
        rtol: 1e-10,
        atol: 1e-10,
        ..Default::default()
    };
    let mut ode = Dop853::new(Osc, 0.0, [1.0, 0.0], tol, None);
    let mut worst: f64 = 0.0;
    while ode.lambda() < 20.0 {
        assert_eq!(ode.step(), StepOutcome::Accepted);
        let d = ode.dense();
        for j in 0..=10 {
            let l = d.lambda0 + d.h * j as f64 / 10.0;
            let y = d.eval(l);
            worst = worst
                .max((y[0] - l.cos()).abs())
                .max((y[1] + l.sin()).abs());
        }
        assert_eq!(
            d.eval(d.lambda1()),
            *ode.state(),
            "interpolant ends on the step"
        );
    }
    assert!(worst < 1e-8, "dense output error {worst:e}");
    assert!(ode.accepted < 200, "too many steps: {}", ode.accepted);
}

/// A system that counts its evaluations and stops the test once they exceed a bound no
/// bounded step attempt comes near (each attempt is a dozen evaluations, retries shrink the
/// step at least tenfold per few attempts).
struct Counted<F: Fn(&[f64; 2]) -> [f64; 2]> {
    rhs: F,
    calls: std::cell::Cell<u64>,
}

impl<F: Fn(&[f64; 2]) -> [f64; 2]> OdeSystem<2> for Counted<F> {
    fn rhs(&self, y: &[f64; 2]) -> [f64; 2] {
        self.calls.set(self.calls.get() + 1);
        assert!(
            self.calls.get() < 1_000_000,
            "a million evaluations: the step attempt retries without end"
        );
        (self.rhs)(y)
    }
}

/// Fuzzing found `godel render` hanging on an observer at r = 1e9 (a = 1): the ray's
/// start was NaN, the first step size came out infinite, and `step` retried an infinite
/// step forever (inf · 0.25 = inf). Now such an attempt ends as not accepted.
#[test]
fn regression_fuzz_infinite_step_size_ends_the_attempt() {
    let nan = Counted {
        rhs: |y: &[f64; 2]| [y[1], -y[0]],
        calls: Default::default(),
    };
    let mut ode = Dop853::new(nan, 0.0, [f64::NAN, 0.0], Tolerances::default(), None);
    assert_ne!(ode.step(), StepOutcome::Accepted);
    let given = Counted {
        rhs: |y: &[f64; 2]| [y[1], -y[0]],
        calls: Default::default(),
    };
    let mut ode = Dop853::new(
        given,
        0.0,
        [1.0, 0.0],
        Tolerances::default(),
        Some(f64::INFINITY),
    );
    assert_eq!(ode.step(), StepOutcome::Stalled);
}

/// Where the error estimate vanishes (here y' = 0) the step grows tenfold per step; it
/// used to overflow to infinity after ~310 steps and then retry forever. Now it stays
/// finite and every step is accepted.
#[test]
fn regression_fuzz_growing_step_stays_finite() {
    let still = Counted {
        rhs: |_: &[f64; 2]| [0.0, 0.0],
        calls: Default::default(),
    };
    let mut ode = Dop853::new(still, 0.0, [1.0, 2.0], Tolerances::default(), Some(1.0));
    for _ in 0..400 {
        assert_eq!(ode.step(), StepOutcome::Accepted);
        assert!(ode.next_step_size().is_finite());
    }
    assert_eq!(*ode.state(), [1.0, 2.0]);
}

#[test]
fn launch_rejects_bad_directions_and_speeds() {
    let m = Metric::Godel(Godel::new(1.0));
    let f = m.static_frame(origin());
    for (dir, speed) in [
        ([0.0, 0.0, 0.0], 1.0),
        ([f64::NAN, 0.0, 1.0], 1.0),
        ([1.0, 0.0, 0.0], 1.5),
        ([1.0, 0.0, 0.0], -0.1),
        ([1.0, 0.0, 0.0], f64::NAN),
    ] {
        assert!(
            Geodesic::launch(&m, origin(), &f, dir, speed, TimeDirection::Future).is_none(),
            "{dir:?} {speed}"
        );
    }
}
