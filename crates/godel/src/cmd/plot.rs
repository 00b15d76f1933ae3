//! `godel plot geodesics`: the r–φ (x–y) plane figure of light rays through the origin of
//! Gödel's universe, as in Gödel, Rev. Mod. Phys. 21, 447 (1949) and the ray-tracing papers
//! after it: a fan of future-directed light rays leaves the origin, each circles
//! counter-clockwise, touches the optical horizon r = 2a tangentially and returns to the origin
//! after Δt = 2πa(√2 − 1); rays tilted out of the plane stay strictly inside the horizon.
//! The rays are traced numerically (one loop each, `TraceLimits::one_loop`), not drawn from
//! the closed form. Output: SVG, or PNG rasterized from it (chosen by the `-o` extension).
//!
//! With `--metric godel-type --m2 --omega`, or `--members` (m²/Ω² of up to three members),
//! the figure is the Gödel-type family's (`plot::family`).

use crate::args::{member, parse_list, usage};
use crate::plot::family::{frame_half, member_figure, members_figure, trace_member};
use crate::plot::kit::{
    arrowhead, caption, prepare_figure_output, trace_ray, write_figure, Frame, Legend, PALETTE,
};
use crate::plot::svg::f;
use spacetime::{Event, Godel, Metric};
use std::f64::consts::PI;
use std::path::PathBuf;

/// `godel plot ...`
#[derive(clap::Args, Debug)]
pub struct PlotArgs {
    #[command(subcommand)]
    pub figure: Figure,
}

/// The figures `godel plot` draws.
#[derive(clap::Subcommand, Debug)]
pub enum Figure {
    /// Light rays through the origin in the x–y plane, with the optical horizon r = 2a.
    Geodesics(GeodesicsPlotArgs),
    /// One light ray and its images under the flow of a Killing field, with the field.
    Isometry(crate::plot::isometry::IsometryPlotArgs),
}

/// The spacetimes `godel plot geodesics` draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PlotMetric {
    Godel,
    /// A member of the Gödel-type family (--m2, --omega), or several (--members).
    GodelType,
}

/// Arguments of `godel plot geodesics`.
#[derive(clap::Args, Debug)]
#[command(after_help = "\
Gödel-type family: --metric godel-type --m2 M2 [--omega OMEGA] draws one member's light rays \
from the origin in the plane z = 0, with the circle ρ = ρ_c beyond which closed timelike \
curves exist and where those rays turn (none for m² ≥ 4Ω²: the rays escape and are drawn \
until they leave the frame); --members 0,2,4.5 draws up to three members side by side, \
given as m²/Ω² at one Ω (--metric godel-type implied). Axes in units of 1/Ω, ρ the proper \
radius. --omega defaults to 1; in units of 1/Ω the picture depends on m²/Ω² only.

Examples: godel plot geodesics -o geodesics.png
          godel plot geodesics --members 0,2,4.5 -o family-geodesics.png")]
pub struct GeodesicsPlotArgs {
    /// Spacetime [default: godel; godel-type with --members].
    #[arg(long, value_enum)]
    pub metric: Option<PlotMetric>,
    /// Gödel parameter a > 0 (axes are in units of a) [default: 1]; metric godel only.
    #[arg(long, allow_hyphen_values = true)]
    pub a: Option<f64>,
    /// m² of the Gödel-type member (any sign; metric godel-type).
    #[arg(long, value_name = "M2", allow_hyphen_values = true)]
    pub m2: Option<f64>,
    /// Vorticity Ω > 0 of the Gödel-type members [default: 1].
    #[arg(long, value_name = "OMEGA", allow_hyphen_values = true)]
    pub omega: Option<f64>,
    /// Gödel-type members side by side: their m²/Ω², comma-separated (1 to 3).
    #[arg(long, value_name = "M2/OMEGA2,...", allow_hyphen_values = true)]
    pub members: Option<String>,
    /// Number of light rays in the plane (evenly spaced azimuths, 1 to 360).
    #[arg(long, value_name = "N", default_value_t = 12)]
    pub rays: usize,
    /// Number of extra rays tilted 45° out of the plane, drawn lighter (0 to 360)
    /// [default: 4]; metric godel only.
    #[arg(long, value_name = "N")]
    pub tilted: Option<usize>,
    /// Output file, .svg or .png (PNG at 2 pixels per SVG unit).
    #[arg(short, long, value_name = "FILE", default_value = "geodesics.svg")]
    pub output: PathBuf,
}

const TILTED_COLOUR: &str = "#9A9A9A";
/// Elevation of the tilted rays above the plane.
const TILT: f64 = PI / 4.0;

/// One traced ray projected on the x–y plane, in units of a.
struct Ray {
    points: Vec<(f64, f64)>,
    /// Coordinate time at the end (the return to the axis).
    t_end: f64,
    tilted: bool,
    colour: &'static str,
}

/// Points of `events` in the x–y plane, in units of a.
fn projected(events: &[Event], a: f64) -> Vec<(f64, f64)> {
    events.iter().map(|e| (e.x / a, e.y / a)).collect()
}

fn trace_fan(a: f64, n_plane: usize, n_tilted: usize) -> anyhow::Result<Vec<Ray>> {
    let metric = Metric::Godel(Godel::new(a));
    let mut rays = Vec::new();
    for k in 0..n_tilted {
        let chi = 2.0 * PI * (k as f64 + 0.5) / n_tilted as f64;
        let dir = [TILT.cos() * chi.cos(), TILT.cos() * chi.sin(), TILT.sin()];
        let (events, t_end) = trace_ray(metric, a, dir)?;
        rays.push(Ray {
            points: projected(&events, a),
            t_end,
            tilted: true,
            colour: TILTED_COLOUR,
        });
    }
    for k in 0..n_plane {
        let chi = 2.0 * PI * k as f64 / n_plane as f64;
        let (events, t_end) = trace_ray(metric, a, [chi.cos(), chi.sin(), 0.0])?;
        rays.push(Ray {
            points: projected(&events, a),
            t_end,
            tilted: false,
            colour: PALETTE[k % PALETTE.len()],
        });
    }
    Ok(rays)
}

/// Builds the figure's SVG text.
fn figure(a: f64, rays: &[Ray], n_plane: usize, n_tilted: usize) -> String {
    let fr = Frame::new(2.5); // data range [-2.5, 2.5] in units of a
    let (left, top, side) = (fr.left, fr.top, fr.side);
    let (px, py, data) = (|x| fr.px(x), |y| fr.py(y), |w| fr.data(w));
    let mut s = fr.canvas("Light rays through the origin of Gödel’s universe");

    // Grid, frame, ticks, labels (pixel coordinates).
    for k in -2..=2 {
        let v = k as f64;
        s.line(
            (px(v), top),
            (px(v), top + side),
            r##"stroke="#ececec" stroke-width="1""##,
        );
        s.line(
            (left, py(v)),
            (left + side, py(v)),
            r##"stroke="#ececec" stroke-width="1""##,
        );
    }
    for k in -5..=5 {
        let v = 0.5 * k as f64;
        let len = if k % 2 == 0 { 7.0 } else { 4.0 };
        let st = r##"stroke="#333" stroke-width="1""##;
        s.line((px(v), top + side), (px(v), top + side - len), st);
        s.line((px(v), top), (px(v), top + len), st);
        s.line((left, py(v)), (left + len, py(v)), st);
        s.line((left + side, py(v)), (left + side - len, py(v)), st);
        if k % 2 == 0 {
            fr.tick_labels(&mut s, v);
        }
    }
    fr.open_data_layer(&mut s);
    s.circle(
        (0.0, 0.0),
        2.0,
        r##"id="horizon-disc" fill="#f4f4f4" stroke="none""##,
    );
    for ray in rays.iter().filter(|r| r.tilted) {
        s.polyline(
            &ray.points,
            &format!(r#"stroke="{}" stroke-width="{}""#, ray.colour, f(data(1.3))),
        );
    }
    for ray in rays.iter().filter(|r| !r.tilted) {
        s.polyline(
            &ray.points,
            &format!(
                r#"stroke="{}" stroke-width="{}" stroke-linejoin="round""#,
                ray.colour,
                f(data(1.8))
            ),
        );
    }
    // Arrowheads showing the future direction.
    for ray in rays {
        let n = ray.points.len();
        let fractions: &[f64] = if ray.tilted { &[0.5] } else { &[0.3, 0.7] };
        for &frac in fractions {
            let i = ((n - 1) as f64 * frac).round() as usize;
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(n - 1));
            let d = (
                ray.points[i1].0 - ray.points[i0].0,
                ray.points[i1].1 - ray.points[i0].1,
            );
            let len = if ray.tilted { data(9.0) } else { data(11.0) };
            s.polygon(
                &arrowhead(ray.points[i], d, len),
                &format!(r#"fill="{}""#, ray.colour),
            );
        }
    }
    fr.horizon(&mut s, 1.6);
    s.circle((0.0, 0.0), data(3.5), r##"fill="#222""##);
    fr.close_data_layer(&mut s);

    // Horizon label with a leader line, in the upper right corner of the frame.
    let at = 0.30 * PI;
    let (lx, ly) = (px(2.0 * at.cos()), py(2.0 * at.sin()));
    let (tx, ty) = (left + side - 10.0, top + 24.0);
    s.line(
        (lx + 3.0, ly - 3.0),
        (tx - 60.0, ty + 6.0),
        r##"stroke="#222" stroke-width="1""##,
    );
    s.text(
        (tx, ty),
        15.0,
        "end",
        r##"fill="#222""##,
        "optical horizon r = 2a",
    );

    // Legend and caption on the right.
    let x0 = fr.legend_left();
    let mut legend = Legend::new(&mut s, x0, top + 20.0, x0 + 80.0);
    let in_plane = format!("light rays in the plane ({n_plane})");
    legend.swatches(&mut s, n_plane, 9.0, &in_plane);
    if n_tilted > 0 {
        let style = format!(r#"stroke="{TILTED_COLOUR}" stroke-width="2""#);
        let text = format!("tilted 45° out of it ({n_tilted})");
        legend.line(&mut s, 72.0, &style, &text);
    }
    let dashed = r##"stroke="#222" stroke-width="1.6" stroke-dasharray="7 5""##;
    legend.line(&mut s, 72.0, dashed, "optical horizon r = 2a");
    legend.arrow(&mut s, 12.0, "#444", "future direction");
    let y = legend.y;

    let t_ret = Godel::new(a).shortest_loop_time();
    let plane: Vec<f64> = rays.iter().filter(|r| !r.tilted).map(|r| r.t_end).collect();
    let t_mean = plane.iter().sum::<f64>() / plane.len().max(1) as f64;
    let lines = [
        format!("Gödel universe, a = {}. Each future-directed", f(a)),
        "light ray from the origin circles counter-".to_string(),
        "clockwise, touches the optical horizon".to_string(),
        "r = 2a and returns to the origin after".to_string(),
        format!("Δt = 2πa(√2 − 1) = {t_ret:.6}"),
        format!("(traced: {t_mean:.6})."),
        String::new(),
        "Rays leaving the plane (grey, projected)".to_string(),
        "make smaller loops, strictly inside r = 2a.".to_string(),
        String::new(),
        "Traced numerically (DOP853), one loop each.".to_string(),
    ];
    caption(&mut s, x0, y + 48.0, &lines);
    s.finish("Light rays through the origin of Gödel's universe")
}

/// Runs `godel plot ...`.
pub fn run(args: PlotArgs) -> anyhow::Result<()> {
    match args.figure {
        Figure::Geodesics(g) => plot_geodesics(g),
        Figure::Isometry(i) => crate::plot::isometry::plot_isometry(i),
    }
}

/// Most members side by side.
const MAX_MEMBERS: usize = 3;

fn plot_geodesics(args: GeodesicsPlotArgs) -> anyhow::Result<()> {
    if !(1..=360).contains(&args.rays) {
        return Err(usage(
            "--rays",
            format!("must be between 1 and 360, got {}", args.rays),
        ));
    }
    let family = match args.metric {
        Some(PlotMetric::GodelType) => true,
        Some(PlotMetric::Godel) => false,
        None => args.members.is_some(),
    };
    if family {
        return plot_family(&args);
    }
    for (flag, given) in [
        ("--m2", args.m2.is_some()),
        ("--omega", args.omega.is_some()),
        ("--members", args.members.is_some()),
    ] {
        if given {
            return Err(usage(
                flag,
                "draws Gödel-type members: not used by --metric godel",
            ));
        }
    }
    let a = crate::args::scale_a("--a", args.a.unwrap_or(1.0))?;
    let tilted = args.tilted.unwrap_or(4);
    if tilted > 360 {
        return Err(usage(
            "--tilted",
            format!("must be between 0 and 360, got {tilted}"),
        ));
    }
    let png = prepare_figure_output(&args.output)?;
    let rays = trace_fan(a, args.rays, tilted)?;
    let svg = figure(a, &rays, args.rays, tilted);
    write_figure(&args.output, svg, png)
}

/// The Gödel-type family's figure: one member (--m2) or several (--members).
fn plot_family(args: &GeodesicsPlotArgs) -> anyhow::Result<()> {
    let why = "not used by --metric godel-type (its constants are --m2 and --omega)";
    if args.a.is_some() {
        return Err(usage("--a", why));
    }
    if args.tilted.is_some() {
        return Err(usage(
            "--tilted",
            "the Gödel-type figure draws the rays in the plane only",
        ));
    }
    let omega = args.omega.unwrap_or(1.0);
    let members = match &args.members {
        Some(list) => {
            if args.m2.is_some() {
                return Err(usage(
                    "--m2",
                    "not used with --members, which gives each member's m²/Ω²",
                ));
            }
            let ratios = parse_list("--members", list, MAX_MEMBERS)?;
            let mut members = Vec::with_capacity(ratios.len());
            for ratio in ratios {
                let one = member(Some(ratio * omega * omega), Some(omega));
                // A bad Ω is --omega's; a bad m² is the list's.
                members.push(
                    one.map_err(|e| match e.downcast::<crate::args::UsageError>() {
                        Ok(u) if u.flag == "--m2" => usage("--members", u.message),
                        Ok(u) => u.into(),
                        Err(e) => e,
                    })?,
                );
            }
            members
        }
        None => vec![member(args.m2, Some(omega))?],
    };
    let png = prepare_figure_output(&args.output)?;
    let half = frame_half(&members);
    let traced = members
        .iter()
        .map(|&g| trace_member(g, args.rays, half))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let svg = match args.members {
        Some(_) => members_figure(&traced, args.rays),
        None => member_figure(&traced[0], args.rays),
    };
    write_figure(&args.output, svg, png)
}
