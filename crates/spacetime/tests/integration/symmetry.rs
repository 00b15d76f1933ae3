//! Symmetries of Gödel's universe: the five Killing fields (Killing's equation and their
//! commutators), the finite isometries (docs/physics.md, "Isometries") and the closed-form
//! geodesics built on them (docs/physics.md, "Closed forms").

use crate::common::{integrate_field, max_abs, Rng};
use spacetime::*;
use std::f64::consts::SQRT_2;

/// ∂_λ ξ^μ by the fourth-order central difference (h = 1e-3: truncation ~h⁴ ≈ 1e-12,
/// rounding ~1e-16/h ≈ 1e-13), indexed `[lambda][mu]`.
fn jacobian(f: impl Fn(Event) -> FourVector, at: Event) -> [[f64; 4]; 4] {
    let h = 1e-3;
    let mut j = [[0.0; 4]; 4];
    for (l, row) in j.iter_mut().enumerate() {
        let mut e = [0.0; 4];
        e[l] = 1.0;
        let d = FourVector::from_array(e);
        let f1 = f(at.offset(d, h)).to_array();
        let fm1 = f(at.offset(d, -h)).to_array();
        let f2 = f(at.offset(d, 2.0 * h)).to_array();
        let fm2 = f(at.offset(d, -2.0 * h)).to_array();
        for m in 0..4 {
            row[m] = (8.0 * (f1[m] - fm1[m]) - (f2[m] - fm2[m])) / (12.0 * h);
        }
    }
    j
}

#[test]
fn killing_fields_satisfy_killings_equation_inside_and_beyond_the_horizon() {
    // (L_ξ g)_μν = ξ^λ ∂_λ g_μν + g_λν ∂_μ ξ^λ + g_μλ ∂_ν ξ^λ, with the analytic ∂g and a
    // fourth-order difference of ξ; compared to the size of the largest single term.
    let mut rng = Rng::new(101);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.6, 2.5] {
        let m = Godel::new(a);
        for i in 0..120 {
            let at = if i == 0 {
                Event::default()
            } else {
                rng.event(6.0 * a)
            };
            let g = m.metric(at);
            let dg = m.metric_derivatives(at);
            for f in KillingField::ALL {
                let xi = f.at(a, at).to_array();
                let dxi = jacobian(|e| f.at(a, e), at);
                for mu in 0..4 {
                    for nu in 0..4 {
                        let mut s = 0.0;
                        let mut scale: f64 = 1.0;
                        for l in 0..4 {
                            let terms = [
                                xi[l] * dg[l][mu][nu],
                                g[l][nu] * dxi[mu][l],
                                g[mu][l] * dxi[nu][l],
                            ];
                            for t in terms {
                                s += t;
                                scale = scale.max(t.abs());
                            }
                        }
                        let err = s.abs() / scale;
                        worst = worst.max(err);
                        assert!(
                            err < 1e-9,
                            "{f:?} a={a} at {at:?}: (L g)[{mu}][{nu}] = {s:e}"
                        );
                    }
                }
            }
        }
    }
    eprintln!("Killing's equation: worst relative residual {worst:e}");
}

#[test]
fn translations_are_the_cartesian_unit_vectors_on_the_axis() {
    for a in [1.0, 0.3] {
        let kx = KillingField::Kx.at(a, Event::new(2.0, 0.0, 0.0, -1.0));
        let ky = KillingField::Ky.at(a, Event::new(-3.0, 0.0, 0.0, 4.0));
        assert_eq!(kx, FourVector::new(0.0, 1.0, 0.0, 0.0));
        assert_eq!(ky, FourVector::new(0.0, 0.0, 1.0, 0.0));
        // Continuous there: the difference from ∂x, ∂y is O(r).
        let e = 1e-7 * a;
        let near = KillingField::Kx.at(a, Event::new(0.0, e, -e, 0.0));
        assert!((near - kx).to_array().iter().all(|v| v.abs() < 1e-7));
    }
}

/// [X, Y]^μ = X^ν ∂_ν Y^μ − Y^ν ∂_ν X^μ.
fn bracket(a: f64, x: KillingField, y: KillingField, at: Event) -> FourVector {
    let (xv, yv) = (x.at(a, at).to_array(), y.at(a, at).to_array());
    let (dx, dy) = (jacobian(|e| x.at(a, e), at), jacobian(|e| y.at(a, e), at));
    let mut out = [0.0; 4];
    for (mu, o) in out.iter_mut().enumerate() {
        for nu in 0..4 {
            *o += xv[nu] * dy[nu][mu] - yv[nu] * dx[nu][mu];
        }
    }
    FourVector::from_array(out)
}

#[test]
fn killing_fields_close_under_the_bracket_as_stated() {
    use KillingField::*;
    let mut rng = Rng::new(102);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.7] {
        for _ in 0..50 {
            let at = rng.event(5.0 * a);
            let f = |k: KillingField| k.at(a, at);
            let cases = [
                (Kx, Ky, (SQRT_2 / a) * f(T) + (1.0 / (a * a)) * f(Phi)),
                (Phi, Kx, -f(Ky)),
                (Phi, Ky, f(Kx)),
                (T, Kx, FourVector::default()),
                (T, Phi, FourVector::default()),
                (Z, Ky, FourVector::default()),
                (Z, Phi, FourVector::default()),
            ];
            for (x, y, want) in cases {
                let got = bracket(a, x, y, at);
                let scale = 1.0 + at.r() * at.r() / (a * a);
                let d = (got - want)
                    .to_array()
                    .iter()
                    .fold(0.0f64, |m, v| m.max(v.abs()));
                worst = worst.max(d / scale);
                assert!(
                    d < 1e-9 * scale,
                    "[{x:?},{y:?}] at {at:?}: {got:?} vs {want:?}"
                );
            }
        }
    }
    eprintln!("commutators: worst deviation {worst:e}");
}

fn random_vector(rng: &mut Rng) -> FourVector {
    FourVector::new(
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
    )
}

/// Random isometries: maps to the origin from events inside and beyond the horizon,
/// some followed by a rotation, and inverses of such maps.
fn random_isometries(rng: &mut Rng, a: f64, n: usize) -> Vec<Isometry> {
    (0..n)
        .map(|i| {
            let p0 = rng.event(6.0 * a);
            let t = Isometry::to_origin(a, p0);
            match i % 3 {
                0 => t,
                1 => t.then_rotate(rng.uniform(-4.0, 4.0)),
                _ => t.then_rotate(rng.uniform(-4.0, 4.0)).inverse(),
            }
        })
        .collect()
}

#[test]
fn the_map_to_the_origin_sends_its_event_to_the_origin_and_the_inverse_undoes_it() {
    let mut rng = Rng::new(201);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.5, 2.0] {
        for _ in 0..100 {
            let p0 = rng.event(6.0 * a);
            let alpha = rng.uniform(-4.0, 4.0);
            let t = Isometry::to_origin(a, p0).then_rotate(alpha);
            let o = t.apply(p0);
            assert!(max_abs(o.to_array()) <= 1e-15 * a, "T(P0) = {o:?}");
            let back = t.inverse().apply(Event::default());
            let d0 = max_abs((back - p0).to_array()) / (1.0 + max_abs(p0.to_array()));
            assert!(d0 < 1e-12, "T⁻¹(origin) = {back:?} vs {p0:?}");
            for _ in 0..5 {
                let x = rng.event(6.0 * a);
                let y = t.inverse().apply(t.apply(x));
                let z = t.apply(t.inverse().apply(x));
                let d = max_abs((y - x).to_array()).max(max_abs((z - x).to_array()))
                    / (1.0 + max_abs(x.to_array()));
                worst = worst.max(d).max(d0);
                assert!(d < 1e-12, "T⁻¹∘T({x:?}) = {y:?}, T∘T⁻¹ = {z:?}");
            }
        }
    }
    eprintln!("isometry round trips: worst relative error {worst:e}");
}

/// `apply_push` (the exact tracer's combined map, with a shortcut for pure t/z shifts) is
/// `apply` and `push` together, for general isometries and for translations.
#[test]
fn apply_push_is_apply_and_push() {
    let mut rng = Rng::new(207);
    for a in [1.0, 0.7] {
        let mut maps = random_isometries(&mut rng, a, 40);
        maps.push(Isometry::to_origin(a, Event::new(1.5, 0.0, 0.0, -0.4)));
        maps.push(Isometry::to_origin(a, Event::new(1.5, 0.0, 0.0, -0.4)).inverse());
        maps.push(Isometry::identity(a));
        for t in maps {
            let x = rng.event(6.0 * a);
            let v = random_vector(&mut rng);
            let (e, k) = t.apply_push(x, v);
            let (e1, k1) = (t.apply(x), t.push(x, v));
            let de = max_abs((e - e1).to_array()) / (1.0 + max_abs(e1.to_array()));
            let dk = max_abs((k - k1).to_array()) / (1.0 + max_abs(k1.to_array()));
            assert!(
                de < 1e-13 && dk < 1e-13,
                "{t:?}: {e:?} vs {e1:?}, {k:?} vs {k1:?}"
            );
        }
    }
}

/// `origin_axes` (the closed form of the map to the origin's differential at its own event)
/// is `push` of ∂x and ∂y there, for events inside and far beyond the horizon and several a;
/// on the axis it is the identity.
#[test]
fn the_axes_at_the_mapped_event_are_the_pushed_coordinate_vectors() {
    let mut rng = Rng::new(208);
    let (ex, ey) = (
        FourVector::new(0.0, 1.0, 0.0, 0.0),
        FourVector::new(0.0, 0.0, 1.0, 0.0),
    );
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.7, 3.0] {
        for i in 0..300 {
            let at = rng.event(if i % 2 == 0 { 2.0 * a } else { 12.0 * a });
            let pushed = Isometry::to_origin(a, at).push_all(at, [ex, ey]);
            for (got, want) in origin_axes(&Godel::new(a), at).into_iter().zip(pushed) {
                let d = max_abs((got - want).to_array()) / max_abs(want.to_array());
                worst = worst.max(d);
                // (The general push rounds 1 − |w0|², which cancels far out: ~1e-14 at 12a.)
                assert!(d < 1e-13, "a = {a}, at {at:?}: {got:?} vs {want:?}");
            }
        }
        assert_eq!(
            origin_axes(&Godel::new(a), Event::new(0.4, 0.0, 0.0, -1.0)),
            [ex, ey]
        );
    }
    eprintln!("axes at the mapped event: worst relative deviation {worst:e}");
}

#[test]
fn the_differential_matches_finite_differences_and_keeps_static_observers_static() {
    let mut rng = Rng::new(202);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.7] {
        // Pure shifts of t and z too, whose differential is taken for the identity.
        let mut maps = random_isometries(&mut rng, a, 60);
        maps.push(Isometry::to_origin(a, Event::new(1.5, 0.0, 0.0, -0.4)));
        maps.push(Isometry::identity(a));
        for t in maps {
            let x = rng.event(6.0 * a);
            let v = random_vector(&mut rng);
            let h = 1e-5;
            let fd = (1.0 / (2.0 * h)) * (t.apply(x.offset(v, h)) - t.apply(x.offset(v, -h)));
            let fd = FourVector::from_array(fd.to_array());
            let pushed = t.push(x, v);
            let d = max_abs((pushed - fd).to_array()) / (1.0 + max_abs(pushed.to_array()));
            worst = worst.max(d);
            assert!(d < 1e-6, "T_* v = {pushed:?}, FD {fd:?}");
            let dt = t.push(x, FourVector::new(1.0, 0.0, 0.0, 0.0));
            assert_eq!(dt, FourVector::new(1.0, 0.0, 0.0, 0.0), "∂t ↦ {dt:?}");
        }
    }
    eprintln!("differential vs finite differences: worst {worst:e}");
}

#[test]
fn isometries_preserve_the_metric() {
    let mut rng = Rng::new(203);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.5, 3.0] {
        let m = Godel::new(a);
        for t in random_isometries(&mut rng, a, 100) {
            let x = rng.event(6.0 * a);
            let (u, v) = (random_vector(&mut rng), random_vector(&mut rng));
            let before = m.dot(x, u, v);
            let after = m.dot(t.apply(x), t.push(x, u), t.push(x, v));
            // Scale: the largest term of the contraction (cancellations beyond the horizon).
            let g = m.metric(x);
            let (ua, va) = (u.to_array(), v.to_array());
            let scale = (0..16)
                .map(|i| (g[i / 4][i % 4] * ua[i / 4] * va[i % 4]).abs())
                .fold(0.0, f64::max);
            let d = (after - before).abs() / scale;
            worst = worst.max(d);
            assert!(d < 1e-12, "g(T_*u, T_*v) = {after} vs g(u, v) = {before}");
        }
    }
    eprintln!("metric preserved: worst relative error {worst:e}");
}

#[test]
fn isometries_map_integrated_geodesics_onto_integrated_geodesics() {
    let mut rng = Rng::new(204);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.8] {
        let m = Metric::Godel(Godel::new(a));
        for (i, t) in random_isometries(&mut rng, a, 12).into_iter().enumerate() {
            let x = rng.event(3.0 * a);
            let speed = if i % 2 == 0 { 1.0 } else { 0.5 };
            let time = if i % 4 < 2 {
                TimeDirection::Future
            } else {
                TimeDirection::Past
            };
            let g1 =
                Geodesic::launch(&m, x, &m.static_frame(x), rng.direction(), speed, time).unwrap();
            let k = g1.start.tangent(&m);
            let g2 = Geodesic::from_tangent(&m, g1.kind, t.apply(x), t.push(x, k));
            // A full loop of the image: λ ≤ 2πa covers the return for E = 1 light and for
            // particles (τ_ret < 2πa/√2).
            let limits = TraceLimits {
                max_affine: 2.0 * std::f64::consts::PI * a,
                ..Default::default()
            };
            let (tr1, tr2) = (trace(m, &g1, &limits), trace(m, &g2, &limits));
            assert_eq!(tr1.stop, StopReason::AffineLimit);
            assert_eq!(tr2.stop, StopReason::AffineLimit);
            for (l, s1) in tr1.samples(200) {
                let mapped = t.apply(s1.x);
                let s2 = tr2.state_at(l);
                // Relative to the coordinates' size: images of far events have large t.
                let d = max_abs((mapped - s2.x).to_array()) / (1.0 + max_abs(s2.x.to_array()));
                worst = worst.max(d);
                assert!(d < 1e-8, "λ={l}: T(γ1) = {mapped:?}, γ2 = {:?}", s2.x);
            }
        }
    }
    eprintln!("mapped geodesics: worst deviation {worst:e}");
}

/// Integrates the flow of `field` from `x` over `s` (RK4, independent of the closed form).
fn integrate_flow(a: f64, field: KillingField, x: Event, s: f64, steps: usize) -> Event {
    integrate_field(|e| field.at(a, e), x, s, steps)
}

#[test]
fn finite_isometries_are_the_flows_of_the_killing_fields() {
    let mut rng = Rng::new(207);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.6] {
        for field in KillingField::ALL {
            for _ in 0..12 {
                let x = rng.event(5.0 * a);
                let s = rng.uniform(-1.5, 1.5) * a;
                let exact = Isometry::flow(a, field, s).apply(x);
                let numeric = integrate_flow(a, field, x, s, 2000);
                let d = max_abs((exact - numeric).to_array()) / (1.0 + max_abs(x.to_array()));
                worst = worst.max(d);
                assert!(
                    d < 1e-9,
                    "{field:?} flow {s} from {x:?}: {exact:?} vs {numeric:?}"
                );
            }
        }
    }
    // The K_x flow moves the origin along the x axis to 2a sinh(s/2a), without a time shift.
    let a = 1.3;
    let p = Isometry::flow(a, KillingField::Kx, 0.9).apply(Event::default());
    assert!((p.x - 2.0 * a * (0.9 / (2.0 * a)).sinh()).abs() < 1e-14 && p.t.abs() < 1e-15);
    eprintln!("Killing flows: closed form vs RK4, worst relative difference {worst:e}");
}
