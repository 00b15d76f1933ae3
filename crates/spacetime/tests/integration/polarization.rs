//! A light ray's polarization vector f along the ray (docs/physics.md, "Polarization"):
//! parallel transport keeps f·k = 0 and f·f = 1 along long rays, by the closed form
//! (`spacetime::transport`) and by the propagator integrated with the ray
//! (`spacetime::propagator`), and the two agree, also when loops are composed as the numeric
//! tracer composes them (P(λ) Mⁿ, M the first loop's propagator).

use crate::common::Rng;
use spacetime::propagator::{self, apply, propagators};
use spacetime::transport::transport_from_origin;
use spacetime::*;

/// A random light ray from the origin (both time orientations) and a unit polarization vector
/// f = (0, s) with s ⟂ k: f·k = 0, f·f = 1 there (the metric is Minkowski's at the origin).
fn ray(rng: &mut Rng, a: f64, past: bool) -> (OriginGeodesic, FourVector) {
    let d = rng.direction();
    let e = if past { -1.0 } else { 1.0 };
    let k = FourVector::new(e, d[0], d[1], d[2]);
    let w = rng.direction();
    let along = w[0] * d[0] + w[1] * d[1] + w[2] * d[2];
    let s = [0, 1, 2].map(|i| w[i] - along * d[i]);
    let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    let f = FourVector::new(0.0, s[0] / n, s[1] / n, s[2] / n);
    (OriginGeodesic::new(a, k).expect("null"), f)
}

/// (f·k, f·f − 1) at the event `x`.
fn invariants(m: &Godel, x: Event, k: FourVector, f: FourVector) -> (f64, f64) {
    (m.dot(x, f, k), m.dot(x, f, f) - 1.0)
}

/// The closed form over a hundred loops: f stays orthogonal to the tangent and of unit length
/// to 1e-9 (f grows along k by a multiple of the parameter where the ray lies in a plane of
/// constant z, so the inner products are sums of large terms at the end).
#[test]
fn the_closed_form_keeps_f_orthogonal_to_k_and_unit_over_a_hundred_loops() {
    let mut rng = Rng::new(25);
    let mut worst: f64 = 0.0;
    for a in [0.6, 1.0, 2.0] {
        let m = Godel::new(a);
        for i in 0..16 {
            let (geo, f) = ray(&mut rng, a, i % 2 == 0);
            let l_ret = geo.return_parameter();
            for loops in [0.3, 1.0, 7.7, 31.4, 100.0] {
                let lambda = loops * l_ret;
                let (x, w) = transport_from_origin(&geo, lambda, f);
                let (_, k) = geo.at(lambda);
                let (fk, ff) = invariants(&m, x, k, w);
                worst = worst.max(fk.abs()).max(ff.abs());
                assert!(
                    fk.abs() < 1e-9 && ff.abs() < 1e-9,
                    "a = {a}, ray {i}, {loops} loops: f·k = {fk:e}, f·f − 1 = {ff:e}"
                );
            }
        }
    }
    eprintln!("closed form, 100 loops: worst |f·k|, |f·f − 1| = {worst:e}");
}

/// What the static observer at `x` measures of the polarization vector `w` of a ray with
/// tangent `k` there: `w` modulo k, as the record's `pol` is taken.
fn modulo_k(m: &Godel, x: Event, k: FourVector, w: FourVector) -> [f64; 3] {
    let g = m.metric(x);
    let frame = m.static_frame(x);
    let kc = measure::vector_components(&g, &frame, k);
    let dir = [kc[1] / kc[0], kc[2] / kc[0], kc[3] / kc[0]];
    let wc = measure::vector_components(&g, &frame, w);
    let a = wc[1] * dir[0] + wc[2] * dir[1] + wc[3] * dir[2];
    polarization::orthogonal_unit(
        [wc[1] - a * dir[0], wc[2] - a * dir[1], wc[3] - a * dir[2]],
        dir,
    )
    .expect("a vector")
}

/// The propagator integrated with the ray (the numeric tracer's) keeps the invariants to
/// 1e-9 over a loop and agrees with the closed form; loops composed as the tracer composes
/// them, the first loop's screen turn n times and then the propagator within the loop
/// (P(λ)(cos nθ f + sin nθ g)), agree with the closed form modulo k to 1e-8 after 20 and 100
/// loops, and keep the invariants there to 1e-9.
#[test]
fn the_integrated_propagator_keeps_the_invariants_and_agrees_with_the_closed_form() {
    let mut rng = Rng::new(26);
    let (mut worst_inv, mut worst_diff): (f64, f64) = (0.0, 0.0);
    let tol = Tolerances {
        rtol: 1e-11,
        atol: 1e-11,
        ..Tolerances::default()
    };
    for a in [0.6, 1.0, 2.0] {
        let m = Godel::new(a);
        for i in 0..6 {
            let (geo, f) = ray(&mut rng, a, i % 2 == 1);
            let (x0, k0) = geo.at(0.0);
            // The other screen vector: g = (0, d × s), d the ray's spatial direction.
            let (d, s) = ([k0.x, k0.y, k0.z], [f.x, f.y, f.z]);
            let r = polarization::cross(d, s);
            let g = FourVector::new(0.0, r[0], r[1], r[2]);
            let start = GeodesicState {
                x: x0,
                p: m.lower(x0, k0),
            };
            let l_ret = geo.return_parameter();
            let p = propagators(
                Metric::Godel(m),
                &start,
                &[0.4 * l_ret, l_ret],
                tol,
                100_000,
            )
            .expect("integrates");
            let turn = propagator::screen_turn(&p[1], &m.metric(x0), f, g);
            for loops in [0, 1, 20, 100] {
                let (prop, lambda) = if loops == 1 {
                    (&p[1], l_ret)
                } else {
                    (&p[0], (loops as f64 + 0.4) * l_ret)
                };
                let n = if loops == 1 { 0.0 } else { loops as f64 };
                let (sn, cn) = (n * turn).sin_cos();
                let w = FourVector::from_array(apply(prop, (cn * f + sn * g).to_array()));
                let (x, w_exact) = transport_from_origin(&geo, lambda, f);
                let (_, k) = geo.at(lambda);
                let (fk, ff) = invariants(&m, x, k, w);
                worst_inv = worst_inv.max(fk.abs()).max(ff.abs());
                assert!(
                    fk.abs() < 1e-9 && ff.abs() < 1e-9,
                    "a = {a}, ray {i}, {loops} loops: f·k = {fk:e}, f·f − 1 = {ff:e}"
                );
                let (u, v) = (modulo_k(&m, x, k, w), modulo_k(&m, x, k, w_exact));
                let diff = (0..3).fold(0.0f64, |m, c| m.max((u[c] - v[c]).abs()));
                worst_diff = worst_diff.max(diff);
                assert!(
                    diff < 1e-8,
                    "a = {a}, ray {i}, {loops} loops: {u:?} vs {v:?}"
                );
            }
        }
    }
    eprintln!(
        "integrated: worst invariant {worst_inv:e}, worst difference from the closed form \
         modulo k {worst_diff:e} (up to 100 loops)"
    );
}

/// Without transport (the vector's components kept as they are) the invariants fail: the
/// tests above could catch a tracer that dropped it.
#[test]
fn components_left_alone_are_no_transport() {
    let mut rng = Rng::new(27);
    let m = Godel::new(1.0);
    let mut failing = 0;
    for i in 0..20 {
        let (geo, f) = ray(&mut rng, 1.0, i % 2 == 0);
        let lambda = 0.45 * geo.return_parameter();
        let (x, k) = geo.at(lambda);
        let (fk, ff) = invariants(&m, x, k, f);
        failing += usize::from(fk.abs() > 1e-3 || ff.abs() > 1e-3);
    }
    assert!(failing >= 18, "only {failing} of 20 rays fail");
}
