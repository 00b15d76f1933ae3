//! The ranges scenes allow for the Gödel parameter and for coordinates ([`A_RANGE`],
//! [`MAX_COORDINATE_PER_A`]), and for the constants of a Gödel-type member and how far from
//! its axis an event may lie ([`MAX_M2_PER_OMEGA2`], [`MAX_M_RHO`]), as checks of values
//! given outside a scene file: the command line's `--a`, `--m2`, `--omega` and events
//! (`godel geodesic`, `connect`, `plot`), the Python module's arguments. The messages name
//! no flag or keyword (the caller does).

use crate::{short, A_RANGE, MAX_COORDINATE_PER_A};
use spacetime::GodelType;

/// Largest |m²|/Ω² of a Gödel-type member: the family's character (causal or not, shells)
/// is decided at m² of the order of Ω² (m² = 4Ω² is the causal boundary).
pub const MAX_M2_PER_OMEGA2: f64 = 100.0;

/// Largest mρ of a position in a Gödel-type member with m² > 0 where the coordinates still
/// hold (Gödel's own bound, 1e6·a of its radius r = 2a sinh(ρ/2a), is mρ ≈ 29): the bound of
/// single geodesics and shadow rays (`crate::ranges`). Scenes are bounded tighter,
/// [`MAX_SCENE_M_RHO`].
pub const MAX_M_RHO: f64 = 30.0;

/// Largest mρ of a scene's position (observer, objects) in a Gödel-type member with m² > 0:
/// what both tracers trace. Measured with a ball at rest and a falling one beside an
/// observer at mρ = 4 … 12 (m²/Ω² = 2, 4, 6; render's exact and numeric tracers): the exact
/// tracer carries each pixel's tangent to the observer's origin frame, where it is null only
/// to ~e^{mρ}·1e-16 of E², past the closed form's tolerance 1e-12 from mρ ≈ 9 (it failed 69
/// of 100 rays at mρ = 10 for m² = 6Ω², half the image at mρ = 12 for Gödel's member); the
/// numeric tracer failed from mρ = 12 (Gödel's member) and in the causal members spent its
/// step budget on some rays from mρ = 6 (m² = 6Ω²: 5 % of the pixels, 11 % at mρ = 8), whose
/// escape it can prove only once they are twice as far from the observer's axis.
pub const MAX_SCENE_M_RHO: f64 = 8.0;

/// How far from the axis a Gödel-type member's scene may reach, and why. m² > 0: the metric
/// grows as e^{mρ}, and beyond mρ = [`MAX_SCENE_M_RHO`] the tracers lose the digits they
/// need (its documentation). m² < 0:
/// the coordinates end at ρ = π/μ (the base's pole opposite the axis); every light ray and
/// free fall is a circle of diameter at most ρ_c on the base, so a scene within π/μ − ρ_c of
/// the axis never reaches that pole.
pub fn member_radius_limit(member: GodelType) -> Option<(f64, String)> {
    radius_limit(
        member,
        MAX_SCENE_M_RHO,
        "the tracers lose the precision of f64 they need",
    )
}

/// The largest distance from a member's axis, and why: mρ ≤ `max_m_rho` for m² > 0 (the
/// metric grows as e^{mρ}; `beyond` says what fails there), π/μ − ρ_c for m² = −μ² < 0;
/// none for m² = 0.
fn radius_limit(member: GodelType, max_m_rho: f64, beyond: &str) -> Option<(f64, String)> {
    if member.m2 > 0.0 {
        let limit = max_m_rho / member.m2.sqrt();
        let why = format!("the metric grows as e^(mρ), and beyond mρ = {max_m_rho} {beyond}");
        Some((limit, why))
    } else {
        let end = member.coordinate_radius()?;
        let rho_c = member.critical_radius()?;
        Some((end - rho_c, format!("rays from there could cross the pole opposite the axis at π/μ = {}, where the coordinates end (light and free falls stay within ρ_c = {} of where they pass)", crate::short(end), crate::short(rho_c))))
    }
}

/// Checks a Gödel parameter: positive and finite, within [`A_RANGE`].
pub fn check_a(a: f64) -> Result<f64, String> {
    if !(a.is_finite() && a > 0.0) {
        return Err(format!("must be positive and finite, got {}", short(a)));
    }
    let (lo, hi) = A_RANGE;
    if !(lo..=hi).contains(&a) {
        return Err(format!(
            "{} is outside [{lo:e}, {hi:e}], as in scenes (spacetime.a): the metric loses the \
             precision of f64 there",
            short(a)
        ));
    }
    Ok(a)
}

/// Checks coordinates (named `names`, e.g. `t`, `R`, `phi`, `z`): each within
/// ±[`MAX_COORDINATE_PER_A`]·a as in scenes (an angle `phi` within ±that number of radians).
pub fn check_coordinates(names: &[&str], values: &[f64], a: f64) -> Result<(), String> {
    for (name, &v) in names.iter().zip(values) {
        let bound = match *name {
            "phi" => MAX_COORDINATE_PER_A,
            _ => MAX_COORDINATE_PER_A * a,
        };
        if v.is_nan() || v.abs() > bound {
            return Err(format!(
                "{name} = {} is beyond ±{bound:e}, as in scenes (1e6 times the scale a): the \
                 tracer loses precision there",
                short(v)
            ));
        }
    }
    Ok(())
}

/// Checks a Gödel-type member's vorticity Ω: positive and finite, with Gödel's a of the same
/// vorticity, 1/(√2 Ω), within [`A_RANGE`] (as scenes' `spacetime.omega`).
pub fn check_omega(omega: f64) -> Result<f64, String> {
    if !(omega.is_finite() && omega > 0.0) {
        return Err(format!("must be positive and finite, got {}", short(omega)));
    }
    let a = 1.0 / (std::f64::consts::SQRT_2 * omega);
    if !(A_RANGE.0..=A_RANGE.1).contains(&a) {
        return Err(format!(
            "{} is outside [{:e}, {:e}] (1/(√2 Ω) must be within the range of Gödel's a): the \
             metric loses the precision of f64 there (choose the unit of length so that Ω is \
             moderate)",
            short(omega),
            1.0 / (std::f64::consts::SQRT_2 * A_RANGE.1),
            1.0 / (std::f64::consts::SQRT_2 * A_RANGE.0)
        ));
    }
    Ok(omega)
}

/// Checks a Gödel-type member's m² for the (checked) vorticity `omega`: finite, |m²| at most
/// [`MAX_M2_PER_OMEGA2`]·Ω² (as scenes' `spacetime.m2`).
pub fn check_m2(m2: f64, omega: f64) -> Result<f64, String> {
    if !m2.is_finite() {
        return Err(format!("must be finite, got {}", short(m2)));
    }
    let ratio = m2 / (omega * omega);
    if ratio.abs() > MAX_M2_PER_OMEGA2 {
        return Err(format!(
            "{} is {} Ω²; |m²| must be at most {MAX_M2_PER_OMEGA2} Ω² = {}: beyond, the \
             curvature scale 1/|m| is so much smaller than the vorticity's that the metric's \
             exponentials lose the precision of f64 within a few units of length",
            short(m2),
            short(ratio),
            short(MAX_M2_PER_OMEGA2 * omega * omega)
        ));
    }
    Ok(m2)
}

/// Checks the distance `rho` of an event from a member's axis, as scenes bound positions:
/// m² > 0: mρ at most [`MAX_M_RHO`] (the metric grows as e^{mρ}); m² = −μ² < 0: ρ at most
/// π/μ − ρ_c (light and free falls from there stay within ρ_c of it and cannot reach the
/// pole opposite the axis at ρ = π/μ, where the coordinates end).
pub fn check_member_radius(member: GodelType, rho: f64) -> Result<(), String> {
    let beyond = "it loses the precision of f64";
    match radius_limit(member, MAX_M_RHO, beyond) {
        Some((limit, why)) if rho.is_nan() || rho > limit => Err(format!(
            "R = {} is beyond {}, as in scenes: {why}",
            short(rho),
            short(limit)
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_and_coordinates_have_the_ranges_of_scenes() {
        assert_eq!(check_a(2.0), Ok(2.0));
        for bad in [1e-300, 1e300, 0.0, -1.0, f64::NAN] {
            assert!(check_a(bad).is_err_and(|e| e.len() < 200), "{bad}");
        }
        let names = ["t", "R", "phi", "z"];
        assert!(check_coordinates(&names, &[1e6, 0.5, -1e6, 0.0], 1.0).is_ok());
        assert_eq!(
            check_coordinates(&names, &[1e300, 0.0, 0.0, 0.0], 1.0).unwrap_err(),
            "t = 1e300 is beyond ±1e6, as in scenes (1e6 times the scale a): the tracer \
             loses precision there"
        );
        // Lengths scale with a; angles do not.
        assert!(check_coordinates(&names, &[0.0, 0.0, 0.0, 5e6], 10.0).is_ok());
        assert!(check_coordinates(&names, &[0.0, 0.0, 2e6, 0.0], 10.0).is_err());
        assert!(check_coordinates(&["x"], &[f64::NAN], 1.0).is_err());
    }

    #[test]
    fn members_have_the_ranges_of_scenes() {
        assert_eq!(check_omega(0.5), Ok(0.5));
        for bad in [0.0, -1.0, f64::NAN, 1e300, 1e-300] {
            assert!(check_omega(bad).is_err(), "{bad}");
        }
        assert_eq!(check_m2(-25.0, 0.5), Ok(-25.0));
        assert!(check_m2(25.1, 0.5)
            .unwrap_err()
            .starts_with("25.1 is 100.4 Ω²"));
        assert!(check_m2(f64::INFINITY, 0.5).is_err());
        // m² = 1: mρ ≤ 30.
        let member = GodelType::new(1.0, 0.5);
        assert!(check_member_radius(member, 30.0).is_ok());
        assert!(check_member_radius(member, 30.01).is_err());
        // m² = −1, Ω = 1/2: π/μ − ρ_c = π − 2 atan(1) = π/2.
        let member = GodelType::new(-1.0, 0.5);
        assert!(check_member_radius(member, 1.57).is_ok());
        assert!(check_member_radius(member, 1.58).is_err());
        assert!(check_member_radius(GodelType::new(0.0, 0.5), 1e5).is_ok());
    }
}
