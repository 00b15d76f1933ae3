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
//! The rays with their directions, area distance and miss distance are
//! `spacetime::connection`'s; this file parses the flags and prints them.

use crate::args::{coordinates, parse_vector, scale_a, usage, Format};
use anyhow::Context;
use scene::short;
use serde_json::json;
use spacetime::connection::{connections, on_the_source_axis, Connections, MAX_WINDINGS};
use spacetime::Cylindrical;
use std::io::Write;

/// Raw command-line arguments of `godel connect`.
#[derive(clap::Args, Debug)]
#[command(after_help = "\
Prints one row per light ray, latest emission first: emission time, travel time, winding \
(returns to the source's axis before arrival), branch (outbound/inbound half of the loop), \
direction of departure at the source and of arrival (where to look) at the event, the \
affine length, the source's area distance D (flux = L/(4πD²)) and the ray's miss distance. \
JSON adds the frequency ratio g between source and receiver at rest (1, computed).

Example: godel connect --from 0,0,0,0 --to-source 1.2,0.5,0.3")]
pub struct ConnectArgs {
    /// The receiving event T,R,PHI,Z (cylindrical, PHI in radians).
    #[arg(long, value_name = "T,R,PHI,Z", allow_hyphen_values = true)]
    pub from: String,
    /// The source's position R,PHI,Z; it is at rest there at all times.
    #[arg(long, value_name = "R,PHI,Z", allow_hyphen_values = true)]
    pub to_source: String,
    /// Gödel parameter a > 0 (optical horizon at r = 2a).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub a: f64,
    /// Largest winding counted (0 to 1000): each winding is an earlier emission.
    #[arg(long, value_name = "N", default_value_t = 2)]
    pub windings: u32,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Csv)]
    pub format: Format,
}

/// Finds and checks every connecting ray for the arguments.
pub fn connect(args: &ConnectArgs) -> anyhow::Result<Connections> {
    let a = scale_a("--a", args.a)?;
    let [t, r, phi, z] = parse_vector::<4>("--from", &args.from)?;
    if r < 0.0 {
        return Err(usage("--from", format!("R must be ≥ 0, got {}", short(r))));
    }
    coordinates("--from", &["t", "R", "phi", "z"], &[t, r, phi, z], a)?;
    let [sr, sphi, sz] = parse_vector::<3>("--to-source", &args.to_source)?;
    if sr < 0.0 {
        return Err(usage(
            "--to-source",
            format!("R must be ≥ 0, got {}", short(sr)),
        ));
    }
    coordinates("--to-source", &["R", "phi", "z"], &[sr, sphi, sz], a)?;
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
    if let Some(why) = on_the_source_axis(a, source, event) {
        return Err(usage("--from/--to-source", why.to_string()));
    }
    connections(a, source, event, args.windings).context("a connecting ray has no closed form")
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
    json!({
        "a": ans.a,
        "event": {"t": ev.t, "x": ev.x, "y": ev.y, "z": ev.z},
        "source": {"x": s.x, "y": s.y, "z": s.z},
        "rho": ans.rho,
        "within_horizon": ans.within_horizon(),
        "rays": rays,
    })
}

/// Runs `godel connect`, printing to standard output (and a note on standard error when
/// the event is beyond the source's horizon).
pub fn run(args: ConnectArgs) -> anyhow::Result<()> {
    let ans = connect(&args)?;
    if !ans.within_horizon() {
        eprintln!(
            "note: no light ray connects them: the event is at ρ = {:.6} from the source's axis, \
             beyond its horizon 2a = {}",
            ans.rho,
            2.0 * ans.a
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
