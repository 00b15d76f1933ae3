//! Colour encoding: linear RGB ↔ sRGB with the standard piecewise sRGB transfer function
//! (IEC 61966-2-1), and conversion to 8-bit with rounding. Values are clamped to [0, 1]
//! before encoding; NaN counts as 0.
//!
//! Pictures for display (PNG) pass shaded colours through [`tone_map`] first: linear up to
//! the knee [`TONE_KNEE`] = 0.8, and above it a rational shoulder
//! `k + (1 − k)·y/(1 + y)`, y = (x − k)/(1 − k), which is continuous with slope 1 at the
//! knee and approaches 1 without reaching it (a film-like highlight roll-off: the
//! x/(1 + x) form of Reinhard et al., "Photographic tone reproduction for digital images",
//! SIGGRAPH 2002, applied above the knee only). Nothing below 0.8 changes, 1.0
//! becomes 0.9, and 8-bit white (255) needs x ≥ 9.6 (ten times white), so lit highlights keep their gradation
//! instead of clipping. Applied per channel to hit pixels; the status colours (failed, not
//! traced) are display codes and skip it.

/// The knee of [`tone_map`]: values up to it are shown unchanged.
pub const TONE_KNEE: f32 = 0.8;

/// The display tone curve of the module doc: identity up to [`TONE_KNEE`], a rational shoulder
/// above it toward 1 (∞ → 1, NaN → 0, negative values unchanged for the encoder to clamp).
pub fn tone_map(x: f32) -> f32 {
    if x.is_nan() {
        return 0.0;
    }
    if x <= TONE_KNEE {
        return x;
    }
    if x.is_infinite() {
        return 1.0;
    }
    let y = (x - TONE_KNEE) / (1.0 - TONE_KNEE);
    TONE_KNEE + (1.0 - TONE_KNEE) * (y / (1.0 + y))
}

/// A shaded linear colour, scaled by `gain` (2^ev), as displayed: tone-mapped, 8-bit sRGB
/// (through [`linear_to_srgb8_fast`]).
#[inline]
pub fn display_srgb8(c: [f32; 3], gain: f32) -> [u8; 3] {
    c.map(|x| linear_to_srgb8_fast(tone_map(x * gain)))
}

/// Encodes one linear component as sRGB in [0, 1] (clamped; NaN → 0).
///
/// `12.92·x` for x ≤ 0.0031308, else `1.055·x^(1/2.4) − 0.055`.
pub fn linear_to_srgb(x: f32) -> f32 {
    let x = clamp01(x);
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// Decodes one sRGB component in [0, 1] to linear (clamped; NaN → 0).
///
/// `s/12.92` for s ≤ 0.04045, else `((s + 0.055)/1.055)^2.4`.
pub fn srgb_to_linear(s: f32) -> f32 {
    let s = clamp01(s);
    if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// One linear component as an 8-bit sRGB value, rounded to nearest.
pub fn linear_to_srgb8(x: f32) -> u8 {
    (linear_to_srgb(x) * 255.0).round() as u8
}

/// A linear RGB colour as 8-bit sRGB.
pub fn rgb_to_srgb8(c: [f32; 3]) -> [u8; 3] {
    [
        linear_to_srgb8(c[0]),
        linear_to_srgb8(c[1]),
        linear_to_srgb8(c[2]),
    ]
}

/// An 8-bit sRGB value decoded to linear.
pub fn srgb8_to_linear(s: u8) -> f32 {
    srgb_to_linear(f32::from(s) / 255.0)
}

/// Clamps to [0, 1]; NaN → 0.
pub fn clamp01(x: f32) -> f32 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(0.0, 1.0)
    }
}

/// The linear values at which 8-bit sRGB steps from k to k + 1: the sRGB decoding of
/// (k + ½)/255, k = 0..254.
fn srgb8_thresholds() -> &'static [f32; 255] {
    static TABLE: std::sync::OnceLock<[f32; 255]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|k| srgb_to_linear((k as f32 + 0.5) / 255.0)))
}

/// Smallest value the fast encoder looks up; below it every value encodes to 0 (the first
/// step is at 1.5e-4).
const FAST_MIN: f32 = 1.0 / 8192.0;
/// Bits of the f32 pattern dropped to form a bin: 7 mantissa bits remain, 128 bins per
/// octave, each at most 0.78 % wide, narrower than the gap between two step thresholds (at
/// least 0.89 %, near 1), so no bin holds two thresholds (`bins_hold_one_threshold_at_most`
/// checks it). 1664 bins, 13 KB: the table stays in L1 cache while records stream past.
const FAST_SHIFT: u32 = 16;

/// Per bin of the f32 bit pattern over [FAST_MIN, 1): the 8-bit value at the bin's low end
/// and the threshold inside the bin where it steps up by one (∞ if none), so that the lookup
/// is exact with respect to [`srgb8_thresholds`]; then one more entry for values from 1 on,
/// (255, NaN): no value, ∞ included, steps past 255.
fn srgb8_bins() -> &'static [(u8, f32)] {
    static TABLE: std::sync::OnceLock<Vec<(u8, f32)>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let th = srgb8_thresholds();
        let first = FAST_MIN.to_bits() >> FAST_SHIFT;
        let last = 1.0f32.to_bits() >> FAST_SHIFT;
        (first..last)
            .map(|bin| {
                let lo = f32::from_bits(bin << FAST_SHIFT);
                let hi = f32::from_bits((bin + 1) << FAST_SHIFT);
                let k = th.partition_point(|&t| t <= lo);
                let step = th
                    .get(k)
                    .copied()
                    .filter(|&t| t < hi)
                    .unwrap_or(f32::INFINITY);
                (k as u8, step)
            })
            .chain([(255, f32::NAN)])
            .collect()
    })
}

/// [`linear_to_srgb8`] without a power function or a search: a table over the f32 bit
/// pattern whose bins each hold at most one step threshold. Exact with respect to the step
/// thresholds (the sRGB decoding of (k + ½)/255), so it agrees with [`linear_to_srgb8`]
/// except, at most by one step, for values within float rounding of a threshold; NaN → 0.
#[inline]
pub fn linear_to_srgb8_fast(x: f32) -> u8 {
    srgb8_lookup(srgb8_bins(), x)
}

/// [`linear_to_srgb8_fast`] of every value of `values` into `out` (the table fetched once).
pub fn linear_to_srgb8_row(values: &[f32], out: &mut [u8]) {
    let bins = srgb8_bins();
    for (o, &x) in out.iter_mut().zip(values) {
        *o = srgb8_lookup(bins, x);
    }
}

/// The lookup of [`linear_to_srgb8_fast`] in `bins` ([`srgb8_bins`]), without branches on
/// the value: NaN becomes 0; the bin index is clamped to the table, so that values below
/// [`FAST_MIN`] (negative ones included: their bit pattern is negative as i32) fall in the
/// first bin, which steps nowhere (0), and values from 1 on in the last entry (255).
#[inline(always)]
fn srgb8_lookup(bins: &[(u8, f32)], x: f32) -> u8 {
    let x = if x.is_nan() { 0.0 } else { x };
    let first = (FAST_MIN.to_bits() >> FAST_SHIFT) as i32;
    let bin = ((x.to_bits() as i32) >> FAST_SHIFT) - first;
    let last = bins.len().saturating_sub(1);
    let bin = (bin.max(0) as usize).min(last);
    match bins.get(bin) {
        Some(&(k, step)) => k + u8::from(x >= step),
        None => 0,
    }
}

/// A linear RGB colour as 8-bit sRGB through [`linear_to_srgb8_fast`].
#[inline]
pub fn rgb_to_srgb8_fast(c: [f32; 3]) -> [u8; 3] {
    c.map(linear_to_srgb8_fast)
}

#[cfg(test)]
mod fast_tests {
    use super::*;

    #[test]
    fn tone_curve_is_identity_below_the_knee_smooth_and_below_white() {
        for x in [0.0f32, 0.1, 0.5, 0.8] {
            assert_eq!(tone_map(x), x);
        }
        assert!((tone_map(1.0) - 0.9).abs() < 1e-6);
        // Slope 1 on both sides of the knee (C¹).
        let h = 1e-3f32;
        let slope = (tone_map(TONE_KNEE + h) - tone_map(TONE_KNEE)) / h;
        assert!((slope - 1.0).abs() < 5e-3, "{slope}");
        // Strictly increasing and below 1; 8-bit white only from 9.6 on.
        let mut last = 0.0;
        for k in 1..2000 {
            let x = k as f32 * 0.05;
            let y = tone_map(x);
            assert!(y > last && y < 1.0, "{x}");
            last = y;
        }
        assert!(linear_to_srgb8(tone_map(9.5)) < 255);
        assert_eq!(linear_to_srgb8(tone_map(9.7)), 255);
        assert_eq!(tone_map(f32::INFINITY), 1.0);
        assert_eq!(tone_map(f32::NAN), 0.0);
    }

    #[test]
    fn bins_hold_one_threshold_at_most() {
        let th = srgb8_thresholds();
        let first = FAST_MIN.to_bits() >> FAST_SHIFT;
        let last = 1.0f32.to_bits() >> FAST_SHIFT;
        for bin in first..last {
            let lo = f32::from_bits(bin << FAST_SHIFT);
            let hi = f32::from_bits((bin + 1) << FAST_SHIFT);
            let n = th.iter().filter(|&&t| t > lo && t < hi).count();
            assert!(n <= 1, "bin {bin} [{lo}, {hi}) holds {n} thresholds");
        }
    }

    #[test]
    fn fast_encoder_steps_at_the_thresholds() {
        let th = srgb8_thresholds();
        // Every f32 from 0 to 1 in steps of 2^7 ulps, plus both sides of every threshold.
        let mut xs: Vec<f32> = (0..=1.0f32.to_bits())
            .step_by(128)
            .map(f32::from_bits)
            .collect();
        for &t in th.iter() {
            xs.extend([
                t,
                f32::from_bits(t.to_bits() - 1),
                f32::from_bits(t.to_bits() + 1),
            ]);
        }
        for x in xs {
            let exact = th.partition_point(|&t| t <= x) as u8;
            let exact = if x < FAST_MIN { 0 } else { exact };
            assert_eq!(linear_to_srgb8_fast(x), exact, "{x}");
        }
    }
}
