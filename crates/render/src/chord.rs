//! Chord exclusion: a light ray near a local ball, seen in the ball's rest frame, is nearly
//! a straight line, so two probes can rule out a graze that the rate bound alone would
//! bisect many times (docs/physics.md, "The intersection search", "Chord exclusion").
//!
//! Along a span [λ_a, λ_b] of length h, let ξ(λ) be the ray point's rest-frame coordinates
//! (the renderer's, second-order normal coordinates at the simultaneous centre). If
//! |ξ''| ≤ K on the span, the straight chord from ξ(λ_a) to ξ(λ_b) stays within
//! K·(λ − λ_a)(λ_b − λ)/2 ≤ K·h²/8 of the path (the interpolation error of a C² curve). So
//! a ball |ξ| ≤ R is not crossed when the chord passes farther than R + K·h²/8 from the
//! centre, or when both ends lie deeper inside than K·h²/8.
//!
//! K in Gödel's universe, for a photon of static energy E and a ball whose speed factor is
//! s = γ(1 + v) (the photon's energy in the ball's frame is at most E·s): the static frame
//! of a ball at rest turns against gyroscopes at the vorticity Ω = 1/(√2 a), a Coriolis
//! bend of 2ΩE² = √2·E²/a; a falling ball's frame does not turn, and its bend comes from the
//! curvature and the second-order coordinates, which grow with the boost and the distance
//! from the centre, and which do not vanish for a slow ball. Measured over random balls and
//! rays (docs/physics.md; the property test in tests/integration/chord.rs prints the table),
//! at most (1.9 at rest; 0.35 below 0.05 c, 3.7 at 0.7 c, 18 at 0.8 c, within 0.5a)·(E·s)²/a,
//! where K = (3.25·[at rest] + 0.75·[falling] + s⁴·ρ/a)·e²/a allows at least twice that
//! (ρ: the span's reach from the centre) with e = E·s. Beyond 0.8 c the second-order match
//! can jump between roots, and the test is not used.
//!
//! The bend is quadratic in the photon's momentum (the path does not depend on how λ is
//! scaled), so a falling ball may take a smaller e than E·s, from the probes themselves:
//! 2·max(ε_a, ε_b), ε = |p·u| at each end (the ray's momentum against the centre's four
//! velocity, the photon's energy in the ball's frame to first order). In the same test, the
//! spans that take it stray at most half the bound down to a margin of 1.3 (0.49 of it).

/// The fastest ball the test is used for: speed factor γ(1 + v) = 3 (v = 0.8).
const MAX_SPEED_FACTOR: f64 = 3.0;

/// Both ends of a span lie within this rest-frame distance of the centre (in units of a)…
const MAX_END_DISTANCE: f64 = 0.4;

/// …and the path strays at most this far from their chord (in units of a): so the whole
/// span lies within 0.45a, where the bend was measured.
const MAX_STRAY: f64 = 0.05;

/// The bend at rest, 2ω = √2/a for the Coriolis term, with room for the tidal terms (in
/// units of (E·s)²/a; 3 left a margin of 1.9).
const BEND_AT_REST: f64 = 3.25;

/// The bend of a falling ball that does not vanish with its speed, from the tidal terms and
/// the second-order coordinates (in units of (E·s)²/a): up to 0.35 for slow balls, where
/// s⁴·ρ/a alone tends to ρ/a (a margin of 1.3 at 0.45a).
const BEND_FALLING: f64 = 0.75;

/// Added to the bound for the match's own noise (in units of a): the secant method stops
/// within 1e-9 a of the simultaneity, at points that differ from probe to probe, which moves
/// ξ by up to ~3e-9 a at 0.8 c.
const NOISE: f64 = 1e-8;

/// A falling ball's bend takes the photon's energy in its frame as this many times the
/// larger of the span's ends' |p·u|: the property test's paths stay within half the bound
/// down to 1.3 (at 1.0 one strays beyond).
pub const LOCAL_ENERGY_MARGIN: f64 = 2.0;

/// The photon's energy in the ball's frame that the bend takes, for a photon of static energy
/// `energy` and a ball of speed factor `speed_factor`: E·s; for a falling ball at most
/// [`LOCAL_ENERGY_MARGIN`] times the larger of the span's ends' |p·u| (`ends`; where either
/// is unknown, NaN: E·s).
pub fn photon_energy(at_rest: bool, speed_factor: f64, energy: f64, ends: (f64, f64)) -> f64 {
    let global = energy * speed_factor;
    // Both ends, or neither: f64::max would drop a NaN.
    let local = if ends.0.is_finite() && ends.1.is_finite() {
        LOCAL_ENERGY_MARGIN * ends.0.max(ends.1)
    } else {
        f64::NAN
    };
    if !at_rest && local < global {
        local
    } else {
        global
    }
}

/// How far, at most, the ray's rest-frame path strays from the chord of a span of length
/// `h` whose ends lie within `end_distance` of the centre of a ball (`at_rest`, or falling
/// with speed factor `speed_factor`) in Gödel's universe with parameter `a`, for a photon of
/// energy at most `e` in the ball's frame ([`photon_energy`]). None where the test does not
/// apply (too fast, too far, too long a span).
pub fn stray(
    a: f64,
    at_rest: bool,
    speed_factor: f64,
    e: f64,
    end_distance: f64,
    h: f64,
) -> Option<f64> {
    if !(speed_factor <= MAX_SPEED_FACTOR && end_distance <= MAX_END_DISTANCE * a) {
        return None;
    }
    let reach = end_distance + MAX_STRAY * a;
    let turn = if at_rest { BEND_AT_REST } else { BEND_FALLING };
    let bend = (turn + speed_factor.powi(4) * reach / a) * e * e / a;
    let stray = bend * h * h / 8.0 + NOISE * a;
    (stray <= MAX_STRAY * a).then_some(stray)
}

/// Whether a ball of radius `radius` centred at the origin cannot be crossed on a span
/// whose path runs within `stray` of the chord between its ends, each given by its
/// rest-frame coordinates ξ and its probe's f = |ξ| − R (both outside, or both inside).
pub fn excludes(
    radius: f64,
    (xa, fa): ([f64; 3], f64),
    (xb, fb): ([f64; 3], f64),
    stray: f64,
) -> bool {
    if fa > 0.0 && fb > 0.0 {
        // The chord's point nearest the centre.
        let d = [xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]];
        let dd = dot(d, d);
        let s = if dd > 0.0 {
            (-dot(xa, d) / dd).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let c = [xa[0] + s * d[0], xa[1] + s * d[1], xa[2] + s * d[2]];
        dot(c, c).sqrt() - stray > radius
    } else if fa <= 0.0 && fb <= 0.0 {
        // The chord lies inside with its ends (the ball is convex).
        fa.max(fb) + stray <= 0.0
    } else {
        false
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chord that passes the centre at distance d: excluded exactly while d − stray > R.
    #[test]
    fn a_chord_is_excluded_only_with_room_for_its_stray() {
        let (r, stray) = (0.2, 0.01);
        let end = |x: [f64; 3]| (x, dot(x, x).sqrt() - r);
        let excl = |xa, xb, stray| excludes(r, end(xa), end(xb), stray);
        for (d, want) in [(0.25, true), (0.2105, true), (0.2095, false), (0.15, false)] {
            assert_eq!(excl([-0.5, d, 0.0], [0.5, d, 0.0], stray), want, "d = {d}");
        }
        // The nearest point is an end when the chord points away.
        assert!(excl([0.0, 0.3, 0.0], [0.0, 0.6, 0.0], 0.05));
        // Inside: both ends deep enough.
        assert!(excl([0.05, 0.0, 0.0], [0.0, 0.1, 0.0], 0.05));
        assert!(!excl([0.05, 0.0, 0.0], [0.0, 0.16, 0.0], 0.05));
        // One end inside, one outside: a crossing, never excluded.
        assert!(!excl([0.0, 0.1, 0.0], [0.0, 0.3, 0.0], 0.0));
    }

    /// The bound refuses fast balls, far ends and long spans.
    #[test]
    fn the_bound_applies_only_where_it_was_measured() {
        assert!(stray(1.0, false, 2.38, 2.38, 0.3, 0.01).is_some());
        assert!(stray(1.0, false, 3.5, 3.5, 0.3, 0.01).is_none());
        assert!(stray(1.0, false, 2.38, 2.38, 0.41, 0.01).is_none());
        assert!(stray(1.0, false, 2.38, 2.38, 0.3, 1.0).is_none());
        assert!(stray(1.0, true, 1.0, 1.0, f64::NAN, 0.01).is_none());
        // The static frame turns: at rest the bound is larger.
        assert!(stray(1.0, true, 1.0, 1.0, 0.1, 0.01) > stray(1.0, false, 1.0, 1.0, 0.1, 0.01));
    }

    /// A falling ball takes its ends' energy where that is the smaller bound; a ball at rest,
    /// and a span with an end without one (NaN), take E·s.
    #[test]
    fn a_falling_ball_takes_the_smaller_energy() {
        assert_eq!(photon_energy(false, 2.0, 1.0, (0.25, 0.1)), 0.5);
        assert_eq!(photon_energy(false, 2.0, 1.0, (0.1, 1.5)), 2.0);
        assert_eq!(photon_energy(false, 2.0, 1.0, (0.1, f64::NAN)), 2.0);
        assert_eq!(photon_energy(false, 2.0, 1.0, (f64::NAN, 0.1)), 2.0);
        assert_eq!(photon_energy(true, 1.0, 1.0, (0.25, 0.25)), 1.0);
    }
}
