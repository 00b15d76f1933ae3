//! The numeric tracer's first loop: DOP853 steps of the geodesic equations, in any metric
//! (docs/physics.md, "Geodesics"), each step scanned as it is taken
//! ("The intersection search"), until the ray ends or, in Gödel's universe, returns to its
//! start's axis ("Closed forms", "Return to the axis"), checked to close in position and
//! momentum. In a causal Gödel-type member a ray beyond every object that will not come back
//! before the time bound is done (`super::escape`). Later loops and the record are the
//! tracer's (`super`).

use super::{End, EscapeStop, FirstLoop, Tracer};
use crate::intersect::Probes;
use crate::segment::{Segment, Shift};
use datafile::record::RayStatus;
use spacetime::{
    AxisWatch, Dop853, GeodesicState, GeodesicSystem, OdeSystem, StepOutcome, TypeExactGeodesic,
};

impl Tracer {
    /// The numeric first loop: DOP853 steps, each scanned as it is taken, until the ray
    /// ends or closes on its axis (Gödel; in other metrics it never closes). `stop`: a causal
    /// Gödel-type member's escape stop with the ray's closed form (for its constants).
    pub(super) fn first_loop_numeric(
        &self,
        start: &GeodesicState,
        segments: &mut Vec<Segment>,
        probes: &mut Probes,
        first_step: &mut Option<f64>,
        stop: Option<(&EscapeStop, &TypeExactGeodesic)>,
    ) -> FirstLoop {
        let (sys, s0) = GeodesicSystem::new(self.objects.metric, start);
        let mut ode = Dop853::new(sys, 0.0, s0, self.tol, *first_step);
        let mut axis = AxisWatch::new(start);
        let mut periodic = self.periodic;
        loop {
            if ode.accepted >= self.max_steps {
                return FirstLoop::Ended(End::Miss(RayStatus::StepBudget));
            }
            let g_prev = axis.g(ode.state(), ode.derivative());
            match ode.step() {
                StepOutcome::Accepted => {}
                StepOutcome::Stalled | StepOutcome::NonFinite => {
                    return FirstLoop::Ended(End::Miss(RayStatus::Failed))
                }
            }
            if ode.accepted == 1 {
                // Bounded by the ray's extent: where the error estimate vanishes (flat
                // spacetime) the proposal grows tenfold per ray and would overflow.
                *first_step = Some(ode.next_step_size().min(self.observer.t - self.t_bound));
            }
            // Kept in place (a step record is large): only the first loop is stored for reuse.
            if !periodic {
                segments.clear();
            }
            segments.push(Segment::step(ode.last_step(), sys));
            let d = segments.last().expect("just pushed");
            let mut hi = d.lambda1();
            probes.activate(0, 0.0, d.lambda0, hi);
            let mut closed = None;
            if periodic {
                let back = axis.after_step(
                    g_prev,
                    &d.y1,
                    ode.derivative(),
                    d.lambda0,
                    d.lambda1(),
                    |l| d.eval(l),
                    |st| sys.rhs(st),
                );
                match back {
                    Some(r) if r.closed => {
                        hi = r.lambda;
                        closed = Some(Shift {
                            dt: r.state[0] - s0[0],
                            dz: r.state[3] - s0[3],
                            dl: r.lambda,
                        });
                    }
                    // Did not close well enough: integrate on.
                    Some(r) if r.near => periodic = false,
                    _ => {}
                }
            }
            if let Some(end) = self.scan_first_loop(segments, d.lambda0, hi, probes) {
                return FirstLoop::Ended(end);
            }
            if d.eval(hi)[0] < self.t_bound || !d.y1.iter().all(|v| v.is_finite()) {
                return FirstLoop::Ended(End::Miss(if d.y1[0] < self.t_bound {
                    RayStatus::Escaped
                } else {
                    RayStatus::Failed
                }));
            }
            if stop.is_some_and(|(s, geo)| s.done(geo, d.lambda1(), &d.y1)) {
                return FirstLoop::Ended(End::Miss(RayStatus::Escaped));
            }
            probes.advance();
            if let Some(p) = closed {
                return FirstLoop::Closed(p);
            }
        }
    }
}
