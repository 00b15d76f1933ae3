//! Shadow rays: light rays from a source at rest to a target event, checked by integrating
//! each one numerically from its emission event, against the in-plane closed-form delays,
//! and for the counts the geometry dictates.

mod common;
use common::Rng;
use spacetime::*;

fn max_abs(v: [f64; 4]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Integrates `r` from its emission event for its affine length; returns the relative
/// miss distance from `target` and the null-condition residual at emission.
fn miss(m: Metric, r: &ShadowRay, target: Event) -> (f64, f64) {
    let g = Geodesic::from_tangent(&m, GeodesicKind::Null, r.emission, r.tangent);
    let limits = TraceLimits {
        max_affine: r.lambda,
        ..Default::default()
    };
    let tr = trace(m, &g, &limits);
    assert_eq!(tr.stop, StopReason::AffineLimit);
    let d = max_abs((tr.end.x - target).to_array()) / (1.0 + max_abs(target.to_array()));
    (d, m.dot(r.emission, r.tangent, r.tangent).abs())
}

#[test]
fn every_ray_from_an_axis_source_lands_on_the_target() {
    let mut rng = Rng::new(401);
    let (mut worst, mut count) = (0.0f64, 0);
    for a in [1.0, 1.5, 0.7] {
        let m = Metric::Godel(Godel::new(a));
        for i in 0..12 {
            let mut p = rng.event(1.95 * a);
            p.z = if i % 4 == 0 {
                0.0
            } else {
                rng.uniform(-3.0, 3.0) * a
            };
            for r in shadow_rays_from_axis(a, p, 3) {
                let (d, null) = miss(m, &r, p);
                assert!(
                    d < 1e-8,
                    "a={a} {p:?} n={} {:?}: miss {d:e}",
                    r.winding,
                    r.branch
                );
                assert!(null < 1e-13, "not null: {null:e}");
                // On the source's worldline, future-directed with E = 1.
                let e = r.emission;
                assert!(e.x == 0.0 && e.y == 0.0 && e.z == 0.0 && e.t < p.t);
                assert!((m.lower(e, r.tangent).t + 1.0).abs() < 1e-15);
                worst = worst.max(d);
                count += 1;
            }
        }
    }
    assert!(count > 100, "only {count} rays");
    eprintln!("{count} axis shadow rays: worst miss {worst:e}");
}

#[test]
fn no_rays_reach_beyond_the_horizon_distance() {
    for a in [1.0, 2.0] {
        for rho in [2.0 * a, 2.01 * a, 2.5 * a, 6.0 * a] {
            for z in [0.0, 0.3, -2.0] {
                let p = Event::new(1.0, rho * 0.6, rho * 0.8, z);
                assert!(shadow_rays_from_axis(a, p, 5).is_empty(), "ρ={rho} z={z}");
            }
        }
    }
}

#[test]
fn in_plane_targets_get_exactly_two_rays_per_winding_with_the_known_delays() {
    // Delays t_P − t_em of the two in-plane rays to ρ = 1 and ρ = 1.9 for a = 1, i.e.
    // 2√2 a Φ(θ) − 2aθ with q = √2 at θ = arcsin(ρ/2a) and π − arcsin(ρ/2a) (values from an
    // independent numerical search), and their repeats every T_ret = 2πa(√2 − 1).
    let a = 1.0;
    let t_ret = 2.0 * std::f64::consts::PI * a * (std::f64::consts::SQRT_2 - 1.0);
    for (rho, d_out, d_in) in [
        (1.0, 0.8894808154, 1.7130997537),
        (1.9, 1.2905097948, 1.3120707743),
    ] {
        let p = Event::new(0.5, rho * 0.3f64.cos(), rho * 0.3f64.sin(), 0.0);
        let rays = shadow_rays_from_axis(a, p, 4);
        assert_eq!(rays.len(), 10);
        for r in &rays {
            let base = match r.branch {
                Branch::Outbound => d_out,
                Branch::Inbound => d_in,
            };
            let want = base + r.winding as f64 * t_ret;
            assert!(
                ((p.t - r.emission.t) - want).abs() < 1e-9,
                "{r:?}: delay vs {want}"
            );
            assert_eq!(r.tangent.z, 0.0);
        }
    }
}

#[test]
fn rays_from_a_source_anywhere_start_on_its_worldline_and_land_on_the_target() {
    let mut rng = Rng::new(402);
    let (mut worst, mut wsrc, mut total) = (0.0f64, 0.0f64, 0);
    for a in [1.0, 0.8] {
        let m = Metric::Godel(Godel::new(a));
        let (mut tries, mut count) = (0, 0);
        while count < 60 && tries < 200 {
            tries += 1;
            let s = rng.event(3.0 * a);
            let p = rng.event(3.0 * a);
            for r in shadow_rays(a, s, p, 2) {
                let (d, null) = miss(m, &r, p);
                let on = max_abs([
                    0.0,
                    r.emission.x - s.x,
                    r.emission.y - s.y,
                    r.emission.z - s.z,
                ]) / (1.0 + s.r());
                assert!(d < 1e-8, "source {s:?} target {p:?}: miss {d:e}");
                assert!(
                    on < 1e-10,
                    "emission {:?} not on the source at {s:?}",
                    r.emission
                );
                assert!(null < 1e-12 && (m.lower(r.emission, r.tangent).t + 1.0).abs() < 1e-12);
                (worst, wsrc) = (worst.max(d), wsrc.max(on));
                count += 1;
            }
        }
        assert!(count >= 60, "only {count} rays for a = {a}");
        total += count;
    }
    eprintln!("{total} general shadow rays: worst miss {worst:e}, off the source {wsrc:e}");
}
