//! The numeric tracer: one backward light ray per pixel, integrated with DOP853 from the
//! observer into the past, tested against every object in space and time.
//!
//! Pixel → ray (formulary §4): a pixel looking along the local unit direction n starts the
//! past-directed null ray k = −e0 + nⁱ eᵢ of the observer's (boosted) frame.
//!
//! Gödel loops: every light ray through an event returns to that event's axis (its x, y)
//! after a finite affine length and then retraces the same loop, shifted in t and z only
//! (formulary §2; ∂t and ∂z are Killing and the isometries of §3 commute with them). So the
//! first loop is integrated once, checked to close (position and momentum), and its dense
//! steps are reused for the later loops with the shift (Δt, Δz, Δλ): the intersection test
//! still runs against each object at each loop's times. This bounds the integration error
//! to one loop, however far into the past a ray is followed.
//!
//! Frequency shift g = (p·u_obs)/(p·u_emit) (DESIGN.md), from the photon's covariant
//! momentum at both ends.

use crate::bounds::Aabb;
use crate::lighting::{HitPoint, LightSource};
use crate::record::{PixelRecord, RayStatus};
use crate::target::{Probe, Target};
use spacetime::{
    refine_root, DenseStep, Dop853, Event, ExactGeodesic, GeodesicState, GeodesicSystem, Metric,
    OdeSystem, Spacetime, StepData, StepOutcome, Tetrad, Tolerances, STATE,
};
use std::cell::OnceCell;

/// Everything a ray needs, built once per render and shared by all threads.
pub struct Tracer {
    pub(crate) metric: Metric,
    observer: Event,
    frame: Tetrad,
    pub(crate) targets: Vec<Target>,
    /// Rays stop at coordinate time observer.t − max_past.
    t_bound: f64,
    tol: Tolerances,
    max_steps: u64,
    /// Reuse the first loop (Gödel only).
    periodic: bool,
    /// Use the closed-form geodesics instead of the integrator (Gödel only).
    exact: bool,
    /// Point lights at rest, for direct illumination (`crate::lighting`).
    pub(crate) lights: Vec<LightSource>,
}

/// Segments per loop for the exact tracer (and the shadow rays' occlusion test). Each
/// segment end costs a closed-form evaluation whether or not a probe is needed there;
/// fewer, longer segments cost more bisection near objects. Measured with callgrind on
/// scenes/bench-static.toml (exact, one thread, whole CLI render): 32 → 1.77 G instructions,
/// 16 → 1.32 G, 8 → 1.25 G; on the reference scene at 440×50, 16 and 8 are within 1 %.
pub(crate) const EXACT_SEGMENTS: usize = 16;

/// Per-thread buffers, reused from ray to ray (no allocation per ray).
#[derive(Default)]
pub struct Scratch {
    steps: Vec<LazyStep>,
    pub(crate) start: Vec<Measured>,
    pub(crate) end: Vec<Measured>,
    /// The first step size the previous ray's integrator settled on: neighbouring pixels
    /// take nearly the same steps, so the next ray starts there instead of with the
    /// initial-step heuristic (two evaluations and a short first step). Reset per tile.
    first_step: Option<f64>,
    /// The last traced ray's hit at full precision (for direct illumination), if any.
    pub(crate) hit: Option<HitPoint>,
}

impl Scratch {
    /// Forget the previous ray's step size (at the start of a tile).
    pub fn reset_first_step(&mut self) {
        self.first_step = None;
    }
}

/// A probe and the ray parameter (absolute: loop shifts included) where it was taken.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Measured {
    probe: Probe,
    at: f64,
}

/// Conservative advancement: since |df/dλ| ≤ rate, a probe showing clearance |f| proves
/// that the ray crosses no surface of that object before λ + |f|/rate, so no probe is
/// needed until then. Capped, because the rate bound is made for spans of a few steps.
const MAX_SKIP: f64 = 1.0;

/// Halvings of a span before the bisection accepts it as a graze without a crossing (a
/// span ~1e-9 of a step): a resolution limit, not a failure.
const SEARCH_DEPTH: u32 = 30;

/// Probes one bisection may spend on one object over one span; beyond it the pixel is marked
/// [`RayStatus::WorkLimit`] instead of searching on. The rate bound excludes spans linearly
/// while a graze approaches the surface quadratically, so ruling out a crossing costs
/// ~rate/√(f''·gap) probes: measured (unit test below) 256 for a graze 1e-3 of the radius
/// clear of a coordinate sphere, 16,384 at 1e-7, 65,536 at 1e-9, near the depth limit. So
/// this bound is reached only by rays that stay within ~1e-9 of a surface for a long
/// stretch, which [`SEARCH_DEPTH`] alone would let cost 2^30 probes.
const SEARCH_PROBES: u32 = 1 << 17;

/// A bounded search ran out of work: the ray is marked, never followed on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct OutOfWork;

/// A stored step whose dense output is made on first use (most steps never need it), or a
/// segment of a closed-form geodesic (the exact tracer), evaluated directly.
pub struct LazyStep {
    data: StepData<STATE>,
    sys: GeodesicSystem<Metric>,
    dense: OnceCell<DenseStep<STATE>>,
    exact: Option<ExactGeodesic>,
}

impl LazyStep {
    fn new(data: StepData<STATE>, sys: GeodesicSystem<Metric>) -> Self {
        LazyStep {
            data,
            sys,
            dense: OnceCell::new(),
            exact: None,
        }
    }
    /// The segment [l0, l1] of a closed-form geodesic whose state at l0 is `y0`.
    pub(crate) fn exact(
        geo: ExactGeodesic,
        sys: GeodesicSystem<Metric>,
        l0: f64,
        y0: [f64; STATE],
        l1: f64,
    ) -> Self {
        let data = StepData {
            lambda0: l0,
            h: l1 - l0,
            y0,
            y1: exact_state(&geo, &sys, l1),
        };
        LazyStep {
            data,
            sys,
            dense: OnceCell::new(),
            exact: Some(geo),
        }
    }
    fn eval(&self, l: f64) -> [f64; STATE] {
        if l == self.data.lambda1() {
            self.data.y1
        } else if l == self.data.lambda0 {
            self.data.y0
        } else if let Some(geo) = &self.exact {
            exact_state(geo, &self.sys, l)
        } else {
            self.dense
                .get_or_init(|| self.data.dense(&self.sys))
                .eval(l)
        }
    }

    /// The phase-space point at `l`.
    fn state_at(&self, l: f64) -> GeodesicState {
        self.sys.state(&self.eval(l))
    }
}

impl std::ops::Deref for LazyStep {
    type Target = StepData<STATE>;
    fn deref(&self) -> &StepData<STATE> {
        &self.data
    }
}

/// The integrated-state form (t, x, y, z, p_x, p_y) of a closed-form geodesic at `l`.
fn exact_state(geo: &ExactGeodesic, sys: &GeodesicSystem<Metric>, l: f64) -> [f64; STATE] {
    let (x, k) = geo.at(l);
    let p = sys.metric.lower(x, k);
    [x.t, x.x, x.y, x.z, p.x, p.y]
}

/// A shift of a stored loop: later loops are the first one moved in t, z and λ.
#[derive(Clone, Copy, Default)]
pub(crate) struct Shift {
    dt: f64,
    dz: f64,
    dl: f64,
}

impl Shift {
    fn times(self, k: f64) -> Shift {
        Shift {
            dt: k * self.dt,
            dz: k * self.dz,
            dl: k * self.dl,
        }
    }
    fn apply(self, mut st: GeodesicState) -> GeodesicState {
        st.x.t += self.dt;
        st.x.z += self.dz;
        st
    }
}

pub(crate) struct Hit {
    target: usize,
    lambda: f64,
    tau: f64,
}

impl Tracer {
    pub fn new(
        metric: Metric,
        observer: Event,
        frame: Tetrad,
        targets: Vec<Target>,
        max_past: f64,
        tolerance: f64,
        max_steps: u64,
        exact: bool,
    ) -> Tracer {
        Tracer {
            metric,
            observer,
            frame,
            targets,
            t_bound: observer.t - max_past,
            tol: Tolerances {
                rtol: tolerance,
                atol: tolerance,
                ..Tolerances::default()
            },
            max_steps,
            periodic: matches!(metric, Metric::Godel(_)),
            exact: exact && matches!(metric, Metric::Godel(_)),
            lights: Vec::new(),
        }
    }

    /// How far into the past rays are followed (coordinate time).
    pub fn max_past(&self) -> f64 {
        self.observer.t - self.t_bound
    }

    /// The same tracer with point lights (direct illumination, `crate::lighting`).
    pub fn with_lights(self, lights: Vec<LightSource>) -> Tracer {
        Tracer { lights, ..self }
    }

    pub fn scratch(&self) -> Scratch {
        let none = Measured {
            probe: Probe {
                f: 0.0,
                rate: 0.0,
                tau: f64::NAN,
            },
            at: 0.0,
        };
        Scratch {
            steps: Vec::new(),
            start: vec![none; self.targets.len()],
            end: vec![none; self.targets.len()],
            first_step: None,
            hit: None,
        }
    }

    /// Traces the pixel looking along the local unit direction `n`.
    pub fn trace(&self, n: [f64; 3], scratch: &mut Scratch) -> PixelRecord {
        let k = self.frame.vector([-1.0, n[0], n[1], n[2]]);
        let start = GeodesicState {
            x: self.observer,
            p: self.metric.lower(self.observer, k),
        };
        let (sys, s0) = GeodesicSystem::new(self.metric, &start);
        let Scratch {
            steps,
            start: probes_a,
            end: probes_b,
            first_step,
            hit,
        } = scratch;
        steps.clear();
        *hit = None;
        self.probe_all(&start, 0.0, probes_a);
        if self.exact {
            return self.trace_exact(&start, k, sys, s0, steps, probes_a, probes_b, hit);
        }
        let mut ode = Dop853::new(sys, 0.0, s0, self.tol, *first_step);
        let (x0, y0) = (s0[1], s0[2]);
        let axis_g = |s: &[f64; STATE], d: &[f64; STATE]| (s[1] - x0) * d[1] + (s[2] - y0) * d[2];
        let mut max_d2: f64 = 0.0;
        let mut periodic = self.periodic;
        let period = loop {
            if ode.accepted >= self.max_steps {
                return PixelRecord::miss(RayStatus::StepBudget);
            }
            let g_prev = axis_g(ode.state(), ode.derivative());
            match ode.step() {
                StepOutcome::Accepted => {}
                StepOutcome::Stalled | StepOutcome::NonFinite => {
                    return PixelRecord::miss(RayStatus::Failed)
                }
            }
            if ode.accepted == 1 {
                // Bounded by the ray's extent: where the error estimate vanishes (flat
                // spacetime) the proposal grows tenfold per ray and would overflow.
                *first_step = Some(ode.next_step_size().min(self.observer.t - self.t_bound));
            }
            // Kept in place (a step record is large): only the first loop is stored for reuse.
            if !periodic {
                steps.clear();
            }
            steps.push(LazyStep::new(ode.last_step(), sys));
            let d = steps.last().expect("just pushed");
            let mut hi = d.lambda1();
            let mut closed = None;
            if periodic {
                let s1 = d.y1;
                let g1 = axis_g(&s1, ode.derivative());
                if max_d2 > 0.0 && g_prev < 0.0 && g1 >= 0.0 {
                    let gl = |l: f64| {
                        let st = d.eval(l);
                        axis_g(&st, &sys.rhs(&st))
                    };
                    let l = refine_root(gl, d.lambda0, d.lambda1(), g_prev, g1);
                    let e = d.eval(l);
                    let dmin2 = (e[1] - x0).powi(2) + (e[2] - y0).powi(2);
                    let dp = (e[4] - s0[4]).abs() + (e[5] - s0[5]).abs();
                    let p = start.p;
                    let pscale = p.t.abs() + p.x.abs() + p.y.abs() + p.z.abs();
                    if dmin2 <= 1e-14 * max_d2 && dp <= 1e-7 * pscale {
                        hi = l;
                        closed = Some(Shift {
                            dt: e[0] - s0[0],
                            dz: e[3] - s0[3],
                            dl: l,
                        });
                    } else if dmin2 <= 1e-6 * max_d2 {
                        periodic = false; // did not close well enough: integrate on
                    }
                }
                max_d2 = max_d2.max((s1[1] - x0).powi(2) + (s1[2] - y0).powi(2));
            }
            match self.scan(d, Shift::default(), d.lambda0, hi, probes_a, probes_b) {
                Ok(Some(h)) => return self.record(&start, d, Shift::default(), h, hit),
                Ok(None) => {}
                Err(OutOfWork) => return PixelRecord::miss(RayStatus::WorkLimit),
            }
            if d.eval(hi)[0] < self.t_bound || !d.y1.iter().all(|v| v.is_finite()) {
                return PixelRecord::miss(if d.y1[0] < self.t_bound {
                    RayStatus::Escaped
                } else {
                    RayStatus::Failed
                });
            }
            std::mem::swap(probes_a, probes_b);
            if let Some(p) = closed {
                break p;
            }
        };
        self.later_loops(&start, s0, period, steps, probes_a, probes_b, hit)
    }

    /// The exact tracer's first loop: closed-form segments (Kajari et al. 2009; formulary §2
    /// carried by the isometries of §3), then the same loop reuse as the numeric tracer,
    /// with the period known exactly.
    #[allow(clippy::too_many_arguments)]
    fn trace_exact(
        &self,
        start: &GeodesicState,
        k: spacetime::FourVector,
        sys: GeodesicSystem<Metric>,
        s0: [f64; STATE],
        steps: &mut Vec<LazyStep>,
        probes_a: &mut Vec<Measured>,
        probes_b: &mut Vec<Measured>,
        hit: &mut Option<HitPoint>,
    ) -> PixelRecord {
        let Some(a) = self.metric.godel_a() else {
            return PixelRecord::miss(RayStatus::Failed);
        };
        let Some(geo) = ExactGeodesic::new(a, self.observer, k) else {
            return PixelRecord::miss(RayStatus::Failed);
        };
        let l_ret = geo.origin.return_parameter();
        for i in 0..EXACT_SEGMENTS {
            let (l0, l1) = (
                l_ret * i as f64 / EXACT_SEGMENTS as f64,
                l_ret * (i + 1) as f64 / EXACT_SEGMENTS as f64,
            );
            let y0 = steps.last().map_or(s0, |d| d.y1);
            steps.push(LazyStep::exact(geo, sys, l0, y0, l1));
            let d = steps.last().expect("just pushed");
            match self.scan(d, Shift::default(), l0, l1, probes_a, probes_b) {
                Ok(Some(h)) => return self.record(start, d, Shift::default(), h, hit),
                Ok(None) => {}
                Err(OutOfWork) => return PixelRecord::miss(RayStatus::WorkLimit),
            }
            if d.y1[0] < self.t_bound {
                return PixelRecord::miss(RayStatus::Escaped);
            }
            std::mem::swap(probes_a, probes_b);
        }
        let end = steps.last().expect("segments").y1;
        let period = Shift {
            dt: end[0] - s0[0],
            dz: end[3] - s0[3],
            dl: l_ret,
        };
        self.later_loops(start, s0, period, steps, probes_a, probes_b, hit)
    }

    /// Later loops: the stored first loop, shifted by whole periods.
    #[allow(clippy::too_many_arguments)]
    fn later_loops(
        &self,
        start: &GeodesicState,
        s0: [f64; STATE],
        period: Shift,
        steps: &[LazyStep],
        probes_a: &mut Vec<Measured>,
        probes_b: &mut Vec<Measured>,
        hit: &mut Option<HitPoint>,
    ) -> PixelRecord {
        if !(period.dt < 0.0) {
            return PixelRecord::miss(RayStatus::Failed); // a backward ray must go to the past
        }
        let loop_box = loop_bounds(steps);
        // Scene validation keeps max_past within MAX_RAY_LOOPS loops of the shortest period;
        // the bound here holds whatever the period of this ray turned out to be.
        for k in 1..=scene::MAX_RAY_LOOPS {
            let shift = period.times(k as f64);
            // Skip a loop that comes near no object (boxes in coordinates, at its times).
            let (t_hi, t_lo) = (s0[0] + shift.dt, s0[0] + shift.dt + period.dt);
            if t_hi < self.t_bound {
                return PixelRecord::miss(RayStatus::Escaped);
            }
            let here = loop_box.shifted_z(shift.dz);
            if !self
                .targets
                .iter()
                .any(|t| t.bounds(&self.metric, t_lo, t_hi).intersects(&here))
            {
                continue;
            }
            let first = shift.apply(steps[0].state_at(steps[0].lambda0));
            self.probe_all(&first, shift.dl, probes_a);
            for (i, d) in steps.iter().enumerate() {
                let hi = if i + 1 == steps.len() {
                    period.dl
                } else {
                    d.lambda1()
                };
                match self.scan(d, shift, d.lambda0, hi, probes_a, probes_b) {
                    Ok(Some(h)) => return self.record(start, d, shift, h, hit),
                    Ok(None) => {}
                    Err(OutOfWork) => return PixelRecord::miss(RayStatus::WorkLimit),
                }
                if d.y1[0] + shift.dt < self.t_bound {
                    return PixelRecord::miss(RayStatus::Escaped);
                }
                std::mem::swap(probes_a, probes_b);
            }
        }
        PixelRecord::miss(RayStatus::WorkLimit)
    }

    pub(crate) fn probe_all(&self, s: &GeodesicState, at: f64, out: &mut [Measured]) {
        for (t, o) in self.targets.iter().zip(out.iter_mut()) {
            *o = Measured {
                probe: t.probe(&self.metric, s, f64::NAN),
                at,
            };
        }
    }

    /// The earliest-λ surface crossing of any object within [lo, hi] of step `d` (moved by
    /// `shift`): an entry, or the exit of a ray that started inside (see
    /// [`Target::crossed`]). Fills `end` with the probes at `hi`; `start` holds those at `lo`.
    pub(crate) fn scan(
        &self,
        d: &LazyStep,
        shift: Shift,
        lo: f64,
        hi: f64,
        start: &[Measured],
        end: &mut [Measured],
    ) -> Result<Option<Hit>, OutOfWork> {
        let (lo_abs, hi_abs) = (lo + shift.dl, hi + shift.dl);
        let mut s_hi = None;
        let mut best: Option<Hit> = None;
        for (i, t) in self.targets.iter().enumerate() {
            let m = start[i];
            let p = m.probe;
            // Clearance from the surface, on either side of it.
            let clear = p.f.abs();
            if t.vouches_for_spans()
                && clear.is_finite()
                && hi_abs < m.at + (clear / p.rate).min(MAX_SKIP)
            {
                end[i] = m; // provably no crossing of this object within [lo, hi]
                continue;
            }
            // A probe taken before lo still bounds |f| at lo from below (same side).
            let pa = Probe {
                f: p.f - p.f.signum() * p.rate * (lo_abs - m.at),
                ..p
            };
            let s_hi = *s_hi.get_or_insert_with(|| shift.apply(d.state_at(hi)));
            let pb = t.probe(&self.metric, &s_hi, pa.tau);
            end[i] = Measured {
                probe: pb,
                at: hi_abs,
            };
            let limit = best.as_ref().map_or(hi, |b| b.lambda);
            if let Some((l, tau)) =
                self.search(t, d, shift, lo, limit.min(hi), pa, pb, SEARCH_PROBES)?
            {
                if best.as_ref().map_or(true, |b| l < b.lambda) {
                    best = Some(Hit {
                        target: i,
                        lambda: l,
                        tau,
                    });
                }
            }
        }
        Ok(best)
    }

    /// Bisection for the first surface crossing of `t` on [a, b]: depth first, the earlier
    /// half first, spans excluded by the rate bound dropped. At most `budget` probes (else
    /// [`OutOfWork`]) and [`SEARCH_DEPTH`] halvings.
    #[allow(clippy::too_many_arguments)]
    fn search(
        &self,
        t: &Target,
        d: &LazyStep,
        shift: Shift,
        a: f64,
        b: f64,
        pa: Probe,
        pb: Probe,
        budget: u32,
    ) -> Result<Option<(f64, f64)>, OutOfWork> {
        // Each halving pops one span and pushes two, so at most SEARCH_DEPTH + 1 are open.
        let mut open = [(a, b, pa, pb, 0u32); SEARCH_DEPTH as usize + 2];
        let mut len = 1;
        let mut probes = 0;
        while len > 0 {
            len -= 1;
            let (a, b, pa, pb, depth) = open[len];
            let finite = pa.f.is_finite() && pb.f.is_finite();
            if b <= a || !(pa.f.is_finite() || pb.f.is_finite()) {
                continue; // the object is not defined over this span (beyond its worldline)
            }
            if finite && Target::crossed(pa.f, pb.f) {
                let f = |l: f64| t.probe(&self.metric, &shift.apply(d.state_at(l)), pa.tau).f;
                let l = refine_root(f, a, b, pa.f, pb.f);
                let s = shift.apply(d.state_at(l));
                if t.accepts(&s) {
                    return Ok(Some((l, t.probe(&self.metric, &s, pa.tau).tau)));
                }
                continue;
            }
            // With one end undefined (no rest-frame match there) nothing can be excluded:
            // halve until both ends are known.
            let rate = pa.rate.max(pb.rate);
            if (finite && Target::excluded(pa.f, pb.f, rate, b - a)) || depth >= SEARCH_DEPTH {
                continue;
            }
            if probes == budget {
                return Err(OutOfWork);
            }
            probes += 1;
            let m = 0.5 * (a + b);
            let pm = t.probe(&self.metric, &shift.apply(d.state_at(m)), pa.tau);
            open[len] = (m, b, pm, pb, depth + 1);
            open[len + 1] = (a, m, pa, pm, depth + 1);
            len += 2;
        }
        Ok(None)
    }

    fn record(
        &self,
        start: &GeodesicState,
        d: &LazyStep,
        shift: Shift,
        h: Hit,
        hit: &mut Option<HitPoint>,
    ) -> PixelRecord {
        let s = shift.apply(d.state_at(h.lambda));
        if s.x.t < self.t_bound {
            return PixelRecord::miss(RayStatus::Escaped);
        }
        let Some(surf) = self.targets[h.target].surface(&self.metric, &s, h.tau) else {
            return PixelRecord::miss(RayStatus::Failed);
        };
        let g = self.frame.e[0].contract(start.p) / surf.emitter_velocity.contract(s.p);
        if !(g > 0.0 && g.is_finite()) {
            // The surface's rest frame could not be matched reliably: never a record with a
            // meaningless frequency shift.
            return PixelRecord::miss(RayStatus::Failed);
        }
        *hit = Some(HitPoint {
            state: s,
            target: h.target,
            tau: h.tau,
        });
        PixelRecord {
            object: h.target as i32,
            status: RayStatus::Hit,
            u: surf.u as f32,
            v: surf.v as f32,
            g: g as f32,
            t_emit: (s.x.t - self.observer.t) as f32,
            x: s.x.x as f32,
            y: s.x.y as f32,
            z: s.x.z as f32,
            lambda: (h.lambda + shift.dl) as f32,
            dir: surf.dir.map(|c| c as f32),
            cos_i: surf.cos_i as f32,
        }
    }
}

/// A coordinate box around a stored loop: step ends, grown by a quarter of the longest
/// chord (an arc of one step, turning by well under a radian, departs from its chord by
/// at most about an eighth of it).
fn loop_bounds(steps: &[LazyStep]) -> Aabb {
    let mut b = Aabb::EMPTY;
    let mut grow: f64 = 0.0;
    for st in steps {
        b.add([st.y0[1], st.y0[2], st.y0[3]]);
        b.add([st.y1[1], st.y1[2], st.y1[3]]);
        let chord = ((st.y1[1] - st.y0[1]).powi(2)
            + (st.y1[2] - st.y0[2]).powi(2)
            + (st.y1[3] - st.y0[3]).powi(2))
        .sqrt();
        grow = grow.max(0.25 * chord);
    }
    b.grown(grow)
}

#[cfg(test)]
mod tests {
    use super::*;
    use spacetime::Godel;

    /// A ray grazing a coordinate sphere within 1e-7 of its radius: ruling a crossing out
    /// takes the bisection many halvings. With a budget of 3 probes it must report
    /// [`OutOfWork`] (the pixel is marked, the search never runs on); with the full budget
    /// it finds no crossing; moved 1 % closer, it finds the crossing.
    #[test]
    fn bisection_stops_at_its_probe_budget() {
        let a = 1.0;
        let metric = Metric::Godel(Godel::new(a));
        let o = Event::new(0.0, 0.0, 0.0, 0.0);
        let frame = metric.static_frame(o);
        let k = frame.vector([-1.0, 1.0, 0.0, 0.0]);
        let geo = ExactGeodesic::new(a, o, k).expect("null ray");
        let dist = |c: [f64; 3], l: f64| {
            let (x, _) = geo.at(l);
            ((x.x - c[0]).powi(2) + (x.y - c[1]).powi(2) + (x.z - c[2]).powi(2)).sqrt()
        };
        let radius = 0.1;
        // Centre beside the ray's point at λ = 0.5, on the side the ray bends away from.
        let (x, v) = geo.at(0.5);
        let side = [-v.y, v.x];
        let norm = side[0].hypot(side[1]);
        let centre = |s: f64, gap: f64| {
            let off = s * radius * (1.0 + gap) / norm;
            [x.x + off * side[0], x.y + off * side[1], 0.0]
        };
        let convex = [1.0, -1.0]
            .into_iter()
            .find(|&s| {
                let c = centre(s, 0.0);
                dist(c, 0.45) > dist(c, 0.5) && dist(c, 0.55) > dist(c, 0.5)
            })
            .expect("one side is convex");
        let outcome = |gap: f64, budget: u32| {
            let target = Target::CoordinateSphere {
                center: centre(convex, gap),
                radius,
            };
            let tracer = Tracer::new(metric, o, frame, vec![target], 30.0, 1e-11, 100_000, true);
            let start = GeodesicState {
                x: o,
                p: metric.lower(o, k),
            };
            let (sys, s0) = GeodesicSystem::new(metric, &start);
            let step = LazyStep::exact(geo, sys, 0.0, s0, 1.0);
            let t = &tracer.targets[0];
            let pa = t.probe(&metric, &start, f64::NAN);
            let pb = t.probe(&metric, &step.state_at(1.0), f64::NAN);
            tracer.search(t, &step, Shift::default(), 0.0, 1.0, pa, pb, budget)
        };
        assert_eq!(outcome(1e-7, 3), Err(OutOfWork));
        assert_eq!(outcome(1e-7, SEARCH_PROBES), Ok(None));
        assert_eq!(outcome(1e-9, SEARCH_PROBES), Ok(None));
        let hit = outcome(-1e-2, SEARCH_PROBES).expect("within budget");
        assert!(hit.is_some_and(|(l, _)| l > 0.3 && l < 0.5), "{hit:?}");
    }
}
