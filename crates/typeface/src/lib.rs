//! `typeface`: the one typeface godel writes with, DejaVu Sans 2.37 (regular and bold),
//! embedded in the binary (`assets/fonts`, licence in `assets/fonts/LICENSE-DejaVu.txt`, see
//! `assets/NOTICE.md`), so that labels on pictures and the text of plots look the same on every
//! machine, whatever fonts it has.
//!
//! Main items: [`Line`], one line of text laid out at an em size in pixels (glyph positions with
//! the font's kerning, advance width, ascent and descent); [`Line::coverage`], its
//! anti-aliased coverage (0 to 1 per pixel, rasterized from the glyph outlines by `ab_glyph`),
//! in a box that holds all of its ink; [`Line::svg_path`], the same glyphs as SVG path data,
//! for plots whose text must not depend on the fonts of the program that shows them;
//! [`Weight`].
//!
//! Sizes are em sizes, as CSS `font-size`: a 20-pixel line has digits about 14.6 pixels tall
//! (DejaVu Sans's cap height is 0.73 em).

use ab_glyph::{point, Font, FontRef, GlyphId, OutlineCurve, PxScale, ScaleFont};
use std::fmt::Write;
use std::sync::OnceLock;

const REGULAR: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
const BOLD: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans-Bold.ttf");

/// The font file's bytes of a weight (DejaVu Sans or DejaVu Sans Bold, TrueType).
pub fn font_data(weight: Weight) -> &'static [u8] {
    match weight {
        Weight::Regular => REGULAR,
        Weight::Bold => BOLD,
    }
}

/// Regular or bold.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Weight {
    #[default]
    Regular,
    Bold,
}

/// The parsed embedded font of a weight.
fn font(weight: Weight) -> &'static FontRef<'static> {
    static FONTS: OnceLock<[FontRef<'static>; 2]> = OnceLock::new();
    let fonts = FONTS.get_or_init(|| {
        // The files are part of the binary, not user input; a test reads both.
        [REGULAR, BOLD].map(|bytes| {
            FontRef::try_from_slice(bytes).expect("the embedded DejaVu Sans is a TrueType font")
        })
    });
    &fonts[weight as usize]
}

/// One line of text laid out at an em size: where each glyph's origin sits on the baseline.
#[derive(Clone, Debug)]
pub struct Line {
    weight: Weight,
    scale: PxScale,
    /// Pixels per font unit.
    per_unit: f32,
    glyphs: Vec<(GlyphId, f32)>,
    /// Width from the first glyph's origin to the pen position after the last, in pixels.
    pub advance: f32,
    /// The font's ascent above the baseline and descent below it (both positive), pixels.
    pub ascent: f32,
    pub descent: f32,
}

/// The anti-aliased coverage of a [`Line`]: `width` × `height` values in [0, 1], row by row,
/// with the line's baseline origin at pixel corner `origin` (x, y). Every pixel the glyphs
/// touch is inside, and so is the line's box from 0 to its advance, ascent to descent.
#[derive(Clone, Debug, PartialEq)]
pub struct Coverage {
    pub width: u32,
    pub height: u32,
    pub origin: (i32, i32),
    pub data: Vec<f32>,
}

impl Coverage {
    /// Coverage at (x, y); 0 outside.
    pub fn at(&self, x: i64, y: i64) -> f32 {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return 0.0;
        }
        self.data[y as usize * self.width as usize + x as usize]
    }
}

impl Line {
    /// `text` at `size` pixels per em. Characters the font lacks are written as '?'.
    pub fn new(text: &str, size: f32, weight: Weight) -> Line {
        let f = font(weight);
        let per_em = f.units_per_em().unwrap_or(2048.0);
        let size = if size.is_finite() { size.max(0.0) } else { 0.0 };
        let scale = PxScale::from(size * f.height_unscaled() / per_em);
        let scaled = f.as_scaled(scale);
        let question = f.glyph_id('?');
        let mut glyphs = Vec::with_capacity(text.len());
        let mut pen = 0.0f32;
        let mut previous: Option<GlyphId> = None;
        for c in text.chars() {
            let id = match f.glyph_id(c) {
                GlyphId(0) => question,
                id => id,
            };
            if let Some(p) = previous {
                pen += scaled.kern(p, id);
            }
            glyphs.push((id, pen));
            pen += scaled.h_advance(id);
            previous = Some(id);
        }
        Line {
            weight,
            scale,
            per_unit: size / per_em,
            glyphs,
            advance: pen,
            ascent: scaled.ascent(),
            descent: -scaled.descent(),
        }
    }

    /// The glyphs' outlines placed with the line's origin at (x, y).
    fn outlined(&self, x: f32, y: f32) -> impl Iterator<Item = ab_glyph::OutlinedGlyph> + '_ {
        let f = font(self.weight);
        self.glyphs.iter().filter_map(move |&(id, pen)| {
            f.outline_glyph(id.with_scale_and_position(self.scale, point(x + pen, y)))
        })
    }

    /// The line's anti-aliased coverage (see [`Coverage`]).
    pub fn coverage(&self) -> Coverage {
        // The box: the advance and the font's ascent and descent, grown to every glyph's ink.
        let (mut x0, mut y0, mut x1, mut y1) = (0.0f32, -self.ascent, self.advance, self.descent);
        for g in self.outlined(0.0, 0.0) {
            let b = g.px_bounds();
            (x0, y0) = (x0.min(b.min.x), y0.min(b.min.y));
            (x1, y1) = (x1.max(b.max.x), y1.max(b.max.y));
        }
        let origin = (-(x0.floor() as i32), -(y0.floor() as i32));
        let width = (x1.ceil() as i32 + origin.0).max(0) as u32;
        let height = (y1.ceil() as i32 + origin.1).max(0) as u32;
        let mut data = vec![0.0f32; width as usize * height as usize];
        for g in self.outlined(origin.0 as f32, origin.1 as f32) {
            let b = g.px_bounds();
            let (gx, gy) = (b.min.x as i64, b.min.y as i64);
            g.draw(|x, y, c| {
                let (px, py) = (gx + i64::from(x), gy + i64::from(y));
                if px >= 0 && py >= 0 && px < i64::from(width) && py < i64::from(height) {
                    let slot = &mut data[py as usize * width as usize + px as usize];
                    *slot = (*slot + c).min(1.0);
                }
            });
        }
        Coverage {
            width,
            height,
            origin,
            data,
        }
    }

    /// SVG path data (`M … L … Q … C … Z`) of the glyphs with the line's origin at (x, y), y
    /// down as in SVG; coordinates to 1/100 pixel. Filled with the nonzero rule (SVG's
    /// default), as TrueType outlines are meant.
    pub fn svg_path(&self, x: f64, y: f64) -> String {
        let f = font(self.weight);
        let k = f64::from(self.per_unit);
        let mut d = String::new();
        for &(id, pen) in &self.glyphs {
            let Some(outline) = f.outline(id) else {
                continue;
            };
            let ox = x + f64::from(pen);
            let p = |q: ab_glyph::Point| {
                let (px, py) = (ox + f64::from(q.x) * k, y - f64::from(q.y) * k);
                format!("{} {}", svg_number(px, 2), svg_number(py, 2))
            };
            let mut end: Option<ab_glyph::Point> = None;
            for curve in &outline.curves {
                let (start, last) = match *curve {
                    OutlineCurve::Line(a, b) => (a, b),
                    OutlineCurve::Quad(a, _, c) => (a, c),
                    OutlineCurve::Cubic(a, _, _, d) => (a, d),
                };
                if end != Some(start) {
                    if end.is_some() {
                        d.push('Z');
                    }
                    let _ = write!(d, "M{}", p(start));
                }
                let _ = match *curve {
                    OutlineCurve::Line(_, b) => write!(d, "L{}", p(b)),
                    OutlineCurve::Quad(_, b, c) => write!(d, "Q{} {}", p(b), p(c)),
                    OutlineCurve::Cubic(_, b, c, e) => write!(d, "C{} {} {}", p(b), p(c), p(e)),
                };
                end = Some(last);
            }
            if end.is_some() {
                d.push('Z');
            }
        }
        d
    }
}

/// `v` as an SVG number with at most `decimals` decimals, trailing zeros trimmed (`-0` is
/// `0`): how the outlines write their coordinates, and the plots theirs.
pub fn svg_number(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_weights_load_and_have_the_characters_godel_writes() {
        for weight in [Weight::Regular, Weight::Bold] {
            let f = font(weight);
            for c in "0123456789−-+.,:;°×ΔφλgtKEWSNa()/= abcdefghijklmnopqrstuvwxyz·√π".chars()
            {
                assert_ne!(f.glyph_id(c), GlyphId(0), "{c:?} in {weight:?}");
            }
        }
    }

    #[test]
    fn lines_scale_with_their_size_and_bold_is_wider() {
        let small = Line::new("-180°", 10.0, Weight::Regular);
        let large = Line::new("-180°", 40.0, Weight::Regular);
        assert!((large.advance / small.advance - 4.0).abs() < 1e-3);
        // DejaVu Sans: ascent 0.928 em, descent 0.236 em.
        assert!((large.ascent - 37.12).abs() < 0.1 && (large.descent - 9.44).abs() < 0.1);
        let bold = Line::new("-180°", 40.0, Weight::Bold);
        assert!(bold.advance > large.advance);
        // Digits are tabular: every digit advances the same.
        let d = |c: &str| Line::new(c, 20.0, Weight::Regular).advance;
        assert!((d("1") - d("8")).abs() < 1e-4 && d("0") > 10.0);
    }

    #[test]
    fn coverage_is_anti_aliased_and_holds_the_ink_in_its_box() {
        let line = Line::new("g = 1: 5800 K", 14.0, Weight::Regular);
        let c = line.coverage();
        assert!(c.width as f32 >= line.advance && c.height as f32 >= line.ascent + line.descent);
        let full = c.data.iter().filter(|&&v| v >= 0.999).count();
        let partial = c.data.iter().filter(|&&v| v > 0.0 && v < 0.999).count();
        assert!(
            full > 20 && partial > full,
            "{full} full, {partial} partial"
        );
        // Ink on both sides of the baseline ('g' descends), none in the far corners.
        let (ox, oy) = (i64::from(c.origin.0), i64::from(c.origin.1));
        let row_ink = |y: i64| (0..i64::from(c.width)).map(|x| c.at(x, y)).sum::<f32>();
        assert!(row_ink(oy - 3) > 1.0 && row_ink(oy + 2) > 0.5);
        assert_eq!(c.at(0, 0), 0.0);
        assert_eq!(c.at(ox - 1, oy), 0.0);
        // The empty line has an empty box that is still as tall as the font.
        let empty = Line::new("", 14.0, Weight::Regular).coverage();
        assert_eq!(empty.width, 0);
        assert!(empty.data.is_empty());
    }

    #[test]
    fn svg_outlines_are_closed_paths_where_the_raster_has_ink() {
        let line = Line::new("30°", 20.0, Weight::Regular);
        let d = line.svg_path(5.0, 25.0);
        assert!(d.starts_with('M') && d.ends_with('Z'));
        // '3' and '0' (two contours) and '°' (two): at least five subpaths.
        assert!(d.matches('M').count() >= 5, "{d}");
        // Every coordinate is within the line's box around (5, 25).
        let numbers: Vec<f64> = d
            .split(|c: char| c.is_ascii_alphabetic() || c == ' ')
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().unwrap())
            .collect();
        for pair in numbers.chunks(2) {
            let (x, y) = (pair[0], pair[1]);
            assert!(
                x >= 5.0 && x <= 5.0 + f64::from(line.advance) + 0.01,
                "x {x}"
            );
            assert!(y >= 25.0 - f64::from(line.ascent), "y {y}");
            // Round glyphs overshoot the baseline a little.
            assert!(y <= 25.0 + f64::from(line.descent) / 2.0, "y {y}");
        }
        // A character the font lacks is written as '?'.
        let unknown = Line::new("\u{10FFFF}", 20.0, Weight::Regular);
        assert_eq!(
            unknown.svg_path(0.0, 0.0),
            Line::new("?", 20.0, Weight::Regular).svg_path(0.0, 0.0)
        );
    }
}
