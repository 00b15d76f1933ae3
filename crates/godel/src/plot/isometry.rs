//! `godel plot isometry`: one light ray moved along a Killing field — the family of its
//! images under the flow exp(s ξ) and the field's arrows, in the x–y plane (the figure of
//! the symmetry technique in Grave et al., PRD 80, 103002 (2009), Sec. III).
//!
//! The ray is traced numerically (one loop from the origin); each image is the exact flow
//! of the Killing field applied to every sample (`spacetime::Isometry::flow`, checked against
//! integrating dX/ds = ξ(X) in `spacetime/tests/integration/symmetry.rs`). Because the flow is an
//! isometry, every image is again a light ray: it leaves its own start event, touches that
//! event's horizon and comes back to it after the same Δt = 2πa(√2 − 1). The translations
//! K_x, K_y move the start along their orbit (for K_x the x axis, to x = 2a sinh(s/2a));
//! ∂φ rotates the loop about the origin.

use crate::args::usage;
use crate::plot::kit::{
    arrowhead, caption, prepare_figure_output, tick_label, trace_ray, write_figure, Frame, Legend,
    PALETTE,
};
use crate::plot::svg::f;
use clap::ValueEnum;
use spacetime::{Event, Godel, Isometry, KillingField, Metric};
use std::path::PathBuf;

/// The Killing fields whose flow shows in the x–y plane (∂t and ∂z do not move a projection).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FieldName {
    /// K_x: the translation that is ∂x on the axis.
    Kx,
    /// K_y: the translation that is ∂y on the axis.
    Ky,
    /// ∂φ: rotation about the axis.
    Phi,
}

impl FieldName {
    fn field(self) -> KillingField {
        match self {
            FieldName::Kx => KillingField::Kx,
            FieldName::Ky => KillingField::Ky,
            FieldName::Phi => KillingField::Phi,
        }
    }
    fn label(self) -> &'static str {
        match self {
            FieldName::Kx => "K_x",
            FieldName::Ky => "K_y",
            FieldName::Phi => "∂φ",
        }
    }
}

/// Arguments of `godel plot isometry`.
#[derive(clap::Args, Debug)]
pub struct IsometryPlotArgs {
    /// Gödel parameter a > 0 (axes are in units of a).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub a: f64,
    /// The Killing field to move the ray along.
    #[arg(long, value_enum, default_value_t = FieldName::Kx)]
    pub field: FieldName,
    /// Number of images (1 to 24), at flow parameters evenly spaced in [−S, S].
    #[arg(long, value_name = "N", default_value_t = 6)]
    pub images: usize,
    /// Largest flow parameter S (units of a for K_x, K_y; radians for ∂φ), 0 < S ≤ 3.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1.2,
        allow_hyphen_values = true
    )]
    pub spread: f64,
    /// Direction of the ray at the origin, degrees from the x axis, in the plane.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 90.0,
        allow_hyphen_values = true
    )]
    pub angle: f64,
    /// Output file, .svg or .png (PNG at 2 pixels per SVG unit).
    #[arg(short, long, value_name = "FILE", default_value = "isometry.svg")]
    pub output: PathBuf,
}

/// Half the plotted range, in units of a.
const HALF: f64 = 3.5;
/// Colour of the original ray.
const ORIGINAL: &str = "#222222";

/// One image of the ray: its flow parameter and points (units of a).
pub struct Image {
    pub s: f64,
    pub points: Vec<(f64, f64)>,
}

/// The flow parameters of the images: N values evenly spaced in [−S, S] (S alone for N = 1).
pub fn parameters(n: usize, spread: f64) -> Vec<f64> {
    if n == 1 {
        return vec![spread];
    }
    (0..n)
        .map(|k| -spread + 2.0 * spread * k as f64 / (n - 1) as f64)
        .collect()
}

/// Draws the figure; `events` is the traced ray (events along it).
fn figure(args: &IsometryPlotArgs, a: f64, events: &[Event], images: &[Image]) -> String {
    let fr = Frame::new(HALF);
    let (left, top, side) = (fr.left, fr.top, fr.side);
    let (px, py, data) = (|x| fr.px(x), |y| fr.py(y), |w| fr.data(w));
    let field = args.field;
    let mut s = fr.canvas(&format!(
        "A light ray moved along the Killing field {}",
        field.label()
    ));

    for k in -3..=3 {
        let v = k as f64;
        let grid = r##"stroke="#ececec" stroke-width="1""##;
        s.line((px(v), top), (px(v), top + side), grid);
        s.line((left, py(v)), (left + side, py(v)), grid);
        fr.tick_labels(&mut s, v);
    }
    fr.open_data_layer(&mut s);

    // The field's arrows: direction of its x–y part on a grid (length fixed; the field
    // grows like r/2a far out).
    s.group(r##"id="field" fill="#9a9a9a" stroke="#9a9a9a""##);
    let step = 0.5;
    let n = (HALF / step) as i32;
    for i in -n..=n {
        for j in -n..=n {
            let (x, y) = (i as f64 * step, j as f64 * step);
            let xi = field.field().at(1.0, Event::new(0.0, x, y, 0.0));
            let len = xi.x.hypot(xi.y);
            if len < 1e-9 {
                continue;
            }
            let (ux, uy) = (0.32 * xi.x / len, 0.32 * xi.y / len);
            let (x0, y0) = (x - 0.5 * ux, y - 0.5 * uy);
            let tip = (x + 0.5 * ux, y + 0.5 * uy);
            s.line(
                (x0, y0),
                tip,
                &format!(r#"stroke-width="{}""#, f(data(1.0))),
            );
            s.polygon(&arrowhead(tip, (ux, uy), data(6.0)), r#"stroke="none""#);
        }
    }
    s.end_group();

    for (k, img) in images.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        s.raw(&format!(r#"<g id="image-{k}" data-s="{}">"#, f(img.s)));
        s.polyline(
            &img.points,
            &format!(
                r#"stroke="{colour}" stroke-width="{}" stroke-linejoin="round""#,
                f(data(1.6))
            ),
        );
        s.circle(img.points[0], data(3.5), &format!(r#"fill="{colour}""#));
        let m = img.points.len() / 3;
        let d = (
            img.points[m + 1].0 - img.points[m - 1].0,
            img.points[m + 1].1 - img.points[m - 1].1,
        );
        s.polygon(
            &arrowhead(img.points[m], d, data(10.0)),
            &format!(r#"fill="{colour}""#),
        );
        s.end_group();
    }
    let original: Vec<(f64, f64)> = events.iter().map(|e| (e.x / a, e.y / a)).collect();
    s.raw(r#"<g id="original">"#);
    s.polyline(
        &original,
        &format!(
            r#"stroke="{ORIGINAL}" stroke-width="{}" stroke-linejoin="round""#,
            f(data(3.0))
        ),
    );
    s.circle((0.0, 0.0), data(4.5), &format!(r#"fill="{ORIGINAL}""#));
    s.end_group();
    fr.horizon(&mut s, 1.2);
    fr.close_data_layer(&mut s);

    // Legend and caption.
    let x0 = fr.legend_left();
    let mut legend = Legend::new(&mut s, x0, top + 20.0, x0 + 70.0);
    let ray = format!(r#"stroke="{ORIGINAL}" stroke-width="3""#);
    legend.line(&mut s, 60.0, &ray, "light ray from the origin");
    let unit = if field == FieldName::Phi { "" } else { "a" };
    let range = format!(
        "its images, s = {}{unit} … {}{unit}",
        tick_label(images[0].s),
        tick_label(images[images.len() - 1].s)
    );
    legend.swatches(&mut s, images.len(), 6.0, &range);
    let direction = format!("direction of {} (x–y part)", field.label());
    legend.arrow(&mut s, 20.0, "#9a9a9a", &direction);
    let dashed = r##"stroke="#222" stroke-width="1.2" stroke-dasharray="7 5""##;
    legend.line(&mut s, 60.0, dashed, "horizon of the origin, r = 2a");
    let y = legend.y;
    let t_ret = spacetime::Godel::new(a).shortest_loop_time();
    let lines = [
        format!("Gödel universe, a = {}. The flow", f(a)),
        format!("exp(s {}) is an isometry, so each image", field.label()),
        "of the ray is again a light ray: it leaves".to_string(),
        "its own start (dot), touches that event's".to_string(),
        "horizon and returns to it after the same".to_string(),
        format!("Δt = 2πa(√2 − 1) = {t_ret:.6}."),
        String::new(),
        "Homogeneity: any event can be moved to".to_string(),
        "the origin, where the light rays are".to_string(),
        "known in closed form.".to_string(),
    ];
    caption(&mut s, x0, y + 44.0, &lines);
    s.finish(&format!(
        "A light ray of Gödel's universe moved along the Killing field {}",
        field.label()
    ))
}

/// Runs `godel plot isometry`.
pub fn plot_isometry(args: IsometryPlotArgs) -> anyhow::Result<()> {
    let a = crate::args::scale_a("--a", args.a)?;
    if !(1..=24).contains(&args.images) {
        return Err(usage(
            "--images",
            format!("must be between 1 and 24, got {}", args.images),
        ));
    }
    if !(args.spread.is_finite() && args.spread > 0.0 && args.spread <= 3.0) {
        return Err(usage(
            "--spread",
            format!("must be in (0, 3], got {}", args.spread),
        ));
    }
    if !args.angle.is_finite() {
        return Err(usage(
            "--angle",
            format!("must be finite, got {}", args.angle),
        ));
    }
    let png = prepare_figure_output(&args.output)?;
    let chi = args.angle.to_radians();
    let metric = Metric::Godel(Godel::new(a));
    let (events, _) = trace_ray(metric, a, [chi.cos(), chi.sin(), 0.0])?;
    // Flow parameters are lengths in units of a for the translations.
    let scale = if args.field == FieldName::Phi { 1.0 } else { a };
    let images: Vec<Image> = parameters(args.images, args.spread)
        .into_iter()
        .map(|s| {
            let iso = Isometry::flow(a, args.field.field(), s * scale);
            let points = events
                .iter()
                .map(|e| {
                    let m = iso.apply(*e);
                    (m.x / a, m.y / a)
                })
                .collect();
            Image { s, points }
        })
        .collect();
    let svg = figure(&args, a, &events, &images);
    write_figure(&args.output, svg, png)
}
