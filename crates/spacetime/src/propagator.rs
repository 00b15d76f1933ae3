//! Parallel transport integrated with the geodesic, in any metric (docs/physics.md,
//! "Polarization"): the transport equation DW/dλ = 0, dW^μ/dλ = −Γ^μ_αβ k^α W^β, solved for
//! the propagator P (W(λ) = P(λ) W(0) for every vector W at the start) together with
//! Hamilton's equations of the geodesic ("Geodesics"), by DOP853 ("Geodesics",
//! "Integrator"), and the turn of the screen over one loop of a Gödel light ray
//! ([`screen_turn`]). The numeric tracer's polarization; the closed form of Gödel's geodesics
//! is `crate::transport`.

use crate::dop853::{Dop853, OdeSystem, StepOutcome, Tolerances};
use crate::geodesic::{GeodesicState, GeodesicSystem, STATE};
use crate::metric::Spacetime;
use crate::vectors::{FourVector, MetricTensor};

/// A propagator: row μ, column ν is component μ of the transported basis vector ∂_ν.
pub type Propagator = [[f64; 4]; 4];

/// Dimension of the integrated state: the reduced geodesic ([`STATE`]), then P row by row.
pub const TRANSPORT_STATE: usize = STATE + 16;

/// The geodesic system with the propagator carried along.
#[derive(Clone, Copy, Debug)]
pub struct TransportSystem<M> {
    pub geodesic: GeodesicSystem<M>,
}

impl<M: Spacetime> OdeSystem<TRANSPORT_STATE> for TransportSystem<M> {
    fn rhs(&self, y: &[f64; TRANSPORT_STATE]) -> [f64; TRANSPORT_STATE] {
        let mut g = [0.0; STATE];
        g.copy_from_slice(&y[..STATE]);
        let st = self.geodesic.state(&g);
        let (v, f) = self.geodesic.metric.hamilton(st.x, st.p);
        let gam = self.geodesic.metric.christoffel(st.x);
        let k = v.to_array();
        let mut out = [0.0; TRANSPORT_STATE];
        out[..STATE].copy_from_slice(&[v.t, v.x, v.y, v.z, f.x, f.y]);
        // Γ^μ_αβ k^α, once per point.
        let mut gk = [[0.0; 4]; 4];
        for mu in 0..4 {
            for b in 0..4 {
                gk[mu][b] = (0..4).map(|a| gam[mu][a][b] * k[a]).sum();
            }
        }
        for mu in 0..4 {
            for nu in 0..4 {
                let s: f64 = (0..4).map(|b| gk[mu][b] * y[STATE + 4 * b + nu]).sum();
                out[STATE + 4 * mu + nu] = -s;
            }
        }
        out
    }
}

/// Integrates the geodesic through `start` with the propagator, and returns the propagator at
/// each parameter of `at` (ascending, ≥ 0). `None` when the integration fails or needs more
/// than `max_steps` steps.
pub fn propagators<M: Spacetime + Copy>(
    metric: M,
    start: &GeodesicState,
    at: &[f64],
    tol: Tolerances,
    max_steps: u64,
) -> Option<Vec<Propagator>> {
    let (geodesic, s0) = GeodesicSystem::new(metric, start);
    let mut y0 = [0.0; TRANSPORT_STATE];
    y0[..STATE].copy_from_slice(&s0);
    for i in 0..4 {
        y0[STATE + 5 * i] = 1.0;
    }
    let mut ode = Dop853::new(TransportSystem { geodesic }, 0.0, y0, tol, None);
    let mut out = Vec::with_capacity(at.len());
    for &target in at {
        loop {
            let gap = target - ode.lambda();
            // Steps are capped to land on the target; one may end a rounding short of it.
            if gap <= 1e-12 * target.abs().max(1.0) {
                break;
            }
            if ode.accepted >= max_steps {
                return None;
            }
            ode.limit_next_step(gap);
            if ode.step() != StepOutcome::Accepted {
                return None;
            }
        }
        let y = if ode.lambda() == target || ode.accepted == 0 {
            *ode.state()
        } else {
            ode.dense().eval(target)
        };
        let p: Propagator =
            std::array::from_fn(|mu| std::array::from_fn(|nu| y[STATE + 4 * mu + nu]));
        if !p.iter().flatten().all(|c| c.is_finite()) {
            return None;
        }
        out.push(p);
    }
    Some(out)
}

/// P·w.
pub fn apply(p: &Propagator, w: [f64; 4]) -> [f64; 4] {
    std::array::from_fn(|mu| (0..4).map(|nu| p[mu][nu] * w[nu]).sum())
}

/// The turn of the screen over one loop of a Gödel light ray: `m` the propagator of the loop
/// (back on its start's axis, moved in t and z only, which leaves components alone), (f, g)
/// an orthonormal screen basis at the start (both orthogonal to the tangent there), `metric`
/// the metric at the start. M f = cos θ f + sin θ g modulo the tangent; returns θ. Loop n
/// then starts with cos nθ f + sin nθ g (modulo the tangent), with no powers of M, whose
/// rounding would grow with n (M is a null rotation where the ray keeps z).
pub fn screen_turn(m: &Propagator, metric: &MetricTensor, f: FourVector, g: FourVector) -> f64 {
    let mf = apply(m, f.to_array());
    let dot = |a: [f64; 4], b: [f64; 4]| -> f64 {
        (0..4)
            .map(|i| (0..4).map(|j| metric[i][j] * a[i] * b[j]).sum::<f64>())
            .sum()
    };
    dot(mf, g.to_array()).atan2(dot(mf, f.to_array()))
}
