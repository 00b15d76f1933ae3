//! How numbers are written in messages, the same in every crate's refusals (scene files,
//! command-line values, the Python module's arguments).

/// `v` as messages show it: plainly where that is short (`0.25`, `-6`), else in scientific
/// notation (`1e300`, `-2.5e-9`), never the 300 digits of a plain `1e300`.
pub fn short(v: f64) -> String {
    let magnitude = v.abs();
    if v.is_finite() && magnitude != 0.0 && !(1e-4..1e6).contains(&magnitude) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::short;

    #[test]
    fn numbers_in_messages_stay_short() {
        assert_eq!(short(1e300), "1e300");
        assert_eq!(short(-2.5e-9), "-2.5e-9");
        assert_eq!(short(0.25), "0.25");
        assert_eq!(short(-6.0), "-6");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(f64::NAN), "NaN");
    }
}
