//! `godel geodesic`: traces one geodesic (a light ray, or a massive particle with `--speed`)
//! from an event given in cylindrical coordinates, launched along a direction of the static
//! observer's local frame there, and prints evenly spaced samples of it as CSV or JSON
//! (JSON adds the constants of motion E, L, p_z, the normalization and their drift).
//!
//! Physics: Gödel, Rev. Mod. Phys. 21, 447 (1949); constants of motion from the Killing fields
//! ∂t, ∂φ, ∂z; integration in pseudo-Cartesian coordinates by the `spacetime` crate.

use crate::args::{parse_vector, positive, usage};
use anyhow::Context;
use clap::ValueEnum;
use serde_json::json;
use spacetime::{
    trace, ConstantsOfMotion, Cylindrical, Drift, Geodesic, GeodesicKind, Godel, Metric, Minkowski,
    Spacetime, StopReason, TimeDirection, TraceLimits, TracedGeodesic,
};
use std::f64::consts::PI;
use std::io::Write;

/// Default `--until-time` for Minkowski, where rays never come back.
pub const MINKOWSKI_DEFAULT_UNTIL: f64 = 10.0;

/// The metrics known on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MetricName {
    Godel,
    Minkowski,
}

/// Output formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    Csv,
    Json,
}

/// Raw command-line arguments of `godel geodesic` (validated by [`Request::from_args`]).
#[derive(clap::Args, Debug)]
#[command(after_help = "\
Stop: with --until-time DT the geodesic stops exactly where |t - T| = DT. Without it, a \
Gödel geodesic stops after one loop: back on the starting axis (the start's x, y), or at \
the latest after |t - T| = 2√2·π·a; a Minkowski geodesic stops at |t - T| = 10.

Output: CSV columns lambda,t,r,phi,z,x,y (phi unwrapped, continuous), or JSON with the \
samples, the stop reason, the constants of motion and their relative drift.

Example: godel geodesic --at 0,0,0,0 --dir 1,0,0")]
pub struct GeodesicArgs {
    /// Spacetime metric.
    #[arg(long, value_enum, default_value_t = MetricName::Godel)]
    pub metric: MetricName,
    /// Gödel parameter a > 0 (optical horizon at r = 2a).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub a: f64,
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
    /// Number of samples, evenly spaced in the parameter (≥ 2; first at the start, last at the stop).
    #[arg(long, value_name = "N", default_value_t = 100)]
    pub samples: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Csv)]
    pub format: Format,
}

/// A validated `godel geodesic` request.
#[derive(Clone, Debug)]
pub struct Request {
    pub metric: Metric,
    pub start: Cylindrical,
    pub direction: [f64; 3],
    /// 1 for light.
    pub speed: f64,
    pub time: TimeDirection,
    pub limits: TraceLimits,
    pub samples: usize,
    pub format: Format,
}

impl Request {
    /// Checks every value; errors name the flag.
    pub fn from_args(args: &GeodesicArgs) -> anyhow::Result<Request> {
        let a = positive("--a", args.a)?;
        let metric = match args.metric {
            MetricName::Godel => Metric::Godel(Godel::new(a)),
            MetricName::Minkowski => Metric::Minkowski(Minkowski),
        };
        let [t, r, phi, z] = parse_vector::<4>("--at", &args.at)?;
        if r < 0.0 {
            return Err(usage("--at", format!("R must be ≥ 0, got {r}")));
        }
        let dir = parse_vector::<3>("--dir", &args.dir)?;
        // Scale by the largest component first so that huge inputs cannot overflow the norm.
        let big = dir.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if big == 0.0 {
            return Err(usage("--dir", "direction must be non-zero, got 0,0,0"));
        }
        let direction = dir.map(|v| v / big);
        let speed = match args.speed {
            None => 1.0,
            Some(v) if (0.0..1.0).contains(&v) => v,
            Some(v) => return Err(usage("--speed", format!("must be in [0, 1), got {v}"))),
        };
        let limits = match (args.until_time, metric) {
            (Some(dt), _) => TraceLimits {
                until_time: Some(positive("--until-time", dt)?),
                ..Default::default()
            },
            (None, Metric::Godel(g)) => TraceLimits::one_loop(g.a),
            (None, Metric::Minkowski(_)) => TraceLimits {
                until_time: Some(MINKOWSKI_DEFAULT_UNTIL),
                ..Default::default()
            },
        };
        if args.samples < 2 {
            return Err(usage(
                "--samples",
                format!("must be at least 2, got {}", args.samples),
            ));
        }
        Ok(Request {
            metric,
            start: Cylindrical { t, r, phi, z },
            direction,
            speed,
            time: if args.past {
                TimeDirection::Past
            } else {
                TimeDirection::Future
            },
            limits,
            samples: args.samples,
            format: args.format,
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

/// Launches and traces the requested geodesic; a failed integration is an error.
pub fn trace_request(req: &Request) -> anyhow::Result<TracedGeodesic> {
    let at = req.start.to_event();
    let frame = req.metric.static_frame(at);
    let geodesic = Geodesic::launch(&req.metric, at, &frame, req.direction, req.speed, req.time)
        .ok_or_else(|| usage("--dir", "cannot launch a geodesic along this direction"))?;
    let traced = trace(req.metric, &geodesic, &req.limits);
    if traced.stop.is_failure() {
        anyhow::bail!(
            "integration failed: {} after {} steps at lambda = {}",
            traced.stop.describe(),
            traced.steps.len(),
            traced.lambda_end
        );
    }
    Ok(traced)
}

/// `n` evenly spaced samples with φ unwrapped continuously from the start's φ. On the axis
/// (r below 1e-9 of the largest r) φ is that of the direction the curve arrives from.
pub fn rows(metric: &Metric, traced: &TracedGeodesic, start_phi: f64, n: usize) -> Vec<Row> {
    let samples = traced.samples(n);
    let r_scale = samples.iter().fold(0.0_f64, |m, (_, s)| m.max(s.x.r()));
    let mut prev_phi = start_phi;
    let mut out = Vec::with_capacity(samples.len());
    for (i, (lambda, s)) in samples.into_iter().enumerate() {
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

/// Snake-case name of a stop reason for machine-readable output.
pub fn stop_name(stop: StopReason) -> &'static str {
    match stop {
        StopReason::TimeReached => "time_reached",
        StopReason::AxisReturn => "axis_return",
        StopReason::AffineLimit => "affine_limit",
        StopReason::StepBudget => "step_budget",
        StopReason::Stalled => "stalled",
        StopReason::NonFinite => "non_finite",
    }
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

fn json_document(req: &Request, traced: &TracedGeodesic, rows: &[Row]) -> serde_json::Value {
    let c = ConstantsOfMotion::of(&req.metric, &traced.start);
    let scale = req.metric.godel_a().unwrap_or(1.0);
    let d = Drift::along(&req.metric, traced, scale);
    let samples: Vec<_> = rows
        .iter()
        .map(|r| json!({"lambda": r.lambda, "t": r.t, "r": r.r, "phi": r.phi, "z": r.z, "x": r.x, "y": r.y}))
        .collect();
    json!({
        "metric": req.metric.name(),
        "a": req.metric.godel_a(),
        "kind": match traced.kind { GeodesicKind::Null => "null", GeodesicKind::Timelike => "timelike" },
        "speed": req.speed,
        "time_direction": match req.time { TimeDirection::Future => "future", TimeDirection::Past => "past" },
        "start": {"t": req.start.t, "r": req.start.r, "phi": req.start.phi, "z": req.start.z},
        "direction": req.direction,
        "stop": stop_name(traced.stop),
        "stop_description": traced.stop.describe(),
        "lambda_end": traced.lambda_end,
        "samples": samples,
        "constants": {"E": c.energy, "L": c.angular_momentum, "p_z": c.pz, "normalization": c.normalization},
        "drift": {"E": d.energy, "L": d.angular_momentum, "p_z": d.pz, "normalization": d.normalization, "max": d.max()},
        "steps": traced.steps.len(),
        "rejected_steps": traced.rejected_steps,
        "evaluations": traced.evaluations,
    })
}

/// Runs `godel geodesic`, printing to standard output.
pub fn run(args: GeodesicArgs) -> anyhow::Result<()> {
    let req = Request::from_args(&args)?;
    let traced = trace_request(&req)?;
    let rows = rows(&req.metric, &traced, req.start.phi, req.samples);
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    match req.format {
        Format::Csv => write_csv(&mut out, &rows),
        Format::Json => {
            let doc = json_document(&req, &traced, &rows);
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
