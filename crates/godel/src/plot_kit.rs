//! Pieces both figures of `godel plot` draw with: the palette, a light ray from the origin
//! sampled for drawing, tick labels, arrowheads, the output type chosen by the extension,
//! and the clipped data layer in units of a.

use crate::args::usage;
use crate::svg::{f, Svg};
use anyhow::Context;
use spacetime::{trace, Event, Geodesic, Metric, Spacetime, TimeDirection, TraceLimits};

/// Samples per ray from the dense output.
const SAMPLES: usize = 600;

/// Colour-blind-safe palette (Okabe & Ito 2008, without yellow and black).
pub const PALETTE: [&str; 6] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9",
];
/// Traces a future-directed light ray from the origin along the local direction `dir`:
/// its events at [`SAMPLES`] evenly spaced parameters, and the time at its end.
pub fn trace_ray(metric: Metric, a: f64, dir: [f64; 3]) -> anyhow::Result<(Vec<Event>, f64)> {
    let origin = Event::new(0.0, 0.0, 0.0, 0.0);
    let frame = metric.static_frame(origin);
    let g = Geodesic::launch(&metric, origin, &frame, dir, 1.0, TimeDirection::Future)
        .context("cannot launch a ray from the origin")?;
    let traced = trace(metric, &g, &TraceLimits::one_loop(a));
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

/// Whether a figure goes to PNG (`.png`) or SVG (`.svg`); any other name is an error.
pub fn output_is_png(output: &std::path::Path) -> anyhow::Result<bool> {
    let ext = output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => Ok(false),
        Some("png") => Ok(true),
        _ => Err(usage(
            "--output",
            format!("must end in .svg or .png, got {}", output.display()),
        )),
    }
}

/// The axis titles x / a and y / a of a square frame at (`left`, `top`) with side `side`,
/// then opens the data layer: clipped to the frame, in units of a with y up and the origin
/// at the centre. The caller closes it with two [`Svg::end_group`].
pub fn open_data_layer(s: &mut Svg, left: f64, top: f64, side: f64, scale: f64) {
    let (cx, cy) = (left + side / 2.0, top + side / 2.0);
    s.text(
        (cx, top + side + 48.0),
        17.0,
        "middle",
        r##"fill="#222""##,
        "x / a",
    );
    s.raw(&format!(
        r##"<text x="0" y="0" transform="translate({},{}) rotate(-90)" font-family="{}" font-size="17" text-anchor="middle" fill="#222">y / a</text>"##,
        f(left - 52.0),
        f(cy),
        crate::svg::FONT_FAMILY
    ));

    // Data layer: units of a, y up, clipped to the frame.
    s.raw(&format!(
        r#"<defs><clipPath id="frame"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath></defs>"#,
        f(left),
        f(top),
        f(side),
        f(side)
    ));
    s.group(r#"clip-path="url(#frame)""#);
    s.group(&format!(
        r#"id="data" transform="translate({},{}) scale({},{})""#,
        f(cx),
        f(cy),
        f(scale),
        f(-scale)
    ));
}
