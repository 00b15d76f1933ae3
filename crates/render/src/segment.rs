//! A ray as a chain of segments over its affine parameter λ: accepted integrator steps
//! (dense output made on first use) or stretches of a closed-form geodesic (Gödel's, or a
//! Gödel-type member's: [`ClosedForm`]), evaluated directly; and the shift that turns a ray's
//! first loop into its later ones.
//!
//! Later loops: in Gödel's universe, and for the returning rays of every Gödel-type member,
//! a light ray returns to its start's axis and then retraces its loop moved in t and z only,
//! since ∂t and ∂z are Killing fields (docs/physics.md, "Closed forms" and "The exact
//! tracer in the family"). So a stored first loop, shifted by (Δt, Δz, Δλ) per period, is
//! every later loop.
//!
//! A stretch of a loop that provably stays beyond every object (`crate::tracer::EscapeStop`) is stored
//! as one segment marked `far`: it is never searched, only stepped over.

use crate::bounds::Aabb;
use spacetime::{
    DenseStep, Event, ExactGeodesic, FourVector, GeodesicState, GeodesicSystem, Metric, Spacetime,
    StepData, TypeExactGeodesic, TypeOriginGeodesic, STATE,
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
    exact: Option<ClosedForm>,
    /// Beyond every object throughout (`crate::tracer::EscapeStop`): stepped over, never
    /// searched.
    pub far: bool,
}

/// A closed-form light ray: Gödel's (`closed_form.rs`) or a Gödel-type member's
/// (`godel_type_geodesic.rs`), both through any event.
#[derive(Clone, Copy)]
pub enum ClosedForm {
    Godel(ExactGeodesic),
    Type(TypeExactGeodesic),
}

impl ClosedForm {
    /// The closed form through `at` with tangent `k` in `metric`, if it has one.
    pub fn new(metric: &Metric, at: Event, k: FourVector) -> Option<ClosedForm> {
        match metric {
            Metric::Godel(g) => ExactGeodesic::new(g.a, at, k).map(ClosedForm::Godel),
            Metric::GodelType(m) => TypeExactGeodesic::new(*m, at, k).map(ClosedForm::Type),
            Metric::Minkowski(_) => None,
        }
    }

    /// Event and tangent at parameter `l` (0 at the start).
    pub fn at(&self, l: f64) -> (Event, FourVector) {
        match self {
            ClosedForm::Godel(g) => g.at(l),
            ClosedForm::Type(g) => g.at(l),
        }
    }

    /// The parameter of the return to the start's axis; `None` for a ray that escapes
    /// ([`family_return`] for a Gödel-type member).
    pub fn return_parameter(&self) -> Option<f64> {
        match self {
            ClosedForm::Godel(g) => Some(g.origin.return_parameter()),
            ClosedForm::Type(g) => family_return(&g.origin),
        }
    }

    /// The λ length of the segments the tracers cut this ray into: Gödel's loop in
    /// [`EXACT_SEGMENTS`]; a member's equal segments of at most [`STEP_PER_SCALE`] length
    /// scales (`length_scale`, the member's), at least [`EXACT_SEGMENTS`] a loop and a whole
    /// number of them to the return where the ray returns.
    pub fn segment_length(&self, length_scale: f64) -> f64 {
        match self {
            ClosedForm::Godel(g) => g.origin.return_parameter() / EXACT_SEGMENTS as f64,
            ClosedForm::Type(g) => {
                // Light moves through the base and z at the proper speed |E|.
                let step = STEP_PER_SCALE * length_scale / g.origin.energy.abs();
                match family_return(&g.origin) {
                    Some(l) => l / (l / step).ceil().max(EXACT_SEGMENTS as f64),
                    None => step,
                }
            }
        }
    }

    /// Gödel's closed form, if this is one.
    pub fn godel(&self) -> Option<&ExactGeodesic> {
        match self {
            ClosedForm::Godel(g) => Some(g),
            ClosedForm::Type(_) => None,
        }
    }

    /// A Gödel-type member's closed form, if this is one.
    pub fn member(&self) -> Option<&TypeExactGeodesic> {
        match self {
            ClosedForm::Godel(_) => None,
            ClosedForm::Type(g) => Some(g),
        }
    }
}

impl Segment {
    /// An accepted integrator step of the system `sys`.
    pub fn step(data: StepData<STATE>, sys: GeodesicSystem<Metric>) -> Self {
        Segment {
            data,
            sys,
            dense: OnceCell::new(),
            exact: None,
            far: false,
        }
    }

    /// The stretch [l0, l1] of a closed-form geodesic whose state at l0 is `y0`.
    pub fn exact(
        geo: ClosedForm,
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
            far: false,
        }
    }

    /// The stretch [l0, l1] of a closed-form geodesic, its start from the closed form too
    /// (the same state as the end of a segment that ends at l0).
    pub fn exact_between(geo: ClosedForm, sys: GeodesicSystem<Metric>, l0: f64, l1: f64) -> Self {
        Self::exact(geo, sys, l0, exact_state(&geo, &sys, l0), l1)
    }

    /// The same stretch, marked as beyond every object throughout (never searched).
    pub fn beyond_objects(mut self) -> Self {
        self.far = true;
        self
    }

    /// Whether the segment is a stretch of a closed form (whose z is linear in λ).
    pub fn is_closed_form(&self) -> bool {
        self.exact.is_some()
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

/// Proper length of one segment of a Gödel-type ray in the exact tracer, per length scale of
/// the member (`Metric::length_scale`): a light ray moves through the base and z at the
/// constant proper speed |E| (dρ² + D²dφ² + dz² = (dt + H dφ)² = E² dλ²), so segments of
/// equal λ are of equal proper length. Gödel's loop, cut in `EXACT_SEGMENTS`, has segments
/// of about half its a.
pub const STEP_PER_SCALE: f64 = 0.5;

/// Below this fraction of Ω²E², Λ = Ω²E² − m²A/4 is taken for 0 (`family_return`).
pub const BOUNDARY_LAMBDA: f64 = 1e-12;

/// The return parameter π/√Λ of a Gödel-type member's light ray `o` from the axis, or `None`
/// for a ray that escapes, where Λ ≤ [`BOUNDARY_LAMBDA`]·Ω²E² counts as the boundary Λ = 0:
/// Λ is the difference of two terms of size Ω²E², computed from a tangent pushed by an
/// isometry, so its sign is rounding within ~1e-14 of that (in m² = 4Ω², Λ = Ω²p_z², every
/// ray in the plane z = 0 of the observer). A ray with 0 < Λ ≤ 1e-12 Ω²E² would loop out to
/// w_max = (m/2)k⊥/√Λ ≥ 1e6·(m/2)k⊥/(Ω|E|), mρ ≳ 28: at the edge of the scenes' chart
/// (mρ ≤ 30), where its return is not resolved either.
pub fn family_return(o: &TypeOriginGeodesic) -> Option<f64> {
    let spin = o.member.omega * o.energy;
    o.return_parameter()
        .filter(|_| o.big_lambda() > BOUNDARY_LAMBDA * spin * spin)
}

/// The integrated-state form (t, x, y, z, p_x, p_y) of a closed-form geodesic at `l`.
fn exact_state(geo: &ClosedForm, sys: &GeodesicSystem<Metric>, l: f64) -> [f64; STATE] {
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
/// most about an eighth of it). Far segments are left out: they come near no object.
pub fn loop_bounds(segments: &[Segment]) -> Aabb {
    let mut b = Aabb::EMPTY;
    let mut grow: f64 = 0.0;
    for st in segments.iter().filter(|st| !st.far) {
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
