//! The Gödel-type family (`spacetime::GodelType`, docs/physics.md "The Gödel-type family"):
//! its Gödel member is Gödel's metric in other coordinates, the inverse, the derivatives and
//! Hamilton's equations are those of the metric, the series and closed forms join, and
//! in-plane light rays from the axis turn at the radius where closed timelike curves begin.

use crate::common::Rng;
use spacetime::*;

/// (m², Ω) of members of every kind, and the largest proper radius to test each at.
fn members() -> Vec<(GodelType, f64)> {
    vec![
        (GodelType::new(-1.0, 0.5), 2.5), // trigonometric: the coordinates hold below π
        (GodelType::new(0.0, 0.7), 3.0),  // Som–Raychaudhuri
        (GodelType::new(0.5, 0.5), 3.0),
        (GodelType::new(1.0, 1.0 / 2f64.sqrt()), 3.0), // Gödel, a = 1
        (GodelType::new(3.5, 1.0), 2.0),
        (GodelType::new(4.0, 1.0), 2.0), // completely causal
        (GodelType::new(6.0, 1.0), 2.0),
    ]
}

fn point(rng: &mut Rng, rho_max: f64) -> Event {
    let e = rng.event(rho_max);
    Event::new(e.t, e.x, e.y, e.z)
}

fn max_diff(a: &MetricTensor, b: &MetricTensor) -> f64 {
    (0..4)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| (a[i][j] - b[i][j]).abs())
        .fold(0.0, f64::max)
}

/// With m² = 1/a², Ω = 1/(√2 a) and r = 2a sinh(ρ/2a) (t, φ, z kept), the family's metric
/// is the pull-back of Gödel's: g = Jᵀ G J, J the Jacobian of (x, y) ↦ (r/ρ)(x, y).
#[test]
fn the_godel_member_is_godels_metric_with_the_proper_radius() {
    let mut rng = Rng::new(34);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.7] {
        let member = GodelType::new(1.0 / (a * a), 1.0 / (2f64.sqrt() * a));
        let godel = Godel::new(a);
        let to_godel = |e: Event| {
            let rho = e.x.hypot(e.y);
            let scale = if rho > 0.0 {
                2.0 * a * (rho / (2.0 * a)).sinh() / rho
            } else {
                1.0
            };
            Event::new(e.t, scale * e.x, scale * e.y, e.z)
        };
        for _ in 0..100 {
            let e = point(&mut rng, 3.0 * a);
            let h = 1e-6;
            let mut jac = [[0.0; 4]; 4]; // jac[i][k] = ∂X^i/∂x^k
            for k in 0..4 {
                let mut plus = e.to_array();
                let mut minus = e.to_array();
                plus[k] += h;
                minus[k] -= h;
                let (p, m) = (
                    to_godel(Event::from_array(plus)),
                    to_godel(Event::from_array(minus)),
                );
                for i in 0..4 {
                    jac[i][k] = (p.to_array()[i] - m.to_array()[i]) / (2.0 * h);
                }
            }
            let big = godel.metric(to_godel(e));
            let mut pulled = [[0.0; 4]; 4];
            for (m, row) in pulled.iter_mut().enumerate() {
                for (n, v) in row.iter_mut().enumerate() {
                    *v = (0..4)
                        .flat_map(|i| (0..4).map(move |j| (i, j)))
                        .map(|(i, j)| jac[i][m] * big[i][j] * jac[j][n])
                        .sum();
                }
            }
            worst = worst.max(max_diff(&pulled, &member.metric(e)));
        }
    }
    assert!(worst < 1e-8, "{worst:e}");
}

#[test]
fn the_inverse_is_the_inverse_and_the_derivatives_are_the_metrics() {
    let mut rng = Rng::new(35);
    for (member, rho_max) in members() {
        for _ in 0..60 {
            let e = point(&mut rng, rho_max);
            let (g, gi) = (member.metric(e), member.inverse_metric(e));
            for i in 0..4 {
                for j in 0..4 {
                    let v: f64 = (0..4).map(|k| g[i][k] * gi[k][j]).sum();
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((v - want).abs() < 1e-11, "{member:?} {e:?}: {v} at {i},{j}");
                }
            }
            let dg = member.metric_derivatives(e);
            let h = 1e-5;
            for (l, dg_l) in dg.iter().enumerate() {
                let mut plus = e.to_array();
                let mut minus = e.to_array();
                plus[l] += h;
                minus[l] -= h;
                let (gp, gm) = (
                    member.metric(Event::from_array(plus)),
                    member.metric(Event::from_array(minus)),
                );
                for i in 0..4 {
                    for j in 0..4 {
                        let fd = (gp[i][j] - gm[i][j]) / (2.0 * h);
                        assert!(
                            (fd - dg_l[i][j]).abs() < 1e-6,
                            "{member:?} ∂{l} g{i}{j}: {fd} vs {}",
                            dg_l[i][j]
                        );
                    }
                }
            }
        }
    }
}

/// ẋ^μ = g^{μν} p_ν and ṗ_μ = −½ ∂_μ(g^{αβ} p_α p_β), the latter by central differences.
#[test]
fn hamiltons_equations_are_the_inverse_metrics() {
    let mut rng = Rng::new(36);
    for (member, rho_max) in members() {
        for _ in 0..60 {
            let e = point(&mut rng, rho_max);
            let p = Covector::new(
                rng.uniform(-2.0, 0.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            );
            let (xdot, pdot) = member.hamilton(e, p);
            let gi = member.inverse_metric(e);
            let pa = p.to_array();
            for (mu, v) in xdot.to_array().iter().enumerate() {
                let want: f64 = (0..4).map(|nu| gi[mu][nu] * pa[nu]).sum();
                assert!((v - want).abs() < 1e-11, "{member:?}: ẋ^{mu} {v} vs {want}");
            }
            let two_h = |x: Event| -> f64 {
                let g = member.inverse_metric(x);
                (0..4)
                    .flat_map(|i| (0..4).map(move |j| (i, j)))
                    .map(|(i, j)| g[i][j] * pa[i] * pa[j])
                    .sum()
            };
            let h = 1e-5;
            for (mu, v) in pdot.to_array().iter().enumerate() {
                let mut plus = e.to_array();
                let mut minus = e.to_array();
                plus[mu] += h;
                minus[mu] -= h;
                let fd = -0.5 * (two_h(Event::from_array(plus)) - two_h(Event::from_array(minus)))
                    / (2.0 * h);
                assert!((v - fd).abs() < 1e-6, "{member:?}: ṗ_{mu} {v} vs {fd}");
            }
        }
    }
}

/// Near m²ρ² = 0.5 the series gives way to the closed forms: the metric is continuous there.
#[test]
fn series_and_closed_forms_join() {
    for member in [GodelType::new(2.0, 1.0), GodelType::new(-2.0, 1.0)] {
        let rho = (0.5 / member.m2.abs()).sqrt();
        let (below, above) = (rho * (1.0 - 1e-14), rho * (1.0 + 1e-14));
        let gb = member.metric(Event::new(0.0, below, 0.0, 0.0));
        let ga = member.metric(Event::new(0.0, above, 0.0, 0.0));
        assert!(max_diff(&gb, &ga) < 1e-12, "{member:?}");
        let db = member.metric_derivatives(Event::new(0.0, below, 0.0, 0.0));
        let da = member.metric_derivatives(Event::new(0.0, above, 0.0, 0.0));
        assert!(max_diff(&db[1], &da[1]) < 1e-10, "{member:?}");
    }
}

/// Hamilton's equations as an ODE system for DOP853.
struct Flow(GodelType);

impl OdeSystem<8> for Flow {
    fn rhs(&self, s: &[f64; 8]) -> [f64; 8] {
        let e = Event::new(s[0], s[1], s[2], s[3]);
        let p = Covector::new(s[4], s[5], s[6], s[7]);
        let (x, q) = self.0.hamilton(e, p);
        let (x, q) = (x.to_array(), q.to_array());
        [x[0], x[1], x[2], x[3], q[0], q[1], q[2], q[3]]
    }
}

/// A light ray from the axis in the plane z = 0 turns at ρ_c, tanh(mρ_c/2) = m/(2Ω)
/// (m² = 0: ρ_c = 1/Ω; m² < 0: tan(μρ_c/2) = μ/(2Ω)), where closed timelike curves begin;
/// the null condition and p_t are kept on the way.
#[test]
fn in_plane_rays_from_the_axis_turn_where_closed_timelike_curves_begin() {
    for (m2, omega) in [
        (1.0, 1.0 / 2f64.sqrt()),
        (0.0, 0.7),
        (0.5, 0.5),
        (0.9, 0.5),
        (-0.3, 0.5),
    ] {
        let member = GodelType::new(m2, omega);
        let rho_c: f64 = if m2 > 0.0 {
            let m = m2.sqrt();
            2.0 / m * (m / (2.0 * omega)).atanh()
        } else if m2 == 0.0 {
            1.0 / omega
        } else {
            let mu = (-m2).sqrt();
            2.0 / mu * (mu / (2.0 * omega)).atan()
        };
        // On the axis the metric is Minkowski's: p = (−1, 1, 0, 0) is a unit-energy null ray.
        let y0 = [0.0, 0.0, 0.0, 0.0, -1.0, 1.0, 0.0, 0.0];
        let tol = Tolerances {
            rtol: 1e-12,
            atol: 1e-12,
            h_max: 0.05,
            h_min: 1e-12,
        };
        let mut ode = Dop853::new(Flow(member), 0.0, y0, tol, None);
        let mut rho_max: f64 = 0.0;
        let mut steps = 0;
        // Out to the turning point and back towards the axis.
        while steps < 20_000 {
            assert_eq!(ode.step(), StepOutcome::Accepted);
            steps += 1;
            let s = *ode.state();
            let rho = s[1].hypot(s[2]);
            if rho < rho_max - 0.05 {
                break;
            }
            // The maximum between steps, from the dense output.
            let dense = ode.dense();
            for k in 0..=20 {
                let l = dense.lambda0 + (dense.lambda1() - dense.lambda0) * k as f64 / 20.0;
                let v = dense.eval(l);
                rho_max = rho_max.max(v[1].hypot(v[2]));
            }
            let e = Event::new(s[0], s[1], s[2], s[3]);
            let p = Covector::new(s[4], s[5], s[6], s[7]);
            let gi = member.inverse_metric(e);
            let pa = p.to_array();
            let null: f64 = (0..4)
                .flat_map(|i| (0..4).map(move |j| (i, j)))
                .map(|(i, j)| gi[i][j] * pa[i] * pa[j])
                .sum();
            assert!(
                null.abs() < 1e-9,
                "({m2}, {omega}): null condition {null:e}"
            );
            assert_eq!(s[4], -1.0, "p_t is kept exactly");
        }
        assert!(
            (rho_max - rho_c).abs() < 1e-6 * rho_c.max(1.0),
            "({m2}, {omega}): turns at {rho_max}, ρ_c = {rho_c}"
        );
    }
}

/// The Gödel-like chart (`spacetime::GodelChart`, docs/physics.md "The Gödel-like chart"):
/// its metric is the member's pulled back (g_member(v, w) = g_chart(J v, J w)), its inverse
/// and derivatives are its metric's, `vector_back` undoes `vector`, and for the Gödel member
/// it is Gödel's metric itself.
#[test]
fn the_godel_like_chart_is_the_member_in_other_coordinates() {
    let mut rng = Rng::new(36);
    for (member, rho_max) in members() {
        let chart = GodelChart::new(member);
        for _ in 0..60 {
            let e = point(&mut rng, rho_max);
            let x = chart.event(e);
            let basis = [0, 1, 2, 3].map(|k| {
                let mut v = [0.0; 4];
                v[k] = 1.0;
                FourVector::from_array(v)
            });
            let (g, gc) = (member.metric(e), chart.metric(x));
            for i in 0..4 {
                for j in 0..4 {
                    let (vi, vj) = (chart.vector(e, basis[i]), chart.vector(e, basis[j]));
                    let pulled = chart.dot(x, vi, vj);
                    assert!(
                        (pulled - g[i][j]).abs() < 1e-10 * (1.0 + g[i][j].abs()),
                        "{member:?} {e:?} g{i}{j}: {pulled} vs {}",
                        g[i][j]
                    );
                    let back = chart.vector_back(e, chart.vector(e, basis[i])).to_array();
                    assert!((back[j] - basis[i].to_array()[j]).abs() < 1e-12);
                }
            }
            let gi = chart.inverse_metric(x);
            for i in 0..4 {
                for j in 0..4 {
                    let v: f64 = (0..4).map(|k| gc[i][k] * gi[k][j]).sum();
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((v - want).abs() < 1e-10, "{member:?} {x:?}: {v} at {i},{j}");
                }
            }
            let dg = chart.metric_derivatives(x);
            let h = 1e-5;
            for (l, dg_l) in dg.iter().enumerate() {
                let (mut plus, mut minus) = (x.to_array(), x.to_array());
                plus[l] += h;
                minus[l] -= h;
                let gp = chart.metric(Event::from_array(plus));
                let gm = chart.metric(Event::from_array(minus));
                for i in 0..4 {
                    for j in 0..4 {
                        let fd = (gp[i][j] - gm[i][j]) / (2.0 * h);
                        let tol = 1e-6 * (1.0 + dg_l[i][j].abs());
                        assert!((fd - dg_l[i][j]).abs() < tol, "{member:?} ∂{l} g{i}{j}");
                    }
                }
            }
        }
    }
    // The Gödel member: Gödel's metric, and the chart's radius Gödel's r = 2a sinh(ρ/2a).
    for a in [1.0, 0.7] {
        let member = GodelType::new(1.0 / (a * a), 1.0 / (2f64.sqrt() * a));
        let (chart, godel) = (GodelChart::new(member), Godel::new(a));
        for _ in 0..40 {
            let e = point(&mut rng, 3.0 * a);
            let x = chart.event(e);
            let r = 2.0 * a * (e.x.hypot(e.y) / (2.0 * a)).sinh();
            assert!((x.x.hypot(x.y) - r).abs() < 1e-13 * (1.0 + r));
            let diff = max_diff(&chart.metric(x), &godel.metric(x));
            assert!(diff < 1e-13, "a = {a}, {x:?}: {diff}");
            let diff = max_diff(&chart.inverse_metric(x), &godel.inverse_metric(x));
            assert!(diff < 1e-13, "a = {a}, {x:?}: inverse {diff}");
        }
    }
}

/// `spacetime::curve` (what `godel geodesic` and Python's `geodesic` print) by the exact
/// method in a Gödel-type member is the numeric method's curve: same stop, same samples
/// (light and a particle, in and out of the plane, from on and off the axis), for
/// m²/Ω² = −1, 0, 1, 2, 3.5, 4, 6.
#[test]
fn the_exact_curve_of_a_member_is_the_numeric_one() {
    use spacetime::curve::{compute, CurveMethod, CurveRequest};
    let omega = 0.7;
    for ratio in [-1.0, 0.0, 1.0, 2.0, 3.5, 4.0, 6.0] {
        let metric = Metric::GodelType(GodelType::new(ratio * omega * omega, omega));
        for (start, direction, speed) in [
            (Event::new(0.0, 0.0, 0.0, 0.0), [1.0, 0.0, 0.0], None),
            (Event::new(0.0, 0.3, -0.2, 0.1), [0.2, 1.0, 0.5], None),
            (Event::new(1.0, -0.4, 0.1, 0.0), [1.0, 0.3, -0.2], Some(0.6)),
        ] {
            let curve = |method| {
                let req = CurveRequest::new(
                    metric,
                    method,
                    start,
                    direction,
                    speed,
                    TimeDirection::Past,
                    // Within what the integrator follows: in m² ≥ 4Ω² rays in the plane
                    // reach infinity within a finite coordinate time.
                    Some(1.0),
                    40,
                )
                .unwrap();
                compute(&req).unwrap()
            };
            let (exact, numeric) = (curve(CurveMethod::Exact), curve(CurveMethod::Numeric));
            assert_eq!(exact.stop, numeric.stop, "m²/Ω² = {ratio}");
            let scale = (exact.lambda_end.abs()).max(1.0);
            assert!(
                (exact.lambda_end - numeric.lambda_end).abs() < 1e-7 * scale,
                "m²/Ω² = {ratio}: λ_end {} vs {}",
                exact.lambda_end,
                numeric.lambda_end
            );
            for ((le, se), (ln, sn)) in exact.samples.iter().zip(&numeric.samples) {
                assert!((le - ln).abs() < 1e-7 * scale);
                let (a, b) = (se.x.to_array(), sn.x.to_array());
                for c in 0..4 {
                    assert!(
                        (a[c] - b[c]).abs() < 1e-6 * (1.0 + a[c].abs()),
                        "m²/Ω² = {ratio} {start:?}: {a:?} vs {b:?}"
                    );
                }
            }
        }
    }
    // The default stop: back on the axis, where returning rays come back (λ = π/√Λ).
    for ratio in [-1.0, 0.0, 1.0, 2.0, 3.5] {
        let metric = Metric::GodelType(GodelType::new(ratio * omega * omega, omega));
        let curve = |method| {
            let start = Event::new(0.0, 0.0, 0.0, 0.0);
            let req = CurveRequest::new(
                metric,
                method,
                start,
                [1.0, 0.0, 0.2],
                None,
                TimeDirection::Past,
                None,
                20,
            )
            .unwrap();
            compute(&req).unwrap()
        };
        let (exact, numeric) = (curve(CurveMethod::Exact), curve(CurveMethod::Numeric));
        assert_eq!(exact.stop, StopReason::AxisReturn, "m²/Ω² = {ratio}");
        assert_eq!(numeric.stop, StopReason::AxisReturn, "m²/Ω² = {ratio}");
        assert!(
            (exact.lambda_end - numeric.lambda_end).abs() < 1e-7 * exact.lambda_end,
            "m²/Ω² = {ratio}: {} vs {}",
            exact.lambda_end,
            numeric.lambda_end
        );
    }
}
