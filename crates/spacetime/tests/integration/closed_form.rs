//! Exact geodesics (closed forms through the origin, carried to any event by isometries)
//! against the numerical integrator, and their tangents' normalization and constants of
//! motion.

use crate::common::{max_abs, Rng};
use spacetime::*;

/// A random launch: light or a particle (speed 0.05..0.95), future or past, from `at`.
fn random_launch(rng: &mut Rng, m: &Metric, at: Event, i: usize) -> Geodesic {
    let speed = if i.is_multiple_of(2) {
        1.0
    } else {
        rng.uniform(0.05, 0.95)
    };
    let time = if i % 4 < 2 {
        TimeDirection::Future
    } else {
        TimeDirection::Past
    };
    Geodesic::launch(m, at, &m.static_frame(at), rng.direction(), speed, time).unwrap()
}

/// Compares the exact geodesic with the integrated one over 1.5 returns to the (image)
/// axis; returns the worst relative deviation of events and of tangents.
fn compare(m: Metric, a: f64, g: &Geodesic) -> (f64, f64) {
    let k = g.start.tangent(&m);
    let exact = ExactGeodesic::new(a, g.start.x, k).expect("causal tangent");
    let limits = TraceLimits {
        max_affine: 1.5 * exact.origin.return_parameter(),
        ..Default::default()
    };
    let tr = trace(m, g, &limits);
    assert_eq!(tr.stop, StopReason::AffineLimit);
    let (mut dx, mut dk) = (0.0f64, 0.0f64);
    for (l, s) in tr.samples(300) {
        let (e, v) = exact.at(l);
        let scale = 1.0 + max_abs(e.to_array());
        dx = dx.max(max_abs((e - s.x).to_array()) / scale);
        let kn = s.tangent(&m);
        dk = dk.max(max_abs((v - kn).to_array()) / (1.0 + max_abs(kn.to_array())));
    }
    (dx, dk)
}

#[test]
fn closed_forms_through_the_origin_match_the_integrator() {
    let mut rng = Rng::new(301);
    let (mut wx, mut wk) = (0.0f64, 0.0f64);
    for a in [1.0, 0.7, 1.8] {
        let m = Metric::Godel(Godel::new(a));
        for i in 0..24 {
            let g = random_launch(&mut rng, &m, Event::default(), i);
            let (dx, dk) = compare(m, a, &g);
            assert!(
                dx < 1e-8 && dk < 1e-8,
                "a={a} #{i}: events {dx:e}, tangents {dk:e}"
            );
            (wx, wk) = (wx.max(dx), wk.max(dk));
        }
    }
    eprintln!("closed form vs integrator from the origin: events {wx:e}, tangents {wk:e}");
}

#[test]
fn exact_geodesics_from_any_event_match_the_integrator() {
    let mut rng = Rng::new(302);
    let (mut wx, mut wk) = (0.0f64, 0.0f64);
    for a in [1.0, 0.6] {
        let m = Metric::Godel(Godel::new(a));
        for i in 0..40 {
            let at = rng.event(4.0 * a);
            let g = random_launch(&mut rng, &m, at, i);
            let (dx, dk) = compare(m, a, &g);
            assert!(
                dx < 1e-8 && dk < 1e-8,
                "a={a} from {at:?}: events {dx:e}, tangents {dk:e}"
            );
            (wx, wk) = (wx.max(dx), wk.max(dk));
        }
    }
    eprintln!("exact vs integrator from random events: events {wx:e}, tangents {wk:e}");
}

#[test]
fn exact_tangents_stay_normalized_and_conserve_e_l_pz() {
    let mut rng = Rng::new(303);
    let (mut wn, mut wc) = (0.0f64, 0.0f64);
    for a in [1.0, 0.5, 2.0] {
        let m = Metric::Godel(Godel::new(a));
        for i in 0..40 {
            let at = if i < 8 {
                Event::default()
            } else {
                rng.event(5.0 * a)
            };
            let g = random_launch(&mut rng, &m, at, i);
            let k = g.start.tangent(&m);
            let exact = ExactGeodesic::new(a, at, k).unwrap();
            let c0 = ConstantsOfMotion::of(&m, &g.start);
            let want = if i % 2 == 0 { 0.0 } else { -1.0 };
            let e2 = c0.energy * c0.energy;
            for j in 0..=200 {
                let l = 2.0 * exact.origin.return_parameter() * j as f64 / 200.0;
                let (x, v) = exact.at(l);
                let s = GeodesicState {
                    x,
                    p: m.lower(x, v),
                };
                let c = ConstantsOfMotion::of(&m, &s);
                let dn = (m.dot(x, v, v) - want).abs() / e2;
                let de = (c.energy - c0.energy).abs() / c0.energy.abs();
                let dl = (c.angular_momentum - c0.angular_momentum).abs()
                    / c0.angular_momentum.abs().max(c0.energy.abs() * a);
                let dz = (c.pz - c0.pz).abs() / c0.energy.abs();
                wn = wn.max(dn);
                wc = wc.max(de).max(dl).max(dz);
                assert!(dn < 1e-12, "g(k,k) off by {dn:e} at λ={l} from {at:?}");
                assert!(
                    de.max(dl).max(dz) < 1e-12,
                    "E {de:e} L {dl:e} p_z {dz:e} at λ={l}"
                );
            }
        }
    }
    eprintln!("exact tangents: normalization {wn:e}, constants {wc:e}");
}

#[test]
fn the_closed_form_starts_where_it_should_and_refuses_spacelike_tangents() {
    let a = 1.3;
    let k = FourVector::new(-1.0, 0.6, -0.8, 0.0);
    let g = OriginGeodesic::new(a, k).unwrap();
    let (e, v) = g.at(0.0);
    assert_eq!(e, Event::default());
    assert!(max_abs((v - k).to_array()) < 1e-15);
    // In-plane light reaches the horizon exactly.
    assert!((g.r_max() - 2.0 * a).abs() < 1e-14);
    assert!(OriginGeodesic::new(a, FourVector::new(1.0, 1.0, 0.5, 0.0)).is_none());
    assert!(OriginGeodesic::new(a, FourVector::default()).is_none());
    let x = Event::new(0.3, 4.0, -2.0, 1.0);
    let ex = ExactGeodesic::new(a, x, FourVector::new(1.0, 0.0, 0.0, 0.0)).unwrap();
    assert!(max_abs((ex.at(0.0).0 - x).to_array()) < 1e-14);
}

/// `OriginGeodesic::time` is the time of `at`'s event, and for light it is monotone in λ
/// with |dt/dλ| ≤ |E| (the bound `render::falling` inverts it with), the slope reaching
/// close to |E| somewhere on every ray.
#[test]
fn a_light_rays_time_is_monotone_with_its_slope_bounded_by_its_energy() {
    for (a, i, g) in light_rays(307) {
        let e = g.energy.abs();
        let n = 2000;
        let dl = 2.5 * g.return_parameter() / n as f64;
        let mut steepest = 0.0f64;
        for j in 0..n {
            let (l0, l1) = (j as f64 * dl, (j + 1) as f64 * dl);
            let (t0, t1) = (g.time(l0), g.time(l1));
            assert!((t0 - g.at(l0).0.t).abs() <= 1e-12 * (1.0 + t0.abs()));
            let slope = (t1 - t0) / dl * g.energy.signum();
            assert!(slope >= -1e-12 * e, "a={a} #{i}: t turns back ({slope})");
            assert!(
                slope <= e * (1.0 + 1e-9),
                "a={a} #{i}: slope {slope} > |E| {e}"
            );
            steepest = steepest.max(slope);
        }
        assert!(
            steepest > 0.99 * e,
            "a={a} #{i}: steepest {steepest} of |E| {e}"
        );
    }
}

/// 40 light rays from the origin in each of the universes a = 1, 0.4 and 2.5, to the future
/// and the past in turn, in random directions with energies 0.2–3: (a, number, ray).
fn light_rays(seed: u64) -> Vec<(f64, usize, OriginGeodesic)> {
    let mut rng = Rng::new(seed);
    let mut rays = Vec::new();
    for a in [1.0, 0.4, 2.5] {
        let m = Metric::Godel(Godel::new(a));
        for i in 0..40 {
            let time = if i % 2 == 0 {
                TimeDirection::Future
            } else {
                TimeDirection::Past
            };
            let k = photon_tangent(&m.static_frame(Event::default()), rng.direction(), time);
            rays.push((
                a,
                i,
                OriginGeodesic::new(a, rng.uniform(0.2, 3.0) * k).unwrap(),
            ));
        }
    }
    rays
}

/// A light ray's time strays from its mean rate Δt/λ_ret by at most
/// `OriginGeodesic::time_deviation` (the GPU kernel's λ window of a band of times: if the bound
/// were too small a loop would skip a stretch it must search), and comes within 0.1 % of it on
/// every ray.
#[test]
fn a_light_rays_time_strays_from_its_mean_rate_at_most_by_its_deviation() {
    for (a, i, g) in light_rays(311) {
        let l_ret = g.return_parameter();
        let rate = g.time(l_ret) / l_ret;
        let bound = g.time_deviation();
        let n = 4000;
        let mut worst = 0.0f64;
        for j in 0..=n {
            let l = 2.5 * l_ret * j as f64 / n as f64;
            let d = (g.time(l) - rate * l).abs();
            assert!(
                d <= bound * (1.0 + 1e-9) + 1e-12 * (a + (rate * l).abs()),
                "a={a} #{i}: λ = {l}: {d} > {bound}"
            );
            worst = worst.max(d);
        }
        assert!(
            worst >= 0.999 * bound,
            "a={a} #{i}: at most {worst} of {bound}"
        );
    }
}
