//! Object worldlines and their transported body frames, computed once per render and
//! shared by all rays.
//!
//! - At rest: constant (x, y, z); four-velocity ∂t (proper time = coordinate time, since
//!   g_tt = −1); body frame = the static frame there (Lie-transported along ∂t).
//! - Free fall: the timelike geodesic through a start event, integrated forward and backward
//!   in proper time with DOP853 dense output, together with the parallel transport of the
//!   body frame, de^μ/dτ = −Γ^μ_αβ u^α e^β (for a geodesic, Fermi–Walker = parallel).
//!
//! A ray point X is matched to the worldline point P(τ) that is simultaneous with it in the
//! object's rest frame: g(u(τ), ξ) = 0, ξ the displacement X − P in Riemann normal
//! coordinates at P to second order, ξ^μ = Δx^μ + ½ Γ^μ_αβ Δx^α Δx^β. At rest the expansion
//! is taken at P; in free fall after the isometry that sends P to the origin, where it holds
//! for a boosted ball's whole radius (docs/physics.md "Local objects", "Simultaneity"). The
//! first-order condition is solved by the secant method (dξ⁰/dτ ≈ −1 along a geodesic), then
//! one Newton step on the second-order one.

use crate::bounds::Aabb;
use crate::chart::LocalChart;
use scene::Motion;
use spacetime::measure::DualFrame;
use spacetime::normal::Expansion;
use spacetime::{
    origin_axes, DenseStep, Dop853, Event, FourVector, Geodesic, GeodesicState, Isometry, Metric,
    MetricTensor, OdeSystem, Spacetime, StepOutcome, Tetrad, Tolerances, TypeIsometry,
};

/// A worldline point: event, four-velocity and body frame (e[0] = u).
#[derive(Clone, Copy, Debug)]
pub struct WorldPoint {
    pub tau: f64,
    pub event: Event,
    pub frame: Tetrad,
}

/// A ray point expressed in an object's rest frame.
#[derive(Clone, Copy, Debug)]
pub struct LocalPoint {
    /// The matched worldline point.
    pub at: WorldPoint,
    /// Spatial rest-frame coordinates of the ray point relative to the object's centre, to
    /// second order.
    pub xi: [f64; 3],
}

/// A ray point's match on an object's worldline ([`Worldline::localize`]).
#[derive(Clone, Copy, Debug)]
pub enum Located {
    /// Near the object: its rest-frame coordinates.
    Near(LocalPoint),
    /// Farther than asked: the first-order rest-frame distance only, an estimate.
    Far(f64),
}

impl Located {
    /// The point's coordinates where it is near.
    pub fn near(self) -> Option<LocalPoint> {
        match self {
            Located::Near(lp) => Some(lp),
            Located::Far(_) => None,
        }
    }

    /// The rest-frame distance from the centre: |ξ| near, the first-order estimate far.
    pub fn distance(&self) -> f64 {
        match self {
            Located::Near(lp) => lp.xi.iter().map(|c| c * c).sum::<f64>().sqrt(),
            Located::Far(d) => *d,
        }
    }
}

/// Worldline of a local object.
#[derive(Clone, Debug)]
pub enum Worldline {
    Rest {
        position: Event,
        frame: Tetrad,
        /// The position, Γ there and the frame's dual basis in the chart of local
        /// descriptions ([`LocalChart`]), constant for an object at rest.
        center: Event,
        gamma: Expansion,
        dual: DualFrame,
    },
    Free(FreeFall),
}

/// A free-fall worldline: dense output forward (τ ≥ 0) and backward (τ ≤ 0) from its start.
#[derive(Clone, Debug)]
pub struct FreeFall {
    forward: Vec<DenseStep<20>>,
    backward: Vec<DenseStep<20>>,
    /// Where to find the step of a τ, forward and backward (see [`StepIndex`]).
    forward_index: StepIndex,
    backward_index: StepIndex,
    start: [f64; 20],
    /// (t, τ) at step ends, sorted by τ, to seed the matching.
    table: Vec<(f64, f64)>,
    /// The table's times, indexed (None where they do not increase: a binary search then).
    times: Option<StepIndex>,
    tau_min: f64,
    tau_max: f64,
    /// Position boxes on a grid in coordinate time (see [`TimeBoxes`]).
    boxes: TimeBoxes,
    /// The metric and Γ at the origin, where [`origin_coords`] expands (once, not per probe).
    origin: (MetricTensor, Expansion),
}

/// Increasing values (the steps' ends, |τ| from the start; or the coordinate times at them)
/// and, on a uniform grid of as many cells as values from the first, the first value that
/// reaches each cell's start: the step of a τ (or of a t) is then found among the few values
/// of its cell's neighbourhood, reading a few bytes a step, not by a binary search over the
/// steps' dense output (whose cache misses were a fifth of a falling ball's probe time) or
/// over the table of times (whose unpredictable halvings were 3 % of the reference scene's).
#[derive(Clone, Debug)]
struct StepIndex {
    ends: Vec<f64>,
    /// The grid's start: 0 for step ends, the first time for times.
    origin: f64,
    /// `first[c]`: the first value ≥ origin + c·cell, for c = 0 ..= cells.
    first: Vec<usize>,
    /// 1/cell: a product where a division would stand in every lookup.
    per_cell: f64,
}

impl StepIndex {
    /// Whether step `i` is the one [`StepIndex::first_reaching`] finds for `s`: the first
    /// whose end is ≥ s.
    fn holds(&self, i: usize, s: f64) -> bool {
        self.ends.get(i).is_some_and(|&e| e >= s) && (i == 0 || self.ends[i - 1] < s)
    }

    fn new(steps: &[DenseStep<20>]) -> StepIndex {
        StepIndex::of_ends(steps.iter().map(|s| s.lambda1()).collect(), 0.0)
    }

    /// The index of the increasing values `ends` on a grid from `origin` (at most the first).
    fn of_ends(ends: Vec<f64>, origin: f64) -> StepIndex {
        let cells = ends.len().max(1);
        let cell = (ends.last().copied().unwrap_or(origin) - origin) / cells as f64;
        let first = (0..=cells)
            .map(|c| ends.partition_point(|&e| e < origin + c as f64 * cell))
            .collect();
        StepIndex {
            ends,
            origin,
            first,
            per_cell: 1.0 / cell,
        }
    }

    /// The first value ≥ `s` (the values' count if none): what a binary search over all the
    /// values gives, found among the few between the cells on either side of `s`'s by walking
    /// from the first (measured faster than a binary search's branches, and than counting
    /// them all).
    fn first_reaching(&self, s: f64) -> usize {
        let cells = self.first.len() - 1;
        let c = (s - self.origin) * self.per_cell;
        if !(c.is_finite() && c >= 0.0) {
            return self.ends.partition_point(|&e| e < s);
        }
        // One cell of slack on each side: (c − 1)·cell ≤ s ≤ (c + 2)·cell despite rounding.
        let c = (c as usize).clamp(1, cells);
        let lo = self.first[c - 1];
        let hi = if c + 2 > cells {
            self.ends.len()
        } else {
            self.first[c + 2]
        };
        // The ends are increasing: the first at or past s, walking from lo (a step or two).
        lo + self.ends[lo..hi].iter().take_while(|&&e| e < s).count()
    }
}

/// Boxes around a worldline's positions, one per cell of a uniform grid in coordinate
/// time: a cell holds every step that overlaps it in time, so that the box of any time
/// window is a union of a few cells, not a scan of all steps (this runs per loop of every
/// ray). Steps need not be monotonic in t.
#[derive(Clone, Debug)]
struct TimeBoxes {
    t0: f64,
    cells: Vec<Aabb>,
}

/// Cell width of [`TimeBoxes`], in coordinate time.
const BOX_CELL: f64 = 0.25;

impl TimeBoxes {
    fn new(steps: impl Iterator<Item = (f64, f64, Aabb)> + Clone) -> Self {
        let (lo, hi) = steps
            .clone()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (l, h, _)| {
                (a.min(l), b.max(h))
            });
        if !(lo <= hi) {
            return TimeBoxes {
                t0: 0.0,
                cells: Vec::new(),
            };
        }
        let n = ((hi - lo) / BOX_CELL).floor() as usize + 1;
        let mut cells = vec![Aabb::EMPTY; n];
        for (l, h, b) in steps {
            for c in &mut cells[Self::cell(lo, n, l)..=Self::cell(lo, n, h)] {
                c.union(&b);
            }
        }
        TimeBoxes { t0: lo, cells }
    }

    fn cell(t0: f64, n: usize, t: f64) -> usize {
        (((t - t0) / BOX_CELL).floor().max(0.0) as usize).min(n - 1)
    }

    /// A box around the positions at times in [t0, t1] (empty outside the worldline).
    fn bounds(&self, t0: f64, t1: f64) -> Aabb {
        let n = self.cells.len();
        let mut b = Aabb::EMPTY;
        let end = self.t0 + n as f64 * BOX_CELL;
        if n == 0 || t1 < self.t0 || t0 > end {
            return b;
        }
        for c in &self.cells[Self::cell(self.t0, n, t0)..=Self::cell(self.t0, n, t1)] {
            b.union(c);
        }
        b
    }
}

/// Geodesic + parallel transport of three vectors: state (x, p, e1, e2, e3), dimension 20.
#[derive(Clone, Copy)]
struct Transport {
    metric: Metric,
    sign: f64,
}

impl OdeSystem<20> for Transport {
    fn rhs(&self, s: &[f64; 20]) -> [f64; 20] {
        let st = GeodesicState::from_array(&[s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7]]);
        let (v, f) = self.metric.hamilton(st.x, st.p);
        let gam = self.metric.christoffel(st.x);
        let u = v.to_array();
        let mut out = [0.0; 20];
        let head = [v.t, v.x, v.y, v.z, f.t, f.x, f.y, f.z];
        for i in 0..8 {
            out[i] = self.sign * head[i];
        }
        for k in 0..3 {
            let e = &s[8 + 4 * k..12 + 4 * k];
            for mu in 0..4 {
                let mut d = 0.0;
                for a in 0..4 {
                    for b in 0..4 {
                        d -= gam[mu][a][b] * u[a] * e[b];
                    }
                }
                out[8 + 4 * k + mu] = self.sign * d;
            }
        }
        out
    }
}

/// Why a worldline could not be built.
#[derive(Debug, thiserror::Error)]
pub enum WorldlineError {
    #[error("the free-fall worldline could not be integrated ({0})")]
    Integration(&'static str),
}

impl Worldline {
    /// Builds the worldline covering coordinate times [t_min, t_max] (as far as it reaches).
    pub fn new(
        metric: Metric,
        motion: &Motion,
        t_min: f64,
        t_max: f64,
    ) -> Result<Worldline, WorldlineError> {
        match *motion {
            Motion::Rest { position } => {
                let p = Event::new(0.0, position.x, position.y, position.z);
                let frame = metric.static_frame(p);
                let chart = LocalChart::of(&metric);
                let center = chart.event(p);
                Ok(Worldline::Rest {
                    position: p,
                    frame,
                    center,
                    gamma: Expansion::new(&chart.christoffel(center)),
                    dual: DualFrame::new(&chart.metric(center), &chart.frame(p, &frame)),
                })
            }
            Motion::Geodesic { start, velocity } => {
                let frame = metric.observer_frame(start, velocity);
                let g = Geodesic::from_tangent(
                    &metric,
                    spacetime::GeodesicKind::Timelike,
                    start,
                    frame.e[0],
                );
                let mut s0 = [0.0; 20];
                s0[..8].copy_from_slice(&g.start.to_array());
                for k in 0..3 {
                    s0[8 + 4 * k..12 + 4 * k].copy_from_slice(&frame.e[k + 1].to_array());
                }
                let fwd = integrate(metric, s0, 1.0, |t| t > t_max)?;
                let bwd = integrate(metric, s0, -1.0, |t| t < t_min)?;
                let mut table: Vec<(f64, f64)> =
                    bwd.iter().rev().map(|s| (s.y1[0], -s.lambda1())).collect();
                table.push((s0[0], 0.0));
                table.extend(fwd.iter().map(|s| (s.y1[0], s.lambda1())));
                let tau_min = -bwd.last().map_or(0.0, |s| s.lambda1());
                let tau_max = fwd.last().map_or(0.0, |s| s.lambda1());
                let boxes = TimeBoxes::new(fwd.iter().chain(bwd.iter()).map(step_box));
                Ok(Worldline::Free(FreeFall {
                    forward_index: StepIndex::new(&fwd),
                    backward_index: StepIndex::new(&bwd),
                    forward: fwd,
                    backward: bwd,
                    start: s0,
                    times: table.windows(2).all(|w| w[0].0 < w[1].0).then(|| {
                        StepIndex::of_ends(table.iter().map(|e| e.0).collect(), table[0].0)
                    }),
                    table,
                    tau_min,
                    tau_max,
                    boxes,
                    origin: {
                        let chart = LocalChart::of(&metric);
                        (
                            chart.metric(ORIGIN),
                            Expansion::new(&chart.christoffel(ORIGIN)),
                        )
                    },
                }))
            }
        }
    }

    /// The worldline point at proper time τ (None outside the integrated range).
    pub fn at(&self, metric: &Metric, tau: f64) -> Option<WorldPoint> {
        match self {
            Worldline::Rest {
                position, frame, ..
            } => Some(WorldPoint {
                tau,
                event: Event::new(tau, position.x, position.y, position.z),
                frame: *frame,
            }),
            Worldline::Free(f) => Some(point(metric, tau, &f.state(tau)?)),
        }
    }

    /// γ(1 + v) of the object relative to the static observers, constant along the worldline:
    /// a photon of energy E = −p_t (static frame, g_tt = −1) has energy at most E·γ(1 + v) in
    /// the object's frame. At rest 1; in free fall γ = −u_t is conserved (∂t is Killing).
    pub fn speed_factor(&self) -> f64 {
        match self {
            Worldline::Rest { .. } => 1.0,
            Worldline::Free(f) => {
                let gamma = (-f.start[4]).max(1.0);
                gamma + (gamma * gamma - 1.0).sqrt()
            }
        }
    }

    /// The proper-time range [τ_min, τ_max] of a free fall and its Lorentz factor γ = −u_t
    /// relative to the static observers (None at rest).
    pub fn free_fall_range(&self) -> Option<(f64, f64, f64)> {
        match self {
            Worldline::Rest { .. } => None,
            Worldline::Free(f) => Some((f.tau_min, f.tau_max, (-f.start[4]).max(1.0))),
        }
    }

    /// How many integration steps the worldline holds (0 at rest).
    pub fn integration_steps(&self) -> usize {
        match self {
            Worldline::Rest { .. } => 0,
            Worldline::Free(f) => f.forward.len() + f.backward.len(),
        }
    }

    /// A coordinate box around the worldline's positions at coordinate times in [t0, t1].
    pub fn bounds(&self, t0: f64, t1: f64) -> Aabb {
        match self {
            Worldline::Rest { position, .. } => Aabb::point([position.x, position.y, position.z]),
            Worldline::Free(f) => f.boxes.bounds(t0, t1),
        }
    }

    /// A first guess of the proper time at which the worldline has coordinate time `t`.
    pub fn tau_guess(&self, t: f64) -> f64 {
        match self {
            Worldline::Rest { .. } => t,
            Worldline::Free(f) => {
                let i = match &f.times {
                    Some(index) => index.first_reaching(t),
                    None => f.table.partition_point(|&(ti, _)| ti < t),
                };
                if i == 0 {
                    f.table[0].1
                } else if i >= f.table.len() {
                    f.table[f.table.len() - 1].1
                } else {
                    let ((t0, u0), (t1, u1)) = (f.table[i - 1], f.table[i]);
                    if t1 > t0 {
                        u0 + (u1 - u0) * (t - t0) / (t1 - t0)
                    } else {
                        u0
                    }
                }
            }
        }
    }

    /// Expresses the ray point `x` in the rest frame of the worldline point simultaneous
    /// with it, starting the search at `tau_guess`. None if the match leaves the worldline.
    ///
    /// Points whose first-order rest-frame distance exceeds `far` are returned with that
    /// first-order distance only ([`Located::Far`]): the second-order terms matter only near
    /// the object, and the caller treats far distances as estimates.
    pub fn localize(&self, metric: &Metric, x: Event, tau_guess: f64, far: f64) -> Option<Located> {
        match self {
            Worldline::Rest {
                position,
                frame,
                center,
                gamma,
                dual,
            } => {
                // Static: u = ∂t; g(u, Δ) = 0 fixes Δt = g_ti Δ^i at first order, and the
                // dual row of e0 = ∂t is −g_tμ. All in the chart of local descriptions.
                let x = LocalChart::of(metric).event(x);
                let dx = [x.x - center.x, x.y - center.y, x.z - center.z];
                let dt = -(dual.0[0][1] * dx[0] + dual.0[0][2] * dx[1] + dual.0[0][3] * dx[2]);
                let mut t = x.t - dt;
                let first =
                    local_coords(dual, None, Event::new(t, center.x, center.y, center.z), x);
                let distance = norm3(&first);
                if !(distance <= far) {
                    return Some(Located::Far(distance));
                }
                let mut xi = first;
                for _ in 0..2 {
                    xi = local_coords(
                        dual,
                        Some(gamma),
                        Event::new(t, center.x, center.y, center.z),
                        x,
                    );
                    t += xi[0];
                }
                let at = WorldPoint {
                    tau: t,
                    event: Event::new(t, position.x, position.y, position.z),
                    frame: *frame,
                };
                Some(Located::Near(LocalPoint {
                    at,
                    xi: [xi[1], xi[2], xi[3]],
                }))
            }
            Worldline::Free(ff) => {
                // Start inside the integrated range: far points (whose rest-frame "now" may
                // lie beyond it) still get a finite distance, so no step is skipped.
                let mut tau = tau_guess.clamp(ff.tau_min, ff.tau_max);
                // The step of the last τ asked: the secant's τ stay near it.
                let mut near_step = usize::MAX;
                let (xi0, distance) = ff.first_order(metric, tau, x, &mut near_step)?;
                if distance > far {
                    // Far: an estimate only (the tracer never lets it vouch for more than
                    // one step: with the worldline looping, "now" is ambiguous far away).
                    return Some(Located::Far(distance));
                }
                // Near: the first-order simultaneity ξ⁰(τ) = −g(u, Δ) = 0 by the secant method,
                // started with the slope dξ⁰/dτ = −1 of a slow object. For a fast one the
                // coordinate acceleration of u changes the slope by up to ~γ²|ξ|/a (measured
                // −2.3 at 0.99 c), where Newton with slope −1 diverges. (The first-order
                // condition has one root near the ball; the second-order one can have more,
                // and a secant on it jumped between them from one ray point to the next.)
                let (mut ta, mut fa) = (tau, xi0);
                tau = (ta + fa).clamp(ff.tau_min, ff.tau_max);
                let (mut fb, mut sb) = ff.time_offset(metric, tau, x, &mut near_step)?;
                for _ in 0..SIMULTANEITY_STEPS {
                    if fb.abs() < SIMULTANEITY_TOLERANCE * metric.length_scale() || tau == ta {
                        break;
                    }
                    let slope = (fb - fa) / (tau - ta);
                    let step = if slope < 0.0 && slope.is_finite() {
                        -fb / slope
                    } else {
                        fb
                    };
                    (ta, fa) = (tau, fb);
                    tau = (tau + step).clamp(ff.tau_min, ff.tau_max);
                    (fb, sb) = ff.time_offset(metric, tau, x, &mut near_step)?;
                }
                // Second order near the object, taken at the origin (`origin_coords`): one
                // more Newton step on its ξ⁰, from the state at the secant's last τ.
                let (event, u) = event_velocity(metric, &sb);
                tau = (tau + origin_time(metric, &ff.origin, event, u, x))
                    .clamp(ff.tau_min, ff.tau_max);
                let pb = point(metric, tau, &ff.state_near(tau, &mut near_step)?);
                let xb = origin_coords(metric, &ff.origin, &pb, x);
                Some(Located::Near(LocalPoint {
                    at: pb,
                    xi: [xb[1], xb[2], xb[3]],
                }))
            }
        }
    }
}

/// The event and four-velocity u^μ of a free fall's transported state `s` (position, u_μ, …).
fn event_velocity(metric: &Metric, s: &[f64]) -> (Event, FourVector) {
    let x = Event::new(s[0], s[1], s[2], s[3]);
    (
        x,
        metric.raise(x, spacetime::Covector::new(s[4], s[5], s[6], s[7])),
    )
}

/// In the metric's own chart, for a free fall's state `s` (position and u_μ): the worldline
/// point, the displacement Δ from it to `x`, and ξ⁰ = −g(u, Δ) = −u_μΔ^μ, with u_μ read from
/// the state (no raise, no metric).
fn own_time_offset(s: &[f64; 8], x: Event) -> (Event, FourVector, f64) {
    let p = Event::new(s[0], s[1], s[2], s[3]);
    let d = (x - p).to_array();
    let xi0 = DualFrame::component(&[-s[4], -s[5], -s[6], -s[7]], d);
    (p, FourVector::from_array(d), xi0)
}

/// The worldline point of a free fall's transported state `s` at proper time τ.
fn point(metric: &Metric, tau: f64, s: &[f64; 20]) -> WorldPoint {
    let (x, u) = event_velocity(metric, s);
    let e = |k: usize| FourVector::new(s[8 + 4 * k], s[9 + 4 * k], s[10 + 4 * k], s[11 + 4 * k]);
    WorldPoint {
        tau,
        event: x,
        frame: Tetrad {
            e: [u, e(0), e(1), e(2)],
        },
    }
}

/// Most secant steps on an object's simultaneity (each converges superlinearly; a handful
/// suffice, the bound keeps a pathological case finite).
const SIMULTANEITY_STEPS: usize = 12;

/// The secant steps stop once the first-order ξ⁰ is below this (in units of a). The Newton
/// step that follows moves τ by the second-order terms (~|ξ|²/a) and takes this residual
/// along, times its slope's error; so it changes a record by ~1e-9, far below the tracers'
/// agreement (1e-6) and below a data file's single precision. (At 1e-12 a third of the
/// steps only refined a root already good to 1e-6.)
const SIMULTANEITY_TOLERANCE: f64 = 1e-9;

/// Most integration steps of a free-fall worldline in each direction of proper time
/// (~1.5 KB each). A worldline whose coordinate time never reaches the traced range (beyond
/// the horizon it need not) simply ends there; the renderer also bounds the sum over all
/// objects.
pub const MAX_WORLDLINE_STEPS: usize = 50_000;

fn norm3(xi: &[f64; 4]) -> f64 {
    (xi[1] * xi[1] + xi[2] * xi[2] + xi[3] * xi[3]).sqrt()
}

/// Rest-frame components (ξ⁰, ξ¹, ξ², ξ³) of the displacement from `p` to `x`, in Riemann
/// normal coordinates to second order when `gamma` (Γ at `p`) is given, else to first
/// order, measured with the `dual` basis of the orthonormal frame at `p`.
fn local_coords(dual: &DualFrame, gamma: Option<&Expansion>, p: Event, x: Event) -> [f64; 4] {
    let d = (x - p).to_array();
    dual.components(match gamma {
        Some(gamma) => gamma.displacement(d),
        None => d,
    })
}

/// Rest-frame components of the displacement from the worldline point `p` to `x` to first
/// order, in the chart of local descriptions ([`LocalChart`]).
fn first_order(metric: &Metric, p: &WorldPoint, x: Event) -> [f64; 4] {
    let chart = LocalChart::of(metric);
    let at = chart.event(p.event);
    let dual = DualFrame::new(&chart.metric(at), &chart.frame(p.event, &p.frame));
    local_coords(&dual, None, at, chart.event(x))
}

/// ξ⁰ of [`first_order`] alone, for the worldline point at `event` with four-velocity `u`:
/// the time row of its frame.
fn first_order_time(metric: &Metric, event: Event, u: FourVector, x: Event) -> f64 {
    let chart = LocalChart::of(metric);
    let at = chart.event(event);
    let row = DualFrame::row(&chart.metric(at), 0, chart.vector(event, u));
    DualFrame::component(&row, (chart.event(x) - at).to_array())
}

/// Rest-frame components of the displacement from the worldline point `p` to `x` in
/// Riemann normal coordinates to second order, taken after the isometry that sends `p` to
/// the origin (docs/physics.md "Simultaneity"), in the chart of local descriptions there
/// (`origin`: its metric and Γ at the origin). There Γ is small and the expansion
/// holds for displacements up to the largest radius, a/2, even for a boosted ball near the
/// horizon: at `p` itself a coordinate displacement of ~γ|ξ| at large r once put a point
/// 1.7 γ|ξ| away (static distance) inside the ball. Minkowski: the displacement itself.
fn origin_coords(
    metric: &Metric,
    origin: &(MetricTensor, Expansion),
    p: &WorldPoint,
    x: Event,
) -> [f64; 4] {
    let Some((there, axes)) = to_origin(metric, p.event, x) else {
        // Minkowski space (and a member's event at the pole opposite the axis, which the
        // scene's bounds keep any object from reaching): the displacement at `p` itself.
        return first_order(metric, p, x);
    };
    // The chart's differential at the origin is the identity: the frame stays as it is.
    let frame = p.frame.e.map(|v| through(axes, v));
    let dual = DualFrame::new(&origin.0, &Tetrad { e: frame });
    local_coords(&dual, Some(&origin.1), ORIGIN, there)
}

/// ξ⁰ of [`origin_coords`] alone, for the worldline point at `event` with four-velocity `u`:
/// the time row of the frame carried to the origin (the other rows, and the frame's other
/// vectors, not needed: the Newton step of the simultaneity).
fn origin_time(
    metric: &Metric,
    origin: &(MetricTensor, Expansion),
    event: Event,
    u: FourVector,
    x: Event,
) -> f64 {
    let Some((there, axes)) = to_origin(metric, event, x) else {
        return first_order_time(metric, event, u, x);
    };
    let row = DualFrame::row(&origin.0, 0, through(axes, u));
    DualFrame::component(&row, origin.1.displacement((there - ORIGIN).to_array()))
}

/// The ray point `x` moved by the isometry that sends `event` to the origin, in the chart of
/// local descriptions there, and the images of ∂x and ∂y at `event` ([`through`]). None in
/// Minkowski space, and at a member's pole opposite the axis.
fn to_origin(metric: &Metric, event: Event, x: Event) -> Option<(Event, [FourVector; 2])> {
    let chart = LocalChart::of(metric);
    let (there, axes) = match *metric {
        Metric::Godel(g) => Some((
            Isometry::to_origin(g.a, event).apply(x),
            origin_axes(&g, event),
        )),
        Metric::GodelType(member) => TypeIsometry::to_origin(member, event)
            .map(|to| (to.apply(x), to.push_all(event, [X_AXIS, Y_AXIS]))),
        Metric::Minkowski(_) => None,
    }?;
    Some((chart.event(there), axes))
}

/// The event at the origin of the coordinates.
const ORIGIN: Event = Event::new(0.0, 0.0, 0.0, 0.0);

/// The coordinate vectors ∂x and ∂y.
const X_AXIS: FourVector = FourVector::new(0.0, 1.0, 0.0, 0.0);
const Y_AXIS: FourVector = FourVector::new(0.0, 0.0, 1.0, 0.0);

/// The image of `v` under an isometry's differential, from the images `axes` of ∂x and ∂y:
/// Gödel's isometries and a member's map ∂t to ∂t and ∂z to ∂z (t and z are only shifted;
/// the base map adds to dt a term linear in dx, dy), so by linearity the image is
/// v^t ∂t + v^x X + v^y Y + v^z ∂z. A tetrad then takes two pushes, not four.
fn through(axes: [FourVector; 2], v: FourVector) -> FourVector {
    let [ix, iy] = axes;
    FourVector::new(
        v.t + v.x * ix.t + v.y * iy.t,
        v.x * ix.x + v.y * iy.x,
        v.x * ix.y + v.y * iy.y,
        v.z,
    )
}

/// Integrates the transported geodesic in the direction `sign` of proper time until `done(t)`.
fn integrate(
    metric: Metric,
    s0: [f64; 20],
    sign: f64,
    done: impl Fn(f64) -> bool,
) -> Result<Vec<DenseStep<20>>, WorldlineError> {
    // Steps scale with the curvature scale a (a loop takes a few a of proper time).
    let scale = metric.length_scale();
    let tol = Tolerances {
        rtol: 1e-11,
        atol: 1e-11,
        h_max: 0.25 * scale,
        h_min: 1e-12 * scale,
    };
    let mut ode = Dop853::new(Transport { metric, sign }, 0.0, s0, tol, None);
    let mut steps = Vec::new();
    while !done(ode.state()[0]) && steps.len() < MAX_WORLDLINE_STEPS {
        match ode.step() {
            StepOutcome::Accepted => steps.push(ode.dense()),
            StepOutcome::Stalled => return Err(WorldlineError::Integration("step size collapsed")),
            StepOutcome::NonFinite => return Err(WorldlineError::Integration("non-finite values")),
        }
    }
    Ok(steps)
}

/// Time range and position box of one worldline step: its ends and midpoint, grown by a
/// quarter of the chord (far more than an arc of one short step departs from its samples).
fn step_box(st: &DenseStep<20>) -> (f64, f64, Aabb) {
    let mid = st.eval(st.lambda0 + 0.5 * st.h);
    let mut b = Aabb::point([st.y0[1], st.y0[2], st.y0[3]]);
    b.add([st.y1[1], st.y1[2], st.y1[3]]);
    b.add([mid[1], mid[2], mid[3]]);
    let chord = ((st.y1[1] - st.y0[1]).powi(2)
        + (st.y1[2] - st.y0[2]).powi(2)
        + (st.y1[3] - st.y0[3]).powi(2))
    .sqrt();
    let (t0, t1) = (st.y0[0].min(st.y1[0]), st.y0[0].max(st.y1[0]));
    (t0, t1, b.grown(0.25 * chord))
}

impl FreeFall {
    /// The first `M` components of the transported state at proper time τ (position and
    /// u_μ: 8; with the frame: 20); None outside the integrated range.
    fn state<const M: usize>(&self, tau: f64) -> Option<[f64; M]> {
        let mut unknown = usize::MAX;
        self.state_near(tau, &mut unknown)
    }

    /// [`FreeFall::state`] where `step` (updated) is the step of a nearby τ asked before: a
    /// match's secant steps stay within a step or two, whose index is then not looked up.
    fn state_near<const M: usize>(&self, tau: f64, step: &mut usize) -> Option<[f64; M]> {
        if !(tau >= self.tau_min && tau <= self.tau_max) {
            return None;
        }
        if tau == 0.0 {
            return Some(std::array::from_fn(|i| self.start[i]));
        }
        let (steps, index, s) = if tau > 0.0 {
            (&self.forward, &self.forward_index, tau)
        } else {
            (&self.backward, &self.backward_index, -tau)
        };
        let i = if index.holds(*step, s) {
            *step
        } else {
            index.first_reaching(s).min(steps.len().checked_sub(1)?)
        };
        *step = i;
        Some(steps[i].eval_head(s))
    }

    /// ξ⁰ of [`first_order`] at the worldline point of proper time τ: the time row alone,
    /// from the position and u (the body frame's other vectors not interpolated). What the
    /// simultaneity's secant steps need; with the state (position and u_μ) it was taken from,
    /// whose event and velocity the match's last step then reuses.
    fn time_offset(
        &self,
        metric: &Metric,
        tau: f64,
        x: Event,
        step: &mut usize,
    ) -> Option<(f64, [f64; 8])> {
        let s: [f64; 8] = self.state_near(tau, step)?;
        let xi0 = if let LocalChart::Own(_) = LocalChart::of(metric) {
            own_time_offset(&s, x).2
        } else {
            let (p, u) = event_velocity(metric, &s);
            first_order_time(metric, p, u, x)
        };
        Some((xi0, s))
    }

    /// ξ⁰ and the spatial length |ξ| of [`first_order`] at the worldline point of proper
    /// time τ. In the metric's own chart from the position and u alone: the frame is
    /// orthonormal, so |ξ|² = g(Δ, Δ) + (ξ⁰)².
    fn first_order(
        &self,
        metric: &Metric,
        tau: f64,
        x: Event,
        step: &mut usize,
    ) -> Option<(f64, f64)> {
        if let LocalChart::Own(_) = LocalChart::of(metric) {
            let (p, d, xi0) = own_time_offset(&self.state_near(tau, step)?, x);
            let dd = metric.dot(p, d, d);
            return Some((xi0, (dd + xi0 * xi0).max(0.0).sqrt()));
        }
        let s: [f64; 20] = self.state_near(tau, step)?;
        let first = first_order(metric, &point(metric, tau, &s), x);
        Some((first[0], norm3(&first)))
    }
}

#[cfg(test)]
mod tests {
    use super::{first_order, norm3, point, through, StepIndex, Worldline, X_AXIS, Y_AXIS};
    use scene::Motion;
    use spacetime::{
        Event, FourVector, Godel, GodelType, Isometry, LocalVelocity, Metric, Minkowski,
        TypeIsometry,
    };

    /// Numbers in [0, 1) from a fixed seed (xorshift64*): the same cases every run.
    fn uniform(state: &mut u64) -> f64 {
        *state ^= *state >> 12;
        *state ^= *state << 25;
        *state ^= *state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The index finds the step a binary search over all the ends finds (and knows that step
    /// when given it), for steps of very uneven lengths (as near a worldline's turning
    /// points), at the cells' edges, the ends themselves and beyond the last; on a grid from
    /// 0 (step ends) and from the first value (the times, here from −7.3, as a table's).
    #[test]
    fn the_step_index_finds_what_a_binary_search_finds() {
        let mut rng = 33u64;
        for (n, shifted) in [1usize, 2, 3, 17, 400]
            .into_iter()
            .flat_map(|n| [(n, false), (n, true)])
        {
            let mut end = 0.0;
            let shift = if shifted { -7.3 } else { 0.0 };
            let ends: Vec<f64> = (0..n)
                .map(|_| {
                    end += 10f64.powf(-4.0 * uniform(&mut rng));
                    end + shift
                })
                .collect();
            let origin = if shifted { ends[0] } else { 0.0 };
            let index = StepIndex::of_ends(ends.clone(), origin);
            let mut queries: Vec<f64> = (0..2000)
                .map(|_| shift + 1.1 * end * uniform(&mut rng))
                .collect();
            queries.extend(ends.iter().copied());
            queries.extend((0..=n).map(|c| origin + c as f64 / index.per_cell));
            queries.extend([
                shift,
                shift - 1.0,
                origin,
                end + shift,
                2.0 * end,
                f64::INFINITY,
            ]);
            queries.push(f64::NEG_INFINITY);
            assert_eq!(index.first_reaching(f64::NAN), 0, "n = {n}");
            for s in queries {
                let want = ends.partition_point(|&e| e < s);
                assert_eq!(index.first_reaching(s), want, "n = {n}, s = {s}");
                // A remembered step is taken for s exactly when it is that one.
                for i in [want.wrapping_sub(1), want, want + 1, usize::MAX] {
                    let holds = i == want && want < n;
                    assert_eq!(index.holds(i, s), holds, "n = {n}, s = {s}, step {i}");
                }
            }
        }
    }

    /// A frame pushed through the images of ∂x and ∂y ([`through`]) is the frame pushed
    /// vector by vector, for Gödel's isometries and for members of the family (m²/Ω² from −1
    /// to 6), at events up to r = 3 (a = 1), within rounding. With the t row's term left out
    /// (the base map's dt part) or ∂z's image assumed to move, it fails.
    #[test]
    fn a_frame_goes_through_the_images_of_two_axes() {
        let mut rng = 7u64;
        let mut draw = |scale: f64| scale * (2.0 * uniform(&mut rng) - 1.0);
        for case in 0..400 {
            let at = Event::new(draw(3.0), draw(2.1), draw(2.1), draw(1.0));
            let vs: [FourVector; 4] = std::array::from_fn(|_| {
                FourVector::new(draw(2.0), draw(2.0), draw(2.0), draw(2.0))
            });
            let member = GodelType::new([-1.0, 0.0, 1.0, 2.0, 3.5, 6.0][case % 6] * 0.49, 0.7);
            let pushed: [([FourVector; 4], [FourVector; 2]); 2] = [
                {
                    let to = Isometry::to_origin(1.0, at);
                    (to.push_all(at, vs), to.push_all(at, [X_AXIS, Y_AXIS]))
                },
                match TypeIsometry::to_origin(member, at) {
                    Some(to) => (to.push_all(at, vs), to.push_all(at, [X_AXIS, Y_AXIS])),
                    None => continue,
                },
            ];
            for (want, axes) in pushed {
                for (w, v) in want.iter().zip(vs) {
                    let got = through(axes, v).to_array();
                    for (g, w) in got.iter().zip(w.to_array()) {
                        assert!(
                            (g - w).abs() <= 1e-12 * (1.0 + w.abs()),
                            "{got:?} vs {w:?} at {at:?}"
                        );
                    }
                }
            }
        }
    }

    /// The first-order match from the position and u alone (ξ⁰ = −u_μΔ^μ, |ξ|² = g(Δ, Δ) +
    /// (ξ⁰)²) is the one measured with the whole transported frame, for fast falls (0.9 c)
    /// in Gödel's universe and in Minkowski space, at points up to 3a from the worldline and
    /// far from simultaneous. With |ξ|² = g(Δ, Δ) − (ξ⁰)², or ξ⁰ of the opposite sign, it
    /// fails.
    #[test]
    fn the_first_order_match_needs_only_position_and_velocity() {
        let mut rng = 11u64;
        let mut draw = |scale: f64| scale * (2.0 * uniform(&mut rng) - 1.0);
        for metric in [Metric::Godel(Godel::new(1.0)), Metric::Minkowski(Minkowski)] {
            let motion = Motion::Geodesic {
                start: Event::new(0.0, -1.0, 0.3, 0.0),
                velocity: LocalVelocity::new(0.9, [1.0, 0.4, 0.2]).unwrap(),
            };
            let Ok(Worldline::Free(ff)) = Worldline::new(metric, &motion, -6.0, 1.0) else {
                panic!("a free fall");
            };
            for _ in 0..300 {
                let tau = ff.tau_min + (ff.tau_max - ff.tau_min) * (0.5 + 0.5 * draw(1.0));
                let c = point(&metric, tau, &ff.state(tau).unwrap()).event;
                let x = Event::new(
                    c.t + draw(3.0),
                    c.x + draw(1.5),
                    c.y + draw(1.5),
                    c.z + draw(1.5),
                );
                let mut unknown = usize::MAX;
                let (xi0, distance) = ff.first_order(&metric, tau, x, &mut unknown).unwrap();
                let want = first_order(&metric, &point(&metric, tau, &ff.state(tau).unwrap()), x);
                let scale = 1.0 + norm3(&want) + want[0].abs();
                assert!(
                    (xi0 - want[0]).abs() <= 1e-12 * scale,
                    "ξ⁰ {xi0} vs {want:?}"
                );
                assert!(
                    (distance - norm3(&want)).abs() <= 1e-9 * scale,
                    "|ξ| {distance} vs {want:?}"
                );
            }
        }
    }
}
