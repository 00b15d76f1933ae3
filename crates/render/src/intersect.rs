//! The intersection search, shared by pixel rays and shadow rays: where along a ray's
//! segments it first crosses the surface of any object, in space and time.
//!
//! Each object ([`Target`]) gives a signed distance f (≤ 0 inside, on the surface counting
//! as inside) and a bound on |df/dλ|. A segment is scanned object by object: a probe showing
//! clearance |f| proves that no crossing happens within |f|/rate (conservative advancement,
//! for objects whose bound holds over several steps); otherwise the span is bisected, the
//! earlier half first, dropping spans where |f(a)| + |f(b)| > rate·(b − a) with both ends on
//! one side (the ray cannot reach the surface and come back), or where a local ball's
//! rest-frame chord passes clear of it ([`crate::chord`]). Any change of side is a hit,
//! so a ray that starts inside an object sees its inner surface.
//!
//! Every search is bounded: [`SEARCH_DEPTH`] halvings (a resolution limit: a graze closer
//! than that is no crossing) and [`SEARCH_PROBES`] probes, beyond which the search reports
//! [`OutOfWork`] and the caller marks the ray instead of searching on.

use crate::circle::Stretches;
use crate::falling::LoopWindow;
use crate::segment::{Segment, Shift};
use crate::target::{Probe, Target};
use spacetime::{refine_root, GeodesicState, Metric};

/// Conservative advancement: a probe showing clearance |f| proves that the ray crosses no
/// surface of that object before λ + |f|/rate. Capped, because the rate bound is made for
/// spans of a few steps.
const MAX_SKIP: f64 = 1.0;

/// Halvings of a span before the bisection accepts it as a graze without a crossing (a
/// span ~1e-9 of a step): a resolution limit, not a failure.
const SEARCH_DEPTH: u32 = 30;

/// Probes one bisection may spend on one object over one span. The rate bound excludes
/// spans linearly while a graze approaches the surface quadratically, so ruling out a
/// crossing costs ~rate/√(f''·gap) probes: measured (unit test below) 256 for a graze 1e-3
/// of the radius clear of a coordinate sphere, 16,384 at 1e-7, 65,536 at 1e-9, near the
/// depth limit. So this bound is reached only by rays that stay within ~1e-9 of a surface
/// for a long stretch, which [`SEARCH_DEPTH`] alone would let cost 2^30 probes.
const SEARCH_PROBES: u32 = 1 << 17;

/// A bounded search ran out of work: the ray is marked, never followed on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutOfWork;

/// The objects of a scene in the metric, ready to be searched along rays; shared by all
/// threads.
pub struct Intersector {
    pub metric: Metric,
    pub targets: Vec<Target>,
    /// Whether spans may also be excluded by their rest-frame chord
    /// ([`Target::chord_excludes`]; off only to compare).
    pub chords: bool,
}

/// A probe and the ray parameter (absolute: loop shifts included) where it was taken.
#[derive(Clone, Copy, Debug)]
pub struct Measured {
    probe: Probe,
    at: f64,
}

/// Per-thread buffers: the probes of every object at the start and the end of the segment
/// being scanned (swapped from segment to segment, reused from ray to ray), and which
/// objects the current ray searches at all.
pub struct Probes {
    pub start: Vec<Measured>,
    pub end: Vec<Measured>,
    /// False for an object the ray provably never comes near (`crate::reject`): it is
    /// neither probed nor searched. Set per segment by its caller (all true by default),
    /// from the following.
    pub active: Vec<bool>,
    /// Whether the current ray searches the object at all (`crate::reject::set_ray`).
    pub on_ray: Vec<bool>,
    /// Whether `loops` limits the search of the object (balls in free fall).
    pub by_loop: Vec<bool>,
    /// Per object and loop k of the ray: the stretch of the loop, λ from its start, that
    /// searches it (none, or a loop past the end: not at all).
    pub loops: Vec<Vec<LoopWindow>>,
    /// Per object: the only stretches of the ray (λ from its start) that search it (balls at
    /// rest: `crate::reject::StaticBall::near`); None: all along.
    pub near: Vec<Option<Stretches>>,
    /// Per object: the only stretch of the ray (λ from its start) where it can be crossed
    /// (planes along a closed form: around the one λ where the ray's linear z reaches the
    /// plane, `crate::reject::set_ray`); None: all along.
    pub crossing: Vec<Option<(f64, f64)>>,
    /// The loop of the segment last activated ([`Probes::activate`]).
    segment_loop: usize,
    /// The closed form's λ per loop of the current ray, where its λ is the closed form's (the
    /// exact tracer's rays and the shadow rays; NaN otherwise).
    pub loop_length: f64,
    /// The bisection's open spans (at most SEARCH_DEPTH + 2; reused, not filled per search).
    spans: Vec<Span>,
}

/// An open span of a bisection: [a, b], its end probes and its depth.
type Span = (f64, f64, Probe, Probe, u32);

impl Probes {
    /// The end probes become the next segment's start probes.
    pub fn advance(&mut self) {
        std::mem::swap(&mut self.start, &mut self.end);
    }

    /// Object `i`'s probe in the start buffer, if it was taken at ray parameter `at` (by
    /// [`Intersector::probe_all`] for an active object).
    pub fn start_at(&self, i: usize, at: f64) -> Option<Probe> {
        let m = self.start[i];
        (self.active[i] && m.at == at).then_some(m.probe)
    }

    /// The stretch of loop `k`, λ from its start, that searches object `i`.
    pub fn window(&self, i: usize, k: usize) -> LoopWindow {
        if !self.on_ray[i] {
            LoopWindow::NONE
        } else if !self.by_loop[i] {
            LoopWindow::ALL
        } else {
            self.loops[i].get(k).copied().unwrap_or(LoopWindow::NONE)
        }
    }

    /// Whether the stretch [l0, l1], from the start of loop `k`, meets the window of a loop
    /// for object `i`. A stretch may run on into later loops (a shadow ray's segments, with
    /// `loop_length` known): then it meets each over its part in that loop.
    fn in_loops(&self, i: usize, k: usize, l0: f64, l1: f64) -> bool {
        let len = self.loop_length;
        if !(self.by_loop[i] && len > 0.0 && l1 > len) {
            return self.window(i, k).meets(l0, l1);
        }
        self.across_loops(i, k, l0, l1)
    }

    /// [`Probes::in_loops`] for a stretch that runs on past its loop. Kept out of line: inlined,
    /// its two `floor`s (a library call on baseline x86-64) were hoisted out of
    /// [`Probes::activate`]'s loop over the objects and paid on every activation.
    #[inline(never)]
    fn across_loops(&self, i: usize, k: usize, l0: f64, l1: f64) -> bool {
        let len = self.loop_length;
        let (first, last) = ((l0 / len).floor().max(0.0), (l1 / len).floor());
        if !(last.is_finite() && first <= last) {
            return true; // unsure
        }
        let loops = self.loops[i].len();
        let (first, last) = (first as usize, (last as usize).min(loops));
        (first..=last).any(|j| {
            let shift = j as f64 * len;
            let from = if j == first { l0 - shift } else { 0.0 };
            let to = if j == last { l1 - shift } else { len };
            self.window(i, k + j).meets(from, to)
        })
    }

    /// The part of [l0, l1] (λ from the start of the segment's loop) that object `i`'s window
    /// in the loop meets (balls in free fall, a segment within one loop; else [l0, l1]).
    fn part(&self, i: usize, l0: f64, l1: f64) -> (f64, f64) {
        let len = self.loop_length;
        if !self.by_loop[i] || len > 0.0 && l1 > len {
            return (l0, l1);
        }
        let w = self.window(i, self.segment_loop);
        let (lo, hi) = (l0.max(w.from), l1.min(w.until));
        if lo <= hi {
            (lo, hi)
        } else {
            (l0, l1)
        }
    }

    /// The least and the greatest λ (from the ray's start, a ray whose segments activate from
    /// loop 0: the shadow rays) at which [`Probes::activate`] may search any object: outside
    /// [first, last] it searches none. From each object's own limits (its near stretches'
    /// heights, its crossing stretch, its loops' windows), each widened far above the
    /// rounding of `activate`'s own comparisons; (−∞, ∞) where an object has none.
    pub fn reach(&self) -> (f64, f64) {
        let len = self.loop_length;
        let (mut first, mut last) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..self.on_ray.len() {
            if !self.on_ray[i] {
                continue;
            }
            let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
            if let Some(n) = &self.near[i] {
                if n.lo <= n.hi {
                    (lo, hi) = (lo.max(n.lo), hi.min(n.hi));
                }
            }
            if let Some((c0, c1)) = self.crossing[i] {
                if c0 <= c1 {
                    (lo, hi) = (lo.max(c0), hi.min(c1));
                }
            }
            if self.by_loop[i] && len > 0.0 {
                // Loop j's window lies at j·len + [from, until].
                let (w0, w1) = self.loops[i].iter().enumerate().fold(
                    (f64::INFINITY, f64::NEG_INFINITY),
                    |(w0, w1), (j, w)| {
                        if w.from <= w.until {
                            let shift = j as f64 * len;
                            (w0.min(shift + w.from), w1.max(shift + w.until))
                        } else {
                            (w0, w1)
                        }
                    },
                );
                (lo, hi) = (lo.max(w0), hi.min(w1));
            }
            if !(lo <= hi) {
                continue; // never searched
            }
            // Each end widened on its own (an open end stays open, and does not open the other).
            let scale = if len > 0.0 { len } else { 0.0 } + 1.0;
            let (lo, hi) = (
                lo - 1e-9 * (lo.abs() + scale),
                hi + 1e-9 * (hi.abs() + scale),
            );
            (first, last) = (first.min(lo), last.max(hi));
        }
        (first, last)
    }

    /// Sets `active` for the stretch [l0, l1] of loop `k`, which starts at λ = `dl` (l0 and
    /// l1 from the loop's start): an object is searched where the stretch meets its window
    /// in the loop (one stretch a loop; a later loop probes afresh), its `near` ones and its
    /// `crossing` stretch. An
    /// object not searched just before starts from a fresh probe ([`Intersector::scan`]).
    /// Whether any is searched.
    pub fn activate(&mut self, k: usize, dl: f64, l0: f64, l1: f64) -> bool {
        self.segment_loop = k;
        let mut any = false;
        for i in 0..self.active.len() {
            let on = self.in_loops(i, k, l0, l1)
                && self.near[i].is_none_or(|n| n.meets(dl + l0, dl + l1))
                && self.crossing[i].is_none_or(|(lo, hi)| dl + l1 >= lo && dl + l0 <= hi);
            if on && !self.active[i] {
                self.start[i].at = f64::NAN;
            }
            self.active[i] = on;
            any |= on;
        }
        any
    }
}

/// What a scan looks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Want {
    /// The earliest crossing, refined to full precision (a pixel ray's hit).
    First,
    /// Whether there is any (a shadow ray's occlusion): the first crossing found ends the
    /// scan, and one of an object that takes every crossing ([`Target::accepts_any`]) is not
    /// refined, its λ only bracketed (the end of the span found to hold it) and τ NaN.
    Any,
}

/// The first crossing found in a scan: the object, the ray parameter (relative to the
/// segment's loop) and the matched proper time on the object's worldline.
pub struct Crossing {
    pub target: usize,
    pub lambda: f64,
    pub tau: f64,
}

/// A pixel ray's hit at full precision: the surface event (with the backward ray's
/// momentum there), the object and the matched proper time on its worldline.
#[derive(Clone, Copy, Debug)]
pub struct HitPoint {
    pub state: GeodesicState,
    pub target: usize,
    pub tau: f64,
}

impl Intersector {
    /// The objects `targets` in `metric`, searched with every exclusion.
    pub fn new(metric: Metric, targets: Vec<Target>) -> Intersector {
        Intersector {
            metric,
            targets,
            chords: true,
        }
    }

    /// Probe buffers for one thread.
    pub fn probes(&self) -> Probes {
        let none = Measured {
            probe: Probe {
                f: 0.0,
                rate: 0.0,
                tau: f64::NAN,
                xi: [f64::NAN; 3],
                energy: f64::NAN,
            },
            at: 0.0,
        };
        Probes {
            start: vec![none; self.targets.len()],
            end: vec![none; self.targets.len()],
            active: vec![true; self.targets.len()],
            on_ray: vec![true; self.targets.len()],
            by_loop: vec![false; self.targets.len()],
            loops: vec![Vec::new(); self.targets.len()],
            near: vec![None; self.targets.len()],
            crossing: vec![None; self.targets.len()],
            segment_loop: 0,
            loop_length: f64::NAN,
            spans: Vec::with_capacity(SEARCH_DEPTH as usize + 2),
        }
    }

    /// Probes every active object at the ray state `s` (taken at absolute parameter `at`)
    /// into the start buffer.
    pub fn probe_all(&self, s: &GeodesicState, at: f64, probes: &mut Probes) {
        for ((t, o), &on) in self
            .targets
            .iter()
            .zip(&mut probes.start)
            .zip(&probes.active)
        {
            if !on {
                continue;
            }
            *o = Measured {
                probe: t.probe(&self.metric, s, f64::NAN),
                at,
            };
        }
    }

    /// The earliest-λ surface crossing of any active object within [lo, hi] of segment `d` (moved
    /// by `shift`): an entry, or the exit of a ray that started inside (see
    /// [`Target::crossed`]); with [`Want::Any`] the first found. Reads the probes at `lo`
    /// from `probes.start` and leaves those at `hi` in `probes.end` (not all of them when a
    /// [`Want::Any`] scan ends early).
    pub fn scan(
        &self,
        d: &Segment,
        shift: Shift,
        (lo, hi): (f64, f64),
        want: Want,
        probes: &mut Probes,
    ) -> Result<Option<Crossing>, OutOfWork> {
        let (seg_lo, seg_hi) = (lo, hi);
        let mut s_hi = None;
        let mut best: Option<Crossing> = None;
        for (i, t) in self.targets.iter().enumerate() {
            if !probes.active[i] {
                continue;
            }
            // Only the part of the segment that the object's window meets.
            let (lo, hi) = probes.part(i, lo, hi);
            let lo_abs = lo + shift.dl;
            let mut m = probes.start[i];
            if m.at.is_nan() || m.at < lo_abs && lo > seg_lo {
                // Not searched just before lo (or the search starts within the segment): a
                // fresh probe there.
                m = Measured {
                    probe: t.probe(&self.metric, &shift.apply(d.state_at(lo)), f64::NAN),
                    at: lo_abs,
                };
            }
            let p = m.probe;
            // Clearance from the surface, on either side of it.
            let clear = p.f.abs();
            if t.vouches_for_spans()
                && clear.is_finite()
                && hi + shift.dl < m.at + (clear / p.rate).min(MAX_SKIP)
            {
                // Provably no crossing of this object within [lo, hi]: its end probe is this one,
                // unless its part ends before the segment (see below).
                probes.end[i] = Measured {
                    at: if hi < seg_hi { f64::NAN } else { m.at },
                    ..m
                };
                continue;
            }
            // A probe taken before lo still bounds |f| at lo from below (same side).
            // (Its rest-frame coordinates are those of its own place, not of lo's.)
            let pa = if m.at == lo_abs {
                p
            } else {
                Probe {
                    f: p.f - p.f.signum() * p.rate * (lo_abs - m.at),
                    xi: [f64::NAN; 3],
                    ..p
                }
            };
            // Searched only up to another object's earlier crossing in this segment (which
            // ends the ray's search): its end probe there, where its span ends. (Its value at
            // hi would bound nothing over the shorter span: a crossing in front could be
            // excluded.)
            let end = best.as_ref().map_or(hi, |b| b.lambda.min(hi));
            let s_end = if end < seg_hi {
                shift.apply(d.state_at(end))
            } else {
                *s_hi.get_or_insert_with(|| shift.apply(d.state_at(seg_hi)))
            };
            let pb = t.probe(&self.metric, &s_end, pa.tau);
            // Where the object's part ends before the segment does, the next segment's
            // search of it (its next stretch) starts from a fresh probe: the bound that a probe
            // at `end` gives there, further on, could have crossed zero.
            probes.end[i] = Measured {
                probe: pb,
                at: if hi < seg_hi {
                    f64::NAN
                } else {
                    end + shift.dl
                },
            };
            // A plane's f is z − height, linear in λ along a closed form (z = z0 + p_z λ):
            // where its end values are the measured ones, no bisection is needed.
            let linear = t.is_plane() && d.is_closed_form() && m.at == lo_abs;
            if let Some((l, tau)) = self.search(
                t,
                d,
                shift,
                (lo, end),
                (pa, pb),
                linear,
                want,
                SEARCH_PROBES,
                &mut probes.spans,
            )? {
                let found = Crossing {
                    target: i,
                    lambda: l,
                    tau,
                };
                if want == Want::Any {
                    return Ok(Some(found));
                }
                if best.as_ref().is_none_or(|b| l < b.lambda) {
                    best = Some(found);
                }
            }
        }
        Ok(best)
    }

    /// Bisection for the first surface crossing of `t` on [a, b]: depth first, the earlier
    /// half first, spans excluded by the rate bound dropped. At most `budget` probes (else
    /// [`OutOfWork`]) and [`SEARCH_DEPTH`] halvings. With [`Want::Any`], a crossing of an
    /// object that takes every crossing is reported unrefined (see [`Want`]). `linear`: f is
    /// linear in λ on [a, b] (a plane along a closed form, `pa` and `pb` measured at a and b),
    /// so a span crosses exactly where its ends change side, at the root of the line through
    /// them (docs/physics.md, "The intersection search").
    #[allow(clippy::too_many_arguments)]
    fn search(
        &self,
        t: &Target,
        d: &Segment,
        shift: Shift,
        (a, b): (f64, f64),
        (pa, pb): (Probe, Probe),
        linear: bool,
        want: Want,
        budget: u32,
        open: &mut Vec<Span>,
    ) -> Result<Option<(f64, f64)>, OutOfWork> {
        // Each halving pops one span and pushes two, so at most SEARCH_DEPTH + 1 are open.
        open.clear();
        open.push((a, b, pa, pb, 0u32));
        let mut probes = 0;
        while let Some((a, b, pa, pb, depth)) = open.pop() {
            let finite = pa.f.is_finite() && pb.f.is_finite();
            if b <= a || !(pa.f.is_finite() || pb.f.is_finite()) {
                continue; // the object is not defined over this span (beyond its worldline)
            }
            if finite && Target::crossed(pa.f, pb.f) {
                if want == Want::Any && t.accepts_any() {
                    return Ok(Some((b, f64::NAN)));
                }
                // The refinement's last probe, which is usually the one at its root.
                let last = std::cell::Cell::new((f64::NAN, f64::NAN));
                let l = if linear {
                    a + (b - a) * (pa.f / (pa.f - pb.f)).clamp(0.0, 1.0)
                } else {
                    let f = |l: f64| {
                        let p = t.probe(&self.metric, &shift.apply(d.state_at(l)), pa.tau);
                        last.set((l, p.tau));
                        p.f
                    };
                    refine_root(f, a, b, pa.f, pb.f)
                };
                let s = shift.apply(d.state_at(l));
                if t.accepts(&s) {
                    let tau = match last.get() {
                        (at, tau) if at == l => tau,
                        _ => t.probe(&self.metric, &s, pa.tau).tau,
                    };
                    return Ok(Some((l, tau)));
                }
                continue;
            }
            // With one end undefined (no rest-frame match there) nothing can be excluded:
            // halve until both ends are known.
            let rate = pa.rate.max(pb.rate);
            let excluded = finite
                && (linear
                    || Target::excluded(pa.f, pb.f, rate, b - a)
                    || self.chords && t.chord_excludes(&self.metric, &pa, &pb, b - a));
            if excluded || depth >= SEARCH_DEPTH {
                continue;
            }
            if probes == budget {
                return Err(OutOfWork);
            }
            probes += 1;
            let m = 0.5 * (a + b);
            // The match at the middle starts from the mean of the ends' (a secant step or
            // two closer than either end's alone).
            let seed = if pb.tau.is_finite() {
                0.5 * (pa.tau + pb.tau)
            } else {
                pa.tau
            };
            let pm = t.probe(&self.metric, &shift.apply(d.state_at(m)), seed);
            open.push((m, b, pm, pb, depth + 1));
            open.push((a, m, pa, pm, depth + 1));
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::segment::ClosedForm;
    use spacetime::TimeDirection;
    use spacetime::{
        photon_tangent, Event, ExactGeodesic, GeodesicSystem, Godel, GodelType, Spacetime,
    };

    /// The past-directed light ray from `o` in the static direction `n`: its start and its
    /// closed form's segment [0, 1].
    fn unit_segment(metric: Metric, o: Event, n: [f64; 3]) -> (GeodesicState, Segment) {
        let k = photon_tangent(&metric.static_frame(o), n, TimeDirection::Past);
        let geo = ClosedForm::new(&metric, o, k).expect("a closed form");
        let start = GeodesicState {
            x: o,
            p: metric.lower(o, k),
        };
        let (sys, s0) = GeodesicSystem::new(metric, &start);
        (start, Segment::exact(geo, sys, 0.0, s0, 1.0))
    }

    /// The search of `target` alone over the segment [0, 1] that starts at `start`, from
    /// probes at its ends.
    fn search_alone(
        metric: Metric,
        target: Target,
        start: &GeodesicState,
        seg: &Segment,
        linear: bool,
        budget: u32,
    ) -> Result<Option<(f64, f64)>, OutOfWork> {
        let intersector = Intersector::new(metric, vec![target]);
        let t = &intersector.targets[0];
        let pa = t.probe(&metric, start, f64::NAN);
        let pb = t.probe(&metric, &seg.state_at(1.0), f64::NAN);
        let span = (0.0, 1.0);
        let (shift, want) = (Shift::default(), Want::First);
        intersector.search(
            t,
            seg,
            shift,
            span,
            (pa, pb),
            linear,
            want,
            budget,
            &mut Vec::new(),
        )
    }

    /// A ray grazing a coordinate sphere within 1e-7 of its radius: ruling a crossing out
    /// takes the bisection many halvings. With a budget of 3 probes it must report
    /// [`OutOfWork`] (the pixel is marked, the search never runs on); with the full budget
    /// it finds no crossing; moved 1 % closer, it finds the crossing.
    #[test]
    fn bisection_stops_at_its_probe_budget() {
        let a = 1.0;
        let metric = Metric::Godel(Godel::new(a));
        let o = Event::new(0.0, 0.0, 0.0, 0.0);
        let k = photon_tangent(
            &metric.static_frame(o),
            [1.0, 0.0, 0.0],
            TimeDirection::Past,
        );
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
        let start = GeodesicState {
            x: o,
            p: metric.lower(o, k),
        };
        let (sys, s0) = GeodesicSystem::new(metric, &start);
        let seg = Segment::exact(ClosedForm::Godel(geo), sys, 0.0, s0, 1.0);
        let outcome = |gap: f64, budget: u32| {
            let ball = Target::CoordinateSphere {
                center: centre(convex, gap),
                radius,
            };
            search_alone(metric, ball, &start, &seg, false, budget)
        };
        assert_eq!(outcome(1e-7, 3), Err(OutOfWork));
        assert_eq!(outcome(1e-7, SEARCH_PROBES), Ok(None));
        assert_eq!(outcome(1e-9, SEARCH_PROBES), Ok(None));
        let hit = outcome(-1e-2, SEARCH_PROBES).expect("within budget");
        assert!(hit.is_some_and(|(l, _)| l > 0.3 && l < 0.5), "{hit:?}");
    }

    /// A plane along a closed form (Gödel's and a Gödel-type member's rays through random
    /// events): its f = z − height is linear in λ, so the search finds its crossing at the
    /// root of the line through the span's end values without a further probe (a budget of
    /// none), where z is the height to rounding and the Illinois refinement agrees; and rules
    /// out a span whose ends are on one side, however close to the plane, where the rate bound
    /// alone must bisect (out of work with no probes to spend).
    #[test]
    fn a_plane_along_a_closed_form_is_crossed_at_its_linear_root() {
        let mut random = testkit::Uniform::new(0x2545_f491_4f6c_dd1du64);
        let mut uniform = || random.draw();
        let metrics = [
            Metric::Godel(Godel::new(1.0)),
            Metric::GodelType(GodelType::new(3.0, 0.5f64.sqrt())),
        ];
        let mut checked = 0;
        for metric in metrics {
            for _ in 0..50 {
                let o = Event::new(
                    4.0 * uniform() - 2.0,
                    1.2 * uniform() - 0.6,
                    1.2 * uniform() - 0.6,
                    uniform() - 0.5,
                );
                let n = [uniform() - 0.5, uniform() - 0.5, uniform() - 0.5];
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                if len < 0.1 || n[2].abs() < 0.1 * len {
                    continue; // a ray (nearly) along the plane has no crossing to look for
                }
                let n = n.map(|c| c / len);
                let (start, seg) = unit_segment(metric, o, n);
                let z = |l: f64| seg.state_at(l).x.z;
                let search = |height: f64, linear: bool, budget: u32| {
                    let plane = Target::Plane {
                        height,
                        extent: None,
                    };
                    search_alone(metric, plane, &start, &seg, linear, budget)
                };
                let at = 0.2 + 0.6 * uniform();
                let height = z(at);
                let (l, _) = search(height, true, 0)
                    .expect("no probe needed")
                    .expect("a crossing");
                assert!((l - at).abs() <= 1e-12, "{metric:?}: λ {l} against {at}");
                assert!(
                    (z(l) - height).abs() <= 1e-12,
                    "{metric:?}: z {} against {height}",
                    z(l)
                );
                let (illinois, _) = search(height, false, SEARCH_PROBES)
                    .expect("within budget")
                    .expect("a crossing");
                assert!(
                    (l - illinois).abs() <= 1e-9,
                    "{metric:?}: {l} against {illinois}"
                );
                // Just beyond the span's end: both ends on one side, 1e-7 apart at the end.
                let beyond = z(1.0) + 1e-7 * (z(1.0) - z(0.0)).signum();
                assert_eq!(search(beyond, true, 0), Ok(None), "{metric:?}");
                assert_eq!(search(beyond, false, 0), Err(OutOfWork), "{metric:?}");
                checked += 1;
            }
        }
        assert!(checked >= 40, "{checked} rays checked");
    }

    /// Two objects crossed in one segment of a closed-form ray: the one listed second is
    /// searched only up to the first one's crossing, from an end probe taken there. So a
    /// crossing of it beyond that is none, and one before it is found at its own place: two
    /// planes, either crossed first; and a small ball in front of a larger one crossed later,
    /// which an end probe taken at the segment's end let the rate bound exclude (the search
    /// then reported the larger ball's crossing behind it).
    #[test]
    fn an_object_listed_second_is_found_in_front_of_the_first() {
        let metric = Metric::Godel(Godel::new(1.0));
        let o = Event::new(0.0, 0.3, -0.2, 0.1);
        let (_, seg) = unit_segment(metric, o, [0.6, 0.0, 0.8]);
        let at = |l: f64| seg.state_at(l).x;
        let first = |targets: Vec<Target>| {
            let intersector = Intersector::new(metric, targets);
            let mut probes = intersector.probes();
            for m in &mut probes.start {
                m.at = f64::NAN; // fresh probes at the segment's start
            }
            let found = intersector
                .scan(&seg, Shift::default(), (0.0, 1.0), Want::First, &mut probes)
                .expect("within budget")
                .expect("a crossing");
            (found.target, found.lambda)
        };
        let plane = |l: f64| Target::Plane {
            height: at(l).z,
            extent: None,
        };
        let (target, l) = first(vec![plane(0.4), plane(0.7)]);
        assert_eq!(
            target, 0,
            "the first plane's crossing, at λ 0.4, is the earliest"
        );
        assert!((l - 0.4).abs() <= 1e-12, "λ {l}");
        let (target, l) = first(vec![plane(0.4), plane(0.3)]);
        assert_eq!(
            target, 1,
            "the second plane's crossing, at λ 0.3, is the earliest"
        );
        assert!((l - 0.3).abs() <= 1e-12, "λ {l}");
        let ball = |l: f64, radius: f64| {
            let x = at(l);
            Target::CoordinateSphere {
                center: [x.x, x.y, x.z],
                radius,
            }
        };
        let (small, large) = (ball(0.25, 0.02), ball(0.6, 0.05));
        let (target, alone) = first(vec![small.clone()]);
        assert_eq!(target, 0);
        assert!(alone < 0.3, "the small ball alone at λ {alone}");
        let (target, l) = first(vec![large, small]);
        assert_eq!(
            target, 1,
            "the small ball in front is the first crossing (λ {l})"
        );
        // The same root, up to the width at which `refine_root` stops (4 ε λ): searched up
        // to the large ball's crossing, not to the segment's end, its bracket differs.
        assert!(
            (l - alone).abs() <= 4.0 * f64::EPSILON * alone,
            "λ {l} against {alone} alone"
        );
    }
}
