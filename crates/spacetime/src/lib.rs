//! Spacetimes for the Gödel ray tracer: metrics, local frames, geodesics.
//!
//! Main types:
//! - [`Event`], [`FourVector`], [`Covector`], [`Tetrad`]: points, tangent vectors,
//!   one-forms and orthonormal frames, all in pseudo-Cartesian coordinates (t, x, y, z).
//! - [`Spacetime`]: the metric interface (metric, inverse, Christoffel symbols,
//!   Hamiltonian geodesic equations, natural static frame, boosts), implemented by
//!   [`Minkowski`] and [`Godel`], dispatched as the closed set [`Metric`].
//! - [`Dop853`]: an adaptive embedded Runge–Kutta 8(5,3) integrator with dense output.
//! - [`Geodesic`], [`trace`]: a geodesic launched from a local direction, integrated with
//!   stop conditions, sampled evenly from the dense output.
//! - [`curve`]: one geodesic from a local direction by either method (numeric or closed
//!   form), its inputs checked, sampled evenly (`godel geodesic`, the Python module).
//! - [`ConstantsOfMotion`]: E = −p_t, L = p_φ, p_z and the normalization, with drift reports.
//! - Gödel's symmetries: [`KillingField`] (the five Killing fields), [`Isometry`] (finite
//!   isometries and their differentials), [`ExactGeodesic`] (closed-form geodesics through
//!   any event), [`shadow_rays`] (light rays from a source at rest to an event), and
//!   [`connection`]: those rays with what an observer measures of them.
//! - The Gödel-type family's symmetries: [`killing_field`], [`TypeIsometry`], and its
//!   closed-form geodesics [`TypeOriginGeodesic`] (from the axis) and [`TypeExactGeodesic`],
//!   and its shadow rays [`type_shadow_rays`] (light rays from a source at rest to an event).
//! - Parallel transport: along the closed forms ([`transport`]) and integrated with a
//!   geodesic in any metric ([`propagator`]); what observers measure of a light ray's
//!   polarization ([`polarization`]).
//!
//! - [`Viewpoint`]: an observer and its camera axes; [`Viewpoint::eye`] displaces it along
//!   the right axis by an isometry (stereo eyes).
//! - [`message::short`]: how numbers are written in messages, in every crate.
//!
//! Conventions (docs/physics.md, "Conventions"): c = 1, signature (−,+,+,+), Gödel parameter
//! `a`, optical horizon at r = 2a; user-facing coordinates cylindrical (t, r, φ, z), integration in
//! pseudo-Cartesian x = r cos φ, y = r sin φ.

pub mod closed_form;
pub mod connect;
pub mod connection;
mod constants;
pub mod curve;
mod dop853;
pub mod eyes;
mod frame;
mod geodesic;
mod godel;
pub mod godel_chart;
pub mod godel_type;
pub mod godel_type_connect;
pub mod godel_type_geodesic;
pub mod godel_type_symmetry;
pub mod isometry;
pub mod killing;
pub mod measure;
pub mod message;
mod metric;
mod minkowski;
pub mod normal;
pub mod polarization;
pub mod propagator;
pub mod transport;
mod vectors;
pub mod worldline;

pub use closed_form::{ExactGeodesic, OriginGeodesic};
pub use connect::{
    shadow_rays, shadow_rays_from_axis, shadow_rays_within, source_area_distance_sq, Branch,
    ShadowRay,
};
pub use constants::{ConstantsOfMotion, Drift};
pub use dop853::{DenseStep, Dop853, OdeSystem, StepData, StepOutcome, Tolerances};
pub use eyes::Viewpoint;
pub use frame::{aberrate, boost, gram_schmidt_static_frame, scaled_unit, LocalVelocity};
pub use geodesic::{
    photon_tangent, refine_root, trace, AxisReturn, AxisWatch, Geodesic, GeodesicKind,
    GeodesicState, GeodesicSystem, StopReason, TimeDirection, TraceLimits, TracedGeodesic, STATE,
};
pub use godel::Godel;
pub use godel_chart::GodelChart;
pub use godel_type::GodelType;
pub use godel_type_connect::{
    type_shadow_rays, type_shadow_rays_from_axis, type_shadow_rays_within,
    type_source_area_distance_sq,
};
pub use godel_type_geodesic::{GeodesicRegime, TypeExactGeodesic, TypeOriginGeodesic};
pub use godel_type_symmetry::{killing_field, TypeIsometry};
pub use isometry::{origin_axes, Complex, Isometry};
pub use killing::KillingField;
pub use metric::{Metric, Spacetime};
pub use minkowski::Minkowski;
pub use vectors::{Christoffel, Covector, Cylindrical, Event, FourVector, MetricTensor, Tetrad};
