//! A ray as a chain of segments over its affine parameter λ: accepted integrator steps
//! (dense output made on first use) or stretches of a closed-form Gödel geodesic, evaluated
//! directly; and the shift that turns a ray's first loop into its later ones.
//!
//! Later loops: in Gödel's universe every light ray returns to its start's axis and then
//! retraces its loop moved in t and z only, since ∂t and ∂z are Killing fields
//! (docs/physics.md, "Closed forms"). So a stored first loop, shifted by (Δt, Δz, Δλ) per
//! period, is every later loop.

use crate::bounds::Aabb;
use spacetime::{
    DenseStep, ExactGeodesic, GeodesicState, GeodesicSystem, Metric, Spacetime, StepData, STATE,
};
use std::cell::OnceCell;

/// Segments per loop of a closed-form ray (the exact tracer's, and the shadow rays'
/// occlusion test). Each segment end costs a closed-form evaluation whether or not a probe
/// is needed there; fewer, longer segments cost more bisection near objects. Measured with
/// callgrind on scenes/bench-static.toml (exact, one thread, whole CLI render): 32 → 1.77 G
/// instructions, 16 → 1.32 G, 8 → 1.25 G; on the reference scene at 440×50, 16 and 8 are
/// within 1 %.
pub const EXACT_SEGMENTS: usize = 16;

/// One segment of a ray on [λ0, λ1]: a stored step whose dense output is made on first use
/// (most steps never need it), or a stretch of a closed-form geodesic.
pub struct Segment {
    data: StepData<STATE>,
    sys: GeodesicSystem<Metric>,
    dense: OnceCell<DenseStep<STATE>>,
    exact: Option<ExactGeodesic>,
}

impl Segment {
    /// An accepted integrator step of the system `sys`.
    pub fn step(data: StepData<STATE>, sys: GeodesicSystem<Metric>) -> Self {
        Segment {
            data,
            sys,
            dense: OnceCell::new(),
            exact: None,
        }
    }

    /// The stretch [l0, l1] of a closed-form geodesic whose state at l0 is `y0`.
    pub fn exact(
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
        Segment {
            data,
            sys,
            dense: OnceCell::new(),
            exact: Some(geo),
        }
    }

    /// The integrated state (t, x, y, z, p_x, p_y) at `l`.
    pub fn eval(&self, l: f64) -> [f64; STATE] {
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
    pub fn state_at(&self, l: f64) -> GeodesicState {
        self.sys.state(&self.eval(l))
    }
}

impl std::ops::Deref for Segment {
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
pub struct Shift {
    pub dt: f64,
    pub dz: f64,
    pub dl: f64,
}

impl Shift {
    /// `k` periods.
    pub fn times(self, k: f64) -> Shift {
        Shift {
            dt: k * self.dt,
            dz: k * self.dz,
            dl: k * self.dl,
        }
    }

    /// The state moved by this shift.
    pub fn apply(self, mut st: GeodesicState) -> GeodesicState {
        st.x.t += self.dt;
        st.x.z += self.dz;
        st
    }
}

/// A coordinate box around a stored loop: segment ends, grown by a quarter of the longest
/// chord (an arc of one step, turning by well under a radian, departs from its chord by at
/// most about an eighth of it).
pub fn loop_bounds(segments: &[Segment]) -> Aabb {
    let mut b = Aabb::EMPTY;
    let mut grow: f64 = 0.0;
    for st in segments {
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
