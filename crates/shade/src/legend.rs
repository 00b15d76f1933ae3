//! False colour for light travel time and its legend (and the polarization layer's legend,
//! laid out alike): a colour bar in the bottom-left corner
//! with the range's two ends, a title and the unit written in the picture's type
//! ([`crate::text`]), so that a picture shaded by travel time can be read without the
//! command that made it; and the labels of the frequency shader's reference squares. Both are
//! laid out here and placed and drawn by the overlay layer ([`crate::layer`]).
//!
//! The colour map runs through five stops of the viridis map (dark violet for the shortest
//! travel time, yellow for the longest), interpolated linearly in linear RGB.

use image::RgbaImage;

use crate::colour::{rgb_to_srgb8, srgb8_to_linear};
use crate::frequency_shader::{reference_square, REFERENCE_SQUARES};
use crate::placement::Rect;
use crate::polarization::cyclic_colour;
use crate::text::{fill, sizes_from, type_size, unit, Label};

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
pub const LEGEND_TITLE: &str = "light travel time −t_emit (units of a, c = 1)";

/// The polarization legend's title: the angle of the observed polarization on the picture.
pub const POLARIZATION_TITLE: &str = "polarization angle from up towards right";

/// The colours of a legend's bar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Travel time ([`false_colour`]).
    Travel,
    /// Polarization angle ([`crate::polarization::cyclic_colour`]).
    Polarization,
}

/// The title beside the frequency shader's reference squares: what the colours mean.
pub const FREQUENCY_TITLE: &str = "frequency shift g: black body at g·T";

/// A label and the top-left corner of its box.
#[derive(Clone, Debug)]
pub struct Placed {
    pub label: Label,
    pub x: i64,
    pub y: i64,
}

impl Placed {
    /// The label's box.
    pub fn rect(&self) -> Rect {
        Rect::at(self.x, self.y, self.label.width(), self.label.height())
    }

    /// Draws the label in white.
    pub fn draw(&self, img: &mut RgbaImage) {
        self.label.draw(img, self.x, self.y, [255, 255, 255]);
    }
}

/// Height of the colour bar and of the reference squares' digits: DejaVu Sans's cap height,
/// 0.73 em.
fn cap_height(size: f32) -> i64 {
    (0.73 * size).round() as i64
}

/// The travel-time legend laid out on a picture: a dark panel in the bottom-left corner with
/// `min`, the colour bar (violet at `min`, yellow at `max`), `max`, and the title with its unit
/// (on the same line, in smaller type on it, above it, or, on pictures too narrow for it even
/// in 10-pixel type, left out rather than cut off).
#[derive(Clone, Debug)]
pub struct Legend {
    /// The panel, which holds everything else.
    pub panel: Rect,
    /// What the bar's colours are.
    pub scale: Scale,
    pub low: Placed,
    pub high: Placed,
    pub bar: Rect,
    pub title: Option<Placed>,
}

impl Legend {
    /// The legend of travel times `min`..`max` on a `w` × `h` picture, its panel's bottom
    /// `above` pixels up from the bottom edge (room for orientation marks' labels); `None`
    /// where the picture has no room for it.
    pub fn new(w: u32, h: u32, min: f64, max: f64, above: u32) -> Option<Legend> {
        let (low, high) = (label(min), label(max));
        Legend::with(w, h, (&low, &high), LEGEND_TITLE, Scale::Travel, above)
    }

    /// The polarization layer's legend ([`crate::polarization`]): the cyclic colour map of the
    /// observed angle from 0° to 180°, laid out as [`Legend::new`].
    pub fn polarization(w: u32, h: u32, above: u32) -> Option<Legend> {
        let title = POLARIZATION_TITLE;
        Legend::with(w, h, ("0°", "180°"), title, Scale::Polarization, above)
    }

    /// A legend with the bar's ends labelled `ends`, the title `title` and the colours of
    /// `scale`.
    fn with(
        w: u32,
        h: u32,
        ends: (&str, &str),
        title_text: &str,
        scale: Scale,
        above: u32,
    ) -> Option<Legend> {
        let size = type_size(w, h);
        let u = unit(size);
        let (wi, hi) = (i64::from(w), i64::from(h));
        let margin = 3 * u;
        let low = Label::new(ends.0, size);
        let high = Label::new(ends.1, size);
        let lh = low.height();
        let y = hi - i64::from(above) - margin - lh;
        let bar_w = i64::from((w / 5).clamp(40, 256));
        let x_bar = margin + low.width() + u;
        let x_high = x_bar + bar_w + u;
        let x_title = x_high + high.width() + 3 * u;
        let cap = cap_height(size);
        let bar = Rect::at(x_bar, y + low.baseline() - cap, bar_w, cap);
        // The title on the line (on its baseline, in smaller type if need be), else above it.
        let fits = |x: i64, l: &Label| x + l.width() <= wi;
        let on_line = sizes_from(size)
            .map(|k| Label::new(title_text, k))
            .find(|l| fits(x_title, l))
            .map(|l| (x_title, y + low.baseline() - l.baseline(), l));
        let title = on_line.or_else(|| {
            sizes_from(size)
                .map(|k| Label::new(title_text, k))
                .find(|l| fits(margin, l))
                .map(|l| (margin, y - l.height() - u, l))
        });
        let title = title.map(|(x, y, label)| Placed { label, x, y });
        let low = Placed {
            label: low,
            x: margin,
            y,
        };
        let high = Placed {
            label: high,
            x: x_high,
            y,
        };
        let right = [Some(&high), title.as_ref()]
            .into_iter()
            .flatten()
            .map(|p| p.rect().x1)
            .max()
            .unwrap_or(0);
        let top = title.as_ref().map_or(y, |t| t.y.min(y));
        let panel = Rect {
            x0: 0,
            y0: top - 2 * u,
            x1: right + 2 * u,
            y1: y + lh + 2 * u,
        };
        if !panel.inside(wi, hi) || w < 48 || h < 24 {
            return None;
        }
        Some(Legend {
            panel,
            scale,
            low,
            high,
            bar,
            title,
        })
    }

    /// Draws the legend into the overlay layer `img`, on its opaque dark panel.
    pub fn draw(&self, img: &mut RgbaImage) {
        let p = self.panel;
        fill(img, p.x0, p.y0, p.x1 - p.x0, p.y1 - p.y0, [12, 12, 12]);
        self.low.draw(img);
        let b = self.bar;
        let n = b.x1 - b.x0;
        for i in 0..n {
            let s = i as f64 / (n - 1).max(1) as f64;
            let c = match self.scale {
                Scale::Travel => rgb_to_srgb8(false_colour(s)),
                Scale::Polarization => cyclic_colour(s * std::f64::consts::PI),
            };
            fill(img, b.x0 + i, b.y0, 1, b.y1 - b.y0, c);
        }
        self.high.draw(img);
        if let Some(t) = &self.title {
            t.draw(img);
        }
    }
}

/// The reference squares shown for `count` objects on a `w` × `h` picture (drawn by the
/// frequency shader into the picture itself: the layer keeps labels off them).
pub fn reference_rects(count: usize, w: u32, h: u32) -> Vec<Rect> {
    (0..count.min(REFERENCE_SQUARES))
        .filter_map(|k| reference_square(k, w as usize, h as usize))
        .map(|(x, y, side)| Rect::at(x as i64, y as i64, side as i64, side as i64))
        .collect()
}

/// What the reference squares of a picture say: beside them the unshifted colours'
/// temperatures, below them the frequency title.
#[derive(Clone, Debug, Default)]
pub struct ReferenceLabels {
    pub temperatures: Option<Placed>,
    pub title: Option<Placed>,
}

/// The labels of the reference squares of a `w`×`h` picture: `g = 1: 5800 K, 3500 K` (one
/// per square shown, `temperatures` in object order) right of the squares, and the frequency
/// title below them. A line too long for the picture is written in smaller type (down to 10
/// pixels) or left out rather than cut off mid-word.
pub fn reference_labels(temperatures: &[f64], w: u32, h: u32) -> ReferenceLabels {
    let squares = reference_rects(temperatures.len(), w, h);
    let (Some(first), Some(last)) = (squares.first(), squares.last()) else {
        return ReferenceLabels::default();
    };
    let temps: Vec<String> = temperatures[..squares.len()]
        .iter()
        .map(|t| format!("{} K", t.round() as i64))
        .collect();
    let text = format!("g = 1: {}", temps.join(", "));
    let size = type_size(w, h);
    let fitting = |x: i64, text: &str| {
        sizes_from(size)
            .map(|k| (k, Label::new(text, k)))
            .find(|(_, l)| x + l.width() <= i64::from(w))
    };
    let side = last.x1 - last.x0;
    let x = last.x1 + side / 2;
    let temperatures = fitting(x, &text).map(|(k, label)| {
        // The digits centred on the squares.
        let y = (last.y0 + side / 2 - label.baseline() + cap_height(k) / 2).max(0);
        Placed { label, x, y }
    });
    // The title under the squares and the temperatures, left-aligned with the first square.
    let below = temperatures
        .as_ref()
        .map_or(first.y1, |t| t.rect().y1.max(first.y1));
    let title = fitting(first.x0, FREQUENCY_TITLE).map(|(k, label)| Placed {
        label,
        x: first.x0,
        y: below + unit(k),
    });
    ReferenceLabels {
        temperatures,
        title,
    }
}
