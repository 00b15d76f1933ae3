//! Metric, inverse, Christoffel symbols, Hamilton's equations and local frames, checked
//! against finite differences, the cylindrical closed forms (docs/physics.md, "The Gödel
//! metric" and "Frames"), and orthonormality.

// Tensor components are indexed as written in the formulas (g[a][c] g⁻¹[c][b], Γ^μ_ab).
#![allow(clippy::needless_range_loop)]

use crate::common::Rng;
use spacetime::*;
use std::f64::consts::SQRT_2;

fn godels() -> Vec<Godel> {
    vec![Godel::new(1.0), Godel::new(0.7), Godel::new(2.3)]
}

#[test]
fn inverse_metric_is_the_inverse() {
    let mut rng = Rng::new(1);
    for g in godels() {
        for _ in 0..200 {
            let x = rng.event(4.0 * g.a);
            let (m, mi) = (g.metric(x), g.inverse_metric(x));
            for a in 0..4 {
                for b in 0..4 {
                    let s: f64 = (0..4).map(|c| m[a][c] * mi[c][b]).sum();
                    let want = if a == b { 1.0 } else { 0.0 };
                    assert!((s - want).abs() < 1e-12, "g·g⁻¹ at {x:?}: [{a}][{b}] = {s}");
                }
            }
        }
    }
}

#[test]
fn metric_matches_the_cylindrical_line_element() {
    // The cylindrical ds² (docs/physics.md, "The Gödel metric") evaluated on a coordinate
    // displacement, vs g_μν in pseudo-Cartesian.
    let mut rng = Rng::new(2);
    for g in godels() {
        let a = g.a;
        for _ in 0..100 {
            let x = rng.event(4.0 * a);
            let v = FourVector::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            );
            let [dt, dr, dphi, dz] = v.to_cylindrical(x);
            let r = x.r();
            let s2 = (r / (2.0 * a)).powi(2);
            let ds2 = -dt * dt - SQRT_2 * r * r / a * dt * dphi
                + dr * dr / (1.0 + s2)
                + r * r * (1.0 - s2) * dphi * dphi
                + dz * dz;
            let got = g.dot(x, v, v);
            assert!(
                (got - ds2).abs() < 1e-11 * (1.0 + ds2.abs()),
                "{got} vs {ds2}"
            );
        }
    }
}

/// Γ^μ_αβ from central finite differences of the metric (h = 1e-5), with the analytic inverse.
fn christoffel_fd(g: &Godel, x: Event) -> Christoffel {
    let h = 1e-5;
    let mut dg = [[[0.0; 4]; 4]; 4];
    for (l, dgl) in dg.iter_mut().enumerate() {
        let mut e = [0.0; 4];
        e[l] = 1.0;
        let v = FourVector::from_array(e);
        let (p, m) = (g.metric(x.offset(v, h)), g.metric(x.offset(v, -h)));
        for a in 0..4 {
            for b in 0..4 {
                dgl[a][b] = (p[a][b] - m[a][b]) / (2.0 * h);
            }
        }
    }
    let gi = g.inverse_metric(x);
    let mut out = [[[0.0; 4]; 4]; 4];
    for mu in 0..4 {
        for a in 0..4 {
            for b in 0..4 {
                out[mu][a][b] = 0.5
                    * (0..4)
                        .map(|n| gi[mu][n] * (dg[a][n][b] + dg[b][n][a] - dg[n][a][b]))
                        .sum::<f64>();
            }
        }
    }
    out
}

#[test]
fn christoffel_symbols_match_finite_differences_inside_and_outside_the_horizon() {
    let mut rng = Rng::new(3);
    let mut outside = 0;
    for g in godels() {
        for i in 0..120 {
            // Half the events beyond the horizon r = 2a.
            let x = if i % 2 == 0 {
                rng.event(2.0 * g.a)
            } else {
                rng.event(6.0 * g.a)
            };
            outside += (x.r() > 2.0 * g.a) as usize;
            let (an, fd) = (g.christoffel(x), christoffel_fd(&g, x));
            let scale = an
                .iter()
                .flatten()
                .flatten()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            for mu in 0..4 {
                for a in 0..4 {
                    for b in 0..4 {
                        let err = (an[mu][a][b] - fd[mu][a][b]).abs() / scale;
                        assert!(
                            err < 1e-6,
                            "Γ^{mu}_{a}{b} at {x:?}: {} vs {} (rel {err:e})",
                            an[mu][a][b],
                            fd[mu][a][b]
                        );
                    }
                }
            }
        }
    }
    assert!(
        outside > 100,
        "too few events beyond the horizon: {outside}"
    );
}

#[test]
fn christoffel_symbols_match_the_closed_forms_in_cylindrical_coordinates() {
    // Transform the pseudo-Cartesian Γ to (t, r, φ, z) and compare with the closed forms
    // (docs/physics.md, "The Gödel metric").
    // Γ'^μ_αβ = ∂x'^μ/∂x^ν (Γ^ν_ρσ J^ρ_α J^σ_β + ∂²x^ν/∂x'^α∂x'^β).
    let mut rng = Rng::new(4);
    for g in godels() {
        let a = g.a;
        for _ in 0..50 {
            let x = rng.event(5.0 * a);
            let (r, phi) = (x.r(), x.phi());
            if r < 0.05 {
                continue;
            }
            let (s, c) = phi.sin_cos();
            // J^ν_α = ∂x^ν/∂x'^α (x' = t, r, φ, z).
            let j = [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, c, -r * s, 0.0],
                [0.0, s, r * c, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ];
            // Inverse Jacobian ∂x'^μ/∂x^ν.
            let ji = [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, c, s, 0.0],
                [0.0, -s / r, c / r, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ];
            // Second derivatives ∂²x^ν/∂x'^α∂x'^β (only x, y depend on r, φ).
            let mut h = [[[0.0; 4]; 4]; 4];
            h[1][1][2] = -s;
            h[1][2][1] = -s;
            h[1][2][2] = -r * c;
            h[2][1][2] = c;
            h[2][2][1] = c;
            h[2][2][2] = -r * s;
            let gc = g.christoffel(x);
            let mut cyl = [[[0.0; 4]; 4]; 4];
            for mu in 0..4 {
                for al in 0..4 {
                    for be in 0..4 {
                        let mut sum = 0.0;
                        for nu in 0..4 {
                            let mut inner = h[nu][al][be];
                            for rho in 0..4 {
                                for sg in 0..4 {
                                    inner += gc[nu][rho][sg] * j[rho][al] * j[sg][be];
                                }
                            }
                            sum += ji[mu][nu] * inner;
                        }
                        cyl[mu][al][be] = sum;
                    }
                }
            }
            let s2 = (r / (2.0 * a)).powi(2);
            let want = [
                ((0, 0, 1), r / (2.0 * a * a * (1.0 + s2))),
                (
                    (0, 1, 2),
                    r.powi(3) / (4.0 * SQRT_2 * a.powi(3) * (1.0 + s2)),
                ),
                ((1, 0, 2), r * (1.0 + s2) / (SQRT_2 * a)),
                ((1, 1, 1), -r / (4.0 * a * a * (1.0 + s2))),
                ((1, 2, 2), -r * (1.0 + s2) * (1.0 - 2.0 * s2)),
                ((2, 0, 1), -1.0 / (SQRT_2 * a * r * (1.0 + s2))),
                ((2, 1, 2), 1.0 / (r * (1.0 + s2))),
            ];
            let mut expected = [[[0.0; 4]; 4]; 4];
            for ((m, p, q), v) in want {
                expected[m][p][q] = v;
                expected[m][q][p] = v;
            }
            for mu in 0..4 {
                for al in 0..4 {
                    for be in 0..4 {
                        let (got, exp) = (cyl[mu][al][be], expected[mu][al][be]);
                        assert!(
                            (got - exp).abs() < 1e-9 * (1.0 + exp.abs()),
                            "Γ^{mu}_{al}{be} at r={r}: {got} vs {exp}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn hamilton_equations_agree_with_the_geodesic_equation() {
    // ẋ = g⁻¹p, and the flow's acceleration d²x/dλ² (central difference along the flow)
    // equals −Γ^μ_αβ ẋ^α ẋ^β.
    let mut rng = Rng::new(5);
    for g in godels() {
        for _ in 0..100 {
            let x = rng.event(5.0 * g.a);
            let p = Covector::new(
                rng.uniform(-2.0, 2.0),
                rng.uniform(-2.0, 2.0),
                rng.uniform(-2.0, 2.0),
                rng.uniform(-2.0, 2.0),
            );
            let (v, f) = g.hamilton(x, p);
            let raised = g.raise(x, p);
            assert!(
                (v - raised).to_array().iter().all(|d| d.abs() < 1e-12),
                "ẋ ≠ g⁻¹p"
            );
            let eps = 1e-5;
            let (vp, _) = g.hamilton(x.offset(v, eps), p + eps * f);
            let (vm, _) = g.hamilton(x.offset(v, -eps), p - eps * f);
            let acc = (1.0 / (2.0 * eps)) * (vp - vm);
            let gam = g.christoffel(x);
            let k = v.to_array();
            for mu in 0..4 {
                let want: f64 = -(0..4)
                    .flat_map(|a| (0..4).map(move |b| (a, b)))
                    .map(|(a, b)| gam[mu][a][b] * k[a] * k[b])
                    .sum::<f64>();
                let got = acc.to_array()[mu];
                assert!(
                    (got - want).abs() < 1e-6 * (1.0 + want.abs()),
                    "ẍ^{mu}: {got} vs {want}"
                );
            }
        }
    }
}

fn assert_orthonormal<M: Spacetime>(m: &M, x: Event, f: &Tetrad) {
    for a in 0..4 {
        for b in 0..4 {
            let want = if a != b {
                0.0
            } else if a == 0 {
                -1.0
            } else {
                1.0
            };
            let got = m.dot(x, f.e[a], f.e[b]);
            assert!((got - want).abs() < 1e-12, "g(e{a}, e{b}) = {got} at {x:?}");
        }
    }
}

#[test]
fn static_and_boosted_frames_are_orthonormal() {
    let mut rng = Rng::new(6);
    for g in godels() {
        for _ in 0..200 {
            let x = rng.event(6.0 * g.a);
            let f = g.static_frame(x);
            assert_orthonormal(&g, x, &f);
            assert_eq!(
                f.e[0],
                FourVector::new(1.0, 0.0, 0.0, 0.0),
                "static observer is ∂t"
            );
            let v = LocalVelocity::new(rng.uniform(0.0, 0.99), rng.direction()).unwrap();
            let b = boost(&f, v);
            assert_orthonormal(&g, x, &b);
            // The boosted observer moves with speed v relative to the static one.
            let gamma = -g.dot(x, b.e[0], f.e[0]);
            assert!((gamma - v.gamma()).abs() < 1e-9 * gamma);
        }
    }
    let m = Minkowski;
    let x = Event::default();
    assert_orthonormal(
        &m,
        x,
        &boost(
            &m.static_frame(x),
            LocalVelocity::new(0.9, [1.0, 2.0, 3.0]).unwrap(),
        ),
    );
}

#[test]
fn static_frame_matches_the_closed_form_on_the_half_plane_phi_zero() {
    // docs/physics.md, "Frames": e_r = D ∂_r, e_φ = (∂_φ − r²/(√2 a) ∂_t)/(r D) with
    // D = √(1 + s²).
    for g in godels() {
        for r in [0.3, 1.0, 1.9, 2.5, 5.0] {
            let r = r * g.a;
            let x = Event::new(0.0, r, 0.0, 0.0);
            let f = g.static_frame(x);
            let d = (1.0 + (r / (2.0 * g.a)).powi(2)).sqrt();
            // At φ = 0: ∂_r = ∂_x, ∂_φ = r ∂_y.
            let er = FourVector::new(0.0, d, 0.0, 0.0);
            let ephi = FourVector::new(-r * r / (SQRT_2 * g.a) / (r * d), 0.0, r / (r * d), 0.0);
            for (got, want) in [(f.e[1], er), (f.e[2], ephi)] {
                assert!(
                    (got - want).to_array().iter().all(|v| v.abs() < 1e-12),
                    "{got:?} vs {want:?}"
                );
            }
        }
    }
}

#[test]
fn aberration_is_the_boost_applied_to_the_photon() {
    // The moving observer's pixel n′ launches k = −e0′ + n′ⁱeᵢ′ in its boosted frame; in the
    // static frame the same vector is (1/D)(−e0 + nⁱeᵢ): `aberrate` must give that n and D.
    let mut rng = Rng::new(7);
    for g in godels() {
        for _ in 0..200 {
            let x = rng.event(4.0 * g.a);
            let f = g.static_frame(x);
            let v = LocalVelocity::new(rng.uniform(0.0, 0.99), rng.direction()).unwrap();
            let own = rng.direction();
            let k = boost(&f, v).vector([-1.0, own[0], own[1], own[2]]);
            // Static-frame components: k = c(−e0 + nⁱeᵢ) with c = g(k, e0), nⁱ = g(k, eᵢ)/c.
            let c = g.dot(x, k, f.e[0]);
            let (n, d) = aberrate(v, own);
            assert!((d * c - 1.0).abs() < 1e-9, "D = {d}, 1/c = {}", 1.0 / c);
            for i in 0..3 {
                let want = g.dot(x, k, f.e[i + 1]) / c;
                assert!((n[i] - want).abs() < 1e-9, "n = {n:?}");
            }
            // g′/g = γ(1 + n·v) with the static direction n.
            let nv: f64 = (0..3).map(|i| n[i] * v.direction[i]).sum();
            assert!((d - v.gamma() * (1.0 + v.speed * nv)).abs() < 1e-9 * d);
        }
    }
}

#[test]
fn aberration_round_trip_and_the_direction_of_motion() {
    // Seen from the moving observer, the static one moves with −v (the boost keeps the axes
    // aligned): boosting back returns the original direction and the inverse factor.
    let mut rng = Rng::new(8);
    for _ in 0..500 {
        let v = LocalVelocity::new(rng.uniform(0.0, 0.999), rng.direction()).unwrap();
        let back = LocalVelocity::new(v.speed, v.direction.map(|c| -c)).unwrap();
        let own = rng.direction();
        let (n, d) = aberrate(v, own);
        let (again, d_back) = aberrate(back, n);
        assert!(
            (0..3).all(|i| (again[i] - own[i]).abs() < 1e-9),
            "{own:?} → {again:?}"
        );
        assert!((d * d_back - 1.0).abs() < 1e-9);
        assert!(((n[0].powi(2) + n[1].powi(2) + n[2].powi(2)).sqrt() - 1.0).abs() < 1e-12);
        // Straight ahead and straight behind keep their direction; ahead is blue-shifted by
        // √((1 + v)/(1 − v)), behind red-shifted by its inverse.
        let ahead = ((1.0 + v.speed) / (1.0 - v.speed)).sqrt();
        let (n, d) = aberrate(v, v.direction);
        assert!(
            (0..3).all(|i| (n[i] - v.direction[i]).abs() < 1e-9) && (d / ahead - 1.0).abs() < 1e-9
        );
        let (n, d) = aberrate(v, back.direction);
        assert!(
            (0..3).all(|i| (n[i] - back.direction[i]).abs() < 1e-9)
                && (d * ahead - 1.0).abs() < 1e-9
        );
    }
    // Looking perpendicular to the motion, the moving observer sees what the static one
    // sees tilted backwards by arcsin v (n = n′/γ − v v̂), red-shifted by 1/γ (the
    // transverse Doppler effect).
    let v = LocalVelocity::new(0.6, [1.0, 0.0, 0.0]).unwrap();
    let (n, d) = aberrate(v, [0.0, 1.0, 0.0]);
    assert!((n[0] + 0.6).abs() < 1e-12 && (n[1] - 0.8).abs() < 1e-12 && (d - 0.8).abs() < 1e-12);
}
