//! Parallel transport along the closed-form geodesics of Gödel's universe, in closed form
//! (docs/physics.md, "Parallel transport along closed forms").
//!
//! Every geodesic through the origin is an orbit of one Killing field ξ (its projection on
//! the disc is a hyperbolic circle run at constant speed): ξ = E ∂t + kˣ Kx + kʸ Ky +
//! p_z ∂z + (√2 E/a) ∂φ for the initial tangent k = (E, kˣ, kʸ, p_z), the ∂φ part fixed by
//! ∇_ξ ξ = 0. A vector Lie-dragged by ξ's flow F_λ changes along the orbit by
//! D V/dλ = ∇_V ξ, and F_λ commutes with ∇ξ, so the parallel transport of W from the
//! origin is
//!
//!   W(λ) = F_λ* exp(−λA) W,   A(W) = ∇_W ξ at the origin,
//!
//! with, at the origin (metric = Minkowski there), the 2-form A_μν = ∇_μ ξ_ν = ½ (dξ♭)_μν:
//! A_xy = E/(√2 a), A_xt = −kʸ/(√2 a), A_yt = kˣ/(√2 a). A annihilates k and ∂z: exp(−λA)
//! turns the rest space of k about the direction of ∂z there. The flow itself is
//! F_λ = T_{γ(λ)}⁻¹ ∘ R_β(λ): the isometry to the origin of the geodesic's point γ(λ),
//! inverted, after a rotation about the axis by β(λ) = α − 2 arg(1 − |h|² e^{iα}), where
//! α = sgn(E)·2ωλ is the angle the flow has turned about the circle's centre h
//! (|h| = tanh(asinh(r_max/2a)/2); "Whole-ray rejection").

use crate::closed_form::OriginGeodesic;
use crate::isometry::Isometry;
use crate::vectors::{Event, FourVector};
use std::f64::consts::SQRT_2;

/// The 2-form A of the origin geodesic `geo` as the operator W ↦ ∇_W ξ on vectors at the
/// origin (components (t, x, y, z)).
fn nabla_xi(geo: &OriginGeodesic, w: [f64; 4]) -> [f64; 4] {
    let (kx, ky) = geo.initial_transverse();
    let s = 1.0 / (SQRT_2 * geo.a);
    let (e, kx, ky) = (geo.energy * s, kx * s, ky * s);
    // (∇_W ξ)^ν = W^μ A_μ^ν, indices raised with η = diag(−1, 1, 1, 1).
    [
        w[1] * ky - w[2] * kx,
        w[0] * ky - w[2] * e,
        -w[0] * kx + w[1] * e,
        0.0,
    ]
}

/// exp(−λA) W: A generates a rotation of rate Ω = √(κ + p_z²)/(√2 a) (A³ = −Ω²A), so
/// exp(−λA) = 1 − sin(Ωλ)/Ω · A + (1 − cos Ωλ)/Ω² · A² (for Ω → 0 the series 1 − λA + λ²A²/2).
fn rotate_rest_space(geo: &OriginGeodesic, lambda: f64, w: [f64; 4]) -> [f64; 4] {
    let aw = nabla_xi(geo, w);
    let aaw = nabla_xi(geo, aw);
    let omega = (geo.kappa + geo.pz * geo.pz).sqrt() / (SQRT_2 * geo.a);
    let x = omega * lambda;
    let (c1, c2) = if x.abs() < 1e-4 {
        (
            lambda * (1.0 - x * x / 6.0),
            0.5 * lambda * lambda * (1.0 - x * x / 12.0),
        )
    } else {
        (x.sin() / omega, (1.0 - x.cos()) / (omega * omega))
    };
    std::array::from_fn(|i| w[i] - c1 * aw[i] + c2 * aaw[i])
}

/// The vector `w` at the origin parallel-transported along the closed-form geodesic `geo`
/// to its point at parameter `lambda`, together with that point.
pub fn transport_from_origin(
    geo: &OriginGeodesic,
    lambda: f64,
    w: FourVector,
) -> (Event, FourVector) {
    let (at, _) = geo.at(lambda);
    let v = rotate_rest_space(geo, lambda, w.to_array());
    let beta = geo.flow_rotation(lambda);
    let (s, c) = beta.sin_cos();
    let v = FourVector::new(v[0], c * v[1] - s * v[2], s * v[1] + c * v[2], v[3]);
    let back = Isometry::to_origin(geo.a, at).inverse();
    (at, back.push(Event::new(0.0, 0.0, 0.0, 0.0), v))
}
