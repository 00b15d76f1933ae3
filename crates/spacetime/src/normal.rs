//! Riemann normal coordinates about an event P, to the order an object's rest frame needs
//! (e.g. Misner, Thorne & Wheeler §11.6): the displacement of a nearby event X,
//! ξ^μ = Δx^μ + ½ Γ^μ_αβ(P) Δx^α Δx^β with Δx = X − P (exact to second order), and a vector
//! carried along the short coordinate line by parallel transport to first order,
//! v ↦ v − Γ^μ_αβ Δx^α v^β (docs/physics.md, "Local objects").

use crate::vectors::Christoffel;

/// ξ = Δx + ½ Γ(Δx, Δx): the normal-coordinate displacement of the event at coordinate
/// displacement `d` from the centre where `gamma` was taken.
pub fn displacement(gamma: &Christoffel, d: [f64; 4]) -> [f64; 4] {
    let mut xi = d;
    for (mu, out) in xi.iter_mut().enumerate() {
        let mut c = 0.0;
        for a in 0..4 {
            for b in 0..4 {
                c += gamma[mu][a][b] * d[a] * d[b];
            }
        }
        *out += 0.5 * c;
    }
    xi
}

/// The vector `v` carried by the coordinate displacement `dx` (from its base point to the
/// destination) with parallel transport to first order: v^μ − Γ^μ_αβ dx^α v^β.
pub fn transport(gamma: &Christoffel, dx: [f64; 4], v: [f64; 4]) -> [f64; 4] {
    let mut out = v;
    for (mu, o) in out.iter_mut().enumerate() {
        for a in 0..4 {
            for b in 0..4 {
                *o -= gamma[mu][a][b] * dx[a] * v[b];
            }
        }
    }
    out
}
