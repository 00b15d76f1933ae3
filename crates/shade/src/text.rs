//! Text on pictures: the labels of legends, reference squares and orientation marks, in the
//! embedded typeface (crate `typeface`: DejaVu Sans, anti-aliased) with a dark halo around the
//! glyphs, so that they read on bright and dark pictures alike. A [`Label`] is measured once
//! (its box holds the glyphs and the halo: what the layout of [`crate::layer`] keeps apart)
//! and drawn into the RGBA overlay layer by the "over" rule, so that its edges stay smooth
//! wherever the layer is composited.
//!
//! Type size follows the picture's size ([`type_size`]), from 10-pixel type on a 240×60 frame
//! to about 31 pixels on a 3840×2160 one.

use image::{Rgba, RgbaImage};
use typeface::{Coverage, Line, Weight};

/// Colour of the halo around the glyphs, and its opacity.
const HALO: [u8; 3] = [12, 12, 12];
const HALO_OPACITY: f32 = 0.9;

/// The em size in pixels of labels on a `width` × `height` picture: 1.75·(W·H)^0.18, at least
/// 10 (still legible, digits 7.3 pixels tall) and at most 64. This grows more slowly than the
/// picture: 10 at 240×60, 15.7 at 1320×150, 24.6 at 1920×1080, 30.8 at 3840×2160.
pub fn type_size(width: u32, height: u32) -> f32 {
    let area = f64::from(width) * f64::from(height);
    (1.75 * area.powf(0.18)).clamp(f64::from(MIN_SIZE), 64.0) as f32
}

/// The unit of the marks' and legends' spacings (tick length, gaps) at type size `size`:
/// an eighth of the em, at least one pixel.
pub fn unit(size: f32) -> i64 {
    ((size / 8.0).round() as i64).max(1)
}

/// The sizes to try for a text that may not fit at `size`: `size`, then 15 % smaller each
/// time, down to 10 pixels (the smallest type written).
pub fn sizes_from(size: f32) -> impl Iterator<Item = f32> {
    let mut next = Some(size.max(MIN_SIZE));
    std::iter::from_fn(move || {
        let s = next?;
        next = (s > MIN_SIZE).then(|| (s * 0.85).max(MIN_SIZE));
        Some(s)
    })
}

/// The smallest type written, in pixels per em.
pub const MIN_SIZE: f32 = 10.0;

/// Radius in pixels of the halo around glyphs of type size `size`.
fn halo_radius(size: f32) -> i64 {
    ((size / 10.0).round() as i64).max(1)
}

/// One line of text, laid out and rasterized, ready to be placed and drawn.
#[derive(Clone, Debug)]
pub struct Label {
    pub text: String,
    coverage: Coverage,
    halo: i64,
}

impl Label {
    /// `text` at em size `size` pixels.
    pub fn new(text: &str, size: f32) -> Label {
        Label {
            text: text.to_string(),
            coverage: Line::new(text, size, Weight::Regular).coverage(),
            halo: halo_radius(size),
        }
    }

    /// Width of the label's box in pixels (glyphs and halo).
    pub fn width(&self) -> i64 {
        i64::from(self.coverage.width) + 2 * self.halo
    }

    /// Height of the label's box in pixels (the font's ascent and descent, and the halo).
    pub fn height(&self) -> i64 {
        i64::from(self.coverage.height) + 2 * self.halo
    }

    /// Row of the baseline within the label's box.
    pub fn baseline(&self) -> i64 {
        i64::from(self.coverage.origin.1) + self.halo
    }

    /// Coverage of the halo at box pixel (x, y): the largest glyph coverage within the halo
    /// radius (a disc).
    fn halo_at(&self, x: i64, y: i64) -> f32 {
        let r = self.halo;
        let mut best = 0.0f32;
        for dy in -r..=r {
            for dx in -r..=r {
                if dx * dx + dy * dy <= r * r + r {
                    best = best.max(self.coverage.at(x - r + dx, y - r + dy));
                }
            }
        }
        best
    }

    /// Draws the label with its box's top-left corner at (x, y), glyphs in `colour` over the
    /// halo; whatever falls outside the image is cut off.
    pub fn draw(&self, img: &mut RgbaImage, x: i64, y: i64, colour: [u8; 3]) {
        let (iw, ih) = (i64::from(img.width()), i64::from(img.height()));
        for by in 0..self.height() {
            for bx in 0..self.width() {
                let (px, py) = (x + bx, y + by);
                if px < 0 || py < 0 || px >= iw || py >= ih {
                    continue;
                }
                let halo = self.halo_at(bx, by) * HALO_OPACITY;
                let ink = self.coverage.at(bx - self.halo, by - self.halo);
                let p = img.get_pixel_mut(px as u32, py as u32);
                blend(p, HALO, halo);
                blend(p, colour, ink);
            }
        }
    }
}

/// Puts `colour` at opacity `alpha` over the straight-alpha pixel `p` (the "over" rule).
fn blend(p: &mut Rgba<u8>, colour: [u8; 3], alpha: f32) {
    if alpha <= 0.0 {
        return;
    }
    let a = alpha.min(1.0);
    let below = f32::from(p.0[3]) / 255.0;
    let out = a + below * (1.0 - a);
    for (c, s) in p.0.iter_mut().zip(colour) {
        let v = (f32::from(s) * a + f32::from(*c) * below * (1.0 - a)) / out;
        *c = v.round().clamp(0.0, 255.0) as u8;
    }
    p.0[3] = (out * 255.0).round() as u8;
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
    fn labels_are_anti_aliased_with_a_halo_inside_their_box() {
        let label = Label::new("−30°", 16.0);
        let (w, h) = (label.width(), label.height());
        let mut img = RgbaImage::new(w as u32 + 20, h as u32 + 20);
        label.draw(&mut img, 10, 10, [255, 255, 0]);
        let inside = |x: u32, y: u32| {
            let (x, y) = (i64::from(x), i64::from(y));
            (10..10 + w).contains(&x) && (10..10 + h).contains(&y)
        };
        let (mut ink, mut edge, mut halo) = (0, 0, 0);
        for (x, y, p) in img.enumerate_pixels() {
            if p.0[3] == 0 {
                continue;
            }
            assert!(inside(x, y), "drawn outside the box at ({x}, {y})");
            match p.0 {
                [255, 255, 0, 255] => ink += 1,
                [r, g, b, _] if r == g && b < r && r > 12 => edge += 1,
                [12, 12, 12, _] => halo += 1,
                _ => {}
            }
        }
        assert!(ink >= 8, "solid glyph pixels: {ink}");
        assert!(edge > 15, "anti-aliased edge pixels: {edge}");
        assert!(halo > 40, "halo pixels: {halo}");
        // The box is the text's: a longer text is wider, at the same height.
        let longer = Label::new("−180°", 16.0);
        assert!(longer.width() > w && longer.height() == h);
    }

    #[test]
    fn type_grows_with_the_picture() {
        assert_eq!(type_size(240, 60), 10.0);
        assert_eq!(type_size(16, 16), 10.0);
        let reference = type_size(1320, 150);
        assert!((15.0..16.5).contains(&reference), "{reference}");
        let uhd = type_size(3840, 2160);
        assert!((29.0..33.0).contains(&uhd), "{uhd}");
        assert_eq!(type_size(u32::MAX, u32::MAX), 64.0);
        assert_eq!(unit(10.0), 1);
        assert_eq!(unit(31.0), 4);
        let sizes: Vec<f32> = sizes_from(16.0).collect();
        assert_eq!(sizes.len(), 4);
        for (s, want) in sizes.iter().zip([16.0, 13.6, 11.56, 10.0]) {
            assert!((s - want).abs() < 1e-4, "{sizes:?}");
        }
        assert_eq!(sizes_from(10.0).collect::<Vec<_>>(), [10.0]);
    }

    #[test]
    fn blending_is_over_with_straight_alpha() {
        let mut p = Rgba([0, 0, 0, 0]);
        blend(&mut p, [200, 100, 0], 0.5);
        assert_eq!(p.0, [200, 100, 0, 128]);
        blend(&mut p, [0, 0, 200], 0.5);
        // out α = 0.5 + (128/255)·0.5 = 0.751; colour (200·0.251, 100·0.251, 200·0.5) / 0.751.
        assert_eq!(p.0, [67, 33, 133, 192]);
        blend(&mut p, [1, 2, 3], 1.0);
        assert_eq!(p.0, [1, 2, 3, 255]);
    }
}
