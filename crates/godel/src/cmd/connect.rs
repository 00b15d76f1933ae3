//! `godel connect`: every light ray from a source at rest to a given event ("shadow rays"),
//! with emission times, directions and the source's area distance.
//!
//! An initial-value integrator cannot aim a ray at a point; Gödel's homogeneity can: the
//! isometry sending the source to the axis turns the problem into the closed forms through
//! the origin (`spacetime::connect`; docs/physics.md, "Light rays between a source and an
//! event"; Grave et al., PRD 80, 103002 (2009)). Rays exist only where the event lies within
//! the source's horizon (ρ < 2a); within it there are two per winding in the source's plane,
//! and more off it.
//!
//! `--metric godel-type --m2 M2 --omega OMEGA` finds them in a member of the Gödel-type
//! family (`spacetime::godel_type_connect`; docs/physics.md, "Shadow rays in the family"):
//! R is the proper radius ρ, bounded as scenes bound positions, and rays reach ρ < ρ_c for
//! m² < 4Ω², every event for the causal members.
//!
//! The rays with their directions, area distance and miss distance are
//! `spacetime::connection`'s; this file parses the flags and prints them.

use crate::args::{coordinates, parse_vector, usage, Format};
use crate::cmd::geodesic::{MetricName, SpacetimeArgs};
use anyhow::Context;
use scene::short;
use serde_json::json;
use spacetime::connection::{
    connections, on_the_source_axis, type_connections, type_on_the_source_axis, Connections,
    MAX_WINDINGS,
};
use spacetime::{Cylindrical, Metric};
use std::io::Write;

/// Raw command-line arguments of `godel connect`.
#[derive(clap::Args, Debug)]
#[command(after_help = "\
Prints one row per light ray, latest emission first: emission time, travel time, winding \
(returns to the source's axis before arrival), branch (outbound/inbound half of the loop), \
direction of departure at the source and of arrival (where to look) at the event, the \
affine length, the source's area distance D (flux = L/(4πD²)) and the ray's miss distance. \
JSON adds the frequency ratio g between source and receiver at rest (1, computed).

Gödel-type family: --metric godel-type --m2 M2 --omega OMEGA (as for godel geodesic); R is \
the proper radius ρ, at most 30/m for m² > 0 and π/μ − ρ_c for m² = −μ² < 0. Rays reach \
ρ < ρ_c from the source's axis for m² < 4Ω², every event for m² ≥ 4Ω² (there only one ray \
escapes to each event in the source's plane).

Example: godel connect --from 0,0,0,0 --to-source 1.2,0.5,0.3
         godel connect --metric godel-type --m2 0 --omega 1 --from 1,0.5,0,1 --to-source 0,0,0")]
pub struct ConnectArgs {
    /// The receiving event T,R,PHI,Z (cylindrical, PHI in radians).
    #[arg(long, value_name = "T,R,PHI,Z", allow_hyphen_values = true)]
    pub from: String,
    /// The source's position R,PHI,Z; it is at rest there at all times.
    #[arg(long, value_name = "R,PHI,Z", allow_hyphen_values = true)]
    pub to_source: String,
    /// The spacetime (godel or godel-type: minkowski has no light rays between a source and
    /// an event in closed form).
    #[command(flatten)]
    pub spacetime: SpacetimeArgs,
    /// Largest winding counted (0 to 1000): each winding is an earlier emission.
    #[arg(long, value_name = "N", default_value_t = 2)]
    pub windings: u32,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Csv)]
    pub format: Format,
}

/// The metric of `--metric` with its constants (`SpacetimeArgs::metric`); connect knows the
/// metrics with closed-form shadow rays.
fn metric(args: &ConnectArgs) -> anyhow::Result<Metric> {
    if args.spacetime.metric == MetricName::Minkowski {
        return Err(usage(
            "--metric",
            "connect knows Gödel's universe (godel) and the Gödel-type family (godel-type)",
        ));
    }
    args.spacetime.metric()
}

/// Finds and checks every connecting ray for the arguments.
pub fn connect(args: &ConnectArgs) -> anyhow::Result<Connections> {
    let metric = metric(args)?;
    // Gödel's a, or the member's length scale.
    let scale = metric.length_scale();
    // A member's R is its proper radius, bounded as in scenes.
    let radius = |flag: &str, r: f64| match metric.godel_type() {
        Some(g) => scene::ranges::check_member_radius(g, r).map_err(|e| usage(flag, e)),
        None => Ok(()),
    };
    let [t, r, phi, z] = parse_vector::<4>("--from", &args.from)?;
    if r < 0.0 {
        return Err(usage("--from", format!("R must be ≥ 0, got {}", short(r))));
    }
    coordinates("--from", &["t", "R", "phi", "z"], &[t, r, phi, z], scale)?;
    radius("--from", r)?;
    let [sr, sphi, sz] = parse_vector::<3>("--to-source", &args.to_source)?;
    if sr < 0.0 {
        return Err(usage(
            "--to-source",
            format!("R must be ≥ 0, got {}", short(sr)),
        ));
    }
    coordinates("--to-source", &["R", "phi", "z"], &[sr, sphi, sz], scale)?;
    radius("--to-source", sr)?;
    if args.windings > MAX_WINDINGS {
        return Err(usage(
            "--windings",
            format!("must be at most {MAX_WINDINGS}, got {}", args.windings),
        ));
    }
    let event = Cylindrical { t, r, phi, z }.to_event();
    let source = Cylindrical {
        t: 0.0,
        r: sr,
        phi: sphi,
        z: sz,
    }
    .to_event();
    // Not single rays there, but cones of them: refused rather than one arbitrary member.
    let (axis, found) = match metric.godel_type() {
        Some(g) => (
            type_on_the_source_axis(g, source, event),
            type_connections(g, source, event, args.windings),
        ),
        None => (
            on_the_source_axis(scale, source, event),
            connections(scale, source, event, args.windings),
        ),
    };
    if let Some(why) = axis {
        return Err(usage("--from/--to-source", why.to_string()));
    }
    found.context("a connecting ray has no closed form")
}

fn write_csv(out: &mut impl Write, ans: &Connections) -> std::io::Result<()> {
    writeln!(
        out,
        "t_emit,travel_time,winding,branch,depart_x,depart_y,depart_z,look_x,look_y,look_z,lambda,area_distance,miss"
    )?;
    for c in &ans.rays {
        let [dx, dy, dz] = c.departure;
        let [lx, ly, lz] = c.look;
        writeln!(
            out,
            "{},{},{},{},{dx},{dy},{dz},{lx},{ly},{lz},{},{},{:e}",
            c.ray.emission.t,
            c.travel_time,
            c.ray.winding,
            c.ray.branch.name(),
            c.ray.lambda,
            c.area_distance,
            c.miss
        )?;
    }
    Ok(())
}

fn json_document(ans: &Connections) -> serde_json::Value {
    let rays: Vec<_> = ans
        .rays
        .iter()
        .map(|c| {
            let e = c.ray.emission;
            json!({
                "emission": {"t": e.t, "x": e.x, "y": e.y, "z": e.z},
                "travel_time": c.travel_time,
                "winding": c.ray.winding,
                "branch": c.ray.branch.name(),
                "departure": c.departure,
                "look": c.look,
                "lambda": c.ray.lambda,
                "area_distance": c.area_distance,
                "g": c.g,
                "miss": c.miss,
            })
        })
        .collect();
    let (ev, s) = (ans.event, ans.source);
    let mut doc = json!({
        "event": {"t": ev.t, "x": ev.x, "y": ev.y, "z": ev.z},
        "source": {"x": s.x, "y": s.y, "z": s.z},
        "rho": ans.rho,
        "within_horizon": ans.within_horizon(),
        "rays": rays,
    });
    match ans.metric {
        Metric::GodelType(g) => {
            doc["metric"] = json!("godel-type");
            doc["m2"] = json!(g.m2);
            doc["omega"] = json!(g.omega);
            doc["reach"] = json!(ans.reach);
        }
        m => doc["a"] = json!(m.godel_a()),
    }
    doc
}

/// Runs `godel connect`, printing to standard output (and a note on standard error when
/// the event is beyond the source's horizon).
pub fn run(args: ConnectArgs) -> anyhow::Result<()> {
    let ans = connect(&args)?;
    if !ans.within_horizon() {
        let reach = ans.reach.unwrap_or(f64::INFINITY);
        let limit = match ans.metric {
            Metric::GodelType(_) => format!("ρ_c = {reach:.6}, where its light turns back"),
            _ => format!("its horizon 2a = {reach}"),
        };
        eprintln!(
            "note: no light ray connects them: the event is at ρ = {:.6} from the source's axis, \
             beyond {limit}",
            ans.rho
        );
    }
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    match args.format {
        Format::Csv => write_csv(&mut out, &ans),
        Format::Json => serde_json::to_writer_pretty(&mut out, &json_document(&ans))
            .map_err(std::io::Error::from)
            .and_then(|_| writeln!(out)),
    }
    .and_then(|_| out.flush())
    .context("writing to standard output")
}
