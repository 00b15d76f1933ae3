//! What an observer with an orthonormal frame (e₀ its four-velocity) measures: the frame
//! components of a vector, v^a = η_aa g(e_a, v), or of a covector, p_a = p(e_a), and the
//! frequency ratio of a photon between emitter and observer, g = (p·u_obs)/(p·u_emit)
//! (docs/physics.md, "Frames" and "Frequency shift").

use crate::vectors::{Covector, FourVector, MetricTensor, Tetrad};

/// The components v^a = η_aa g(e_a, v) of `v` in the orthonormal `frame` (η = diag(−1, 1, 1, 1)),
/// with `g` the metric at the frame's event. v^0 is the energy an observer moving with e₀
/// measures of a photon of momentum v.
pub fn vector_components(g: &MetricTensor, frame: &Tetrad, v: FourVector) -> [f64; 4] {
    let v = v.to_array();
    let mut out = [0.0; 4];
    for (i, e) in frame.e.iter().enumerate() {
        let e = e.to_array();
        let s: f64 = (0..4)
            .map(|m| (0..4).map(|n| g[m][n] * e[m] * v[n]).sum::<f64>())
            .sum();
        out[i] = if i == 0 { -s } else { s };
    }
    out
}

/// The components p_a = p(e_a) of the covector `p` on the `frame`'s vectors.
pub fn covector_components(frame: &Tetrad, p: Covector) -> [f64; 4] {
    frame.e.map(|e| e.contract(p))
}

/// The dual basis of an orthonormal frame, precomputed: row a is the covector η_aa g(e_a, ·),
/// so the frame components of any vector at that event are ξ^a = Σ_n row_a[n] ξ^n. Worth it
/// where one frame measures many vectors (an object at rest, its frame fixed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DualFrame(pub [[f64; 4]; 4]);

impl DualFrame {
    pub fn new(g: &MetricTensor, frame: &Tetrad) -> DualFrame {
        DualFrame(std::array::from_fn(|a| DualFrame::row(g, a, frame.e[a])))
    }

    /// Row `a` alone, η_aa g(e_a, ·), for the frame vector `e` = e_a: where only one
    /// component is measured (the time component of a ball's simultaneity).
    pub fn row(g: &MetricTensor, a: usize, e: FourVector) -> [f64; 4] {
        let e = e.to_array();
        let sign = if a == 0 { -1.0 } else { 1.0 };
        std::array::from_fn(|n| sign * (0..4).map(|m| g[m][n] * e[m]).sum::<f64>())
    }

    /// The frame components of the coordinate components `v`.
    pub fn components(&self, v: [f64; 4]) -> [f64; 4] {
        self.0.map(|row| DualFrame::component(&row, v))
    }

    /// One frame component of `v`, from its row ([`DualFrame::row`]).
    pub fn component(row: &[f64; 4], v: [f64; 4]) -> f64 {
        (0..4).map(|n| row[n] * v[n]).sum()
    }
}

/// The frequency ratio g = ν_obs/ν_emit = (p·u_obs)/(p·u_emit) of a photon whose covariant
/// momentum is `p_obs` at the observer (four-velocity `u_obs`) and `p_emit` at the emitter
/// (four-velocity `u_emit`): the same geodesic, so any scale or time orientation of p
/// cancels. g > 1 is a blue shift.
pub fn frequency_ratio(
    u_obs: FourVector,
    p_obs: Covector,
    u_emit: FourVector,
    p_emit: Covector,
) -> f64 {
    u_obs.contract(p_obs) / u_emit.contract(p_emit)
}
