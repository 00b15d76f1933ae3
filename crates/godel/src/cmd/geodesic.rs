//! `godel geodesic`: traces one geodesic (a light ray, or a massive particle with `--speed`)
//! from an event given in cylindrical coordinates, launched along a direction of the static
//! observer's local frame there, and prints evenly spaced samples of it as CSV or JSON
//! (JSON adds the constants of motion E, L, p_z, the normalization and their drift).
//!
//! The curve itself, by either method (numeric integration or the closed form), and the
//! checks of the inputs are `spacetime::curve`'s; this file parses the flags, names them in
//! refusals and writes the samples.
//!
//! `--metric godel-type --m2 M2 --omega OMEGA` traces in a member of the Gödel-type family of
//! Rebouças and Tiomno (docs/physics.md, "The Gödel-type family"); there R is the proper
//! radius ρ, bounded as scenes bound positions (`scene::ranges::check_member_radius`).
//!
//! Physics: Gödel, Rev. Mod. Phys. 21, 447 (1949); constants of motion from the Killing fields
//! ∂t, ∂φ, ∂z; integration in pseudo-Cartesian coordinates by the `spacetime` crate.

use crate::args::{coordinates, member, parse_vector, scale_a, usage, Format};
use anyhow::Context;
use clap::ValueEnum;
use scene::short;
use serde_json::json;
use spacetime::curve::{compute, stop_name, Curve, CurveError, CurveMethod, CurveRequest, Input};
use spacetime::{
    ConstantsOfMotion, Cylindrical, GeodesicKind, GeodesicState, Godel, Metric, Minkowski,
    StopReason, TimeDirection,
};
use std::f64::consts::PI;
use std::io::Write;

/// The metrics known on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MetricName {
    Godel,
    Minkowski,
    /// A member of the Gödel-type family (needs --m2 and --omega).
    GodelType,
}

/// How the geodesic is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// Integrate the geodesic equations (DOP853).
    Numeric,
    /// Evaluate the closed form (isometry ∘ closed form through the origin ∘ inverse).
    Exact,
}

/// Raw command-line arguments of `godel geodesic` (validated by [`Request::from_args`]).
/// The spacetime flags of `godel geodesic` and `godel connect`: `--metric` and its
/// constants.
#[derive(clap::Args, Debug, Clone)]
pub struct SpacetimeArgs {
    /// Spacetime metric (`godel connect`: godel or godel-type).
    #[arg(long, value_enum, default_value_t = MetricName::Godel)]
    pub metric: MetricName,
    /// Gödel parameter a > 0 (optical horizon at r = 2a) [default: 1]; metric godel only.
    #[arg(long, allow_hyphen_values = true)]
    pub a: Option<f64>,
    /// m² of a Gödel-type member (any sign; metric godel-type only).
    #[arg(long, value_name = "M2", allow_hyphen_values = true)]
    pub m2: Option<f64>,
    /// Vorticity Ω > 0 of a Gödel-type member (metric godel-type only).
    #[arg(long, value_name = "OMEGA", allow_hyphen_values = true)]
    pub omega: Option<f64>,
}

#[derive(clap::Args, Debug)]
#[command(after_help = "\
Stop: with --until-time DT the geodesic stops exactly where |t - T| = DT. Without it, a \
Gödel geodesic stops after one loop: back on the starting axis (the start's x, y), or at \
the latest after |t - T| = 2√2·π·a; a Gödel-type one likewise with a = 1/(√2·Ω); a \
Minkowski geodesic stops at |t - T| = 10. Either method stops at the latest at parameter \
λ = 10⁶ (a note on stderr says so when that comes before DT); the numeric one also after \
100000 steps (an error).

Gödel-type family: --metric godel-type --m2 M2 --omega OMEGA is the member ds² = \
−(dt + H dφ)² + dρ² + D² dφ² + dz² (docs/physics.md); R is the proper radius ρ. Gödel's \
universe with parameter a is m2 = 1/a², omega = 1/(√2·a). --method exact follows the member's closed form.

Limits: --samples at most 1000000; --a within [1e-6, 1e6]; --omega with 1/(√2·Ω) in that \
range, |--m2| at most 100·Ω²; R at most 30/m for m² > 0, at most π/μ − ρ_c for m² = −μ² < 0.

Output: CSV columns lambda,t,r,phi,z,x,y (phi unwrapped, continuous), or JSON with the \
samples, the stop reason, the constants of motion and their relative drift.

Examples: godel geodesic --at 0,0,0,0 --dir 1,0,0
          godel geodesic --metric godel-type --m2 0 --omega 1 --at 0,0,0,0 --dir 1,0,0")]
pub struct GeodesicArgs {
    #[command(flatten)]
    pub spacetime: SpacetimeArgs,
    /// Integrate numerically, or evaluate the closed form.
    #[arg(long, value_enum, default_value_t = Method::Numeric)]
    pub method: Method,
    /// Start event T,R,PHI,Z in cylindrical coordinates (PHI in radians, R ≥ 0).
    #[arg(long, value_name = "T,R,PHI,Z", allow_hyphen_values = true)]
    pub at: String,
    /// Direction X,Y,Z in the static observer's local frame at the start (any length ≠ 0).
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub dir: String,
    /// Speed 0 ≤ V < 1 in the local frame for a massive particle (parameter = proper time);
    /// without it, a light ray (affine parameter).
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    pub speed: Option<f64>,
    /// Integrate toward the past instead of the future.
    #[arg(long)]
    pub past: bool,
    /// Stop exactly at |t - T| = DT (coordinate time, DT > 0).
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    pub until_time: Option<f64>,
    /// Number of samples, evenly spaced in the parameter (2 to 1000000; first at the start,
    /// last at the stop).
    #[arg(long, value_name = "N", default_value_t = 100)]
    pub samples: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Csv)]
    pub format: Format,
}

/// A validated `godel geodesic` request: the curve's, and how to print it.
#[derive(Clone, Debug)]
pub struct Request {
    pub curve: CurveRequest,
    pub method: Method,
    /// The start as given (its φ starts the unwrapped φ column).
    pub start: Cylindrical,
    pub format: Format,
}

/// The flag of each input that `spacetime::curve` checks.
fn flag(input: Input) -> &'static str {
    match input {
        Input::Start => "--at",
        Input::Direction => "--dir",
        Input::Speed => "--speed",
        Input::UntilTime => "--until-time",
        Input::Samples => "--samples",
        Input::Method => "--method",
    }
}

/// A refusal of `spacetime::curve` as a usage error naming the flag; a failed integration
/// as a plain error (exit 1).
fn curve_error(e: CurveError) -> anyhow::Error {
    match e {
        CurveError::Input { input, message } => usage(flag(input), message),
        e => e.into(),
    }
}

impl Request {
    /// Checks every value; errors name the flag.
    pub fn from_args(args: &GeodesicArgs) -> anyhow::Result<Request> {
        let metric = args.spacetime.metric()?;
        let [t, r, phi, z] = parse_vector::<4>("--at", &args.at)?;
        if r < 0.0 {
            return Err(usage("--at", format!("R must be ≥ 0, got {}", short(r))));
        }
        let scale = metric.length_scale();
        coordinates("--at", &["t", "R", "phi", "z"], &[t, r, phi, z], scale)?;
        if let Some(g) = metric.godel_type() {
            scene::ranges::check_member_radius(g, r).map_err(|e| usage("--at", e))?;
        }
        let start = Cylindrical { t, r, phi, z };
        let direction = parse_vector::<3>("--dir", &args.dir)?;
        let curve = CurveRequest::new(
            metric,
            match args.method {
                Method::Numeric => CurveMethod::Numeric,
                Method::Exact => CurveMethod::Exact,
            },
            start.to_event(),
            direction,
            args.speed,
            if args.past {
                TimeDirection::Past
            } else {
                TimeDirection::Future
            },
            args.until_time,
            args.samples,
        )
        .map_err(curve_error)?;
        Ok(Request {
            curve,
            method: args.method,
            start,
            format: args.format,
        })
    }
}

impl SpacetimeArgs {
    /// The metric of `--metric` with its constants `--a` (Gödel's, default 1) or `--m2` and
    /// `--omega` (a Gödel-type member's, both required), each checked as in scenes; the other
    /// metrics' constants refused naming their flag.
    pub fn metric(&self) -> anyhow::Result<Metric> {
        let (name, a, m2, omega) = (self.metric, self.a, self.m2, self.omega);
        let refuse_member = |metric: &str| -> anyhow::Result<()> {
            for (flag, value) in [("--m2", m2), ("--omega", omega)] {
                if value.is_some() {
                    let why = format!(
                        "is a constant of --metric godel-type: not used by --metric {metric}"
                    );
                    return Err(usage(flag, why));
                }
            }
            Ok(())
        };
        Ok(match name {
            MetricName::Godel => {
                refuse_member("godel")?;
                Metric::Godel(Godel::new(scale_a("--a", a.unwrap_or(1.0))?))
            }
            MetricName::Minkowski => {
                refuse_member("minkowski")?;
                if a.is_some() {
                    return Err(usage(
                        "--a",
                        "is the Gödel parameter: not used by --metric minkowski",
                    ));
                }
                Metric::Minkowski(Minkowski)
            }
            MetricName::GodelType => {
                if a.is_some() {
                    return Err(usage(
                        "--a",
                        "not used by --metric godel-type: its constants are --m2 and --omega \
                         (Gödel's a is m2 = 1/a², omega = 1/(√2·a))",
                    ));
                }
                Metric::GodelType(member(m2, omega)?)
            }
        })
    }
}

/// One output row: parameter, cylindrical and Cartesian position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    pub lambda: f64,
    pub t: f64,
    pub r: f64,
    pub phi: f64,
    pub z: f64,
    pub x: f64,
    pub y: f64,
}

/// `n` evenly spaced samples with φ unwrapped continuously from the start's φ. On the axis
/// (r below 1e-9 of the largest r) φ is that of the direction the curve arrives from.
pub fn rows(metric: &Metric, samples: &[(f64, GeodesicState)], start_phi: f64) -> Vec<Row> {
    let r_scale = samples.iter().fold(0.0_f64, |m, (_, s)| m.max(s.x.r()));
    let mut prev_phi = start_phi;
    let mut out = Vec::with_capacity(samples.len());
    for (i, &(lambda, s)) in samples.iter().enumerate() {
        let e = s.x;
        let phi = if i == 0 {
            start_phi
        } else {
            let v = s.tangent(metric);
            let raw = if e.r() > 1e-9 * r_scale {
                e.phi()
            } else if v.x != 0.0 || v.y != 0.0 {
                (-v.y).atan2(-v.x)
            } else {
                prev_phi
            };
            raw + 2.0 * PI * ((prev_phi - raw) / (2.0 * PI)).round()
        };
        prev_phi = phi;
        out.push(Row {
            lambda,
            t: e.t,
            r: e.r(),
            phi,
            z: e.z,
            x: e.x,
            y: e.y,
        });
    }
    out
}

/// Shortest round-trip decimal text of `v` (plain for ordinary magnitudes, else exponent).
fn num(v: f64) -> String {
    let m = v.abs();
    if m == 0.0 || (1e-4..1e15).contains(&m) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

fn write_csv(out: &mut impl Write, rows: &[Row]) -> std::io::Result<()> {
    writeln!(out, "lambda,t,r,phi,z,x,y")?;
    for r in rows {
        let fields = [r.lambda, r.t, r.r, r.phi, r.z, r.x, r.y].map(num);
        writeln!(out, "{}", fields.join(","))?;
    }
    Ok(())
}

fn json_document(req: &Request, curve: &Curve, rows: &[Row]) -> serde_json::Value {
    let c = ConstantsOfMotion::of(&req.curve.metric, &curve.start);
    let d = curve.drift;
    let (steps, rejected, evaluations) = match curve.integration {
        Some((s, r, e)) => (json!(s), json!(r), json!(e)),
        None => (json!(null), json!(null), json!(null)),
    };
    let samples: Vec<_> = rows
        .iter()
        .map(|r| json!({"lambda": r.lambda, "t": r.t, "r": r.r, "phi": r.phi, "z": r.z, "x": r.x, "y": r.y}))
        .collect();
    json!({
        "metric": req.curve.metric.name(),
        "a": req.curve.metric.godel_a(),
        "m2": req.curve.metric.godel_type().map(|g| g.m2),
        "omega": req.curve.metric.godel_type().map(|g| g.omega),
        "method": match req.method { Method::Numeric => "numeric", Method::Exact => "exact" },
        "kind": match curve.kind { GeodesicKind::Null => "null", GeodesicKind::Timelike => "timelike" },
        "speed": req.curve.speed,
        "time_direction": match req.curve.time { TimeDirection::Future => "future", TimeDirection::Past => "past" },
        "start": {"t": req.start.t, "r": req.start.r, "phi": req.start.phi, "z": req.start.z},
        "direction": req.curve.direction,
        "stop": stop_name(curve.stop),
        "stop_description": curve.stop.describe(),
        "lambda_end": curve.lambda_end,
        "samples": samples,
        "constants": {"E": c.energy, "L": c.angular_momentum, "p_z": c.pz, "normalization": c.normalization},
        "drift": {"E": d.energy, "L": d.angular_momentum, "p_z": d.pz, "normalization": d.normalization, "max": d.max()},
        "steps": steps,
        "rejected_steps": rejected,
        "evaluations": evaluations,
    })
}

/// Runs `godel geodesic`, printing to standard output.
pub fn run(args: GeodesicArgs) -> anyhow::Result<()> {
    let req = Request::from_args(&args)?;
    let curve = compute(&req.curve).map_err(curve_error)?;
    if let (Some(dt), StopReason::AffineLimit) = (args.until_time, curve.stop) {
        eprintln!(
            "note: stopped at lambda = {} ({}) before |t - T| reached {}",
            num(curve.lambda_end),
            curve.stop.describe(),
            num(dt)
        );
    }
    let rows = rows(&req.curve.metric, &curve.samples, req.start.phi);
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    match req.format {
        Format::Csv => write_csv(&mut out, &rows),
        Format::Json => {
            let doc = json_document(&req, &curve, &rows);
            serde_json::to_writer_pretty(&mut out, &doc)
                .map_err(std::io::Error::from)
                .and_then(|_| writeln!(out))
        }
    }
    .and_then(|_| out.flush())
    .context("writing to standard output")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip() {
        for v in [
            0.0,
            -0.0,
            1.0,
            2.6025805691,
            1e-300,
            -3.5e-7,
            1e20,
            123456.789,
        ] {
            assert_eq!(num(v).parse::<f64>().unwrap(), v);
        }
    }
}
