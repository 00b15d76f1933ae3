//! Constants of motion of geodesics in Gödel's (and Minkowski) spacetime, from the Killing
//! fields ∂t, ∂φ, ∂z (docs/physics.md, "Geodesics"): E = −p_t, L = p_φ = x p_y − y p_x, p_z,
//! and the normalization N = g^{μν} p_μ p_ν (0 for light, −1 for particles with proper time).

use crate::geodesic::{GeodesicState, TracedGeodesic};
use crate::metric::Spacetime;

/// The conserved quantities of one phase-space point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstantsOfMotion {
    pub energy: f64,
    pub angular_momentum: f64,
    pub pz: f64,
    pub normalization: f64,
}

impl ConstantsOfMotion {
    pub fn of<M: Spacetime>(metric: &M, s: &GeodesicState) -> Self {
        let v = metric.raise(s.x, s.p);
        ConstantsOfMotion {
            energy: -s.p.t,
            angular_momentum: s.x.x * s.p.y - s.x.y * s.p.x,
            pz: s.p.z,
            normalization: v.contract(s.p),
        }
    }
}

/// Largest drift of each constant along a geodesic, relative to a natural scale:
/// |ΔE|/|E|, |ΔL|/max(|L|, |E|·ℓ), |Δp_z|/max(|p_z|, |E|), |ΔN|/E², with ℓ the metric's
/// length scale (a for Gödel). L and p_z may vanish (rays through the axis), hence the floors.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Drift {
    pub energy: f64,
    pub angular_momentum: f64,
    pub pz: f64,
    pub normalization: f64,
}

impl Drift {
    pub fn max(&self) -> f64 {
        self.energy
            .max(self.angular_momentum)
            .max(self.pz)
            .max(self.normalization)
    }

    /// Drift over the start, every step end, every step's dense midpoint, and the end.
    pub fn along<M: Spacetime>(metric: &M, g: &TracedGeodesic, length_scale: f64) -> Drift {
        let states = g.steps.iter().flat_map(|st| {
            [
                g.system.state(&st.y1),
                g.system.state(&st.eval(st.lambda0 + 0.5 * st.h)),
            ]
        });
        Drift::over(metric, &g.start, states.chain([g.end]), length_scale)
    }

    /// Drift of the constants at each of `states` relative to those at `start` (for curves
    /// not produced by the integrator, e.g. closed forms sampled at given parameters).
    pub fn over<M: Spacetime>(
        metric: &M,
        start: &GeodesicState,
        states: impl IntoIterator<Item = GeodesicState>,
        length_scale: f64,
    ) -> Drift {
        let c0 = ConstantsOfMotion::of(metric, start);
        let e = c0.energy.abs().max(f64::MIN_POSITIVE);
        let sl = c0.angular_momentum.abs().max(e * length_scale);
        let sz = c0.pz.abs().max(e);
        let mut d = Drift::default();
        for s in states {
            let c = ConstantsOfMotion::of(metric, &s);
            d.energy = d.energy.max((c.energy - c0.energy).abs() / e);
            d.angular_momentum = d
                .angular_momentum
                .max((c.angular_momentum - c0.angular_momentum).abs() / sl);
            d.pz = d.pz.max((c.pz - c0.pz).abs() / sz);
            d.normalization = d
                .normalization
                .max((c.normalization - c0.normalization).abs() / (e * e));
        }
        d
    }
}
