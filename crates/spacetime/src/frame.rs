//! Local frames: the static observer's frame by Gram–Schmidt of (∂t, ∂x, ∂y, ∂z)
//! (docs/physics.md, "Frames"), Lorentz boosts of a frame to an observer moving with a given
//! velocity, and the aberration and Doppler factor between two observers at one event
//! (docs/physics.md, "Observers at one event: aberration and Doppler").

use crate::vectors::{FourVector, MetricTensor, Tetrad};

/// A velocity given in an observer's local frame: speed 0 ≤ v < 1 along a unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalVelocity {
    pub speed: f64,
    /// Unit vector in the frame's spatial axes (e1, e2, e3).
    pub direction: [f64; 3],
}

/// `v` as a unit vector, `None` for a zero or non-finite vector. Where the squares of its
/// components would overflow or lose precision (lengths beyond 1e150 or below 1e-150), it is
/// scaled by its largest component first; otherwise it is v/|v| as written.
pub fn scaled_unit(v: [f64; 3]) -> Option<[f64; 3]> {
    if !v.iter().all(|c| c.is_finite()) {
        return None;
    }
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let n = norm(v);
    if n > 1e-150 && n < 1e150 {
        return Some(v.map(|c| c / n));
    }
    let largest = v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if largest == 0.0 {
        return None;
    }
    let v = v.map(|c| c / largest);
    let n = norm(v);
    Some(v.map(|c| c / n))
}

impl LocalVelocity {
    pub const REST: LocalVelocity = LocalVelocity {
        speed: 0.0,
        direction: [1.0, 0.0, 0.0],
    };

    /// Velocity from a speed and any non-zero direction (normalized here; a direction
    /// whose length overflows, such as (1e308, 1e308, 0), through [`scaled_unit`]).
    /// Returns `None` for a zero or non-finite direction or a speed outside [0, 1).
    pub fn new(speed: f64, direction: [f64; 3]) -> Option<Self> {
        if !(speed.is_finite() && (0.0..1.0).contains(&speed)) {
            return None;
        }
        let n = (direction[0].powi(2) + direction[1].powi(2) + direction[2].powi(2)).sqrt();
        if !(n.is_finite() && n > 0.0) {
            return Some(LocalVelocity {
                speed,
                direction: scaled_unit(direction)?,
            });
        }
        Some(LocalVelocity {
            speed,
            direction: [direction[0] / n, direction[1] / n, direction[2] / n],
        })
    }

    /// Lorentz factor γ = 1/√(1 − v²).
    pub fn gamma(&self) -> f64 {
        1.0 / (1.0 - self.speed * self.speed).sqrt()
    }
}

fn g(metric: &MetricTensor, u: FourVector, v: FourVector) -> f64 {
    let (u, v) = (u.to_array(), v.to_array());
    let mut s = 0.0;
    for m in 0..4 {
        for n in 0..4 {
            s += metric[m][n] * u[m] * v[n];
        }
    }
    s
}

/// Gram–Schmidt orthonormalization of (∂t, ∂x, ∂y, ∂z) in that order with respect to
/// `metric` (signature −+++). Requires ∂t timelike, as in Gödel (g_tt = −1) and Minkowski.
pub fn gram_schmidt_static_frame(metric: &MetricTensor) -> Tetrad {
    let basis = [
        FourVector::new(1.0, 0.0, 0.0, 0.0),
        FourVector::new(0.0, 1.0, 0.0, 0.0),
        FourVector::new(0.0, 0.0, 1.0, 0.0),
        FourVector::new(0.0, 0.0, 0.0, 1.0),
    ];
    let mut e = basis;
    let norm = (-g(metric, e[0], e[0])).sqrt();
    e[0] = (1.0 / norm) * e[0];
    for i in 1..4 {
        let mut v = basis[i];
        // Projections use the signs η_aa: + for e0 (since g(e0,e0) = −1), − for spatial.
        let c0 = g(metric, v, e[0]);
        v = v + c0 * e[0];
        for &ej in &e[1..i] {
            let cj = g(metric, v, ej);
            v = v - cj * ej;
        }
        let n = g(metric, v, v).sqrt();
        e[i] = (1.0 / n) * v;
    }
    Tetrad { e }
}

/// The frame of an observer moving with `velocity` relative to `frame`: the standard boost
/// Λ with Λ⁰₀ = γ, Λ⁰ᵢ = Λⁱ₀ = γ v nᵢ, Λⁱⱼ = δᵢⱼ + (γ − 1) nᵢ nⱼ. Spatial axes stay
/// aligned with the original ones as seen in the boost direction's orthogonal plane.
pub fn boost(frame: &Tetrad, velocity: LocalVelocity) -> Tetrad {
    let gamma = velocity.gamma();
    let v = velocity.speed;
    let n = velocity.direction;
    let mut out = frame.e;
    out[0] = frame.vector([gamma, gamma * v * n[0], gamma * v * n[1], gamma * v * n[2]]);
    for i in 0..3 {
        let mut comps = [gamma * v * n[i], 0.0, 0.0, 0.0];
        for j in 0..3 {
            comps[j + 1] = if i == j { 1.0 } else { 0.0 } + (gamma - 1.0) * n[i] * n[j];
        }
        out[i + 1] = frame.vector(comps);
    }
    Tetrad { e: out }
}

/// Aberration and Doppler factor between an observer moving with `velocity` (relative to a
/// frame, here called static) and that frame's observer at the same event.
///
/// `own` is a unit direction the moving observer looks along (towards the source, in its
/// boosted frame of [`boost`]); the photon it receives travels along −`own`. Returns the
/// unit direction n along which the static observer sees the same photon, and the ratio of
/// the photon's frequencies seen by the two, ν_moving/ν_static = γ(1 + n·v)
/// = 1/(γ(1 − n′·v)) (docs/physics.md, "Observers at one event: aberration and Doppler"):
///
/// n = (n′ + ((γ − 1)(n′·v̂) − γv) v̂) / (γ(1 − n′·v)).
pub fn aberrate(velocity: LocalVelocity, own: [f64; 3]) -> ([f64; 3], f64) {
    let gamma = velocity.gamma();
    let (v, d) = (velocity.speed, velocity.direction);
    let along = own[0] * d[0] + own[1] * d[1] + own[2] * d[2];
    let scale = 1.0 / (gamma * (1.0 - v * along));
    let c = (gamma - 1.0) * along - gamma * v;
    let n = [
        (own[0] + c * d[0]) * scale,
        (own[1] + c * d[1]) * scale,
        (own[2] + c * d[2]) * scale,
    ];
    (n, scale)
}
