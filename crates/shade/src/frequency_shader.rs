//! The frequency shader: shows each object as a black body of its own temperature T_k seen
//! with the pixel's frequency shift g, without re-tracing (docs/physics.md, "Black body and
//! colour").
//!
//! A black body at T seen with shift g = ν_obs/ν_emit is a black body at g·T (Planck's law
//! with the invariance of I_ν/ν³; see [`crate::blackbody`]), so a hit pixel of object k shows
//! the CIE 1931 colour of a black body at g·T_k, converted to sRGB (IEC 61966-2-1), read from
//! the lookup table [`crate::blackbody::table`]. A black body is a Lambertian emitter (its
//! radiance does not depend on direction), so there is no `cos_i` shading.
//!
//! | pixel | colour (linear sRGB) |
//! | --- | --- |
//! | hit object k, [`Brightness::Normalized`] | colour of g·T_k with its largest component 1 |
//! | hit object k, [`Brightness::Physical`] | `exposure · Y(g·T_k)/Y(T_k)` times the colour of g·T_k at luminance 1, tone-clamped |
//! | nothing hit | [`BACKGROUND`] |
//! | failed, step budget, not traced | as the texture shader ([`crate::texture_shader::FAILED`], [`crate::texture_shader::STEP_BUDGET`], [`crate::texture_shader::NOT_TRACED`]) |
//! | object without a temperature, T ≤ 0, or g not finite and positive | [`FAILED`] |
//!
//! Physical brightness is relative to each object's own unshifted luminance: an object seen
//! with g = 1 has luminance `exposure`, and a shifted part is brighter or darker by the
//! physical ratio of the luminances Y(gT)/Y(T) (the visible-band part of the g⁴ law for the
//! bolometric radiance). The tone clamp keeps the hue: a colour whose largest component
//! exceeds 1 is divided by it.
//!
//! Reference squares: in the top-left corner, one square for each of the first two objects
//! shows its unshifted colour (g = 1) in the same brightness mode, as in the frequency-shift
//! figures of the Gödel-universe visualizations; see [`reference_square`] for the layout.
//! Rows are shaded in parallel; the result does not depend on the thread count.

use datafile::record::PixelRecord;
use datafile::DataFile;
use image::RgbImage;

use crate::blackbody::table;
use crate::colour::display_srgb8;
use crate::texture_shader::{shade_pixels, status_colour, BACKGROUND, FAILED};

/// How bright a black-body pixel is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Brightness {
    /// Colour only: largest linear component 1, whatever the shift.
    Normalized,
    /// Physical luminance relative to the object's unshifted luminance, times `exposure`.
    Physical { exposure: f64 },
}

/// How many objects get a reference square.
pub const REFERENCE_SQUARES: usize = 2;

/// Shades every pixel of `data` as black bodies at `temperatures[k]` (K) for object k, seen
/// with the pixel's shift g, and draws the reference squares. Never panics on inconsistent
/// data: missing records and temperatures show as [`FAILED`].
pub fn shade_frequency(data: &DataFile, temperatures: &[f64], brightness: Brightness) -> RgbImage {
    let mut img = shade_pixels(data, |record| {
        frequency_colour(record, temperatures, brightness)
    });
    for (k, &t) in temperatures.iter().take(REFERENCE_SQUARES).enumerate() {
        let (w, h) = data.picture_size();
        let Some((x0, y0, side)) = reference_square(k, w, h) else {
            continue;
        };
        // The colour a pixel at g = 1 shows (through the display tone curve).
        let colour = display_srgb8(blackbody_colour(1.0, t, brightness).unwrap_or(FAILED), 1.0);
        for y in y0..y0 + side {
            for x in x0..x0 + side {
                img.put_pixel(x as u32, y as u32, image::Rgb(colour));
            }
        }
    }
    img
}

/// Linear sRGB of one pixel (see the table in the module documentation).
pub fn frequency_colour(
    record: &PixelRecord,
    temperatures: &[f64],
    brightness: Brightness,
) -> [f32; 3] {
    if let Some(c) = status_colour(record, BACKGROUND) {
        return c;
    }
    let Some(&t) = temperatures.get(record.object as usize) else {
        return FAILED;
    };
    blackbody_colour(f64::from(record.g), t, brightness).unwrap_or(FAILED)
}

/// Linear sRGB of a black body at temperature `t` (K) seen with shift `g`; `None` unless both
/// are finite and positive (and, in physical mode, the exposure is finite and ≥ 0).
pub fn blackbody_colour(g: f64, t: f64, brightness: Brightness) -> Option<[f32; 3]> {
    let valid = |v: f64| v.is_finite() && v > 0.0;
    if !valid(g) || !valid(t) {
        return None;
    }
    let tab = table();
    let shifted = g * t;
    let rgb = match brightness {
        Brightness::Normalized => tab.colour(shifted),
        Brightness::Physical { exposure } => {
            if !(exposure.is_finite() && exposure >= 0.0) {
                return None;
            }
            let scale = exposure * tab.luminance(shifted) / tab.luminance(t);
            let rgb = tab.unit_colour(shifted).map(|c| c * scale);
            let max = rgb[0].max(rgb[1]).max(rgb[2]);
            if max > 1.0 {
                rgb.map(|c| c / max)
            } else {
                rgb
            }
        }
    };
    Some(rgb.map(|c| c as f32))
}

/// Where reference square `k` lies in a `width` × `height` image: `(x0, y0, side)` in pixels,
/// top-left corner, or `None` if it does not fit. The side is min(width, height)/8 clamped to
/// 8 px at least and 16 px at most, or max(width, height)/120 on pictures wider or taller than
/// 1920 pixels (32 px at 3840, beside the larger type there); the squares sit side/4 from the
/// top and left edges and side/4 apart.
pub fn reference_square(k: usize, width: usize, height: usize) -> Option<(usize, usize, usize)> {
    let side = (width.min(height) / 8).clamp(8, (width.max(height) / 120).max(16));
    let gap = side / 4;
    let x0 = gap + k * (side + gap);
    let y0 = gap;
    (x0 + side <= width && y0 + side <= height).then_some((x0, y0, side))
}
