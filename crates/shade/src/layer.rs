//! The overlay layer: everything drawn over a shaded picture — orientation marks
//! ([`crate::marks`]), the travel-time legend and the labels of the frequency shader's
//! reference squares ([`crate::legend`]), all text in the picture's type ([`crate::text`]) —
//! drawn into one RGBA image of the picture's size, transparent where nothing is drawn.
//!
//! Every piece of text is placed by one layout ([`Overlays::layout`]) on a
//! [`Board`](crate::placement::Board): the reference squares are blocked first, then the
//! squares' temperatures, the legend's panel, the squares' title, the azimuth labels and the
//! elevation labels are placed in that order, each only where it stays inside the picture and keeps a gap to
//! everything placed before; a label that finds no room is left out. So no two labels or
//! legends ever overlap or leave the picture, at any size and for any camera.
//!
//! `godel shade` composites the layer over the picture ([`composite`]); the viewer serves it as
//! a PNG and the page composites it over the picture it shades on the GPU, so both show the
//! same overlays from the same code. Compositing is the usual "over" rule per 8-bit channel:
//! out = round((layer·α + picture·(255 − α)) / 255), α the layer's alpha.

use image::{RgbImage, RgbaImage};
use scene::Camera;

use crate::legend::{reference_labels, reference_rects, Legend, Placed};
use crate::marks::{bottom_band, draw_grid_and_ticks, mark_labels, Axis, MARK_COLOUR};
use crate::placement::{Board, Rect};
use crate::text::{type_size, unit, Label};

/// What the layer shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overlays {
    /// Orientation marks for this camera (resized to the picture).
    pub marks: Option<Camera>,
    /// The travel-time legend for this range (travel_min, travel_max).
    pub legend: Option<(f64, f64)>,
    /// The polarization layer's legend (above the travel-time legend where both show).
    pub polarization: bool,
    /// Labels of the reference squares: the temperatures (K) of the objects whose unshifted
    /// colours they show, in object order; empty for no squares.
    pub reference_labels: Vec<f64>,
}

/// What a placed piece of the layout is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// The temperatures beside the reference squares, or the title below them.
    ReferenceLabel,
    /// The travel-time legend's panel (with everything on it).
    Legend,
    /// A label of the orientation marks.
    Mark(Axis),
}

/// One placed piece of the layout: what it is, its box, and what it draws.
#[derive(Clone, Debug)]
pub struct Piece {
    pub kind: Kind,
    pub rect: Rect,
    art: Art,
}

#[derive(Clone, Debug)]
enum Art {
    Text(Placed),
    Legend(Box<Legend>),
}

impl Overlays {
    /// Whether the layer would be empty whatever the picture's size.
    pub fn is_empty(&self) -> bool {
        self.marks.is_none()
            && self.legend.is_none()
            && !self.polarization
            && self.reference_labels.is_empty()
    }

    /// Where the text goes on a `width` × `height` picture: every piece that finds room, in
    /// the order of the module doc. No two pieces come closer than one unit of the type
    /// (an eighth of its em), none leaves the picture or covers a reference square.
    pub fn layout(&self, width: u32, height: u32) -> Vec<Piece> {
        let mut board = Board::new(width, height, unit(type_size(width, height)));
        let mut pieces = Vec::new();
        let squares = reference_rects(self.reference_labels.len(), width, height);
        for r in &squares {
            board.block(*r);
        }
        let mut place = |board: &mut Board, kind, art: Art| {
            let rect = match &art {
                Art::Text(p) => p.rect(),
                Art::Legend(l) => l.panel,
            };
            if board.place(rect) {
                pieces.push(Piece { kind, rect, art });
            }
        };
        // The temperatures, then the legend, then the squares' title (where the two compete
        // for room, the legend's colour scale says more).
        let squares_labels = reference_labels(&self.reference_labels, width, height);
        if let Some(p) = squares_labels.temperatures {
            place(&mut board, Kind::ReferenceLabel, Art::Text(p));
        }
        // Above the azimuth labels, where there are marks.
        let mut above = self.marks.map_or(0, |c| bottom_band(&c, width, height));
        if let Some((min, max)) = self.legend {
            if let Some(legend) = Legend::new(width, height, min, max, above) {
                above = u32::try_from(i64::from(height) - legend.panel.y0).unwrap_or(above);
                place(&mut board, Kind::Legend, Art::Legend(Box::new(legend)));
            }
        }
        if self.polarization {
            if let Some(legend) = Legend::polarization(width, height, above) {
                place(&mut board, Kind::Legend, Art::Legend(Box::new(legend)));
            }
        }
        if let Some(p) = squares_labels.title {
            place(&mut board, Kind::ReferenceLabel, Art::Text(p));
        }
        if let Some(camera) = &self.marks {
            for m in mark_labels(camera, width, height) {
                let text = Placed {
                    label: m.label,
                    x: m.x,
                    y: m.y,
                };
                place(&mut board, Kind::Mark(m.axis), Art::Text(text));
            }
        }
        pieces
    }

    /// The layer for a `width` × `height` picture; `None` when there is nothing to draw.
    /// The grid and ticks first, then the pieces of [`Overlays::layout`] over them.
    pub fn draw(&self, width: u32, height: u32) -> Option<RgbaImage> {
        if self.is_empty() || width == 0 || height == 0 {
            return None;
        }
        let mut layer = RgbaImage::new(width, height);
        if let Some(camera) = &self.marks {
            draw_grid_and_ticks(&mut layer, camera);
        }
        for piece in self.layout(width, height) {
            match &piece.art {
                Art::Text(p) if matches!(piece.kind, Kind::Mark(_)) => {
                    p.label.draw(&mut layer, p.x, p.y, MARK_COLOUR)
                }
                Art::Text(p) => p.draw(&mut layer),
                Art::Legend(l) => l.draw(&mut layer),
            }
        }
        Some(layer)
    }
}

/// The label of a piece of text (`None` for the legend's panel).
impl Piece {
    pub fn label(&self) -> Option<&Label> {
        match &self.art {
            Art::Text(p) => Some(&p.label),
            Art::Legend(_) => None,
        }
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

    /// White glyph ink (coverage above about 3/4 over the halo) inside the rectangle.
    fn ink(layer: &RgbaImage, r: Rect) -> usize {
        (r.y0.max(0)..r.y1.min(i64::from(layer.height())))
            .flat_map(|y| (r.x0.max(0)..r.x1.min(i64::from(layer.width()))).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let p = layer.get_pixel(x as u32, y as u32).0;
                p[3] > 200 && p[..3].iter().all(|&c| c >= 200)
            })
            .count()
    }

    fn legend_only(min: f64, max: f64) -> Overlays {
        Overlays {
            legend: Some((min, max)),
            ..Overlays::default()
        }
    }

    #[test]
    fn nothing_to_draw_is_no_layer() {
        assert!(Overlays::default().draw(200, 100).is_none());
        let legend = legend_only(0.0, 5.0);
        assert!(legend.draw(0, 100).is_none());
        assert!(legend.draw(200, 100).is_some());
    }

    #[test]
    fn legend_title_is_written_right_of_the_bar_at_the_bottom() {
        let (w, h) = (1400, 300);
        let layer = legend_only(0.5, 6.0).draw(w, h).unwrap();
        let legend = Legend::new(w, h, 0.5, 6.0, 0).unwrap();
        let (bar, panel) = (legend.bar, legend.panel);
        // The colour bar: violet at its left end, yellow at its right end, in the left third.
        let y = ((bar.y0 + bar.y1) / 2) as u32;
        assert_eq!(layer.get_pixel(bar.x0 as u32, y).0, [68, 1, 84, 255]);
        assert_eq!(layer.get_pixel(bar.x1 as u32 - 1, y).0, [253, 231, 37, 255]);
        assert!(bar.x1 < i64::from(w) / 3, "{bar:?}");
        // The range's ends beside the bar, the title with its unit right of the high end, all
        // on the bottom line (about 14 ink pixels a glyph at 20-pixel type).
        let (low, high) = (legend.low.rect(), legend.high.rect());
        assert!(low.x1 <= bar.x0 && high.x0 >= bar.x1);
        assert!(ink(&layer, low) > 10 && ink(&layer, high) > 10);
        let title = legend.title.as_ref().expect("room for the title").rect();
        assert!(title.x0 > high.x1 && title.x1 <= i64::from(w));
        assert_eq!(title.y1, high.y1, "on the same line");
        let glyphs = LEGEND_TITLE.chars().filter(|c| *c != ' ').count();
        let title_ink = ink(&layer, title);
        assert!(
            title_ink > glyphs * 14,
            "title ink at the bottom: {title_ink}"
        );
        // The panel at the bottom-left holds it all; the rest of the layer is clear.
        assert_eq!((panel.x0, panel.y1 > i64::from(h) - 20), (0, true));
        assert!([low, high, title, bar]
            .iter()
            .all(|r| r.inside(panel.x1, panel.y1)));
        let above = Rect::at(0, 0, i64::from(w), panel.y0);
        assert!(layer
            .enumerate_pixels()
            .filter(|(x, y, _)| above.near(&Rect::at(i64::from(*x), i64::from(*y), 1, 1), 0))
            .all(|(_, _, p)| p.0[3] == 0));
        assert_eq!(layer.get_pixel(w - 1, h / 2).0[3], 0);
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
        let overlays = Overlays {
            marks: Some(camera),
            legend: Some((0.0, 12.0)),
            ..Overlays::default()
        };
        let with_marks = overlays.draw(w, h).unwrap();
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
        // The legend's panel is just above that band, and every azimuth label was placed.
        let pieces = overlays.layout(w, h);
        let panel = pieces.iter().find(|p| p.kind == Kind::Legend).unwrap().rect;
        let floor = i64::from(h - band);
        assert!(panel.y1 <= floor && panel.y1 + 8 > floor, "{panel:?}");
        let azimuths = pieces
            .iter()
            .filter(|p| p.kind == Kind::Mark(Axis::Azimuth))
            .count();
        let ticks = crate::marks::ticks(&camera);
        let want = ticks.iter().filter(|t| t.axis == Axis::Azimuth).count();
        assert_eq!(azimuths, want, "−105° to 105° in steps of 15°");
        assert_eq!(want, 15);
    }

    /// On a picture too narrow for a title even in 10-pixel type (a 160×60 frame), the title
    /// is left out rather than cut off at the picture's edge; the rest still shows.
    #[test]
    fn titles_too_wide_for_the_picture_are_left_out_not_cut_off() {
        let (w, h) = (160, 60);
        for title in [FREQUENCY_TITLE, LEGEND_TITLE] {
            assert!(Label::new(title, 10.0).width() > i64::from(w));
        }
        for overlays in [
            Overlays {
                reference_labels: vec![5800.0, 3500.0],
                ..Overlays::default()
            },
            legend_only(0.0, 12.0),
        ] {
            let layer = overlays.draw(w, h).unwrap();
            assert!(
                ink(&layer, Rect::at(0, 0, 160, 60)) > 0,
                "the labels are drawn"
            );
            for piece in overlays.layout(w, h) {
                let text = piece.label().map(|l| l.text.clone()).unwrap_or_default();
                assert!(text != FREQUENCY_TITLE && text != LEGEND_TITLE, "{text}");
            }
            assert_eq!(
                ink(&layer, Rect::at(157, 0, 3, 60)),
                0,
                "no text runs into the right edge"
            );
        }
    }

    #[test]
    fn reference_labels_name_the_temperatures_beside_the_squares() {
        let (w, h) = (640, 320);
        let overlays = |temps: &[f64]| Overlays {
            reference_labels: temps.to_vec(),
            ..Overlays::default()
        };
        let layer = overlays(&[5800.0, 3500.0]).draw(w, h).unwrap();
        let pieces = overlays(&[5800.0, 3500.0]).layout(w, h);
        let squares = reference_rects(2, w, h);
        let text = |p: &Piece| p.label().unwrap().text.clone();
        assert_eq!(
            pieces.iter().map(text).collect::<Vec<_>>(),
            ["g = 1: 5800 K, 3500 K", FREQUENCY_TITLE]
        );
        let (temps, title) = (pieces[0].rect, pieces[1].rect);
        // The temperatures right of the squares, on their line; the title below them, from
        // the left edge of the first.
        let mid = (squares[1].y0 + squares[1].y1) / 2;
        assert!(temps.x0 > squares[1].x1 && temps.y0 < mid && temps.y1 > mid);
        assert!(ink(&layer, temps) > 100, "{}", ink(&layer, temps));
        assert!(title.x0 == squares[0].x0 && title.y0 > squares[0].y1);
        assert!(ink(&layer, title) > 200);
        // The squares themselves are the picture's: the layer leaves them clear.
        for s in &squares {
            assert_eq!(layer.get_pixel(s.x0 as u32 + 1, s.y0 as u32 + 1).0[3], 0);
        }
        // Another temperature writes another label, at the same place.
        let other = overlays(&[5800.0, 9100.0]).draw(w, h).unwrap();
        let differ: Vec<(i64, i64)> = layer
            .enumerate_pixels()
            .zip(other.pixels())
            .filter(|((_, _, a), b)| a != b)
            .map(|((x, y, _), _)| (i64::from(x), i64::from(y)))
            .collect();
        assert!(!differ.is_empty(), "the label names the temperatures");
        assert!(
            differ
                .iter()
                .all(|&(x, y)| temps.near(&Rect::at(x, y, 1, 1), 0)),
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
