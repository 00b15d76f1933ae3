//! `godel geodesic`: traces one geodesic (a light ray, or a massive particle with `--speed`)
//! from an event given in cylindrical coordinates, launched along a direction of the static
//! observer's local frame there, and prints evenly spaced samples of it as CSV or JSON
//! (JSON adds the constants of motion E, L, p_z, the normalization and their drift).
//!
//! Two methods give the same curve: `numeric` integrates the geodesic equations (DOP853 in
//! pseudo-Cartesian coordinates, `spacetime::trace`); `exact` evaluates the closed form
//! through the origin carried to the start by an isometry (`spacetime::ExactGeodesic`;
//! Grave et al., PRD 80, 103002 (2009), Sec. III), with its stops solved on the closed form:
//! the axis return at λ = π/ω, the time limit by root finding (t is monotonic along causal
//! curves since ∂t is timelike everywhere). In Minkowski spacetime the exact curve is the
//! straight line.
//!
//! Physics: Gödel, Rev. Mod. Phys. 21, 447 (1949); constants of motion from the Killing fields
//! ∂t, ∂φ, ∂z; integration in pseudo-Cartesian coordinates by the `spacetime` crate.

use crate::args::{coordinates, parse_vector, positive, scale_a, usage, Format};
use anyhow::Context;
use clap::ValueEnum;
use scene::short;
use serde_json::json;
use spacetime::{
    refine_root, trace, ConstantsOfMotion, Cylindrical, Drift, Event, ExactGeodesic, FourVector,
    Geodesic, GeodesicKind, GeodesicState, Godel, Metric, Minkowski, Spacetime, StopReason,
    TimeDirection, TraceLimits,
};
use std::f64::consts::PI;
use std::io::Write;

/// Default `--until-time` for Minkowski, where rays never come back.
pub const MINKOWSKI_DEFAULT_UNTIL: f64 = 10.0;
/// Most samples (`--samples`): each costs ~130 bytes until printed.
pub const MAX_SAMPLES: usize = 1_000_000;

/// The metrics known on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MetricName {
    Godel,
    Minkowski,
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
#[derive(clap::Args, Debug)]
#[command(after_help = "\
Stop: with --until-time DT the geodesic stops exactly where |t - T| = DT. Without it, a \
Gödel geodesic stops after one loop: back on the starting axis (the start's x, y), or at \
the latest after |t - T| = 2√2·π·a; a Minkowski geodesic stops at |t - T| = 10. Either \
method stops at the latest at parameter λ = 10⁶ (a note on stderr says so when that \
comes before DT); the numeric one also after 100000 steps (an error).

Limits: --samples at most 1000000.

Output: CSV columns lambda,t,r,phi,z,x,y (phi unwrapped, continuous), or JSON with the \
samples, the stop reason, the constants of motion and their relative drift.

Example: godel geodesic --at 0,0,0,0 --dir 1,0,0")]
pub struct GeodesicArgs {
    /// Spacetime metric.
    #[arg(long, value_enum, default_value_t = MetricName::Godel)]
    pub metric: MetricName,
    /// Integrate numerically, or evaluate the closed form.
    #[arg(long, value_enum, default_value_t = Method::Numeric)]
    pub method: Method,
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
    /// Number of samples, evenly spaced in the parameter (2 to 1000000; first at the start,
    /// last at the stop).
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
    pub method: Method,
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
        let (metric, a) = match args.metric {
            MetricName::Godel => {
                let a = scale_a("--a", args.a)?;
                (Metric::Godel(Godel::new(a)), a)
            }
            MetricName::Minkowski => {
                positive("--a", args.a)?;
                (Metric::Minkowski(Minkowski), 1.0)
            }
        };
        let [t, r, phi, z] = parse_vector::<4>("--at", &args.at)?;
        if r < 0.0 {
            return Err(usage("--at", format!("R must be ≥ 0, got {}", short(r))));
        }
        coordinates("--at", &["t", "R", "phi", "z"], &[t, r, phi, z], a)?;
        let start = Cylindrical { t, r, phi, z };
        let frame = metric.static_frame(start.to_event());
        if !frame.e.iter().all(|e| e.is_finite()) {
            return Err(usage(
                "--at",
                format!("the metric cannot be evaluated at R = {r} (too far from the axis)"),
            ));
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
        if args.samples > MAX_SAMPLES {
            return Err(usage(
                "--samples",
                format!("at most {MAX_SAMPLES}, got {}", args.samples),
            ));
        }
        Ok(Request {
            metric,
            method: args.method,
            start,
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

/// A computed geodesic, by either method: samples and how it ended.
#[derive(Clone, Debug)]
pub struct Curve {
    pub kind: GeodesicKind,
    pub start: GeodesicState,
    /// `n` samples evenly spaced in the parameter, first at the start, last at the stop.
    pub samples: Vec<(f64, GeodesicState)>,
    pub stop: StopReason,
    pub lambda_end: f64,
    /// Drift of the constants of motion along the curve.
    pub drift: Drift,
    /// Integrator counts (accepted steps, rejected steps, evaluations); numeric only.
    pub integration: Option<(usize, u64, u64)>,
}

/// Computes the requested geodesic by its method; a failed integration is an error.
pub fn compute(req: &Request) -> anyhow::Result<Curve> {
    let at = req.start.to_event();
    let frame = req.metric.static_frame(at);
    let geodesic = Geodesic::launch(&req.metric, at, &frame, req.direction, req.speed, req.time)
        .filter(|g| g.start.x.is_finite() && g.start.p.is_finite())
        .ok_or_else(|| usage("--at", "cannot launch a geodesic from this event"))?;
    let scale = req.metric.godel_a().unwrap_or(1.0);
    match req.method {
        Method::Numeric => {
            let traced = trace(req.metric, &geodesic, &req.limits);
            if traced.stop.is_failure() {
                anyhow::bail!(
                    "integration failed: {} after {} steps at lambda = {}",
                    traced.stop.describe(),
                    traced.steps.len(),
                    traced.lambda_end
                );
            }
            Ok(Curve {
                kind: traced.kind,
                start: traced.start,
                samples: traced.samples(req.samples),
                stop: traced.stop,
                lambda_end: traced.lambda_end,
                drift: Drift::along(&req.metric, &traced, scale),
                integration: Some((
                    traced.steps.len(),
                    traced.rejected_steps,
                    traced.evaluations,
                )),
            })
        }
        Method::Exact => {
            let tangent = geodesic.start.tangent(&req.metric);
            // The launch succeeded, so the direction is fine: what fails is carrying the
            // start to the origin in floating point, which loses the null condition far out.
            let curve = ExactCurve::new(req.metric, at, tangent).ok_or_else(|| {
                usage(
                    "--at",
                    format!(
                        "the closed form cannot start this far from the axis (R = {}); \
                         use --method numeric",
                        req.start.r
                    ),
                )
            })?;
            let (lambda_end, stop) = curve.stop(&req.limits)?;
            let n = req.samples;
            let samples: Vec<(f64, GeodesicState)> = (0..n)
                .map(|i| {
                    let lambda = if i == n - 1 {
                        lambda_end
                    } else {
                        lambda_end * i as f64 / (n - 1) as f64
                    };
                    (lambda, curve.state(lambda))
                })
                .collect();
            let drift = Drift::over(
                &req.metric,
                &geodesic.start,
                samples.iter().map(|(_, s)| *s),
                scale,
            );
            Ok(Curve {
                kind: geodesic.kind,
                start: geodesic.start,
                samples,
                stop,
                lambda_end,
                drift,
                integration: None,
            })
        }
    }
}

/// The closed-form curve of either metric: Gödel's through an isometry, Minkowski's a line.
enum ExactCurve {
    Godel {
        metric: Metric,
        a: f64,
        g: ExactGeodesic,
    },
    Line {
        metric: Metric,
        at: Event,
        k: FourVector,
    },
}

impl ExactCurve {
    fn new(metric: Metric, at: Event, k: FourVector) -> Option<ExactCurve> {
        match metric.godel_a() {
            Some(a) => Some(ExactCurve::Godel {
                metric,
                a,
                g: ExactGeodesic::new(a, at, k)?,
            }),
            None => Some(ExactCurve::Line { metric, at, k }),
        }
    }

    fn event_and_tangent(&self, lambda: f64) -> (Event, FourVector) {
        match self {
            ExactCurve::Godel { g, .. } => g.at(lambda),
            ExactCurve::Line { at, k, .. } => (
                Event::new(
                    at.t + lambda * k.t,
                    at.x + lambda * k.x,
                    at.y + lambda * k.y,
                    at.z + lambda * k.z,
                ),
                *k,
            ),
        }
    }

    fn state(&self, lambda: f64) -> GeodesicState {
        let metric = match self {
            ExactCurve::Godel { metric, .. } | ExactCurve::Line { metric, .. } => metric,
        };
        let (x, k) = self.event_and_tangent(lambda);
        GeodesicState {
            x,
            p: metric.lower(x, k),
        }
    }

    /// The parameter where the curve stops under `limits`, and why: the first of the
    /// return to the starting axis (λ = π/ω, Gödel only, not for curves along the axis),
    /// |t − t_start| = until_time, and λ = max_affine (as the numeric method).
    fn stop(&self, limits: &TraceLimits) -> anyhow::Result<(f64, StopReason)> {
        let axis = match self {
            ExactCurve::Godel { a, g, .. }
                if limits.stop_at_axis_return && g.origin.r_max() > 1e-12 * a =>
            {
                Some(g.origin.return_parameter())
            }
            _ => None,
        };
        let time =
            limits
                .until_time
                .map(|dt| match self.parameter_at_time(dt, limits.max_affine) {
                    Some(lt) => (lt, StopReason::TimeReached),
                    None => (limits.max_affine, StopReason::AffineLimit),
                });
        match (axis, time) {
            (Some(la), Some((lt, why))) if lt < la => Ok((lt, why)),
            (Some(la), _) => Ok((la, StopReason::AxisReturn)),
            (None, Some(stop)) => Ok(stop),
            (None, None) => anyhow::bail!("the exact method needs --until-time here"),
        }
    }

    /// The parameter 0 < λ ≤ `max` with |t(λ) − t(0)| = dt (bracketed by doubling, then
    /// refined), or `None` when t does not get that far by λ = `max`.
    fn parameter_at_time(&self, dt: f64, max: f64) -> Option<f64> {
        let t0 = self.event_and_tangent(0.0).0.t;
        let f = |lambda: f64| (self.event_and_tangent(lambda).0.t - t0).abs() - dt;
        let mut hi = dt.min(max);
        while f(hi) < 0.0 && hi < max {
            hi = (2.0 * hi).min(max);
        }
        let f_hi = f(hi);
        if f_hi.is_nan() || f_hi < 0.0 {
            return None; // not reached by λ = max (or not finite there)
        }
        if f_hi == 0.0 {
            return Some(hi);
        }
        Some(refine_root(f, 0.0, hi, -dt, f_hi))
    }
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

fn json_document(req: &Request, curve: &Curve, rows: &[Row]) -> serde_json::Value {
    let c = ConstantsOfMotion::of(&req.metric, &curve.start);
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
        "metric": req.metric.name(),
        "a": req.metric.godel_a(),
        "method": match req.method { Method::Numeric => "numeric", Method::Exact => "exact" },
        "kind": match curve.kind { GeodesicKind::Null => "null", GeodesicKind::Timelike => "timelike" },
        "speed": req.speed,
        "time_direction": match req.time { TimeDirection::Future => "future", TimeDirection::Past => "past" },
        "start": {"t": req.start.t, "r": req.start.r, "phi": req.start.phi, "z": req.start.z},
        "direction": req.direction,
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
    let curve = compute(&req)?;
    if let (Some(dt), StopReason::AffineLimit) = (args.until_time, curve.stop) {
        eprintln!(
            "note: stopped at lambda = {} ({}) before |t - T| reached {}",
            num(curve.lambda_end),
            curve.stop.describe(),
            num(dt)
        );
    }
    let rows = rows(&req.metric, &curve.samples, req.start.phi);
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
