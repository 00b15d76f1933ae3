//! Geodesics: launch from a local direction, integrate with stop conditions, sample.
//!
//! A geodesic is integrated in Hamiltonian form (see `metric.rs`) with state
//! (t, x, y, z, p_t, p_x, p_y, p_z). The parameter is affine for light and proper time for
//! massive particles (normalization g^{μν} p_μ p_ν = −1).
//!
//! Launch (docs/physics.md, "Geodesics" and "Pixels and cameras"): a photon seen along the
//! local unit direction n moves with tangent k = ±e0 + nⁱ eᵢ (+ future, − past: the
//! past-directed curve moves spatially along n as the parameter grows, as a pixel's backward
//! ray does); a particle of speed v has u = γ(±e0 + v nⁱ eᵢ).

use crate::dop853::{DenseStep, Dop853, OdeSystem, StepOutcome, Tolerances};
use crate::frame::LocalVelocity;
use crate::metric::{Metric, Spacetime};
use crate::vectors::{Covector, Event, FourVector, Tetrad};
use std::f64::consts::{PI, SQRT_2};

/// Light ray or massive particle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeodesicKind {
    Null,
    Timelike,
}

/// The time orientation in which the parameter runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeDirection {
    Future,
    Past,
}

/// A point of phase space: event and covariant momentum p_μ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeodesicState {
    pub x: Event,
    pub p: Covector,
}

impl GeodesicState {
    pub fn to_array(self) -> [f64; 8] {
        let (x, p) = (self.x, self.p);
        [x.t, x.x, x.y, x.z, p.t, p.x, p.y, p.z]
    }
    pub fn from_array(s: &[f64; 8]) -> Self {
        GeodesicState {
            x: Event::new(s[0], s[1], s[2], s[3]),
            p: Covector::new(s[4], s[5], s[6], s[7]),
        }
    }
    /// The tangent ẋ^μ = g^{μν} p_ν.
    pub fn tangent<M: Spacetime>(&self, metric: &M) -> FourVector {
        metric.raise(self.x, self.p)
    }
}

/// The tangent of a photon that an observer with `frame` sees along the unit local
/// direction `n`: k = ±e0 + nⁱ eᵢ (+ future, − past). The past-directed one moves spatially
/// along n as its parameter grows: a pixel looking along n traces it backward.
pub fn photon_tangent(frame: &Tetrad, n: [f64; 3], time: TimeDirection) -> FourVector {
    let sign = match time {
        TimeDirection::Future => 1.0,
        TimeDirection::Past => -1.0,
    };
    frame.vector([sign, n[0], n[1], n[2]])
}

/// Initial data of a geodesic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geodesic {
    pub kind: GeodesicKind,
    pub start: GeodesicState,
}

impl Geodesic {
    /// A geodesic through `at` moving spatially along the local direction `direction` of
    /// `frame`, with `speed` (1 for light, 0 ≤ v < 1 for a particle) toward `time`.
    /// `direction` need not be normalized; returns `None` if it is zero or non-finite, or the
    /// speed is not in [0, 1].
    pub fn launch<M: Spacetime>(
        metric: &M,
        at: Event,
        frame: &Tetrad,
        direction: [f64; 3],
        speed: f64,
        time: TimeDirection,
    ) -> Option<Geodesic> {
        let sign = match time {
            TimeDirection::Future => 1.0,
            TimeDirection::Past => -1.0,
        };
        let (kind, tangent) = if speed == 1.0 {
            let n = LocalVelocity::new(0.0, direction)?.direction;
            (GeodesicKind::Null, photon_tangent(frame, n, time))
        } else {
            let v = LocalVelocity::new(speed, direction)?;
            let g = v.gamma();
            let n = v.direction;
            (
                GeodesicKind::Timelike,
                frame.vector([
                    sign * g,
                    g * speed * n[0],
                    g * speed * n[1],
                    g * speed * n[2],
                ]),
            )
        };
        if !at.is_finite() {
            return None;
        }
        Some(Geodesic {
            kind,
            start: GeodesicState {
                x: at,
                p: metric.lower(at, tangent),
            },
        })
    }

    /// A geodesic from an event and a coordinate tangent vector.
    pub fn from_tangent<M: Spacetime>(
        metric: &M,
        kind: GeodesicKind,
        at: Event,
        tangent: FourVector,
    ) -> Geodesic {
        Geodesic {
            kind,
            start: GeodesicState {
                x: at,
                p: metric.lower(at, tangent),
            },
        }
    }
}

/// Hamilton's equations as an ODE system for the integrator, reduced by the two constants
/// of motion every metric here has: both are independent of t and z (∂t and ∂z are Killing),
/// so ṗ_t = ṗ_z = 0 identically and p_t, p_z are parameters. The integrated state is
/// (t, x, y, z, p_x, p_y): a quarter less work per step than carrying all eight.
#[derive(Clone, Copy, Debug)]
pub struct GeodesicSystem<M> {
    pub metric: M,
    pub pt: f64,
    pub pz: f64,
}

/// Dimension of the integrated state.
pub const STATE: usize = 6;

impl<M: Spacetime> GeodesicSystem<M> {
    /// The system of the geodesic through `start`, and its initial integrated state.
    pub fn new(metric: M, start: &GeodesicState) -> (Self, [f64; STATE]) {
        let (x, p) = (start.x, start.p);
        (
            GeodesicSystem {
                metric,
                pt: p.t,
                pz: p.z,
            },
            [x.t, x.x, x.y, x.z, p.x, p.y],
        )
    }
    /// The phase-space point of an integrated state.
    #[inline]
    pub fn state(&self, y: &[f64; STATE]) -> GeodesicState {
        GeodesicState {
            x: Event::new(y[0], y[1], y[2], y[3]),
            p: Covector::new(self.pt, y[4], y[5], self.pz),
        }
    }
}

impl<M: Spacetime> OdeSystem<STATE> for GeodesicSystem<M> {
    #[inline]
    fn rhs(&self, y: &[f64; STATE]) -> [f64; STATE] {
        let st = self.state(y);
        let (v, f) = self.metric.hamilton(st.x, st.p);
        [v.t, v.x, v.y, v.z, f.x, f.y]
    }
}

/// When to stop integrating.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceLimits {
    /// Stop exactly where |t − t_start| reaches this value.
    pub until_time: Option<f64>,
    /// Stop where the curve's projection returns to the start's (x, y) (its "axis").
    pub stop_at_axis_return: bool,
    /// Stop at this affine parameter (or proper time).
    pub max_affine: f64,
    /// Give up after this many accepted steps.
    pub max_steps: u64,
    pub tolerances: Tolerances,
}

impl Default for TraceLimits {
    fn default() -> Self {
        TraceLimits {
            until_time: None,
            stop_at_axis_return: false,
            max_affine: 1e6,
            max_steps: 100_000,
            tolerances: Tolerances::default(),
        }
    }
}

impl TraceLimits {
    /// The `godel geodesic` default for the Gödel metric with parameter `a`: back on the
    /// starting axis, bounded by 2√2πa of coordinate time, longer than any return time
    /// (docs/physics.md, "Closed forms": T_ret ≤ √2πa for light, < 2√2πa for particles).
    pub fn one_loop(a: f64) -> Self {
        TraceLimits {
            until_time: Some(2.0 * SQRT_2 * PI * a),
            stop_at_axis_return: true,
            ..Default::default()
        }
    }
}

/// Why an integration ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    TimeReached,
    AxisReturn,
    AffineLimit,
    StepBudget,
    /// The step size collapsed (a stalled integration).
    Stalled,
    /// The equations produced NaN or infinity.
    NonFinite,
}

impl StopReason {
    pub fn is_failure(self) -> bool {
        matches!(
            self,
            StopReason::StepBudget | StopReason::Stalled | StopReason::NonFinite
        )
    }
    pub fn describe(self) -> &'static str {
        match self {
            StopReason::TimeReached => "coordinate-time bound reached",
            StopReason::AxisReturn => "back on the starting axis",
            StopReason::AffineLimit => "affine-parameter bound reached",
            StopReason::StepBudget => "step budget spent",
            StopReason::Stalled => "step size collapsed",
            StopReason::NonFinite => "non-finite values",
        }
    }
}

/// An integrated geodesic with its dense output.
#[derive(Clone, Debug)]
pub struct TracedGeodesic {
    pub kind: GeodesicKind,
    pub start: GeodesicState,
    /// The reduced system (it turns integrated states into phase-space points).
    pub system: GeodesicSystem<Metric>,
    /// Accepted steps with their interpolants, in order (integrated states, see
    /// [`GeodesicSystem::state`]).
    pub steps: Vec<DenseStep<STATE>>,
    /// The parameter where the integration stopped (inside or at the end of the last step).
    pub lambda_end: f64,
    pub end: GeodesicState,
    pub stop: StopReason,
    pub rejected_steps: u64,
    pub evaluations: u64,
}

impl TracedGeodesic {
    /// State at parameter `lambda` ∈ [0, lambda_end] from the dense output.
    pub fn state_at(&self, lambda: f64) -> GeodesicState {
        if lambda <= 0.0 || self.steps.is_empty() {
            return self.start;
        }
        if lambda >= self.lambda_end {
            return self.end;
        }
        let i = self
            .steps
            .partition_point(|s| s.lambda1() < lambda)
            .min(self.steps.len() - 1);
        self.system.state(&self.steps[i].eval(lambda))
    }

    /// `n` samples evenly spaced in the parameter: the first at the start, the last at the stop.
    pub fn samples(&self, n: usize) -> Vec<(f64, GeodesicState)> {
        match n {
            0 => vec![],
            1 => vec![(0.0, self.start)],
            _ => (0..n)
                .map(|i| {
                    if i == n - 1 {
                        return (self.lambda_end, self.end);
                    }
                    let l = self.lambda_end * i as f64 / (n - 1) as f64;
                    (l, self.state_at(l))
                })
                .collect(),
        }
    }
}

/// Watches an integration for the curve's return to its start's axis (the start's x, y):
/// g = (X − X₀)·Ẋ in the x–y plane changes sign from − to + at each closest approach, which
/// is refined on the step's dense output. In Gödel's universe every geodesic returns there
/// and then retraces its loop shifted in t and z only (docs/physics.md, "Closed forms").
#[derive(Clone, Copy, Debug)]
pub struct AxisWatch {
    x0: f64,
    y0: f64,
    p0: [f64; 2],
    pscale: f64,
    max_d2: f64,
}

/// A closest approach to the start's axis, found inside one step.
#[derive(Clone, Copy, Debug)]
pub struct AxisReturn {
    /// Its parameter and integrated state.
    pub lambda: f64,
    pub state: [f64; STATE],
    /// Whether the curve is back on its axis with its starting momentum: distance² within
    /// 1e-14 of the largest distance² so far, transverse momentum within 1e-7 of its scale
    /// (both well above the integrator's error, far below any near miss).
    pub closed: bool,
    /// Whether it passes near the axis (distance² within 1e-6 of the largest) without
    /// closing: the loop is not reproduced well enough to be reused.
    pub near: bool,
}

impl AxisWatch {
    pub fn new(start: &GeodesicState) -> AxisWatch {
        let p = start.p;
        AxisWatch {
            x0: start.x.x,
            y0: start.x.y,
            p0: [p.x, p.y],
            pscale: p.t.abs() + p.x.abs() + p.y.abs() + p.z.abs(),
            max_d2: 0.0,
        }
    }

    /// g at an integrated state `s` with derivative `d`; take it before each step.
    pub fn g(&self, s: &[f64; STATE], d: &[f64; STATE]) -> f64 {
        (s[1] - self.x0) * d[1] + (s[2] - self.y0) * d[2]
    }

    /// After an accepted step on [lo, hi] ending at `s1` with derivative `d1`, given g before
    /// it: the closest approach to the axis inside the step, once the curve has moved away.
    /// `eval` is the step's dense output, `rhs` the system's right-hand side.
    #[allow(clippy::too_many_arguments)]
    pub fn after_step(
        &mut self,
        g_prev: f64,
        s1: &[f64; STATE],
        d1: &[f64; STATE],
        lo: f64,
        hi: f64,
        eval: impl Fn(f64) -> [f64; STATE],
        rhs: impl Fn(&[f64; STATE]) -> [f64; STATE],
    ) -> Option<AxisReturn> {
        let g1 = self.g(s1, d1);
        let mut found = None;
        if self.max_d2 > 0.0 && g_prev < 0.0 && g1 >= 0.0 {
            let gl = |l: f64| {
                let st = eval(l);
                self.g(&st, &rhs(&st))
            };
            let l = refine_root(gl, lo, hi, g_prev, g1);
            let e = eval(l);
            let dmin2 = (e[1] - self.x0).powi(2) + (e[2] - self.y0).powi(2);
            let dp = (e[4] - self.p0[0]).abs() + (e[5] - self.p0[1]).abs();
            let closed = dmin2 <= 1e-14 * self.max_d2 && dp <= 1e-7 * self.pscale;
            found = Some(AxisReturn {
                lambda: l,
                state: e,
                closed,
                near: !closed && dmin2 <= 1e-6 * self.max_d2,
            });
        }
        self.max_d2 = self
            .max_d2
            .max((s1[1] - self.x0).powi(2) + (s1[2] - self.y0).powi(2));
        found
    }
}

/// Finds a root of `f` in [lo, hi] given opposite signs at the ends (Illinois variant of
/// regula falsi; converges superlinearly, never leaves the bracket).
pub fn refine_root(
    f: impl Fn(f64) -> f64,
    mut lo: f64,
    mut hi: f64,
    mut flo: f64,
    mut fhi: f64,
) -> f64 {
    let mut side = 0;
    for _ in 0..100 {
        let m = if fhi != flo {
            (lo * fhi - hi * flo) / (fhi - flo)
        } else {
            0.5 * (lo + hi)
        };
        let m = if m > lo && m < hi { m } else { 0.5 * (lo + hi) };
        let fm = f(m);
        if fm == 0.0 || (hi - lo) <= 4.0 * f64::EPSILON * hi.abs().max(lo.abs()).max(1e-300) {
            return m;
        }
        if (fm > 0.0) == (fhi > 0.0) {
            hi = m;
            fhi = fm;
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        } else {
            lo = m;
            flo = fm;
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        }
    }
    0.5 * (lo + hi)
}

/// Integrates `geodesic` in `metric` until one of `limits` stops it.
pub fn trace(metric: Metric, geodesic: &Geodesic, limits: &TraceLimits) -> TracedGeodesic {
    let start = geodesic.start;
    let (sys, s0) = GeodesicSystem::new(metric, &start);
    let mut ode = Dop853::new(sys, 0.0, s0, limits.tolerances, None);
    let mut steps = Vec::new();
    let t0 = s0[0];
    let mut axis = AxisWatch::new(&start);
    let finish = |steps: Vec<DenseStep<STATE>>,
                  l: f64,
                  end: [f64; STATE],
                  stop,
                  ode: &Dop853<STATE, GeodesicSystem<Metric>>| TracedGeodesic {
        kind: geodesic.kind,
        start,
        system: sys,
        steps,
        lambda_end: l,
        end: sys.state(&end),
        stop,
        rejected_steps: ode.rejected,
        evaluations: ode.evaluations,
    };
    loop {
        if ode.accepted >= limits.max_steps {
            let (l, s) = (ode.lambda(), *ode.state());
            return finish(steps, l, s, StopReason::StepBudget, &ode);
        }
        ode.limit_next_step(limits.max_affine - ode.lambda());
        let g_prev = axis.g(ode.state(), ode.derivative());
        match ode.step() {
            StepOutcome::Accepted => {}
            StepOutcome::Stalled => {
                let (l, s) = (ode.lambda(), *ode.state());
                return finish(steps, l, s, StopReason::Stalled, &ode);
            }
            StepOutcome::NonFinite => {
                let (l, s) = (ode.lambda(), *ode.state());
                return finish(steps, l, s, StopReason::NonFinite, &ode);
            }
        }
        let dense = ode.dense();
        steps.push(dense);
        let s1 = *ode.state();
        // Coordinate-time bound.
        if let Some(dt) = limits.until_time {
            let f = |st: &[f64; STATE]| (st[0] - t0).abs() - dt;
            if f(&s1) >= 0.0 {
                let lo = dense.lambda0;
                let l = refine_root(
                    |l| f(&dense.eval(l)),
                    lo,
                    dense.lambda1(),
                    f(&dense.y0),
                    f(&s1),
                );
                let mut end = dense.eval(l);
                end[0] = t0 + (end[0] - t0).signum() * dt; // exactly on the bound
                return finish(steps, l, end, StopReason::TimeReached, &ode);
            }
        }
        // Axis return.
        if limits.stop_at_axis_return {
            let back = axis.after_step(
                g_prev,
                &s1,
                ode.derivative(),
                dense.lambda0,
                dense.lambda1(),
                |l| dense.eval(l),
                |st| sys.rhs(st),
            );
            if let Some(r) = back.filter(|r| r.closed) {
                return finish(steps, r.lambda, r.state, StopReason::AxisReturn, &ode);
            }
        }
        if ode.lambda() >= limits.max_affine {
            let (l, s) = (ode.lambda(), *ode.state());
            return finish(steps, l, s, StopReason::AffineLimit, &ode);
        }
    }
}
