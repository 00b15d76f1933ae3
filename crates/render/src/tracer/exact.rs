//! The exact tracer's first loop: Gödel's closed-form geodesic from the origin, carried to
//! the observer by an isometry (docs/physics.md, "Closed forms" and "Isometries"), cut into
//! [`EXACT_SEGMENTS`] segments up to its return to the axis, whose parameter and shift are
//! known exactly. The GPU kernel (crates/gpu) mirrors this tracer. Later loops and the
//! record are the tracer's (`super`).

use super::{End, FirstLoop, Tracer};
use crate::intersect::Probes;
use crate::segment::{Segment, Shift, EXACT_SEGMENTS};
use datafile::record::RayStatus;
use spacetime::{ExactGeodesic, GeodesicState, GeodesicSystem};

impl Tracer {
    /// The exact first loop: [`EXACT_SEGMENTS`] closed-form segments up to the return to
    /// the axis, whose parameter and shift are known exactly.
    pub(super) fn first_loop_exact(
        &self,
        start: &GeodesicState,
        geo: Option<ExactGeodesic>,
        segments: &mut Vec<Segment>,
        probes: &mut Probes,
    ) -> FirstLoop {
        let (sys, s0) = GeodesicSystem::new(self.objects.metric, start);
        let Some(geo) = geo else {
            return FirstLoop::Ended(End::Miss(RayStatus::Failed));
        };
        let l_ret = geo.origin.return_parameter();
        for i in 0..EXACT_SEGMENTS {
            let (l0, l1) = (
                l_ret * i as f64 / EXACT_SEGMENTS as f64,
                l_ret * (i + 1) as f64 / EXACT_SEGMENTS as f64,
            );
            let y0 = segments.last().map_or(s0, |d| d.y1);
            segments.push(Segment::exact(geo, sys, l0, y0, l1));
            let d = segments.last().expect("just pushed");
            probes.activate(0, l0);
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
}
