//! The arctangent of a direction and the arccosine by polynomials, within [`ERROR`] of the
//! exact angle: for the arcs of a ray's circle near a point (`crate::circle`), which are
//! widened by that error, so they stay conservative (docs/physics.md, "Whole-ray rejection":
//! "The arcs' angles"). ~38 instructions an arc where glibc's correctly rounded atan2 and
//! acos took ~228.
//!
//! atan t = t·P(t²) on [0, 1] and acos x = √(1 − x)·Q(x) on [0, 1], P and Q of degree 9,
//! fitted to the absolute error (iteratively reweighted least squares on Chebyshev nodes);
//! other arguments by the identities atan t = π/2 − atan(1/t) and acos(−x) = π − acos x.
//! Largest errors measured on 4 million points: 8.9e-10 for atan, 2.7e-10 for acos.

use std::f64::consts::{FRAC_PI_2, PI};

/// The largest error of [`atan2`] and [`acos`] (radians), checked by the unit tests.
pub const ERROR: f64 = 1e-9;

/// P: atan t ≈ t·P(t²) on [0, 1].
const ATAN: [f64; 10] = [
    0.999999980559045,
    -0.333331803690013,
    0.1999643667018665,
    -0.1424722151199304,
    0.10878004792819895,
    -0.08213748444639543,
    0.055027894761891724,
    -0.028490585574467278,
    0.009567244166945904,
    -0.0015092827835656297,
];

/// Q: acos x ≈ √(1 − x)·Q(x) on [0, 1].
const ACOS: [f64; 10] = [
    1.5707963265282705,
    -0.21460177392486024,
    0.08904620425606506,
    -0.05075657216016983,
    0.033402777489634,
    -0.023117915339055137,
    0.015072892873049856,
    -0.007969916581352259,
    0.0028157074463425174,
    -0.00047417367482936734,
];

fn horner(c: &[f64; 10], u: f64) -> f64 {
    c.iter().rev().fold(0.0, |r, &k| r * u + k)
}

/// The angle of (x, y) in (−π, π], within [`ERROR`] of `f64::atan2` (NaN at the origin and
/// for NaN).
pub fn atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ay > ax;
    let t = if steep { ax / ay } else { ay / ax };
    let a = t * horner(&ATAN, t * t);
    let a = if steep { FRAC_PI_2 - a } else { a };
    let a = if x < 0.0 { PI - a } else { a };
    a.copysign(y)
}

/// The arccosine of x in [−1, 1], within [`ERROR`] of `f64::acos` (NaN outside and for NaN).
pub fn acos(x: f64) -> f64 {
    let ax = x.abs();
    let a = (1.0 - ax).sqrt() * horner(&ACOS, ax);
    if x < 0.0 {
        PI - a
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every direction (a million angles round the circle, at lengths from 1e-300 to 1e300)
    /// within ERROR of the correctly rounded angle; the axes and the signs of zero as
    /// atan2's; the origin and NaN give NaN.
    #[test]
    fn atan2_is_within_its_error_everywhere() {
        let mut worst = 0.0f64;
        for i in 0..1_000_000 {
            let theta = -PI + 2.0 * PI * (i as f64 + 0.5) / 1e6;
            let r = 10f64.powi((i % 601) - 300);
            let (y, x) = (r * theta.sin(), r * theta.cos());
            let err = (atan2(y, x) - y.atan2(x)).abs();
            worst = worst.max(err.min(2.0 * PI - err));
        }
        assert!(worst <= ERROR, "largest error {worst:e}");
        assert!(
            worst > 0.1 * ERROR,
            "largest error {worst:e}: the bound is loose"
        );
        for (y, x) in [
            (0.0, 1.0),
            (1.0, 0.0),
            (0.0, -1.0),
            (-1.0, 0.0),
            (-0.0, 1.0),
        ] {
            assert_eq!(atan2(y, x).to_bits(), y.atan2(x).to_bits(), "({x}, {y})");
        }
        assert!((atan2(-0.0, -1.0) + PI).abs() <= ERROR);
        assert!(atan2(0.0, 0.0).is_nan() && atan2(f64::NAN, 1.0).is_nan());
    }

    /// [−1, 1] on four million points within ERROR of the correctly rounded arccosine; NaN
    /// outside.
    #[test]
    fn acos_is_within_its_error_everywhere() {
        let mut worst = 0.0f64;
        for i in 0..=4_000_000 {
            let x = -1.0 + 2.0 * i as f64 / 4e6;
            worst = worst.max((acos(x) - x.acos()).abs());
        }
        assert!(worst <= ERROR, "largest error {worst:e}");
        assert!(
            worst > 0.1 * ERROR,
            "largest error {worst:e}: the bound is loose"
        );
        assert!(acos(1.5).is_nan() && acos(f64::NAN).is_nan());
    }
}
