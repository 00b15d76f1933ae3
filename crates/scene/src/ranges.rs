//! The ranges scenes allow for the Gödel parameter and for coordinates ([`A_RANGE`],
//! [`MAX_COORDINATE_PER_A`]), as checks of values given outside a scene file: the command
//! line's `--a` and events (`godel geodesic`, `connect`, `plot`), the Python module's
//! arguments. The messages name no flag or keyword (the caller does).

use crate::{short, A_RANGE, MAX_COORDINATE_PER_A};

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
}
