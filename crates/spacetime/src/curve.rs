//! One geodesic (a light ray, or a massive particle of a given speed) from an event, launched
//! along a direction of the static observer's local frame there, computed by either method
//! and sampled evenly in its parameter: what `godel geodesic` prints and the Python module's
//! `geodesic` returns.
//!
//! Two methods give the same curve: `numeric` integrates the geodesic equations (DOP853 in
//! pseudo-Cartesian coordinates, [`crate::trace`]); `exact` evaluates the closed form through
//! the origin carried to the start by an isometry ([`ExactGeodesic`]; Grave et al., PRD 80,
//! 103002 (2009), Sec. III), with its stops solved on the closed form: the axis return at
//! λ = π/ω, the time limit by root finding. (t is monotonic along causal curves where
//! r < 2a, since there the surfaces of constant t are spacelike: g^tt = −(1 − r²/4a²)/(1 +
//! r²/4a²) < 0. A curve from off the axis may go beyond; there the root found is a place
//! where |t − t_start| reaches the limit, not necessarily the first.) In a Gödel-type member
//! it is the member's closed form ([`TypeExactGeodesic`], docs/physics.md "The Gödel-type
//! family"), stopping at the axis return λ = π/√Λ of a returning ray; in Minkowski
//! spacetime the exact curve is the straight line.
//!
//! Every input is checked here ([`CurveRequest::new`]); a refusal names the input at fault
//! ([`Input`]), so that each front end names it as its user wrote it.

use crate::message::short;
use crate::{
    refine_root, trace, Drift, Event, ExactGeodesic, FourVector, Geodesic, GeodesicKind,
    GeodesicState, Metric, Spacetime, StopReason, TimeDirection, TraceLimits, TypeExactGeodesic,
};

/// Default time limit in Minkowski spacetime, where rays never come back.
pub const MINKOWSKI_DEFAULT_UNTIL: f64 = 10.0;
/// Most samples of one curve: each costs ~130 bytes until used.
pub const MAX_SAMPLES: usize = 1_000_000;

/// How the geodesic is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveMethod {
    /// Integrate the geodesic equations (DOP853).
    Numeric,
    /// Evaluate the closed form (isometry ∘ closed form through the origin ∘ inverse).
    Exact,
}

/// The input a refusal is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// The start event.
    Start,
    /// The launch direction.
    Direction,
    /// The particle's speed.
    Speed,
    /// The limit on |t − t_start|.
    UntilTime,
    /// The number of samples.
    Samples,
    /// The method (the exact one needs closed forms for the metric).
    Method,
}

/// Why no curve was computed.
#[derive(Clone, Debug, PartialEq)]
pub enum CurveError {
    /// An input is refused (a user's mistake); the message does not name the input.
    Input { input: Input, message: String },
    /// The numeric integration failed; `note` says why it could, where that is known.
    Integration {
        reason: String,
        steps: usize,
        lambda: f64,
        note: Option<String>,
    },
}

impl std::fmt::Display for CurveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CurveError::Input { message, .. } => f.write_str(message),
            CurveError::Integration {
                reason,
                steps,
                lambda,
                note,
            } => {
                write!(
                    f,
                    "integration failed: {reason} after {steps} steps at lambda = {lambda}"
                )?;
                match note {
                    Some(note) => write!(f, ": {note}"),
                    None => Ok(()),
                }
            }
        }
    }
}

impl std::error::Error for CurveError {}

fn refuse(input: Input, message: impl Into<String>) -> CurveError {
    CurveError::Input {
        input,
        message: message.into(),
    }
}

/// A checked request for one geodesic.
#[derive(Clone, Debug)]
pub struct CurveRequest {
    pub metric: Metric,
    pub method: CurveMethod,
    pub start: Event,
    /// The launch direction, scaled so that its largest component is ±1.
    pub direction: [f64; 3],
    /// 1 for light.
    pub speed: f64,
    pub time: TimeDirection,
    pub limits: TraceLimits,
    pub samples: usize,
}

impl CurveRequest {
    /// Checks every input: the metric can be evaluated at `start`; `direction` is finite and
    /// not zero; `speed` (none for light) in [0, 1); `until_time` positive (without it: one
    /// loop in Gödel's metric, back on the starting axis or at the latest after
    /// |t − t_start| = 2√2·π·a, and [`MINKOWSKI_DEFAULT_UNTIL`] in Minkowski's); `samples`
    /// from 2 to [`MAX_SAMPLES`].
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        metric: Metric,
        method: CurveMethod,
        start: Event,
        direction: [f64; 3],
        speed: Option<f64>,
        time: TimeDirection,
        until_time: Option<f64>,
        samples: usize,
    ) -> Result<CurveRequest, CurveError> {
        let frame = metric.static_frame(start);
        if !start.to_array().iter().all(|c| c.is_finite()) || !frame.e.iter().all(|e| e.is_finite())
        {
            return Err(refuse(
                Input::Start,
                format!(
                    "the metric cannot be evaluated at R = {} (too far from the axis)",
                    short(start.r())
                ),
            ));
        }
        if !direction.iter().all(|c| c.is_finite()) {
            return Err(refuse(Input::Direction, "components must be finite"));
        }
        // Scale by the largest component first so that huge inputs cannot overflow the norm.
        let big = direction.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if big == 0.0 {
            return Err(refuse(
                Input::Direction,
                "direction must be non-zero, got 0,0,0",
            ));
        }
        let speed = match speed {
            None => 1.0,
            Some(v) if (0.0..1.0).contains(&v) => v,
            Some(v) => {
                let message = format!("must be in [0, 1), got {}", short(v));
                return Err(refuse(Input::Speed, message));
            }
        };
        let limits = match (until_time, metric) {
            (Some(dt), _) if dt.is_finite() && dt > 0.0 => TraceLimits {
                until_time: Some(dt),
                ..Default::default()
            },
            (Some(dt), _) => {
                let message = format!("must be positive and finite, got {}", short(dt));
                return Err(refuse(Input::UntilTime, message));
            }
            (None, Metric::Godel(g)) => TraceLimits::one_loop(g.a),
            // Members near m² = 4Ω² take longer to return: the default is Gödel's loop for
            // the same vorticity, and `until_time` sets another.
            (None, Metric::GodelType(g)) => TraceLimits::one_loop(g.godel_a()),
            (None, Metric::Minkowski(_)) => TraceLimits {
                until_time: Some(MINKOWSKI_DEFAULT_UNTIL),
                ..Default::default()
            },
        };
        if samples < 2 {
            let message = format!("must be at least 2, got {samples}");
            return Err(refuse(Input::Samples, message));
        }
        if samples > MAX_SAMPLES {
            let message = format!("at most {MAX_SAMPLES}, got {samples}");
            return Err(refuse(Input::Samples, message));
        }
        Ok(CurveRequest {
            metric,
            method,
            start,
            direction: direction.map(|v| v / big),
            speed,
            time,
            limits,
            samples,
        })
    }
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

/// Where a Gödel-type member with m² > 0 was integrated far from the axis: why the
/// integration could fail there, and what follows the curve instead. The metric's terms grow
/// as e^{mρ} and cancel to leave terms of e^{mρ} less (D² − H² in the causal members), so
/// about mρ·log₁₀ e of its 16 digits are lost; beyond mρ = 8 (the scenes' bound) say so.
fn far_out(metric: &Metric, at: Event) -> Option<String> {
    let member = metric.godel_type().filter(|g| g.m2 > 0.0)?;
    let m_rho = member.m2.sqrt() * at.r();
    (m_rho > 8.0).then(|| {
        format!(
            "it had come to m·R = {m_rho:.1}, where the member's metric has lost about {:.0} of \
             its 16 digits to cancellation; --method exact follows the closed form",
            m_rho * std::f64::consts::LOG10_E
        )
    })
}

/// Computes the requested geodesic by its method; a failed integration is an error.
pub fn compute(req: &CurveRequest) -> Result<Curve, CurveError> {
    let at = req.start;
    let frame = req.metric.static_frame(at);
    let geodesic = Geodesic::launch(&req.metric, at, &frame, req.direction, req.speed, req.time)
        .filter(|g| g.start.x.is_finite() && g.start.p.is_finite())
        .ok_or_else(|| refuse(Input::Start, "cannot launch a geodesic from this event"))?;
    let scale = req.metric.length_scale();
    match req.method {
        CurveMethod::Numeric => {
            let traced = trace(req.metric, &geodesic, &req.limits);
            if traced.stop.is_failure() {
                return Err(CurveError::Integration {
                    reason: traced.stop.describe().to_string(),
                    steps: traced.steps.len(),
                    lambda: traced.lambda_end,
                    note: far_out(&req.metric, traced.end.x),
                });
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
        CurveMethod::Exact => {
            let tangent = geodesic.start.tangent(&req.metric);
            // The launch succeeded, so the direction is fine: what fails is carrying the
            // start to the origin in floating point, which loses the null condition far out.
            let curve = ExactCurve::new(req.metric, at, tangent).ok_or_else(|| {
                let message = format!(
                    "the closed form cannot start this far from the axis (R = {}); \
                     use the numeric method",
                    short(at.r())
                );
                refuse(Input::Start, message)
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

/// The closed-form curve of each metric: Gödel's and a Gödel-type member's through an
/// isometry, Minkowski's a line.
enum ExactCurve {
    Godel {
        metric: Metric,
        a: f64,
        g: ExactGeodesic,
    },
    Family {
        metric: Metric,
        g: TypeExactGeodesic,
    },
    Line {
        metric: Metric,
        at: Event,
        k: FourVector,
    },
}

impl ExactCurve {
    fn new(metric: Metric, at: Event, k: FourVector) -> Option<ExactCurve> {
        match metric {
            Metric::Godel(godel) => Some(ExactCurve::Godel {
                metric,
                a: godel.a,
                g: ExactGeodesic::new(godel.a, at, k)?,
            }),
            Metric::GodelType(member) => Some(ExactCurve::Family {
                metric,
                g: TypeExactGeodesic::new(member, at, k)?,
            }),
            Metric::Minkowski(_) => Some(ExactCurve::Line { metric, at, k }),
        }
    }

    fn event_and_tangent(&self, lambda: f64) -> (Event, FourVector) {
        match self {
            ExactCurve::Godel { g, .. } => g.at(lambda),
            ExactCurve::Family { g, .. } => g.at(lambda),
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
            ExactCurve::Godel { metric, .. }
            | ExactCurve::Family { metric, .. }
            | ExactCurve::Line { metric, .. } => metric,
        };
        let (x, k) = self.event_and_tangent(lambda);
        GeodesicState {
            x,
            p: metric.lower(x, k),
        }
    }

    /// The parameter where the curve stops under `limits`, and why: the first of the
    /// return to the starting axis (λ = π/ω in Gödel's universe, π/√Λ for a returning ray
    /// of a Gödel-type member; not for curves along the axis),
    /// |t − t_start| = until_time, and λ = max_affine (as the numeric method).
    fn stop(&self, limits: &TraceLimits) -> Result<(f64, StopReason), CurveError> {
        let axis = match self {
            ExactCurve::Godel { a, g, .. }
                if limits.stop_at_axis_return && g.origin.r_max() > 1e-12 * a =>
            {
                Some(g.origin.return_parameter())
            }
            ExactCurve::Family { metric, g } if limits.stop_at_axis_return => g
                .origin
                .rho_max()
                .filter(|r| *r > 1e-12 * metric.length_scale())
                .and_then(|_| g.origin.return_parameter()),
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
            (None, None) => Err(refuse(
                Input::UntilTime,
                "the exact method needs a time limit here",
            )),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Godel;

    fn request(direction: [f64; 3], speed: Option<f64>, samples: usize) -> CurveRequest {
        CurveRequest::new(
            Metric::Godel(Godel::new(1.0)),
            CurveMethod::Exact,
            Event::new(0.0, 0.0, 0.0, 0.0),
            direction,
            speed,
            TimeDirection::Past,
            None,
            samples,
        )
        .unwrap()
    }

    #[test]
    fn refusals_name_their_input() {
        let godel = Metric::Godel(Godel::new(1.0));
        let origin = Event::new(0.0, 0.0, 0.0, 0.0);
        let input_of = |direction, speed, until, samples| {
            let r = CurveRequest::new(
                godel,
                CurveMethod::Numeric,
                origin,
                direction,
                speed,
                TimeDirection::Future,
                until,
                samples,
            );
            match r {
                Err(CurveError::Input { input, .. }) => Some(input),
                _ => None,
            }
        };
        let x = [1.0, 0.0, 0.0];
        assert_eq!(input_of([0.0; 3], None, None, 10), Some(Input::Direction));
        assert_eq!(
            input_of([f64::NAN, 0., 0.], None, None, 10),
            Some(Input::Direction)
        );
        assert_eq!(input_of(x, Some(1.0), None, 10), Some(Input::Speed));
        assert_eq!(input_of(x, None, Some(-1.0), 10), Some(Input::UntilTime));
        assert_eq!(input_of(x, None, None, 1), Some(Input::Samples));
        assert_eq!(
            input_of(x, None, None, MAX_SAMPLES + 1),
            Some(Input::Samples)
        );
        assert_eq!(input_of(x, Some(0.5), Some(2.0), 10), None);
    }

    #[test]
    fn a_light_ray_from_the_axis_returns_to_it_after_one_loop() {
        // Back on the axis after coordinate time 2πa(√2 − 1) (docs/physics.md).
        let curve = compute(&request([1.0, 0.0, 0.0], None, 50)).unwrap();
        assert_eq!(curve.stop, StopReason::AxisReturn);
        let (_, last) = curve.samples[49];
        let loop_time = 2.0 * std::f64::consts::PI * (2f64.sqrt() - 1.0);
        assert!((last.x.t + loop_time).abs() < 1e-9, "{}", last.x.t);
        assert!(last.x.r() < 1e-9);
    }
}
