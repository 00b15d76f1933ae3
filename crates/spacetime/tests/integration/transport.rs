//! Parallel transport along closed-form geodesics (docs/physics.md, "Parallel transport
//! along closed forms") against an independent integration of the transport equations
//! dx/dλ = k, dk/dλ = −Γ(k, k), dW/dλ = −Γ(k, W) straight from the Christoffel symbols, for
//! light and particles, both time orientations, several a; and the invariants the transport
//! must keep (inner products with the tangent and between transported vectors).

use crate::common::Rng;
use spacetime::transport::transport_from_origin;
use spacetime::*;

/// State: event, tangent, one transported vector (12 components).
struct Transport(Godel);

impl OdeSystem<12> for Transport {
    fn rhs(&self, s: &[f64; 12]) -> [f64; 12] {
        let x = Event::new(s[0], s[1], s[2], s[3]);
        let gam = self.0.christoffel(x);
        let mut out = [0.0; 12];
        for mu in 0..4 {
            out[mu] = s[4 + mu];
            let (mut dk, mut dw) = (0.0, 0.0);
            for a in 0..4 {
                for b in 0..4 {
                    dk -= gam[mu][a][b] * s[4 + a] * s[4 + b];
                    dw -= gam[mu][a][b] * s[4 + a] * s[8 + b];
                }
            }
            out[4 + mu] = dk;
            out[8 + mu] = dw;
        }
        out
    }
}

fn integrate(a: f64, k: FourVector, w: FourVector, lambda: f64) -> (Event, FourVector) {
    let mut s0 = [0.0; 12];
    s0[4..8].copy_from_slice(&k.to_array());
    s0[8..12].copy_from_slice(&w.to_array());
    let tol = Tolerances {
        rtol: 1e-12,
        atol: 1e-12,
        h_max: 0.1,
        h_min: 1e-14,
    };
    let mut ode = Dop853::new(Transport(Godel::new(a)), 0.0, s0, tol, None);
    let mut steps = 0;
    while ode.lambda() < lambda {
        assert!(matches!(ode.step(), StepOutcome::Accepted));
        steps += 1;
        assert!(steps < 200_000);
    }
    let d = ode.dense();
    let s = d.eval(lambda);
    (
        Event::new(s[0], s[1], s[2], s[3]),
        FourVector::new(s[8], s[9], s[10], s[11]),
    )
}

#[test]
fn closed_form_transport_matches_the_integrated_transport() {
    let mut rng = Rng::new(5);
    let mut worst: f64 = 0.0;
    for a in [1.0, 0.6, 2.0] {
        for i in 0..12 {
            let d = rng.direction();
            let (e, speed) = match i % 4 {
                0 => (1.0, 1.0),
                1 => (-1.0, 1.0),
                2 => (1.0, rng.uniform(0.1, 0.95)),
                _ => (-1.0, rng.uniform(0.1, 0.95)),
            };
            let k = FourVector::new(e, speed * d[0], speed * d[1], speed * d[2]);
            let w = FourVector::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            );
            let geo = OriginGeodesic::new(a, k).expect("causal");
            for lambda in [0.3, 2.0, 1.7 * geo.return_parameter() + 0.1] {
                let (x, v) = transport_from_origin(&geo, lambda, w);
                let (xi, vi) = integrate(a, k, w, lambda);
                let dx = (x - xi)
                    .to_array()
                    .iter()
                    .map(|c| c.abs())
                    .fold(0.0, f64::max);
                let dv = (v - vi)
                    .to_array()
                    .iter()
                    .map(|c| c.abs())
                    .fold(0.0, f64::max);
                worst = worst.max(dx).max(dv);
                assert!(
                    dx < 1e-8 && dv < 1e-8,
                    "a = {a}, k = {k:?}, λ = {lambda}: closed form {v:?}, integrated {vi:?} (Δx {dx:e})"
                );
            }
        }
    }
    eprintln!("worst deviation {worst:e}");
}
