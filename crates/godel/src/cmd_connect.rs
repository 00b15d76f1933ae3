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
//! Each ray is re-evaluated from its emission event with the closed form (isometry ∘ closed
//! form ∘ inverse) and its miss distance at the event printed, so a user sees that it lands.
//! Directions are unit vectors in the static observer's local frame (docs/physics.md,
//! "Frames"): at the source, where the light leaves to; at the event, where it is seen
//! (the opposite of its propagation). Static source and static receiver see no frequency
//! shift (g = 1: ∂t is a Killing field of unit norm), so none is printed.

use crate::args::{coordinates, parse_vector, scale_a, usage, Format};
use anyhow::Context;
use scene::short;
use serde_json::json;
use spacetime::{
    measure, shadow_rays, source_area_distance_sq, Branch, Cylindrical, Event, ExactGeodesic,
    FourVector, Godel, Isometry, ShadowRay, Spacetime,
};
use std::io::Write;

/// Raw command-line arguments of `godel connect`.
#[derive(clap::Args, Debug)]
#[command(after_help = "\
Prints one row per light ray, latest emission first: emission time, travel time, winding \
(returns to the source's axis before arrival), branch (outbound/inbound half of the loop), \
direction of departure at the source and of arrival (where to look) at the event, the \
affine length, the source's area distance D (flux = L/(4πD²)) and the ray's miss distance.

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

/// One connecting ray as printed.
#[derive(Clone, Debug, PartialEq)]
pub struct Connection {
    pub ray: ShadowRay,
    pub travel_time: f64,
    /// Unit direction of departure in the source's static frame.
    pub departure: [f64; 3],
    /// Unit direction toward the source as seen at the event, in its static frame.
    pub look: [f64; 3],
    /// Area distance D of the source along the ray.
    pub area_distance: f64,
    /// |closed form from the emission event at λ − event|, coordinates.
    pub miss: f64,
}

/// The validated request and its answer.
pub struct Answer {
    pub a: f64,
    pub event: Event,
    pub source: Event,
    /// The event's distance from the source's axis in the source's frame (horizon at 2a).
    pub rho: f64,
    pub connections: Vec<Connection>,
}

/// Local spatial components of `v` in the static frame at `at`, normalized.
fn local_direction(metric: &Godel, at: Event, v: FourVector) -> [f64; 3] {
    let frame = metric.static_frame(at);
    let [_, n @ ..] = measure::vector_components(&metric.metric(at), &frame, v);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|c| c / len)
}

/// Finds and checks every connecting ray for the arguments.
pub fn connect(args: &ConnectArgs) -> anyhow::Result<Answer> {
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
    if args.windings > 1000 {
        return Err(usage(
            "--windings",
            format!("must be at most 1000, got {}", args.windings),
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
    let metric = Godel::new(a);
    let rho = Isometry::to_origin(a, source).apply(event).r();
    let connections = shadow_rays(a, source, event, args.windings)
        .into_iter()
        .map(|ray| {
            let g = ExactGeodesic::new(a, ray.emission, ray.tangent)
                .context("a connecting ray has no closed form")?;
            let (end, k_end) = g.at(ray.lambda);
            let miss = (end - event)
                .to_array()
                .iter()
                .fold(0.0_f64, |m, d| m.max(d.abs()));
            let arrival = local_direction(&metric, event, k_end);
            Ok(Connection {
                ray,
                travel_time: event.t - ray.emission.t,
                departure: local_direction(&metric, ray.emission, ray.tangent),
                look: arrival.map(|c| -c),
                area_distance: source_area_distance_sq(a, source, &ray).sqrt(),
                miss,
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    Ok(Answer {
        a,
        event,
        source,
        rho,
        connections,
    })
}

fn branch_name(b: Branch) -> &'static str {
    match b {
        Branch::Outbound => "outbound",
        Branch::Inbound => "inbound",
    }
}

fn write_csv(out: &mut impl Write, ans: &Answer) -> std::io::Result<()> {
    writeln!(
        out,
        "t_emit,travel_time,winding,branch,depart_x,depart_y,depart_z,look_x,look_y,look_z,lambda,area_distance,miss"
    )?;
    for c in &ans.connections {
        let [dx, dy, dz] = c.departure;
        let [lx, ly, lz] = c.look;
        writeln!(
            out,
            "{},{},{},{},{dx},{dy},{dz},{lx},{ly},{lz},{},{},{:e}",
            c.ray.emission.t,
            c.travel_time,
            c.ray.winding,
            branch_name(c.ray.branch),
            c.ray.lambda,
            c.area_distance,
            c.miss
        )?;
    }
    Ok(())
}

fn json_document(ans: &Answer) -> serde_json::Value {
    let rays: Vec<_> = ans
        .connections
        .iter()
        .map(|c| {
            let e = c.ray.emission;
            json!({
                "emission": {"t": e.t, "x": e.x, "y": e.y, "z": e.z},
                "travel_time": c.travel_time,
                "winding": c.ray.winding,
                "branch": branch_name(c.ray.branch),
                "departure": c.departure,
                "look": c.look,
                "lambda": c.ray.lambda,
                "area_distance": c.area_distance,
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
        "within_horizon": ans.rho < 2.0 * ans.a,
        "rays": rays,
    })
}

/// Runs `godel connect`, printing to standard output (and a note on standard error when
/// the event is beyond the source's horizon).
pub fn run(args: ConnectArgs) -> anyhow::Result<()> {
    let ans = connect(&args)?;
    if ans.rho >= 2.0 * ans.a {
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
