//! Text on pictures: labels of legends, reference squares and orientation marks, written with
//! the public-domain 8×8 bitmap font of the `font8x8` crate (ASCII, Latin-1 and Greek, so
//! `°`, `×`, `Δ` and `φ` are available). Each font pixel is a `scale`×`scale` block, and
//! the text gets a one-block dark outline so that it reads on bright and dark pictures alike.
//! Everything is drawn opaque into the RGBA overlay layer ([`crate::layer`]).

use font8x8::{UnicodeFonts, BASIC_FONTS, GREEK_FONTS, LATIN_FONTS};
use image::{Rgba, RgbaImage};

/// Width and height of one glyph in font pixels.
pub const GLYPH: u32 = 8;

/// The font's rows for `c` (bit 0 the leftmost pixel); characters the font lacks fall back
/// to a close ASCII one ('−' → '-') or to '?'.
fn glyph(c: char) -> [u8; 8] {
    let c = match c {
        '−' | '–' => '-',
        other => other,
    };
    BASIC_FONTS
        .get(c)
        .or_else(|| LATIN_FONTS.get(c))
        .or_else(|| GREEK_FONTS.get(c))
        .or_else(|| BASIC_FONTS.get('?'))
        .unwrap_or([0; 8])
}

/// Width in pixels of `text` at `scale`.
pub fn text_width(text: &str, scale: u32) -> u32 {
    text.chars().count() as u32 * GLYPH * scale
}

/// Height in pixels of a line at `scale`.
pub fn text_height(scale: u32) -> u32 {
    GLYPH * scale
}

/// A scale at which type is readable on an image of this size without covering it: 1 (8-pixel
/// type) on small images, 2 from 400×90 pixels on, 3 from 900 pixels on the shorter side.
pub fn readable_scale(width: u32, height: u32) -> u32 {
    if width.min(height) >= 900 {
        3
    } else if width >= 400 && height >= 90 {
        2
    } else {
        1
    }
}

/// The pixels a glyph covers, as (x, y) offsets in font pixels.
fn ink(text: &str) -> impl Iterator<Item = (u32, u32)> + '_ {
    text.chars().enumerate().flat_map(|(n, c)| {
        let rows = glyph(c);
        (0..GLYPH).flat_map(move |j| {
            (0..GLYPH).filter_map(move |i| {
                (rows[j as usize] & (1 << i) != 0).then_some((n as u32 * GLYPH + i, j))
            })
        })
    })
}

/// Writes `text` with its top-left corner at (x, y) in `colour`, outlined in near-black;
/// whatever falls outside the image is cut off.
pub fn draw_text(img: &mut RgbaImage, x: i64, y: i64, scale: u32, text: &str, colour: [u8; 3]) {
    let s = i64::from(scale);
    let outline = [12, 12, 12];
    for (i, j) in ink(text) {
        let (px, py) = (x + i64::from(i) * s, y + i64::from(j) * s);
        fill(img, px - s, py - s, 3 * s, 3 * s, outline);
    }
    for (i, j) in ink(text) {
        let (px, py) = (x + i64::from(i) * s, y + i64::from(j) * s);
        fill(img, px, py, s, s, colour);
    }
}

/// Fills the rectangle at (x, y) of size w × h with opaque `colour`, clipped to the image.
pub fn fill(img: &mut RgbaImage, x: i64, y: i64, w: i64, h: i64, colour: [u8; 3]) {
    let (iw, ih) = (i64::from(img.width()), i64::from(img.height()));
    let [r, g, b] = colour;
    for py in y.max(0)..(y + h).min(ih) {
        for px in x.max(0)..(x + w).min(iw) {
            img.put_pixel(px as u32, py as u32, Rgba([r, g, b, 255]));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_drawn_in_its_colour_and_outlined() {
        let mut img = RgbaImage::new(60, 20);
        draw_text(&mut img, 2, 2, 1, "30°", [255, 255, 0]);
        let count = |c: [u8; 4]| img.pixels().filter(|p| p.0 == c).count();
        assert!(count([255, 255, 0, 255]) > 20, "glyph ink");
        assert!(count([12, 12, 12, 255]) > 20, "outline");
        // Nothing beyond the three glyphs and their outline.
        assert!(img.get_pixel(2 + 3 * 8 + 2, 10).0 == [0, 0, 0, 0]);
    }

    #[test]
    fn every_label_character_has_a_glyph() {
        let unknown = glyph('\u{2603}');
        for c in "0123456789-.°×ΔφgtKEWSNa()/ =:,ztravelime".chars() {
            assert_ne!(glyph(c), unknown, "{c}");
        }
    }
}
