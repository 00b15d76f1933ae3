//! Where a light ray of a causal Gödel-type member (m² ≥ 4Ω²) is done: once it is beyond
//! every object and will not come back before the trace's time bound, it has escaped
//! (docs/physics.md, "The exact tracer in the family"). Both tracers stop there; the exact
//! one also steps over the far stretch of a returning ray's loop in one unsearched segment.
//!
//! Why it holds. In a causal member H² < D² everywhere, so t is a time function: along a
//! past-directed light ray t decreases, and the ray stays within the trace's time window
//! [t_bound, t_obs] until it leaves it for good. The objects' coordinate boxes over that
//! window lie within `reach` of the chart's axis (ρ is the proper radius, the base
//! dρ² + D² dφ² is the hyperbolic plane of curvature −m²), so within ρ_obs + reach of the
//! observer's axis, by the triangle inequality. The ray's distance d from the observer's
//! axis is the closed form's ρ in the observer's origin frame (the isometries move the base
//! rigidly): for an escaping or boundary ray (Λ ≤ 0, up to rounding: `family_return`) it
//! grows monotonically (ρ̇ ∝ C1 ≥ 1),
//! so once d > ρ_obs + reach it never meets an object again; a returning ray's ρ is
//! symmetric about half its return parameter λ_ret and rises until then, so if d(λ) >
//! ρ_obs + reach at λ ≤ λ_ret/2 the ray stays beyond every object until λ_ret − λ, and it is
//! done if there its time is already below t_bound or its z past the objects' z range. For
//! z = z_obs + p_z λ is monotone: a ray past the objects' z range, moving away from it, never
//! meets them again. (In m² = 4Ω² a ray with small p_z loops out to mρ ≈ 2 asinh(k⊥/|p_z|)
//! but returns at z ± π/Ω: the numeric tracer could not follow it, the stop ends it.)
//!
//! The distance from the observer's axis is computed from chart positions (so the numeric
//! tracer uses it too) by the hyperbolic law of cosines in a form without cancellation:
//! cosh(m d) = cosh(m(ρ₁ − ρ₂)) + 2 sinh(mρ₁) sinh(mρ₂) sin²(Δφ/2).

use crate::segment::{family_return, BOUNDARY_LAMBDA};
use crate::target::Target;
use spacetime::{Event, Metric, TypeExactGeodesic, STATE};

/// The most segments an escaping ray (or a returning ray's first loop) is cut into: beyond
/// it the pixel is marked as out of work. Rays near the boundary between the regimes rise
/// only as log λ (w = sinh(mρ/2) ≈ Ω k⊥ λ in m² = 4Ω²), so reaching past the objects' reach
/// R takes λ ≈ sinh(mR/2)/(Ω k⊥), and comes back as slowly: scenes/godel-type.toml as
/// m² = 4Ω² (110×100) had 604 pixels out of work at 1024 segments, none at 16384 (3.9 s
/// instead of 2.8 s). Only rays that stay within the objects' reach (planes without extent)
/// or within their z range for long run into it.
pub const MAX_FAMILY_SEGMENTS: usize = 16_384;

/// Margin added to the objects' reach, per length scale: covers rounding of the distance and
/// the numeric tracer's deviation from the closed form (the boxes themselves are already
/// grown around the objects).
const MARGIN_PER_SCALE: f64 = 1e-3;

/// What a causal member's ray must pass to be done (module documentation).
#[derive(Clone, Copy, Debug)]
pub struct EscapeStop {
    m: f64,
    observer: Event,
    /// ρ_obs + the objects' reach + margin: no object is farther from the observer's axis.
    radius: f64,
    /// The objects' z range over the time window.
    z_range: (f64, f64),
    t_bound: f64,
}

impl EscapeStop {
    /// The stop for rays from `observer` among `targets`, traced back to `t_bound`; `None`
    /// unless `metric` is a causal Gödel-type member (m² ≥ 4Ω², up to rounding; in the others
    /// every light ray returns to its axis within a bounded loop).
    pub fn new(
        metric: &Metric,
        observer: Event,
        targets: &[Target],
        t_bound: f64,
    ) -> Option<EscapeStop> {
        let member = metric.godel_type()?;
        // Within rounding of m² = 4Ω² (m2 = 2 with Ω = 1/√2 in f64 is one step below) the
        // member counts as causal, as its in-plane rays count as boundary rays
        // (`family_return`): ρ_c lies beyond mρ ≈ 28, where no scene reaches, and within it
        // t still falls along every past-directed ray.
        let w2 = member.omega * member.omega;
        if member.m2 < 4.0 * w2 * (1.0 - BOUNDARY_LAMBDA) {
            return None;
        }
        let mut reach: f64 = 0.0;
        let mut z_range = (f64::INFINITY, f64::NEG_INFINITY);
        for t in targets {
            let b = t.bounds(metric, t_bound, observer.t);
            if !(b.min[0] <= b.max[0]) {
                continue; // no part of the object within the window (a worldline's end)
            }
            reach = reach.max(b.max_radius());
            z_range = (z_range.0.min(b.min[2]), z_range.1.max(b.max[2]));
        }
        Some(EscapeStop {
            m: member.m2.sqrt(),
            observer,
            radius: observer.x.hypot(observer.y) + reach + MARGIN_PER_SCALE * metric.length_scale(),
            z_range,
            t_bound,
        })
    }

    /// The proper distance in the base from the observer's axis to the chart position (x, y).
    pub fn distance(&self, x: f64, y: f64) -> f64 {
        let (r1, r2) = (self.observer.x.hypot(self.observer.y), x.hypot(y));
        // sin²(Δφ/2) = |û₁ − û₂|²/4 (no cancellation at small angles).
        let unit = |x: f64, y: f64, r: f64| if r > 0.0 { (x / r, y / r) } else { (1.0, 0.0) };
        let (u1, u2) = (unit(self.observer.x, self.observer.y, r1), unit(x, y, r2));
        let half = ((u1.0 - u2.0).powi(2) + (u1.1 - u2.1).powi(2)) / 4.0;
        let m = self.m;
        let c = (m * (r1 - r2)).cosh() + 2.0 * (m * r1).sinh() * (m * r2).sinh() * half;
        c.acosh() / m
    }

    /// Whether the ray state `y` (chart, integrated form) is farther from the observer's axis
    /// than any object can be.
    pub fn beyond_reach(&self, y: &[f64; STATE]) -> bool {
        self.distance(y[1], y[2]) > self.radius
    }

    /// Whether a ray moving along z at rate `kz` (= p_z, constant) is past the objects' z
    /// range at `z` and moving away from it.
    pub fn beyond_z(&self, z: f64, kz: f64) -> bool {
        (kz > 0.0 && z > self.z_range.1) || (kz < 0.0 && z < self.z_range.0)
    }

    /// Whether the ray `geo`, at parameter `lambda` in state `y`, is done: beyond every object
    /// for the rest of the trace (module documentation).
    pub fn done(&self, geo: &TypeExactGeodesic, lambda: f64, y: &[f64; STATE]) -> bool {
        if self.beyond_z(y[3], geo.origin.pz) {
            return true;
        }
        if !self.beyond_reach(y) {
            return false;
        }
        match family_return(&geo.origin) {
            None => true,
            Some(l_ret) => {
                // Beyond every object until λ_ret − λ: done if by then the ray is past the
                // time bound or past the objects' z range.
                let back = geo.at(l_ret - lambda).0;
                lambda <= 0.5 * l_ret
                    && (back.t < self.t_bound || self.beyond_z(back.z, geo.origin.pz))
            }
        }
    }
}
