//! The `Spacetime` interface and the closed set of metrics the tracer knows.
//!
//! Geodesics are integrated in Hamiltonian form, H = ½ g^{μν} p_μ p_ν:
//! ẋ^μ = ∂H/∂p_μ = g^{μν} p_ν,  ṗ_μ = −∂H/∂x^μ (Misner, Thorne & Wheeler, eq. 25.24).
//! For metrics independent of t and z (both here) p_t and p_z are then conserved exactly.
//! Christoffel symbols Γ^μ_αβ = ½ g^{μν}(∂_α g_νβ + ∂_β g_να − ∂_ν g_αβ) come from the
//! closed-form metric derivatives each metric supplies.

use crate::frame::{boost, gram_schmidt_static_frame, LocalVelocity};
use crate::vectors::{Christoffel, Covector, Event, FourVector, MetricTensor, Tetrad};
use crate::{Godel, GodelType, Minkowski};

/// A spacetime metric in pseudo-Cartesian coordinates (t, x, y, z).
///
/// Implementations are pure and immutable, so one value is shared by all threads.
pub trait Spacetime {
    /// g_μν at `x`.
    fn metric(&self, x: Event) -> MetricTensor;
    /// g^μν at `x`.
    fn inverse_metric(&self, x: Event) -> MetricTensor;
    /// ∂_λ g_μν at `x`, indexed `[lambda][mu][nu]`, in closed form.
    fn metric_derivatives(&self, x: Event) -> [MetricTensor; 4];
    /// Hamilton's equations for H = ½ g^{μν} p_μ p_ν: returns (ẋ^μ, ṗ_μ).
    fn hamilton(&self, x: Event, p: Covector) -> (FourVector, Covector);

    /// Christoffel symbols of the second kind at `x`.
    fn christoffel(&self, x: Event) -> Christoffel {
        let gi = self.inverse_metric(x);
        let dg = self.metric_derivatives(x);
        let mut out = [[[0.0; 4]; 4]; 4];
        for (mu, out_mu) in out.iter_mut().enumerate() {
            for a in 0..4 {
                for b in a..4 {
                    let mut s = 0.0;
                    for (nu, gi_nu) in gi[mu].iter().enumerate() {
                        s += gi_nu * (dg[a][nu][b] + dg[b][nu][a] - dg[nu][a][b]);
                    }
                    out_mu[a][b] = 0.5 * s;
                    out_mu[b][a] = 0.5 * s;
                }
            }
        }
        out
    }

    /// g(u, v) at `x`.
    fn dot(&self, x: Event, u: FourVector, v: FourVector) -> f64 {
        let g = self.metric(x);
        let (u, v) = (u.to_array(), v.to_array());
        let mut s = 0.0;
        for m in 0..4 {
            for n in 0..4 {
                s += g[m][n] * u[m] * v[n];
            }
        }
        s
    }

    /// Lowers an index: p_μ = g_μν v^ν.
    fn lower(&self, x: Event, v: FourVector) -> Covector {
        let g = self.metric(x);
        let v = v.to_array();
        let mut p = [0.0; 4];
        for m in 0..4 {
            p[m] = (0..4).map(|n| g[m][n] * v[n]).sum();
        }
        Covector::from_array(p)
    }

    /// Raises an index: v^μ = g^μν p_ν.
    fn raise(&self, x: Event, p: Covector) -> FourVector {
        let g = self.inverse_metric(x);
        let p = p.to_array();
        let mut v = [0.0; 4];
        for m in 0..4 {
            v[m] = (0..4).map(|n| g[m][n] * p[n]).sum();
        }
        FourVector::from_array(v)
    }

    /// The static observer's orthonormal frame: Gram–Schmidt of (∂t, ∂x, ∂y, ∂z)
    /// (docs/physics.md, "Frames").
    fn static_frame(&self, x: Event) -> Tetrad {
        gram_schmidt_static_frame(&self.metric(x))
    }

    /// The frame of an observer at `x` moving with `velocity` relative to the static one:
    /// the static frame boosted (see [`boost`]).
    fn observer_frame(&self, x: Event, velocity: LocalVelocity) -> Tetrad {
        boost(&self.static_frame(x), velocity)
    }
}

/// The metrics the tracer knows, as one closed type (cheap to copy, shared by all rays).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Metric {
    Minkowski(Minkowski),
    Godel(Godel),
    GodelType(GodelType),
}

impl Metric {
    /// Gödel's parameter `a`, if this is the Gödel metric.
    pub fn godel_a(&self) -> Option<f64> {
        match self {
            Metric::Godel(g) => Some(g.a),
            Metric::Minkowski(_) | Metric::GodelType(_) => None,
        }
    }
    /// The member of the Gödel-type family, if this is one given by (m², Ω).
    pub fn godel_type(&self) -> Option<GodelType> {
        match self {
            Metric::GodelType(g) => Some(*g),
            Metric::Minkowski(_) | Metric::Godel(_) => None,
        }
    }
    /// The unit that sizes the scene's bounds, local objects and step limits: a in Gödel's
    /// universe; in the Gödel-type family the shorter of Gödel's a for the same vorticity,
    /// 1/(√2 Ω), and the curvature scale 1/|m| (both a for the Gödel member); 1 in flat
    /// spacetime.
    pub fn length_scale(&self) -> f64 {
        match self {
            Metric::Godel(g) => g.a,
            Metric::GodelType(g) => g.godel_a().min(1.0 / g.m2.abs().sqrt()),
            Metric::Minkowski(_) => 1.0,
        }
    }
    /// The most coordinate length (x, y) that a unit of proper length spans within
    /// `radius` of the axis: √(1 + (r/2a)²) in Gödel's universe (g_rr = 1/(1 + (r/2a)²)),
    /// μρ/sin(μρ) in members with m² = −μ² < 0 (the circles' proper length D dφ is less
    /// than ρ dφ), 1 otherwise (ρ is the proper radius and D ≥ ρ).
    pub fn coordinate_stretch(&self, radius: f64) -> f64 {
        match self {
            Metric::Godel(g) => (1.0 + (radius / (2.0 * g.a)).powi(2)).sqrt(),
            Metric::GodelType(g) if g.m2 < 0.0 => {
                let x = (-g.m2).sqrt() * radius;
                if x >= std::f64::consts::PI {
                    f64::INFINITY
                } else if x > 0.0 {
                    x / x.sin()
                } else {
                    1.0
                }
            }
            Metric::GodelType(_) | Metric::Minkowski(_) => 1.0,
        }
    }
    /// The radius beyond which the coordinates end (D = 0 at μρ = π where m² = −μ² < 0).
    pub fn coordinate_radius(&self) -> Option<f64> {
        self.godel_type().and_then(|g| g.coordinate_radius())
    }
    /// The shortest coordinate time in which a light ray returns to the axis it left: Gödel's
    /// 2πa(√2 − 1), or the member's ([`GodelType::shortest_loop_time`]); None in flat
    /// spacetime, where rays do not return.
    pub fn shortest_loop_time(&self) -> Option<f64> {
        match self {
            Metric::Godel(g) => Some(g.shortest_loop_time()),
            Metric::GodelType(g) => Some(g.shortest_loop_time()),
            Metric::Minkowski(_) => None,
        }
    }
    /// Short name as used in scene files and on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Metric::Godel(_) => "godel",
            Metric::Minkowski(_) => "minkowski",
            Metric::GodelType(_) => "godel-type",
        }
    }
}

macro_rules! dispatch {
    ($self:ident, $m:ident => $e:expr) => {
        match $self {
            Metric::Minkowski($m) => $e,
            Metric::Godel($m) => $e,
            Metric::GodelType($m) => $e,
        }
    };
}

impl Spacetime for Metric {
    #[inline]
    fn metric(&self, x: Event) -> MetricTensor {
        dispatch!(self, m => m.metric(x))
    }
    #[inline]
    fn inverse_metric(&self, x: Event) -> MetricTensor {
        dispatch!(self, m => m.inverse_metric(x))
    }
    #[inline]
    fn metric_derivatives(&self, x: Event) -> [MetricTensor; 4] {
        dispatch!(self, m => m.metric_derivatives(x))
    }
    #[inline]
    fn hamilton(&self, x: Event, p: Covector) -> (FourVector, Covector) {
        dispatch!(self, m => m.hamilton(x, p))
    }
    #[inline]
    fn static_frame(&self, x: Event) -> Tetrad {
        dispatch!(self, m => m.static_frame(x))
    }
}
