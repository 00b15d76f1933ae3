//! The pixel tracer: one backward light ray per pixel, from the observer into the past,
//! searched for its first surface crossing of any object in space and time
//! (`crate::intersect`). Two ways to follow the ray, with the same search and the same
//! records to f32 rounding:
//!
//! - numeric: DOP853 steps of the geodesic equations (any metric; its first loop in
//!   `tracer/numeric.rs`);
//! - exact: closed-form geodesics carried to the observer's event by an isometry, Gödel's
//!   (docs/physics.md, "Closed forms" and "Isometries") or a Gödel-type member's ("The
//!   Gödel-type family", "The exact tracer in the family"); its first loop in
//!   `tracer/exact.rs`.
//!
//! This file holds what both share: the pixel's ray, later loops, transport and record.
//!
//! Pixel → ray: a pixel looking along the local unit direction n starts the past-directed
//! null ray k = −e₀ + nⁱ eᵢ of the observer's (boosted) frame ([`photon_tangent`]).
//!
//! Gödel loops: every light ray returns to its start's axis and then retraces its loop
//! shifted in t and z only (`crate::segment`). So the first loop is followed once (the
//! numeric one checked to close, position and momentum, by [`AxisWatch`]) and stored; later
//! loops are its copies, each still searched against every object at its own times. This
//! bounds the integration error to one loop, however far into the past a ray is followed.
//! The number of copies is bounded by [`scene::MAX_RAY_LOOPS`]. The same holds for the
//! returning rays of every Gödel-type member (the exact tracer's loops; the numeric tracer
//! integrates the family's rays without reuse).
//!
//! Causal Gödel-type members (m² ≥ 4Ω²): some rays escape to infinity, and returning ones may
//! loop far out. A ray beyond every object that will not come back before the time bound is
//! marked escaped by both tracers (`tracer/escape.rs`); the exact one steps over the far
//! stretch of a loop in one unsearched segment.
//!
//! Objects at rest that a ray provably never comes near (`crate::reject`, one test per ray
//! and object for all its loops) are left out of its search; a ray of the exact tracer that
//! comes near none of the objects is not followed at all (it escapes, as its search would
//! have found). A ball in free fall is left out of each loop from the last λ on where the
//! ray may be within its reach (`crate::falling`, docs/physics.md "Balls in free fall"):
//! only a loop's start probes afresh, so only a loop's end may go unsearched.
//!
//! The record's frequency shift is g = (p·u_obs)/(p·u_emit) ([`frequency_ratio`]); its
//! polarization is the pixel's screen-up carried back to the hit (`crate::polarization`:
//! in closed form for Gödel's exact tracer, integrated with the ray otherwise).

mod escape;
mod exact;
mod numeric;

pub use escape::{EscapeStop, MAX_FAMILY_SEGMENTS};

use crate::falling::LoopWindow;
use crate::intersect::{Crossing, HitPoint, Intersector, OutOfWork, Probes, Want};
use crate::polarization::{self, RayPlace};
use crate::reject::{set_ray, Rejection, NUMERIC_TOLERANCE};
use crate::segment::{loop_bounds, ClosedForm, Segment, Shift};
use datafile::record::{PixelRecord, RayStatus};
use scene::Observer;
use spacetime::measure::frequency_ratio;
use spacetime::{
    photon_tangent, Event, FourVector, GeodesicState, GeodesicSystem, Spacetime, Tetrad,
    TimeDirection, Tolerances,
};

/// Everything a pixel's ray needs, built once per render and shared by all threads.
pub struct Tracer {
    /// The scene's objects, ready to be searched.
    pub objects: Intersector,
    observer: Event,
    frame: Tetrad,
    /// The camera's axes in the observer's frame (for the pixels' screen-up).
    up: [f64; 3],
    forward: [f64; 3],
    /// Rays stop at coordinate time observer.t − max_past.
    t_bound: f64,
    tol: Tolerances,
    max_steps: u64,
    /// Reuse the first loop (Gödel only).
    periodic: bool,
    /// Use the closed-form geodesics instead of the integrator (Gödel and the Gödel-type
    /// family).
    exact: bool,
    /// Where rays of a causal Gödel-type member are done (`tracer/escape.rs`).
    escape: Option<EscapeStop>,
    /// Per object, its whole-ray rejection test (balls at rest and planes, Gödel only; none
    /// where the numeric tracer's tolerance is too loose for its margin).
    rejections: Vec<Option<Rejection>>,
}

/// How a tracer follows rays (from the scene's `[trace]` table).
#[derive(Clone, Copy, Debug)]
pub struct TraceOptions {
    pub max_past: f64,
    pub tolerance: f64,
    pub max_steps: u64,
    pub exact: bool,
}

/// Per-thread buffers, reused from ray to ray (no allocation per ray).
pub struct Scratch {
    segments: Vec<Segment>,
    pub probes: Probes,
    /// The first step size the previous ray's integrator settled on: neighbouring pixels
    /// take nearly the same steps, so the next ray starts there instead of with the
    /// initial-step heuristic (two evaluations and a short first step). Reset per tile.
    first_step: Option<f64>,
}

impl Scratch {
    /// Forget the previous ray's step size (at the start of a tile).
    pub fn reset_first_step(&mut self) {
        self.first_step = None;
    }
}

/// What a pixel's ray found: its record and, for a hit, the hit at full precision.
pub struct Traced {
    pub record: PixelRecord,
    pub hit: Option<HitPoint>,
}

/// How a stretch of the ray ended.
enum End {
    /// A crossing in segment `segment` of the stored ones, moved by `shift`: `loops` whole
    /// loops of parameter `period` each (0 and 0 in the first loop).
    Hit {
        segment: usize,
        shift: Shift,
        loops: u64,
        period: f64,
        crossing: Crossing,
    },
    Miss(RayStatus),
}

/// The first loop either ends the ray or closes with a period (the shift to the next loop).
enum FirstLoop {
    Ended(End),
    Closed(Shift),
}

impl Tracer {
    /// The tracer of the pixels of `observer`'s camera among `objects`.
    pub fn new(objects: Intersector, observer: &Observer, opt: TraceOptions) -> Tracer {
        let frame = objects
            .metric
            .observer_frame(observer.event, observer.velocity);
        let observer_axes = (observer.up, observer.forward);
        let observer = observer.event;
        let godel = objects.metric.godel_a().is_some();
        let exact = opt.exact && (godel || objects.metric.godel_type().is_some());
        let t_bound = observer.t - opt.max_past;
        let escape = EscapeStop::new(&objects.metric, observer, &objects.targets, t_bound);
        let rejections = objects
            .targets
            .iter()
            .map(|t| {
                let a = objects.metric.godel_a()?;
                let sure = exact || opt.tolerance <= NUMERIC_TOLERANCE;
                Rejection::new(a, observer, t).filter(|_| sure)
            })
            .collect();
        Tracer {
            objects,
            observer,
            frame,
            up: observer_axes.0,
            forward: observer_axes.1,
            t_bound,
            tol: Tolerances {
                rtol: opt.tolerance,
                atol: opt.tolerance,
                ..Tolerances::default()
            },
            max_steps: opt.max_steps,
            periodic: godel,
            exact,
            escape,
            rejections,
        }
    }

    /// The same tracer without whole-ray rejection: every ray searches every object (for
    /// tests and benchmarks that compare the two).
    pub fn without_rejection(mut self) -> Tracer {
        self.rejections.iter_mut().for_each(|b| *b = None);
        self
    }

    /// The same tracer without the chord exclusion ([`crate::chord`]; for tests that
    /// compare the two).
    pub fn without_chords(mut self) -> Tracer {
        self.objects.chords = false;
        self
    }

    /// The same tracer with the reach of its balls in free fall scaled by `factor`
    /// ([`crate::falling::FallingBall::scaled`]; for tests that must see an over-eager bound
    /// change records).
    pub fn with_falling_reach_scaled(mut self, factor: f64) -> Tracer {
        for r in &mut self.rejections {
            if let Some(Rejection::Falling(f)) = r {
                *f = f.clone().scaled(factor);
            }
        }
        self
    }

    /// How far into the past rays are followed (coordinate time).
    pub fn max_past(&self) -> f64 {
        self.observer.t - self.t_bound
    }

    /// Buffers for one thread.
    pub fn scratch(&self) -> Scratch {
        Scratch {
            segments: Vec::new(),
            probes: self.objects.probes(),
            first_step: None,
        }
    }

    /// Traces the pixel looking along the local unit direction `n`.
    pub fn trace(&self, n: [f64; 3], scratch: &mut Scratch) -> Traced {
        let k = photon_tangent(&self.frame, n, TimeDirection::Past);
        let start = GeodesicState {
            x: self.observer,
            p: self.objects.metric.lower(self.observer, k),
        };
        let Scratch {
            segments,
            probes,
            first_step,
        } = scratch;
        segments.clear();
        // The closed form: the exact tracer's ray, and the numeric one's rejection tests and
        // escape stop.
        let geo =
            (self.exact || self.escape.is_some() || self.rejections.iter().any(Option::is_some))
                .then(|| ClosedForm::new(&self.objects.metric, self.observer, k))
                .flatten();
        set_ray(
            &self.rejections,
            geo.as_ref().and_then(ClosedForm::godel).map(|g| &g.origin),
            0.0,
            f64::INFINITY,
            self.exact,
            probes,
        );
        if !self.exact {
            // A numeric first loop that does not close runs on without fresh probes: it
            // may leave a ball in free fall out of its end only if no later loop needs it.
            for (i, loops) in probes.loops.iter_mut().enumerate() {
                if probes.by_loop[i] && loops.len() > 1 {
                    loops[0] = LoopWindow::ALL;
                }
            }
        }
        probes.activate(0, 0.0, 0.0, 0.0);
        if self.exact && !probes.on_ray.iter().any(|&on| on) {
            if let Some(status) = self.escape_unsearched(&start, geo) {
                return Traced {
                    record: PixelRecord::miss(status),
                    hit: None,
                };
            }
        }
        self.objects.probe_all(&start, 0.0, probes);
        let first = if self.exact {
            self.first_loop_exact(&start, geo, segments, probes)
        } else {
            let stop = self
                .escape
                .as_ref()
                .zip(geo.as_ref().and_then(ClosedForm::member));
            self.first_loop_numeric(&start, segments, probes, first_step, stop)
        };
        let end = match first {
            FirstLoop::Ended(end) => end,
            FirstLoop::Closed(period) => self.later_loops(&start, period, segments, probes),
        };
        match end {
            End::Hit {
                segment,
                shift,
                loops,
                period,
                crossing,
            } => {
                let f = polarization::screen(&self.frame, self.up, self.forward, n);
                let place = RayPlace {
                    lambda: crossing.lambda,
                    loops,
                    period,
                };
                let f = self.transport(&start, geo.as_ref(), f, place, shift);
                self.record(&start, &segments[segment], shift, crossing, f)
            }
            End::Miss(status) => Traced {
                record: PixelRecord::miss(status),
                hit: None,
            },
        }
    }

    /// Scans the latest segment of the first loop (not shifted) over [lo, hi]: the ray's
    /// end when an object is hit there or the search runs out of work, else `None`.
    fn scan_first_loop(
        &self,
        segments: &[Segment],
        lo: f64,
        hi: f64,
        probes: &mut Probes,
    ) -> Option<End> {
        let d = segments.last().expect("a segment");
        match self
            .objects
            .scan(d, Shift::default(), (lo, hi), Want::First, probes)
        {
            Ok(Some(crossing)) => Some(End::Hit {
                segment: segments.len() - 1,
                shift: Shift::default(),
                loops: 0,
                period: 0.0,
                crossing,
            }),
            Ok(None) => None,
            Err(OutOfWork) => Some(End::Miss(RayStatus::WorkLimit)),
        }
    }

    /// The status of an exact ray that searches no object, if it surely escapes: its search
    /// would find nothing, and it reaches the time bound within the loop limit (the period
    /// computed as the first loop computes it), or never returns to its axis (a Gödel-type
    /// member's escaping ray). None: trace it in full.
    fn escape_unsearched(
        &self,
        start: &GeodesicState,
        geo: Option<ClosedForm>,
    ) -> Option<RayStatus> {
        let geo = geo?;
        let (sys, s0) = GeodesicSystem::new(self.objects.metric, start);
        let Some(l_ret) = geo.return_parameter() else {
            return Some(RayStatus::Escaped);
        };
        let end = Segment::exact(geo, sys, 0.0, s0, l_ret).y1;
        let dt = end[0] - s0[0];
        let last = start.x.t + scene::MAX_RAY_LOOPS as f64 * dt;
        (dt < 0.0 && last < self.t_bound).then_some(RayStatus::Escaped)
    }

    /// Later loops: the stored first loop, shifted by whole periods.
    fn later_loops(
        &self,
        start: &GeodesicState,
        period: Shift,
        segments: &[Segment],
        probes: &mut Probes,
    ) -> End {
        if !(period.dt < 0.0) {
            return End::Miss(RayStatus::Failed); // a backward ray must go to the past
        }
        let t0 = start.x.t;
        let loop_box = loop_bounds(segments);
        // Scene validation keeps max_past within MAX_RAY_LOOPS loops of the shortest period;
        // the bound here holds whatever the period of this ray turned out to be.
        for loops in 1..=scene::MAX_RAY_LOOPS {
            let shift = period.times(loops as f64);
            // Skip a loop that comes near no object (boxes in coordinates, at its times).
            let (t_hi, t_lo) = (t0 + shift.dt, t0 + shift.dt + period.dt);
            if t_hi < self.t_bound {
                return End::Miss(RayStatus::Escaped);
            }
            let here = loop_box.shifted_z(shift.dz);
            let metric = &self.objects.metric;
            // Objects this loop searches at all (`crate::reject`), and whose box it meets.
            let k = loops as usize;
            if !probes.activate(k, shift.dl, 0.0, period.dl)
                || !(self.objects.targets.iter().zip(&probes.active))
                    .any(|(t, &on)| on && t.bounds(metric, t_lo, t_hi).intersects(&here))
            {
                continue;
            }
            let first = shift.apply(segments[0].state_at(segments[0].lambda0));
            self.objects.probe_all(&first, shift.dl, probes);
            for (i, d) in segments.iter().enumerate() {
                let hi = if i + 1 == segments.len() {
                    period.dl
                } else {
                    d.lambda1()
                };
                probes.activate(k, shift.dl, d.lambda0, hi);
                if d.far {
                    // Beyond every object throughout: probe afresh at its end (never the
                    // loop's last segment).
                    let end = shift.apply(d.state_at(hi));
                    if end.x.t < self.t_bound {
                        return End::Miss(RayStatus::Escaped);
                    }
                    self.objects.probe_all(&end, hi + shift.dl, probes);
                    continue;
                }
                match self
                    .objects
                    .scan(d, shift, (d.lambda0, hi), Want::First, probes)
                {
                    Ok(Some(crossing)) => {
                        return End::Hit {
                            segment: i,
                            shift,
                            loops,
                            period: period.dl,
                            crossing,
                        }
                    }
                    Ok(None) => {}
                    Err(OutOfWork) => return End::Miss(RayStatus::WorkLimit),
                }
                if d.y1[0] + shift.dt < self.t_bound {
                    return End::Miss(RayStatus::Escaped);
                }
                probes.advance();
            }
        }
        End::Miss(RayStatus::WorkLimit)
    }

    /// The pixel's screen-up and screen-right, transported along the pixel's ray to the hit at
    /// `place` (moved by `shift`): in closed form along Gödel's exact ray `geo`, else
    /// integrated with the ray (`None` if that fails; the Gödel-type family has no closed-form
    /// transport yet).
    fn transport(
        &self,
        start: &GeodesicState,
        geo: Option<&ClosedForm>,
        screen: [FourVector; 2],
        place: RayPlace,
        shift: Shift,
    ) -> Option<[FourVector; 2]> {
        match geo.and_then(ClosedForm::godel).filter(|_| self.exact) {
            Some(geo) => Some(polarization::exact(
                geo,
                self.observer,
                screen,
                place.lambda + shift.dl,
            )),
            None => polarization::integrated(
                self.objects.metric,
                start,
                screen,
                place,
                self.tol,
                transport_steps(self.max_steps),
            ),
        }
    }

    /// The record of a crossing found in segment `d` moved by `shift`, with the pixel's
    /// screen-up and screen-right `screen` transported to it (`None`: the transport failed).
    fn record(
        &self,
        start: &GeodesicState,
        d: &Segment,
        shift: Shift,
        h: Crossing,
        screen: Option<[FourVector; 2]>,
    ) -> Traced {
        let miss = |status| Traced {
            record: PixelRecord::miss(status),
            hit: None,
        };
        let s = shift.apply(d.state_at(h.lambda));
        if s.x.t < self.t_bound {
            return miss(RayStatus::Escaped);
        }
        let metric = &self.objects.metric;
        let Some(screen) = screen else {
            return miss(RayStatus::Failed);
        };
        let Some(surf) = self.objects.targets[h.target].surface(metric, &s, h.tau, screen) else {
            return miss(RayStatus::Failed);
        };
        let g = frequency_ratio(self.frame.e[0], start.p, surf.emitter_velocity, s.p);
        if !(g > 0.0 && g.is_finite()) {
            // The surface's rest frame could not be matched reliably: never a record with a
            // meaningless frequency shift.
            return miss(RayStatus::Failed);
        }
        Traced {
            record: PixelRecord {
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
                view: [0.0; 3],
                pol: surf.pol.map(|c| c as f32),
            },
            hit: Some(HitPoint {
                state: s,
                target: h.target,
                tau: h.tau,
            }),
        }
    }
}

/// The step budget of the propagator integrated along a ray the numeric tracer traced within
/// `max_steps`: the same ray with 16 more components in the error norm may take a few more
/// steps (rays that hit the ball around the observer within a budget of 1 or 2 steps were
/// marked failed), so four times the budget and 64 steps more, still fixed in advance.
fn transport_steps(max_steps: u64) -> u64 {
    max_steps.saturating_mul(4).saturating_add(64)
}
