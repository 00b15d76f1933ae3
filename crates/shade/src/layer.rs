//! The overlay layer: everything drawn over a shaded picture — orientation marks
//! ([`crate::marks`]), the travel-time legend and the labels of the frequency shader's
//! reference squares ([`crate::legend`]), all text in the readable type of [`crate::text`] —
//! drawn into one RGBA image of the picture's size, transparent where nothing is drawn.
//!
//! `godel shade` composites it over the picture ([`composite`]); the viewer serves it as a
//! PNG and the page composites it over the picture it shades on the GPU, so both show the
//! same overlays from the same code. Compositing is the usual "over" rule per 8-bit channel:
//! out = round((layer·α + picture·(255 − α)) / 255), α the layer's alpha.

use image::{RgbImage, RgbaImage};
use scene::Camera;

use crate::legend::{draw_legend, label_reference_squares};
use crate::marks::{bottom_band, draw_marks};

/// What the layer shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overlays {
    /// Orientation marks for this camera (resized to the picture).
    pub marks: Option<Camera>,
    /// The travel-time legend for this range (travel_min, travel_max).
    pub legend: Option<(f64, f64)>,
    /// Labels of the reference squares: the temperatures (K) of the objects whose unshifted
    /// colours they show, in object order; empty for no squares.
    pub reference_labels: Vec<f64>,
}

impl Overlays {
    /// Whether the layer would be empty whatever the picture's size.
    pub fn is_empty(&self) -> bool {
        self.marks.is_none() && self.legend.is_none() && self.reference_labels.is_empty()
    }

    /// The layer for a `width` × `height` picture; `None` when there is nothing to draw.
    /// Marks first, then the square labels and the legend over them (the legend above the
    /// marks' azimuth labels).
    pub fn draw(&self, width: u32, height: u32) -> Option<RgbaImage> {
        if self.is_empty() || width == 0 || height == 0 {
            return None;
        }
        let mut layer = RgbaImage::new(width, height);
        if let Some(camera) = &self.marks {
            draw_marks(&mut layer, camera);
        }
        if !self.reference_labels.is_empty() {
            label_reference_squares(&mut layer, &self.reference_labels);
        }
        if let Some((min, max)) = self.legend {
            // Above the azimuth labels, where there are marks.
            let above = self.marks.map_or(0, |c| bottom_band(&c, width, height));
            draw_legend(&mut layer, min, max, above);
        }
        Some(layer)
    }
}

/// Composites `layer` over `img` (same size; a layer of another size is ignored).
pub fn composite(img: &mut RgbImage, layer: &RgbaImage) {
    if img.dimensions() != layer.dimensions() {
        return;
    }
    for (p, l) in img.pixels_mut().zip(layer.pixels()) {
        let a = u32::from(l.0[3]);
        if a == 0 {
            continue;
        }
        for (c, s) in p.0.iter_mut().zip(l.0) {
            *c = ((u32::from(s) * a + u32::from(*c) * (255 - a) + 127) / 255) as u8;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::legend::{FREQUENCY_TITLE, LEGEND_TITLE};
    use crate::text::{readable_scale, text_height, text_width};

    /// Opaque white (glyph ink) pixels of `layer` inside the rectangle.
    fn ink(layer: &RgbaImage, x0: u32, y0: u32, w: u32, h: u32) -> usize {
        (y0..(y0 + h).min(layer.height()))
            .flat_map(|y| (x0..(x0 + w).min(layer.width())).map(move |x| (x, y)))
            .filter(|&(x, y)| layer.get_pixel(x, y).0 == [255, 255, 255, 255])
            .count()
    }

    #[test]
    fn nothing_to_draw_is_no_layer() {
        assert!(Overlays::default().draw(200, 100).is_none());
        let legend = Overlays {
            legend: Some((0.0, 5.0)),
            ..Overlays::default()
        };
        assert!(legend.draw(0, 100).is_none());
        assert!(legend.draw(200, 100).is_some());
    }

    #[test]
    fn legend_title_is_written_right_of_the_bar_at_the_bottom() {
        let (w, h) = (1400, 300);
        let layer = Overlays {
            legend: Some((0.5, 6.0)),
            ..Overlays::default()
        }
        .draw(w, h)
        .unwrap();
        let scale = readable_scale(w, h);
        let th = text_height(scale);
        let y = h - 3 * scale - th;
        // The colour bar on the bottom line: violet at its left end, yellow at its right end.
        let row: Vec<[u8; 4]> = (0..w).map(|x| layer.get_pixel(x, y + th / 2).0).collect();
        let violet = row.iter().position(|p| *p == [68, 1, 84, 255]).unwrap() as u32;
        let yellow = row.iter().rposition(|p| *p == [253, 231, 37, 255]).unwrap() as u32;
        assert!(
            violet < yellow && yellow < w / 3,
            "bar from {violet} to {yellow}"
        );
        // Right of the bar and of the range's end ("6"): the title with its unit, all of it
        // on the bottom line (about 4 × 20 ink pixels a glyph at scale 2).
        let x = yellow + 4 * scale + text_width("6", scale) + scale;
        let title = ink(&layer, x, y, w - x, th);
        let glyphs = LEGEND_TITLE.chars().filter(|c| *c != ' ').count();
        assert!(title > glyphs * 40, "title ink at the bottom: {title}");
        assert!(x + text_width(LEGEND_TITLE, scale) <= w);
        // Nothing else: the rest of the layer is clear.
        assert_eq!(
            ink(&layer, 0, 0, w, y - 3 * scale),
            0,
            "nothing above the legend"
        );
        assert_eq!(layer.get_pixel(w / 2, h / 2).0[3], 0);
    }

    #[test]
    fn with_marks_the_legend_sits_above_the_azimuth_labels() {
        let (w, h) = (1320, 150);
        let camera = Camera::Panorama {
            h_fov_deg: 220.0,
            v_fov_deg: 25.0,
            width: w,
            height: h,
        };
        let with_marks = Overlays {
            marks: Some(camera),
            legend: Some((0.0, 12.0)),
            ..Overlays::default()
        }
        .draw(w, h)
        .unwrap();
        let marks_only = Overlays {
            marks: Some(camera),
            ..Overlays::default()
        }
        .draw(w, h)
        .unwrap();
        // The azimuth labels' band is as the marks alone draw it.
        let band = bottom_band(&camera, w, h);
        assert!(band > 0);
        for y in h - band + 1..h {
            for x in 0..w {
                assert_eq!(
                    with_marks.get_pixel(x, y),
                    marks_only.get_pixel(x, y),
                    "({x}, {y})"
                );
            }
        }
        // The legend's bar (its violet end) is just above that band.
        let violet = (0..h)
            .rev()
            .find(|&y| (0..w).any(|x| with_marks.get_pixel(x, y).0 == [68, 1, 84, 255]))
            .unwrap();
        assert!(
            violet < h - band && violet + band / 2 > h - band,
            "bar bottom at {violet}"
        );
    }

    /// On a picture too narrow for a title even in 8-pixel type (a 240×60 sequence frame),
    /// the title is left out rather than cut off at the picture's edge; the rest still shows.
    #[test]
    fn titles_too_wide_for_the_picture_are_left_out_not_cut_off() {
        let (w, h) = (240, 60);
        assert!(text_width(FREQUENCY_TITLE, 1) > w && text_width(LEGEND_TITLE, 1) > w);
        for overlays in [
            Overlays {
                reference_labels: vec![5800.0, 3500.0],
                ..Overlays::default()
            },
            Overlays {
                legend: Some((0.0, 12.0)),
                ..Overlays::default()
            },
        ] {
            let layer = overlays.draw(w, h).unwrap();
            assert!(ink(&layer, 0, 0, w, h) > 0, "the labels are drawn");
            assert_eq!(
                ink(&layer, w - 3, 0, 3, h),
                0,
                "no text runs into the right edge"
            );
        }
    }

    #[test]
    fn reference_labels_name_the_temperatures_beside_the_squares() {
        let (w, h) = (640, 320);
        let draw = |temps: &[f64]| {
            Overlays {
                reference_labels: temps.to_vec(),
                ..Overlays::default()
            }
            .draw(w, h)
            .unwrap()
        };
        let layer = draw(&[5800.0, 3500.0]);
        let (x0, y0, side) =
            crate::frequency_shader::reference_square(1, w as usize, h as usize).unwrap();
        let (x0, y0, side) = (x0 as u32, y0 as u32, side as u32);
        let scale = readable_scale(w, h);
        let th = text_height(scale);
        // "g = 1: 5800 K, 3500 K" right of the squares, on their line.
        let x = x0 + side + side / 2;
        let tw = text_width("g = 1: 5800 K, 3500 K", scale);
        let beside = ink(&layer, x, 0, tw, y0 + side + th / 2);
        assert!(beside > 250, "temperatures beside the squares: {beside}");
        assert_eq!(
            ink(&layer, x + tw + 2 * scale, 0, w, y0 + side),
            0,
            "nothing further"
        );
        // The title below the squares, from the left edge of the first.
        let (first, _, _) = crate::frequency_shader::reference_square(0, 640, 320).unwrap();
        let below = ink(
            &layer,
            first as u32,
            y0 + side + 1,
            text_width(FREQUENCY_TITLE, scale),
            3 * th,
        );
        assert!(below > 400, "title below the squares: {below}");
        // The squares themselves are the picture's: the layer leaves them clear.
        assert_eq!(layer.get_pixel(x0 + 1, y0 + 1).0[3], 0);
        // Another temperature writes another label, at the same place.
        let other = draw(&[5800.0, 9100.0]);
        let differ = layer
            .pixels()
            .zip(other.pixels())
            .enumerate()
            .filter(|(_, (a, b))| a != b)
            .map(|(i, _)| (i as u32 % w, i as u32 / w))
            .collect::<Vec<_>>();
        assert!(!differ.is_empty(), "the label names the temperatures");
        assert!(
            differ
                .iter()
                .all(|&(px, py)| px >= x && py < y0 + side + th),
            "only the temperatures change"
        );
    }

    #[test]
    fn composite_is_over_with_rounding() {
        let mut img = RgbImage::from_pixel(2, 1, image::Rgb([100, 0, 255]));
        let mut layer = RgbaImage::new(2, 1);
        layer.put_pixel(0, 0, image::Rgba([200, 220, 255, 89]));
        composite(&mut img, &layer);
        // 200·89/255 + 100·166/255 = 134.9…; 220·89/255 = 76.8…; 255.
        assert_eq!(img.get_pixel(0, 0).0, [135, 77, 255]);
        assert_eq!(
            img.get_pixel(1, 0).0,
            [100, 0, 255],
            "clear pixels untouched"
        );
        layer.put_pixel(1, 0, image::Rgba([1, 2, 3, 255]));
        composite(&mut img, &layer);
        assert_eq!(img.get_pixel(1, 0).0, [1, 2, 3]);
    }
}
