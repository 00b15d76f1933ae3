//! False colour for light travel time and its legend: a colour bar in the bottom-left corner
//! with the range's two ends written in a 3×5 pixel digit font, so that a picture shaded by
//! travel time can be read without the command that made it.
//!
//! The colour map runs through five stops of the viridis map (dark violet for the shortest
//! travel time, yellow for the longest), interpolated linearly in linear RGB.

use image::RgbImage;

use crate::colour::{rgb_to_srgb8, srgb8_to_linear};

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

/// Glyphs 3 wide, 5 high, rows top to bottom, bit 2 = left column.
fn glyph(c: char) -> Option<[u8; 5]> {
    Some(match c {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 1, 1],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        _ => return None,
    })
}

/// Writes `text` (digits, '.', '-') at (x, y), each font pixel a `scale`×`scale` block.
fn draw_text(img: &mut RgbImage, x: u32, y: u32, scale: u32, text: &str, colour: [u8; 3]) {
    for (n, c) in text.chars().enumerate() {
        let Some(rows) = glyph(c) else { continue };
        for (j, bits) in rows.iter().enumerate() {
            for i in 0..3u32 {
                if bits & (4 >> i) == 0 {
                    continue;
                }
                for dy in 0..scale {
                    for dx in 0..scale {
                        let px = x + (n as u32 * 4 + i) * scale + dx;
                        let py = y + j as u32 * scale + dy;
                        if px < img.width() && py < img.height() {
                            img.put_pixel(px, py, image::Rgb(colour));
                        }
                    }
                }
            }
        }
    }
}

/// Short decimal form of a range end: at most one decimal.
fn label(v: f64) -> String {
    if (v - v.round()).abs() < 1e-9 {
        format!("{}", v.round() as i64)
    } else {
        format!("{v:.1}")
    }
}

/// Draws the legend of travel times `min`..`max` in the bottom-left corner: the colour bar
/// (left end `min`), with `min` above its left end and `max` above its right end. Images too
/// small for it (under 48×24 pixels) are left as they are.
pub fn draw_legend(img: &mut RgbImage, min: f64, max: f64) {
    let (w, h) = (img.width(), img.height());
    if w < 48 || h < 24 {
        return;
    }
    let scale = (h / 60).clamp(1, 3);
    let bar_w = (w / 4).clamp(40, 256);
    let bar_h = (h / 25).clamp(3, 12);
    let margin = 2 * scale;
    let y_bar = h - margin - bar_h;
    let y_text = y_bar.saturating_sub(6 * scale + scale);
    for x in 0..bar_w {
        let c = rgb_to_srgb8(false_colour(f64::from(x) / f64::from(bar_w - 1)));
        for y in y_bar..y_bar + bar_h {
            img.put_pixel(margin + x, y, image::Rgb(c));
        }
    }
    let white = [255, 255, 255];
    draw_text(img, margin, y_text, scale, &label(min), white);
    let right = label(max);
    let text_w = right.chars().count() as u32 * 4 * scale;
    draw_text(
        img,
        (margin + bar_w).saturating_sub(text_w),
        y_text,
        scale,
        &right,
        white,
    );
}
