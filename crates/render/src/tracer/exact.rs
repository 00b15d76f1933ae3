//! The exact tracer's first loop: a closed-form geodesic from the origin, carried to the
//! observer by an isometry, cut into segments, each searched as it is made.
//!
//! - Gödel's universe (docs/physics.md, "Closed forms" and "Isometries"): [`EXACT_SEGMENTS`]
//!   segments up to the ray's return to the axis, whose parameter and shift are known
//!   exactly. The GPU kernel (crates/gpu) mirrors this.
//! - A Gödel-type member ("The Gödel-type family", "The exact tracer in the family"): equal
//!   segments of at most [`crate::segment::STEP_PER_SCALE`] length scales of proper length
//!   (at least [`EXACT_SEGMENTS`] per loop), up to the return to the axis for a returning
//!   ray, else until the ray is done; in a causal member a stretch beyond every object is
//!   one unsearched segment (`super::escape`). At most [`MAX_FAMILY_SEGMENTS`] segments.
//!
//! Later loops and the record are the tracer's (`super`).

use super::escape::MAX_FAMILY_SEGMENTS;
use super::{End, FirstLoop, Tracer};
use crate::intersect::Probes;
use crate::segment::{ClosedForm, Segment, Shift, EXACT_SEGMENTS};
use datafile::record::RayStatus;
use spacetime::{GeodesicState, GeodesicSystem, Metric, TypeExactGeodesic, STATE};

impl Tracer {
    /// The exact first loop: closed-form segments up to the return to the axis (whose
    /// parameter and shift are known exactly) or the ray's end.
    pub(super) fn first_loop_exact(
        &self,
        start: &GeodesicState,
        geo: Option<ClosedForm>,
        segments: &mut Vec<Segment>,
        probes: &mut Probes,
    ) -> FirstLoop {
        let (sys, s0) = GeodesicSystem::new(self.objects.metric, start);
        // Gödel's rays all return, after λ_ret = π/ω.
        let (geo, l_ret) = match geo {
            Some(ClosedForm::Godel(g)) => (ClosedForm::Godel(g), g.origin.return_parameter()),
            Some(ClosedForm::Type(g)) => {
                return self.first_loop_family(g, sys, s0, segments, probes)
            }
            None => return FirstLoop::Ended(End::Miss(RayStatus::Failed)),
        };
        // Past the last λ at which any object is searched (`Probes::reach`) the ray finds
        // nothing: where it surely escapes, it ends there as a ray that searches no object
        // does (its record is the same miss), without the rest of its segments.
        let (_, mut last) = probes.reach();
        for i in 0..EXACT_SEGMENTS {
            let (l0, l1) = (
                l_ret * i as f64 / EXACT_SEGMENTS as f64,
                l_ret * (i + 1) as f64 / EXACT_SEGMENTS as f64,
            );
            if l0 > last {
                if let Some(status) = self.escape_unsearched(start, Some(geo)) {
                    return FirstLoop::Ended(End::Miss(status));
                }
                last = f64::INFINITY; // it does not escape so: asked once
            }
            let y0 = segments.last().map_or(s0, |d| d.y1);
            segments.push(Segment::exact(geo, sys, l0, y0, l1));
            let d = segments.last().expect("just pushed");
            probes.activate(0, 0.0, l0, l1);
            if let Some(end) = self.scan_first_loop(segments, l0, l1, probes) {
                return FirstLoop::Ended(end);
            }
            if d.y1[0] < self.t_bound {
                return FirstLoop::Ended(End::Miss(RayStatus::Escaped));
            }
            probes.advance();
        }
        let end = segments.last().expect("segments").y1;
        FirstLoop::Closed(Shift {
            dt: end[0] - s0[0],
            dz: end[3] - s0[3],
            dl: l_ret,
        })
    }

    /// A Gödel-type member's first loop (module documentation): `s0` is the start in the
    /// integrated form of `sys`.
    fn first_loop_family(
        &self,
        g: TypeExactGeodesic,
        sys: GeodesicSystem<Metric>,
        s0: [f64; STATE],
        segments: &mut Vec<Segment>,
        probes: &mut Probes,
    ) -> FirstLoop {
        let geo = ClosedForm::Type(g);
        let l_ret = geo.return_parameter();
        let h = geo.segment_length(self.objects.metric.length_scale());
        let mut l0 = 0.0;
        for _ in 0..MAX_FAMILY_SEGMENTS {
            let l1 = match l_ret {
                // The last segment ends on the return, exactly.
                Some(l) if l - (l0 + h) < 0.5 * h => l,
                _ => l0 + h,
            };
            let y0 = segments.last().map_or(s0, |d| d.y1);
            let segment = Segment::exact(geo, sys, l0, y0, l1);
            let y1 = segment.y1;
            segments.push(segment);
            probes.activate(0, 0.0, l0, l1);
            if let Some(end) = self.scan_first_loop(segments, l0, l1, probes) {
                return FirstLoop::Ended(end);
            }
            if y1[0] < self.t_bound {
                return FirstLoop::Ended(End::Miss(RayStatus::Escaped));
            }
            if l_ret == Some(l1) {
                return FirstLoop::Closed(Shift {
                    dt: y1[0] - s0[0],
                    dz: y1[3] - s0[3],
                    dl: l1,
                });
            }
            probes.advance();
            l0 = l1;
            let Some(stop) = &self.escape else { continue };
            if stop.done(&g, l1, &y1) {
                return FirstLoop::Ended(End::Miss(RayStatus::Escaped));
            }
            // A returning ray beyond every object rises to half its loop and comes back down
            // symmetrically: beyond them all until λ_ret − l1, one segment never searched.
            if let Some(l) = l_ret.filter(|&l| stop.beyond_reach(&y1) && l - l1 > l1 + h) {
                let back = l - l1;
                let far = Segment::exact(geo, sys, l1, y1, back).beyond_objects();
                let end = far.state_at(back);
                segments.push(far);
                self.objects.probe_all(&end, back, probes);
                l0 = back;
            }
        }
        FirstLoop::Ended(End::Miss(RayStatus::WorkLimit))
    }
}
