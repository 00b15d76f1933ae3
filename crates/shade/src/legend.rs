//! False colour for light travel time and its legend: a colour bar in the bottom-left corner
//! with the range's two ends, a title and the unit written in readable type
//! ([`crate::text`]), so that a picture shaded by travel time can be read without the
//! command that made it; and the label of the frequency shader's reference squares. Both are
//! drawn into the overlay layer ([`crate::layer`]).
//!
//! The colour map runs through five stops of the viridis map (dark violet for the shortest
//! travel time, yellow for the longest), interpolated linearly in linear RGB.

use image::RgbaImage;

use crate::colour::{rgb_to_srgb8, srgb8_to_linear};
use crate::frequency_shader::{reference_square, REFERENCE_SQUARES};
use crate::text::{draw_text, fill, readable_scale, text_height, text_width};

/// The viridis stops, 8-bit sRGB.
const STOPS: [[u8; 3]; 5] = [
    [68, 1, 84],
    [59, 82, 139],
    [33, 145, 140],
    [94, 201, 98],
    [253, 231, 37],
];

/// Linear RGB of the colour map at `s` ∈ [0, 1] (clamped; NaN → 0).
pub fn false_colour(s: f64) -> [f32; 3] {
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) } as f32;
    let x = s * (STOPS.len() - 1) as f32;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f32;
    let stops = linear_stops();
    let (a, b) = (stops[i], stops[i + 1]);
    [0, 1, 2].map(|k| a[k] + f * (b[k] - a[k]))
}

/// The stops in linear RGB, decoded once.
fn linear_stops() -> &'static [[f32; 3]; 5] {
    static TABLE: std::sync::OnceLock<[[f32; 3]; 5]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| STOPS.map(|s| s.map(srgb8_to_linear)))
}

/// Short decimal form of a range end: at most one decimal.
fn label(v: f64) -> String {
    if (v - v.round()).abs() < 1e-9 {
        format!("{}", v.round() as i64)
    } else {
        format!("{v:.1}")
    }
}

/// The legend's title, with the unit: travel time is coordinate time −t_emit, in the
/// scene's units (those of the Gödel parameter a, with c = 1).
pub const LEGEND_TITLE: &str = "light travel time -t_emit (units of a, c = 1)";

/// The title beside the frequency shader's reference squares: what the colours mean.
pub const FREQUENCY_TITLE: &str = "frequency shift g: black body at g·T";

/// Draws the legend of travel times `min`..`max` into the overlay layer `img`, in its
/// bottom-left corner, `above` pixels up from the bottom edge (room for orientation marks'
/// labels): `min`, the colour bar (violet at `min`, yellow at `max`), `max`, and the title
/// with its unit (on the same line, or above it on narrow pictures), in the readable type of
/// [`crate::text`], on a dark panel that hides whatever lies beneath. Layers too small for
/// it (under 48×24 pixels, or with no room above `above`) are left as they are.
pub fn draw_legend(img: &mut RgbaImage, min: f64, max: f64, above: u32) {
    let (w, h) = (img.width(), img.height());
    if w < 48 || h < 24 {
        return;
    }
    let scale = readable_scale(w, h);
    let s = i64::from(scale);
    let th = i64::from(text_height(scale));
    let bar_w = i64::from((w / 5).clamp(40, 256));
    let margin = 3 * s;
    let y = i64::from(h) - i64::from(above) - margin - th;
    if y < 2 * s {
        return;
    }
    // The line: low, bar, high, then the title (in smaller type if need be, or above the
    // line where it would not fit).
    let (low, high) = (label(min), label(max));
    let x_bar = margin + i64::from(text_width(&low, scale)) + 3 * s;
    let x_high = x_bar + bar_w + 3 * s;
    let x_title = x_high + i64::from(text_width(&high, scale)) + 6 * s;
    let fits = |k: u32| x_title + i64::from(text_width(LEGEND_TITLE, k)) <= i64::from(w);
    // The title on the line, in smaller type on the line, above the line, or (on pictures
    // too narrow for it even in the smallest type) left out rather than cut off.
    let title = if fits(scale) {
        Some((x_title, y, scale))
    } else if scale > 1 && fits(scale - 1) {
        Some((
            x_title,
            y + th - i64::from(text_height(scale - 1)),
            scale - 1,
        ))
    } else {
        (1..=scale)
            .rev()
            .find(|&k| margin + i64::from(text_width(LEGEND_TITLE, k)) <= i64::from(w))
            .map(|k| (margin, y - i64::from(text_height(k)) - 3 * s, k))
    };
    // A dark panel behind it all, so that it reads on any picture and over the marks.
    let mut right = x_high + i64::from(text_width(&high, scale));
    let mut top = y;
    if let Some((tx, ty, ts)) = title {
        right = right.max(tx + i64::from(text_width(LEGEND_TITLE, ts)));
        top = top.min(ty);
    }
    let (right, top) = (right + 2 * s, top - 2 * s);
    fill(img, 0, top, right, y + th + 2 * s - top, [12, 12, 12]);
    let white = [255, 255, 255];
    draw_text(img, margin, y, scale, &low, white);
    for i in 0..bar_w {
        let c = rgb_to_srgb8(false_colour(i as f64 / (bar_w - 1) as f64));
        fill(img, x_bar + i, y, 1, th, c);
    }
    draw_text(img, x_high, y, scale, &high, white);
    if let Some((tx, ty, ts)) = title {
        draw_text(img, tx, ty, ts, LEGEND_TITLE, white);
    }
}

/// Writes what the reference squares of a `w`×`h` picture show into its overlay layer
/// `img`: beside them the unshifted colours' temperatures, `g = 1: 5800 K, 3500 K` (one per
/// square shown, `temperatures` in object order), and below them the frequency title.
/// Lines too long for the picture are written in smaller type (down to 8-pixel type); a
/// line too long even then is left out rather than cut off mid-word.
pub fn label_reference_squares(img: &mut RgbaImage, temperatures: &[f64]) {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let shown = temperatures.len().min(REFERENCE_SQUARES);
    let Some((x0, y0, side)) = (0..shown).rev().find_map(|k| reference_square(k, w, h)) else {
        return;
    };
    let temps: Vec<String> = temperatures[..shown]
        .iter()
        .map(|t| format!("{} K", t.round() as i64))
        .collect();
    let text = format!("g = 1: {}", temps.join(", "));
    let readable = readable_scale(w as u32, h as u32);
    let fitting = |x: i64, text: &str| {
        (1..=readable)
            .rev()
            .find(|&k| x + i64::from(text_width(text, k)) <= w as i64)
    };
    let white = [255, 255, 255];
    let x = (x0 + side + side / 2) as i64;
    if let Some(scale) = fitting(x, &text) {
        let th = i64::from(text_height(scale));
        let y = (y0 as i64 + (side as i64 - th) / 2).max(0);
        draw_text(img, x, y, scale, &text, white);
    }
    // The title under the squares, left-aligned with the first.
    let (first_x, _, _) = reference_square(0, w, h).unwrap_or((x0, y0, side));
    let x = first_x as i64;
    if let Some(scale) = fitting(x, FREQUENCY_TITLE) {
        let y = (y0 + side) as i64 + (y0 as i64).max(i64::from(scale) * 2) + i64::from(scale);
        draw_text(img, x, y, scale, FREQUENCY_TITLE, white);
    }
}
