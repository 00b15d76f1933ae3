//! Symmetries of Gödel's universe: the five Killing fields (Killing's equation and their
//! commutators), the finite isometries (formulary §3) and the closed-form geodesics built
//! on them (formulary §2).

mod common;
use common::Rng;
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
