//! The polarization of a pixel's light, in the frames where it is measured
//! (docs/physics.md, "Polarization").
//!
//! A light ray's polarization vector f (f·k = 0, f·f = 1, defined modulo the tangent k) is
//! parallel-transported along the ray. An observer measures it by its representative
//! orthogonal to its four-velocity, a unit vector orthogonal to the photon's direction: the
//! spatial part of f's frame components minus their part along the direction (with
//! f·k = 0 the two differ by exactly a multiple of k). The data file's `pol` is the
//! observer's *screen-up* (the camera's up projected orthogonal to the pixel's direction)
//! carried back to the emitter and measured there ([`measured`]); what an emitter polarized
//! along e sends is then seen at the angle χ = atan2(e·(pol × dir), e·pol) from screen-up
//! towards screen-right, since transport keeps inner products and handedness. Between two observers
//! at one event the screen-up of one is the other's turned about the photon
//! ([`look_rotation`]).
//!
//! Plain 3-vectors in an orthonormal frame's spatial axes (right-handed); no metric here.

use crate::frame::LocalVelocity;

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a × b.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The part of `v` orthogonal to the unit vector `n`, normalized; `None` where `v` is along
/// `n` (to 1e-9) or not finite.
pub fn orthogonal_unit(v: [f64; 3], n: [f64; 3]) -> Option<[f64; 3]> {
    let a = dot(v, n);
    let w = [v[0] - a * n[0], v[1] - a * n[1], v[2] - a * n[2]];
    let len = dot(w, w).sqrt();
    (len > 1e-9 && len.is_finite()).then(|| w.map(|c| c / len))
}

/// The screen-up direction of a pixel looking along the unit vector `n`: the camera's `up`
/// projected orthogonal to `n`, normalized. Where `n` is along `up` (a sphere's poles, never
/// a pixel centre), `forward` projected instead.
pub fn screen_up(up: [f64; 3], forward: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    orthogonal_unit(up, n)
        .or_else(|| orthogonal_unit(forward, n))
        .unwrap_or(up)
}

/// The screen-right direction n × s of a pixel looking along `n` with screen-up `s`: the
/// camera's right at the pixel (at the image centre, forward × up).
pub fn screen_right(n: [f64; 3], s: [f64; 3]) -> [f64; 3] {
    cross(n, s)
}

/// The record's `pol` from the frame components (v⁰, v¹, v², v³) of the pixel's screen-up
/// `f` and screen-right `r`, both transported to the emitter, for a photon travelling along
/// the unit direction `dir` in that frame. Each is measured by its representative orthogonal
/// to the four-velocity, its spatial part minus its part along `dir` (with v·k = 0 the two
/// differ by a multiple of k): a and b. Transport is an isometry that keeps handedness, so
/// b = a × dir; where the frame is only approximately the emitter's at the hit (a local
/// object's, carried there to first order) the two differ slightly, and `pol` is the
/// rotation part of the map from the screen: a + dir × b, normalized (= a where exact), so
/// that pol × dir is the screen-right's image and every screen direction turns alike.
/// `None` where that vanishes.
pub fn measured(f: [f64; 4], r: [f64; 4], dir: [f64; 3]) -> Option<[f64; 3]> {
    let across = |v: [f64; 4]| {
        let w = [v[1], v[2], v[3]];
        let a = dot(w, dir);
        [0, 1, 2].map(|i| w[i] - a * dir[i])
    };
    let (a, b) = (across(f), across(r));
    let c = cross(dir, b);
    orthogonal_unit([a[0] + c[0], a[1] + c[1], a[2] + c[2]], dir)
}

/// The angle χ (radians, in (−π, π]) from screen-up towards screen-right at which the
/// observer sees the polarization of light sent polarized along `axis` (the emitter's body
/// axes), given the record's `pol` and `dir`; `None` where `axis` is along `dir` (no
/// polarization in that direction). The polarization is a line: χ and χ + π are the same.
pub fn observed_angle(pol: [f64; 3], dir: [f64; 3], axis: [f64; 3]) -> Option<f64> {
    let e = orthogonal_unit(axis, dir)?;
    let (c, s) = (dot(e, pol), dot(e, cross(pol, dir)));
    Some(s.atan2(c))
}

/// Between two observers at one event (docs/physics.md, "Observers at one event"): the
/// screen-up of a pixel of an observer moving with `velocity` relative to the static one, the
/// pixel looking along `own` (its own frame) with camera axes `up`, `forward`, as (cos ψ,
/// sin ψ) in the static observer's screen basis (s, n × s) for the same photon, which the
/// static observer sees along `n` with camera axes `up0`, `forward0`.
///
/// The moving observer's screen-up s′ is the four-vector s′ⁱ eᵢ′ of its boosted frame:
/// (γ v (v̂·s′), s′ + (γ − 1)(v̂·s′) v̂) in the static frame. Modulo the photon's k ∝
/// (1, −n), its representative without a time component is s′ + (γ − 1)(v̂·s′) v̂ +
/// γ v (v̂·s′) n, orthogonal to n.
pub fn look_rotation(
    velocity: LocalVelocity,
    own: [f64; 3],
    up: [f64; 3],
    forward: [f64; 3],
    n: [f64; 3],
    up0: [f64; 3],
    forward0: [f64; 3],
) -> (f64, f64) {
    let s1 = screen_up(up, forward, own);
    let (g, v, d) = (velocity.gamma(), velocity.speed, velocity.direction);
    let along = dot(d, s1);
    let f = [0, 1, 2].map(|i| s1[i] + (g - 1.0) * along * d[i] + g * v * along * n[i]);
    let s0 = screen_up(up0, forward0, n);
    let (c, s) = (dot(f, s0), dot(f, screen_right(n, s0)));
    let len = c.hypot(s);
    if len > 0.0 && len.is_finite() {
        (c / len, s / len)
    } else {
        (1.0, 0.0)
    }
}

/// The record's `pol` for a pixel whose screen-up is (cos ψ, sin ψ) in the screen basis of the
/// pixel that traced `pol` ([`look_rotation`]): transport is linear and keeps handedness, so
/// that pixel's screen-right arrives as pol × dir.
pub fn turned(pol: [f64; 3], dir: [f64; 3], (c, s): (f64, f64)) -> [f64; 3] {
    let r = cross(pol, dir);
    [0, 1, 2].map(|i| c * pol[i] + s * r[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn screen_up_is_up_at_the_centre_and_orthogonal_elsewhere() {
        let (f, u) = ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        assert_eq!(screen_up(u, f, f), u);
        // right = forward × up at the centre.
        assert_eq!(screen_right(f, u), cross(f, u));
        let n = [0.6, 0.0, 0.8];
        let s = screen_up(u, f, n);
        assert!(dot(s, n).abs() < 1e-15 && (dot(s, s) - 1.0).abs() < 1e-15);
        assert!(s[2] > 0.0 && s[0] < 0.0, "tilted back: {s:?}");
        // Straight up: forward's projection (never a pixel centre).
        assert_eq!(screen_up(u, f, u), f);
    }

    #[test]
    fn measured_is_the_rotation_part_of_the_screen_map() {
        let dir = [0.0, 0.0, 1.0];
        // Exact: b = a × dir, with parts along k (time and dir components) that drop out.
        let (a, b) = ([0.6, 0.8, 0.0], cross([0.6, 0.8, 0.0], dir));
        let p = measured([0.3, a[0], a[1], 0.3], [-0.2, b[0], b[1], -0.2], dir).unwrap();
        assert!(max_diff(p, a) < 1e-15, "{p:?}");
        // A map that keeps the screen-up a = (1, 0, 0) but stretches the screen-right
        // (exactly a × dir = (0, −1, 0)) by 2 % and turns it by 0.01 rad towards a: pol is
        // their rotation part, turned by about half of that, atan(1.02 sin 0.01 / (1 + 1.02
        // cos 0.01)) = 0.00505.
        let (s, c) = (0.01f64).sin_cos();
        let right = [1.02 * s, -1.02 * c, 0.0];
        let p = measured([0.0, 1.0, 0.0, 0.0], [0.0, right[0], right[1], 0.0], dir).unwrap();
        let turn = p[1].atan2(p[0]);
        let expected = (1.02 * s).atan2(1.0 + 1.02 * c);
        assert!((turn - expected).abs() < 1e-15, "turned by {turn}");
        assert!((expected - 0.00505).abs() < 1e-5);
    }

    fn max_diff(a: [f64; 3], b: [f64; 3]) -> f64 {
        (0..3).fold(0.0, |m, i| f64::max(m, (a[i] - b[i]).abs()))
    }

    #[test]
    fn the_angle_turns_with_the_axis_and_is_a_line() {
        let (pol, dir) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        // pol × dir = (0, 1, 0): the axis there is a quarter turn.
        assert!(observed_angle(pol, dir, pol).unwrap().abs() < 1e-15);
        let q = observed_angle(pol, dir, [0.0, 1.0, 0.0]).unwrap();
        assert!((q - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        // An axis with a part along the photon: only its projection counts.
        let t = observed_angle(pol, dir, [5.0, 1.0, 1.0]).unwrap();
        assert!((t - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
        assert!(observed_angle(pol, dir, dir).is_none());
    }

    #[test]
    fn at_rest_the_same_camera_turns_nothing() {
        let (f, u) = ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        let n = [0.36, 0.48, 0.8];
        let (c, s) = look_rotation(LocalVelocity::REST, n, u, f, n, u, f);
        assert!((c - 1.0).abs() < 1e-15 && s.abs() < 1e-15);
        // A camera rolled by 30° about the pixel's direction turns it by 30°.
        let roll = 30f64.to_radians();
        let (s0, r0) = (screen_up(u, f, n), screen_right(n, screen_up(u, f, n)));
        let up = [0, 1, 2].map(|i| roll.cos() * s0[i] + roll.sin() * r0[i]);
        let (c, s) = look_rotation(LocalVelocity::REST, n, up, f, n, u, f);
        assert!((s.atan2(c) - roll).abs() < 1e-12);
    }
}
