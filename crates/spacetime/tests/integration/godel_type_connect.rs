//! Shadow rays in the Gödel-type family (`spacetime::godel_type_connect`, docs/physics.md
//! "Shadow rays in the family"): for m²/Ω² = −1, 0, 1, 2, 3.5, 4, 6 each ray is null, starts
//! on the source's worldline and lands on the target when integrated with DOP853; the set is
//! complete against a scan of emission directions; the Gödel member's rays are Gödel's
//! `shadow_rays`; the area distance against a numerically integrated bundle; and targets
//! that no ray reaches give none.

// `!(a > b)` is "not a > b, NaN included": a NaN must be skipped too.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::common::{max_abs, numeric_area_distance_sq, Rng};
use crate::godel_type_symmetry::{to_godel, to_godel_vector};
use spacetime::*;
use std::f64::consts::{PI, SQRT_2};

const OMEGA: f64 = 0.7;
const RATIOS: [f64; 7] = [-1.0, 0.0, 1.0, 2.0, 3.5, 4.0, 6.0];

fn member(ratio: f64) -> GodelType {
    GodelType::new(ratio * OMEGA * OMEGA, OMEGA)
}

/// Integrates `r` from its emission event for its affine length in `member`; returns the
/// relative miss distance from `target` and the null-condition residual at emission.
fn miss(member: GodelType, r: &ShadowRay, target: Event) -> (f64, f64) {
    let m = Metric::GodelType(member);
    let g = Geodesic::from_tangent(&m, GeodesicKind::Null, r.emission, r.tangent);
    let limits = TraceLimits {
        max_affine: r.lambda,
        ..Default::default()
    };
    let tr = trace(m, &g, &limits);
    assert_eq!(tr.stop, StopReason::AffineLimit, "{member:?} {r:?}");
    let d = max_abs((tr.end.x - target).to_array()) / (1.0 + max_abs(target.to_array()));
    (d, m.dot(r.emission, r.tangent, r.tangent).abs())
}

/// A target within `reach` (in each coordinate) of `source`, in the chart.
fn near(rng: &mut Rng, member: GodelType, source: Event, reach: f64) -> Event {
    loop {
        let p = Event::new(
            rng.uniform(-5.0, 5.0),
            source.x + rng.uniform(-reach, reach),
            source.y + rng.uniform(-reach, reach),
            source.z + rng.uniform(-2.0, 2.0),
        );
        if member
            .coordinate_radius()
            .is_none_or(|edge| p.r() < 0.9 * edge)
        {
            return p;
        }
    }
}

#[test]
fn every_ray_is_null_starts_on_the_source_and_lands_on_the_target() {
    let mut rng = Rng::new(3401);
    let mut total = 0;
    for ratio in RATIOS {
        let m = member(ratio);
        // Sources on the axis, then anywhere (on the sphere up to 0.7 of the way to the pole).
        let far = m.coordinate_radius().map_or(3.0, |edge| 0.7 * edge);
        let reach = m.critical_radius().map_or(3.0, |rc| 0.9 * rc);
        let (mut worst, mut wsrc, mut wnull, mut count) = (0.0f64, 0.0f64, 0.0f64, 0);
        for i in 0..24 {
            let s = if i < 8 {
                Event::default()
            } else {
                let mut s = rng.event(far);
                s.t = 0.0;
                s
            };
            let mut p = near(&mut rng, m, s, reach);
            if i % 6 == 0 {
                p.z = s.z; // in the source's plane
            }
            for r in type_shadow_rays(m, s, p, 2) {
                let (d, null) = miss(m, &r, p);
                let on = max_abs([
                    0.0,
                    r.emission.x - s.x,
                    r.emission.y - s.y,
                    r.emission.z - s.z,
                ]) / (1.0 + s.r());
                let energy = (m.lower(r.emission, r.tangent).t + 1.0).abs();
                assert!(
                    d < 1e-8,
                    "m²/Ω² = {ratio}, source {s:?}, target {p:?}, {r:?}: miss {d:e}"
                );
                assert!(null < 1e-10, "m²/Ω² = {ratio}: not null {null:e}");
                assert!(
                    on < 1e-10 && energy < 1e-10,
                    "m²/Ω² = {ratio}: {r:?} off {s:?}"
                );
                // Future-directed: E = −g(∂t, k) = 1 for the static source (above); from
                // the axis t grows along the ray where the source sees it leave.
                assert!(r.tangent.t > 0.0 || i >= 8, "m²/Ω² = {ratio}: {r:?}");
                (worst, wsrc, wnull) = (worst.max(d), wsrc.max(on), wnull.max(null));
                count += 1;
            }
        }
        assert!(count >= 24, "m²/Ω² = {ratio}: only {count} rays");
        eprintln!(
            "m²/Ω² = {ratio}: {count} rays, worst miss {worst:e}, off the source {wsrc:e}, \
             g(k,k) {wnull:e}"
        );
        total += count;
    }
    eprintln!("{total} shadow rays in the family");
}

/// The crossings of the cylinder ρ = ρ_P by the closed form from the axis leaving at angle ψ
/// to the z axis, sampled in λ up to `l_max` (independent of the solver's inversion of ρ(λ)):
/// z − z_P at each crossing, in order, at most `n`.
fn crossings(m: GodelType, psi: f64, rho: f64, zp: f64, l_max: f64, n: usize) -> Vec<f64> {
    let g = TypeOriginGeodesic::new(m, FourVector::new(1.0, psi.sin(), 0.0, psi.cos())).unwrap();
    let steps = (l_max / 0.02) as usize;
    let mut out = Vec::new();
    let mut prev = (0.0, -rho, 0.0);
    for i in 1..=steps {
        let l = l_max * i as f64 / steps as f64;
        let (e, _) = g.at(l);
        let now = (l, e.r() - rho, e.z);
        if (prev.1 < 0.0) != (now.1 < 0.0) {
            let f = prev.1 / (prev.1 - now.1);
            out.push(prev.2 + f * (now.2 - prev.2) - zp);
            if out.len() == n {
                break;
            }
        }
        prev = now;
    }
    out
}

#[test]
fn the_rays_found_are_all_a_scan_of_emission_directions_finds() {
    // Rays from the axis over a fine grid of ψ ∈ (0, π) (the azimuth only rotates the
    // picture); crossing j of the target's cylinder is winding j/2 (escaping rays cross once),
    // and each sign change of z_j(ψ) − z_P between neighbouring ψ is one ray. Rays are
    // compared up to λ = L (near Λ = 0 returning rays take arbitrarily long to come back),
    // so that the scan sees escaping rays and the windings of the returning ones.
    let windings = 2u32;
    let mut checked = 0;
    for ratio in RATIOS {
        let m = member(ratio);
        let rc = m.critical_radius().unwrap_or(3.0);
        for (rho, zp) in [
            (0.5 * rc, 1.3),
            (0.9 * rc, -0.6),
            (0.2 * rc, 4.0),
            (0.4 * rc, 9.0),
        ] {
            let target = Event::new(0.0, rho * 0.6, rho * 0.8, zp);
            let rays = type_shadow_rays_from_axis(m, target, windings);
            // The scan's end L, away from every ray's λ (a crossing there may come and go).
            let l = [40.0, 47.0, 55.0, 64.0]
                .into_iter()
                .find(|l| rays.iter().all(|r| (r.lambda - l).abs() > 0.05 * l))
                .unwrap();
            let want = rays.iter().filter(|r| r.lambda < l).count();
            let n = 2 * (windings as usize + 1);
            let n_psi = 2000;
            let mut prev: Option<Vec<f64>> = None;
            let mut found = 0;
            for i in 1..n_psi {
                let psi = PI * i as f64 / n_psi as f64;
                let z = crossings(m, psi, rho, zp, l, n);
                if let Some(p) = &prev {
                    found += p
                        .iter()
                        .zip(&z)
                        .filter(|(u, v)| (**u < 0.0) != (**v < 0.0))
                        .count();
                }
                prev = Some(z);
            }
            assert_eq!(
                found, want,
                "m²/Ω² = {ratio} ρ = {rho} z = {zp}: scan {found}, solver {want}"
            );
            eprintln!("m²/Ω² = {ratio} ρ = {rho:.3} z = {zp}: {want} rays, as the scan");
            checked += want;
        }
    }
    assert!(checked > 60, "only {checked} rays compared");
}

#[test]
fn in_plane_targets_get_two_rays_per_winding_or_one_escaping_ray() {
    for ratio in RATIOS {
        let m = member(ratio);
        let rho = m.critical_radius().map_or(2.0, |rc| 0.7 * rc);
        let p = Event::new(1.0, rho * 0.8, -rho * 0.6, 0.0);
        let rays = type_shadow_rays_from_axis(m, p, 3);
        let want = if ratio < 4.0 { 8 } else { 1 };
        assert_eq!(rays.len(), want, "m²/Ω² = {ratio}");
        for r in &rays {
            assert_eq!(r.tangent.z, 0.0);
            assert!(miss(m, r, p).0 < 1e-8);
        }
    }
}

#[test]
fn targets_on_the_source_axis_get_the_straight_ray_and_the_returning_cones() {
    for ratio in RATIOS {
        let m = member(ratio);
        for s in [Event::default(), Event::new(0.0, 0.5, -0.3, 0.2)] {
            let p = Event::new(3.0, s.x, s.y, s.z + 2.5);
            let rays = type_shadow_rays(m, s, p, 2);
            assert!(
                rays.iter()
                    .any(|r| r.winding == 0 && (p.t - r.emission.t - 2.5).abs() < 1e-9),
                "m²/Ω² = {ratio}: no straight ray"
            );
            for r in &rays {
                assert!(miss(m, r, p).0 < 1e-8, "m²/Ω² = {ratio} {r:?}");
            }
        }
    }
}

#[test]
fn targets_no_ray_reaches_give_none() {
    for ratio in RATIOS {
        let m = member(ratio);
        let s = Event::new(0.0, 0.4, 0.1, 0.0);
        let to = TypeIsometry::to_origin(m, s).unwrap();
        let back = to.inverse();
        let mut bad = vec![
            Event::new(f64::NAN, 0.1, 0.0, 0.0),
            Event::new(0.0, f64::INFINITY, 0.0, 0.0),
        ];
        // On the source's worldline (on the axis: after the map back and forth a target on
        // it lies 1e-17 away, where the loops returning to the source are rays).
        assert!(type_shadow_rays_from_axis(m, Event::new(7.0, 0.0, 0.0, 0.0), 3).is_empty());
        if let Some(rc) = m.critical_radius() {
            // At and beyond ρ_c from the source (only causal members reach everything).
            for f in [1.0, 1.001, 1.5] {
                let rho = f * rc;
                if m.coordinate_radius().is_none_or(|edge| rho < edge) {
                    bad.push(back.apply(Event::new(1.0, rho * 0.6, rho * 0.8, 0.3)));
                    bad.push(back.apply(Event::new(1.0, rho, 0.0, -2.0)));
                }
            }
            // Just inside ρ_c there are rays.
            let inside = Event::new(1.0, 0.999 * rc, 0.0, 0.0);
            assert!(!type_shadow_rays_from_axis(m, inside, 0).is_empty());
        }
        if let Some(edge) = m.coordinate_radius() {
            // The pole, beyond the chart, and a source beyond the chart.
            bad.push(Event::new(0.0, edge, 0.0, 0.0));
            bad.push(Event::new(0.0, 0.0, 1.2 * edge, 0.0));
            let outside = Event::new(0.0, 1.1 * edge, 0.0, 0.0);
            assert!(type_shadow_rays(m, outside, Event::new(1.0, 0.0, 0.0, 1.0), 2).is_empty());
        }
        for p in bad {
            let rays = type_shadow_rays(m, s, p, 3);
            assert!(rays.is_empty(), "m²/Ω² = {ratio} target {p:?}: {rays:?}");
        }
    }
}

/// Gödel's a and the Gödel member of vorticity 1/(√2 a).
fn godel_member(a: f64) -> GodelType {
    GodelType::new(1.0 / (a * a), 1.0 / (SQRT_2 * a))
}

#[test]
fn the_godel_member_has_godels_shadow_rays() {
    let mut rng = Rng::new(3402);
    let (mut worst_t, mut worst_k, mut worst_area, mut count) = (0.0f64, 0.0f64, 0.0f64, 0);
    for a in [1.0, 0.7] {
        let m = godel_member(a);
        for i in 0..30 {
            let s = if i < 5 {
                Event::default()
            } else {
                rng.event(2.0 * a)
            };
            let p = near(&mut rng, m, s, 1.5 * a);
            let mine = type_shadow_rays(m, s, p, 2);
            let gs = to_godel(a, Event::new(0.0, s.x, s.y, s.z));
            let theirs = shadow_rays(a, gs, to_godel(a, p), 2);
            assert_eq!(
                mine.len(),
                theirs.len(),
                "a = {a} source {s:?} target {p:?}"
            );
            for (r, q) in mine.iter().zip(&theirs) {
                assert_eq!((r.winding, r.branch), (q.winding, q.branch));
                let dt = (r.emission.t - q.emission.t).abs();
                let e = to_godel(a, r.emission);
                let dx = max_abs((e - q.emission).to_array());
                let k = to_godel_vector(a, r.emission, r.tangent);
                let dk = max_abs((k - q.tangent).to_array());
                assert!(dt < 1e-9 && dx < 1e-9, "a = {a}: {r:?} vs {q:?}");
                assert!(dk < 1e-9 && (r.lambda - q.lambda).abs() < 1e-9 * q.lambda);
                let mine_area = type_source_area_distance_sq(m, s, r);
                let their_area = source_area_distance_sq(a, gs, q);
                let da = (mine_area - their_area).abs() / their_area.max(1e-3);
                assert!(da < 1e-6, "a = {a}: D² {mine_area} vs Gödel's {their_area}");
                (worst_t, worst_k, worst_area) =
                    (worst_t.max(dt.max(dx)), worst_k.max(dk), worst_area.max(da));
                count += 1;
            }
        }
    }
    assert!(count > 50, "only {count} rays");
    eprintln!(
        "Gödel member vs shadow_rays: {count} rays, emission {worst_t:e}, tangent {worst_k:e}, \
         D² {worst_area:e}"
    );
}

#[test]
fn area_distance_matches_a_numeric_bundle_in_every_member() {
    let mut rng = Rng::new(3403);
    let mut worst = 0.0f64;
    for ratio in RATIOS {
        let m = member(ratio);
        let reach = m.critical_radius().map_or(2.0, |rc| 0.8 * rc);
        let (mut checked, mut tries) = (0, 0);
        while checked < 4 && tries < 100 {
            tries += 1;
            let mut s = rng.event(m.coordinate_radius().map_or(2.0, |e| 0.5 * e));
            s.t = 0.0;
            let p = near(&mut rng, m, s, reach);
            for r in type_shadow_rays(m, s, p, 1) {
                let exact = type_source_area_distance_sq(m, s, &r);
                let numeric = numeric_area_distance_sq(Metric::GodelType(m), &r);
                if !(numeric > 1e-3) {
                    continue; // too near a caustic for finite differences
                }
                let d = (exact - numeric).abs() / numeric.max(1.0);
                assert!(
                    d < 1e-5,
                    "m²/Ω² = {ratio} source {s:?} target {p:?}: D² {exact} vs numeric {numeric}"
                );
                worst = worst.max(d);
                checked += 1;
            }
        }
        assert!(
            checked >= 4,
            "m²/Ω² = {ratio}: only {checked} area distances"
        );
        // Near the source spacetime is flat to first order: D → λ.
        let s = Event::new(0.0, 0.7, -0.4, 0.2);
        for d in [1e-3, 1e-2] {
            let p = Event::new(5.0, 0.7 + 0.6 * d, -0.4 + 0.8 * d, 0.2);
            let r = type_shadow_rays(m, s, p, 0)[0];
            let d2 = type_source_area_distance_sq(m, s, &r);
            assert!(
                (d2 / (r.lambda * r.lambda) - 1.0).abs() < 5.0 * d,
                "m²/Ω² = {ratio}, {d}: {d2} vs λ² {}",
                r.lambda.powi(2)
            );
        }
    }
    eprintln!("area distance vs numeric bundle: worst {worst:e}");
}

/// On the sphere (m² < 0) a source beyond |ζ_S| = 4Ω/μ² sees its rays cross the cut of the
/// map back, where the principal time shift jumps by 8πΩ/μ²: the rays must still land.
#[test]
fn rays_across_the_cut_of_the_sphere_land_on_the_target() {
    let mut rng = Rng::new(3404);
    let m = member(-1.0);
    let (edge, rc) = (m.coordinate_radius().unwrap(), m.critical_radius().unwrap());
    let (mut worst, mut count) = (0.0f64, 0);
    for _ in 0..40 {
        let rho_s = rng.uniform(0.75, 0.8) * edge;
        let phi = rng.uniform(-PI, PI);
        let s = Event::new(0.0, rho_s * phi.cos(), rho_s * phi.sin(), 0.3);
        let back = TypeIsometry::to_origin(m, s).unwrap().inverse();
        // A target within reach of the source, placed from the source's axis frame.
        let mut q = rng.event(0.95 * rc);
        q.t = rng.uniform(-3.0, 3.0);
        let p = back.apply(q);
        for r in type_shadow_rays(m, s, p, 1) {
            let (d, null) = miss(m, &r, p);
            assert!(
                d < 1e-8 && null < 1e-10,
                "source {s:?} target {p:?}: miss {d:e}"
            );
            worst = worst.max(d);
            count += 1;
        }
    }
    assert!(count >= 40, "only {count} rays");
    eprintln!("{count} rays from sources beyond the cut: worst miss {worst:e}");
}

/// Near the source's axis the ray that climbs almost along z has 1 − cos ψ ~ ρ², below what
/// f64 resolves of c near 1: found in ψ (as for Gödel), every ray lands down to ρ = 10⁻¹².
#[test]
fn rays_to_targets_near_the_source_axis_land_too() {
    for ratio in RATIOS {
        let m = member(ratio);
        for rho in [1e-12, 1e-9, 1e-6, 1e-3] {
            for z in [1.0, -0.3, 2.5] {
                let p = Event::new(0.5, rho * 0.6, -rho * 0.8, z);
                let rays = type_shadow_rays_from_axis(m, p, 2);
                assert!(
                    rays.iter().any(
                        |r| r.winding == 0 && (p.t - r.emission.t - z.abs()).abs() < 1e-9 + rho
                    ),
                    "m²/Ω² = {ratio} ρ = {rho} z = {z}: no direct ray"
                );
                for r in &rays {
                    let (d, null) = miss(m, r, p);
                    assert!(
                        d < 1e-8 && null < 1e-12,
                        "m²/Ω² = {ratio} ρ = {rho} z = {z}: {d:e}"
                    );
                    let area = type_source_area_distance_sq(m, Event::default(), r);
                    assert!(
                        area.is_finite() && area > 0.0,
                        "ρ = {rho} z = {z}: D² = {area}"
                    );
                }
            }
        }
    }
}
