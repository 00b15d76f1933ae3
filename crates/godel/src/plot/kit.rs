//! Pieces both figures of `godel plot` draw with: the palette, a light ray from the origin
//! sampled for drawing, tick labels, arrowheads, the output checked before any work and its
//! type chosen by the extension, the shared layout (canvas, frame, clipped data layer in units
//! of a, horizon, legend, caption) and writing the figure.

use crate::args::usage;
use crate::output::{prepare_file, write_atomic};
use crate::plot::svg::{f, to_png, Svg, Weight};
use anyhow::Context;
use spacetime::{trace, Event, Geodesic, Metric, Spacetime, TimeDirection, TraceLimits};

/// Samples per ray from the dense output.
const SAMPLES: usize = 600;

/// Colour-blind-safe palette (Okabe & Ito 2008, without yellow and black).
pub const PALETTE: [&str; 6] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9",
];
/// Traces a future-directed light ray from the origin along the local direction `dir`, one
/// loop of Gödel's universe with parameter `a` ([`TraceLimits::one_loop`]): its events at
/// [`SAMPLES`] evenly spaced parameters, and the time at its end.
pub fn trace_ray(metric: Metric, a: f64, dir: [f64; 3]) -> anyhow::Result<(Vec<Event>, f64)> {
    trace_ray_within(metric, dir, &TraceLimits::one_loop(a))
}

/// [`trace_ray`] with the stops `limits`.
pub fn trace_ray_within(
    metric: Metric,
    dir: [f64; 3],
    limits: &TraceLimits,
) -> anyhow::Result<(Vec<Event>, f64)> {
    let origin = Event::new(0.0, 0.0, 0.0, 0.0);
    let frame = metric.static_frame(origin);
    let g = Geodesic::launch(&metric, origin, &frame, dir, 1.0, TimeDirection::Future)
        .context("cannot launch a ray from the origin")?;
    let traced = trace(metric, &g, limits);
    if traced.stop.is_failure() {
        anyhow::bail!(
            "tracing a ray along {dir:?} failed: {}",
            traced.stop.describe()
        );
    }
    let events = traced.samples(SAMPLES).iter().map(|(_, s)| s.x).collect();
    Ok((events, traced.end.x.t))
}

/// Unicode minus for negative tick labels.
pub fn tick_label(v: f64) -> String {
    let s = f(v);
    match s.strip_prefix('-') {
        Some(rest) => format!("\u{2212}{rest}"),
        None => s,
    }
}

/// A small filled arrowhead (data units) with its tip at `p`, pointing along `d`.
pub fn arrowhead(p: (f64, f64), d: (f64, f64), len: f64) -> [(f64, f64); 3] {
    let n = d.0.hypot(d.1).max(f64::MIN_POSITIVE);
    let (ux, uy) = (d.0 / n, d.1 / n);
    let (bx, by) = (p.0 - len * ux, p.1 - len * uy);
    let w = 0.42 * len;
    [p, (bx - w * uy, by + w * ux), (bx + w * uy, by - w * ux)]
}

/// Before any work: whether a figure goes to PNG (`.png`) or SVG (`.svg`), any other name a
/// usage error; the folder created where missing (as `render` does) and the file checked
/// writable, refusals naming `--output` (exit 2, as every command's).
pub fn prepare_figure_output(output: &std::path::Path) -> anyhow::Result<bool> {
    let ext = output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let png = match ext.as_deref() {
        Some("svg") => false,
        Some("png") => true,
        _ => {
            return Err(usage(
                "--output",
                format!("must end in .svg or .png, got {}", output.display()),
            ))
        }
    };
    prepare_file("--output", output)?;
    Ok(png)
}

/// The layout both figures share: a white 1040 × 660 canvas, a square frame of 520 pixels at
/// (90, 64) showing [−half, half]² in units of a, the legend and caption to its right.
pub struct Frame {
    pub left: f64,
    pub top: f64,
    pub side: f64,
    /// Pixels per unit of a.
    pub scale: f64,
}

impl Frame {
    pub fn new(half: f64) -> Frame {
        Frame::at(90.0, 64.0, 520.0, half)
    }

    /// A frame of `side` pixels with its top left corner at (`left`, `top`), showing
    /// [−half, half]² (a panel of a figure with several).
    pub fn at(left: f64, top: f64, side: f64, half: f64) -> Frame {
        Frame {
            left,
            top,
            side,
            scale: side / (2.0 * half),
        }
    }

    /// The canvas, white, with `title` above the frame.
    pub fn canvas(&self, title: &str) -> Svg {
        let (width, height) = (1040.0, 660.0);
        let mut s = Svg::new(width, height);
        s.rect((0.0, 0.0), (width, height), r#"fill="white""#);
        s.text((self.left, 38.0), 22.0, "start", r##"fill="#222""##, title);
        s
    }

    /// Pixel column of the data coordinate x.
    pub fn px(&self, x: f64) -> f64 {
        (self.left + self.side / 2.0) + self.scale * x
    }

    /// Pixel row of the data coordinate y (y up).
    pub fn py(&self, y: f64) -> f64 {
        (self.top + self.side / 2.0) - self.scale * y
    }

    /// A width in pixels, in data units.
    pub fn data(&self, w: f64) -> f64 {
        w / self.scale
    }

    /// The left edge of the legend.
    pub fn legend_left(&self) -> f64 {
        self.left + self.side + 40.0
    }

    /// The tick labels of the value `v` below the frame (x) and left of it (y).
    pub fn tick_labels(&self, s: &mut Svg, v: f64) {
        s.text(
            (self.px(v), self.top + self.side + 20.0),
            15.0,
            "middle",
            r##"fill="#333""##,
            &tick_label(v),
        );
        s.text(
            (self.left - 10.0, self.py(v) + 5.0),
            15.0,
            "end",
            r##"fill="#333""##,
            &tick_label(v),
        );
    }

    /// The axis titles x / a and y / a, then opens the data layer: clipped to the frame, in
    /// units of a with y up and the origin at the centre. [`Frame::close_data_layer`] closes it.
    pub fn open_data_layer(&self, s: &mut Svg) {
        self.open_data_layer_titled(s, ("x / a", "y / a"), ("frame", "data"));
    }

    /// [`Frame::open_data_layer`] with other axis titles (x, y) and ids (of the clip path, of
    /// the data layer: one pair per frame of a figure).
    pub fn open_data_layer_titled(&self, s: &mut Svg, titles: (&str, &str), ids: (&str, &str)) {
        let (clip, data) = ids;
        let (left, top, side, scale) = (self.left, self.top, self.side, self.scale);
        let (cx, cy) = (left + side / 2.0, top + side / 2.0);
        s.text(
            (cx, top + side + 48.0),
            17.0,
            "middle",
            r##"fill="#222""##,
            titles.0,
        );
        s.text_as(
            (left - 52.0, cy),
            17.0,
            Weight::Regular,
            -90.0,
            "middle",
            r##"fill="#222""##,
            titles.1,
        );

        // Data layer: units of a, y up, clipped to the frame.
        s.raw(&format!(
            r#"<defs><clipPath id="{clip}"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath></defs>"#,
            f(left),
            f(top),
            f(side),
            f(side)
        ));
        s.group(&format!(r#"clip-path="url(#{clip})""#));
        s.group(&format!(
            r#"id="{data}" transform="translate({},{}) scale({},{})""#,
            f(cx),
            f(cy),
            f(scale),
            f(-scale)
        ));
    }

    /// The optical horizon r = 2a of the origin, dashed, `width` pixels wide (data layer).
    pub fn horizon(&self, s: &mut Svg, width: f64) {
        s.circle(
            (0.0, 0.0),
            2.0,
            &format!(
                r##"id="horizon" fill="none" stroke="#222" stroke-width="{}" stroke-dasharray="{} {}""##,
                f(self.data(width)),
                f(self.data(7.0)),
                f(self.data(5.0))
            ),
        );
    }

    /// Closes the data layer and draws the frame over it.
    pub fn close_data_layer(&self, s: &mut Svg) {
        s.end_group();
        s.end_group();
        s.rect(
            (self.left, self.top),
            (self.side, self.side),
            r##"fill="none" stroke="#333" stroke-width="1.2""##,
        );
    }
}

/// A figure's legend: the bold heading, then rows 26 pixels apart (the first 28 below the
/// heading), each a key drawn from `x0` and its text at `text_x`.
pub struct Legend {
    x0: f64,
    text_x: f64,
    /// The text line of the last row drawn (of the heading before any).
    pub y: f64,
    rows: usize,
}

impl Legend {
    /// Draws the heading at (`x0`, `top`); keys go on the left of `text_x`.
    pub fn new(s: &mut Svg, x0: f64, top: f64, text_x: f64) -> Legend {
        s.text_as(
            (x0, top),
            16.0,
            Weight::Bold,
            0.0,
            "start",
            r##"fill="#222""##,
            "Legend",
        );
        Legend {
            x0,
            text_x,
            y: top,
            rows: 0,
        }
    }

    /// A new row's text line, after the last.
    fn next(&mut self) -> f64 {
        self.y += if self.rows == 0 { 28.0 } else { 26.0 };
        self.rows += 1;
        self.y
    }

    fn text(&self, s: &mut Svg, text: &str) {
        s.text(
            (self.text_x, self.y),
            15.0,
            "start",
            r##"fill="#222""##,
            text,
        );
    }

    /// A row keyed by the first `n` palette colours: short lines `step` pixels apart,
    /// overlapping.
    pub fn swatches(&mut self, s: &mut Svg, n: usize, step: f64, text: &str) {
        let y = self.next();
        for (k, colour) in PALETTE.iter().enumerate().take(n.min(PALETTE.len())) {
            let xk = self.x0 + step * k as f64;
            s.line(
                (xk, y - 5.0),
                (xk + 30.0, y - 5.0),
                &format!(r#"stroke="{colour}" stroke-width="2""#),
            );
        }
        self.text(s, text);
    }

    /// A row keyed by a line `length` pixels long, drawn with `style`.
    pub fn line(&mut self, s: &mut Svg, length: f64, style: &str, text: &str) {
        let y = self.next();
        s.line((self.x0, y - 5.0), (self.x0 + length, y - 5.0), style);
        self.text(s, text);
    }

    /// A row keyed by an arrowhead pointing right, `length` pixels long, its tip 44 pixels
    /// from the key's start, filled with `fill`.
    pub fn arrow(&mut self, s: &mut Svg, length: f64, fill: &str, text: &str) {
        let y = self.next();
        let (tip, base) = (self.x0 + 44.0, self.x0 + 44.0 - length);
        s.polygon(
            &[(tip, y - 5.0), (base, y - 10.0), (base, y)],
            &format!(r#"fill="{fill}""#),
        );
        self.text(s, text);
    }
}

/// The caption's lines from (`x`, `y`) down, 22 pixels apart.
pub fn caption(s: &mut Svg, x: f64, mut y: f64, lines: &[String]) {
    for line in lines {
        s.text((x, y), 15.0, "start", r##"fill="#333""##, line);
        y += 22.0;
    }
}

/// Writes the figure `svg` to `output`, as PNG (at twice the size) when `png`, else as SVG.
pub fn write_figure(output: &std::path::Path, svg: String, png: bool) -> anyhow::Result<()> {
    let bytes = if png {
        to_png(&svg, 2.0)?
    } else {
        svg.into_bytes()
    };
    write_atomic(output, &bytes)
}
