//! Every light ray from a source at rest to an event, as an observer uses them: emission
//! event and travel time, the direction of departure at the source and where to look at the
//! event, the source's area distance, the frequency ratio and how well the ray lands
//! (`godel connect` and the Python module's `connect`).
//!
//! The rays themselves are [`crate::shadow_rays`] (docs/physics.md, "Light rays between a
//! source and an event"; Grave et al., PRD 80, 103002 (2009)): they exist only where the
//! event lies within the source's horizon (ρ < 2a); within it there are two per winding in
//! the source's plane, and more off it. Each ray is re-evaluated from its emission event with
//! the closed form (isometry ∘ closed form ∘ inverse) and its miss distance at the event
//! kept, so a user sees that it lands. Directions are unit vectors in the static observer's
//! local frame (docs/physics.md, "Frames"). The frequency ratio g between the static source
//! and a static receiver is (k·u_obs)/(k·u_emit) at the two ends; it is 1, since ∂t is a
//! Killing field of unit norm, and computed rather than assumed.
//!
//! In a member of the Gödel-type family ([`type_connections`]) the rays are
//! [`crate::type_shadow_rays`] (docs/physics.md, "Shadow rays in the family") and are
//! re-evaluated with [`TypeExactGeodesic`]; they exist only within ρ_c of the source's axis
//! for m² < 4Ω², and everywhere for the causal members.

use crate::measure::{frequency_ratio, vector_components};
use crate::{
    shadow_rays, source_area_distance_sq, type_shadow_rays, type_source_area_distance_sq, Event,
    ExactGeodesic, FourVector, Godel, GodelType, Isometry, Metric, ShadowRay, Spacetime,
    TypeExactGeodesic, TypeIsometry,
};

/// Most windings counted: each is an earlier emission, and costs a root search.
pub const MAX_WINDINGS: u32 = 1000;

/// One connecting ray.
#[derive(Clone, Debug, PartialEq)]
pub struct Connection {
    pub ray: ShadowRay,
    /// The event's time minus the emission time.
    pub travel_time: f64,
    /// Unit direction of departure in the source's static frame.
    pub departure: [f64; 3],
    /// Unit direction toward the source as seen at the event, in its static frame.
    pub look: [f64; 3],
    /// Area distance D of the source along the ray.
    pub area_distance: f64,
    /// Frequency ratio ν_received/ν_emitted between static source and static receiver.
    pub g: f64,
    /// |closed form from the emission event at λ − event|, largest coordinate.
    pub miss: f64,
}

/// The rays between a source and an event.
#[derive(Clone, Debug, PartialEq)]
pub struct Connections {
    /// Gödel's universe or a Gödel-type member.
    pub metric: Metric,
    pub event: Event,
    /// The source's position (t = 0).
    pub source: Event,
    /// The event's distance from the source's axis in the source's frame (Gödel's r, or a
    /// member's proper radius ρ).
    pub rho: f64,
    /// The distance from the source's axis that light from it reaches: Gödel's horizon 2a,
    /// a member's ρ_c; `None` for the causal members (m² ≥ 4Ω²), whose light reaches all.
    pub reach: Option<f64>,
    /// Latest emission first.
    pub rays: Vec<Connection>,
}

impl Connections {
    /// Whether the event lies within the source's horizon (else there is no ray).
    pub fn within_horizon(&self) -> bool {
        self.reach.is_none_or(|reach| self.rho < reach)
    }
}

/// Why the rays from a source to an event on the source's own axis are not single rays:
/// there (ρ = 0 after the isometry that moves the source to the axis) the azimuth χ of
/// emission is free (docs/physics.md, "Light rays between a source and an event"), so light
/// reaches the event along whole cones of directions, every azimuth at once; at the source's
/// own place the event also sees it with travel time 0. [`connections`] would list one
/// arbitrary member of each cone, so its callers refuse these events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OnTheSourceAxis {
    /// The event at the source's place (any time).
    AtTheSource,
    /// The event above or below the source, on its axis.
    OnItsAxis,
}

impl std::fmt::Display for OnTheSourceAxis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            OnTheSourceAxis::AtTheSource => {
                "the source is at the event's place: the event sees it with travel time 0, and \
                 the light it sent earlier in its plane returns to it from every direction of \
                 that plane after each loop, not along single rays; put the source elsewhere"
            }
            OnTheSourceAxis::OnItsAxis => {
                "the event is on the source's axis (ρ = 0): light from the source reaches it \
                 along whole cones of directions, every azimuth at once, not along single rays; \
                 move the event off the axis"
            }
        })
    }
}

/// Whether `event` lies on the axis of a source at rest at `source` (x, y, z; its t ignored)
/// in Gödel's universe of parameter `a`, to the float rounding of the isometry (10⁻¹² a).
pub fn on_the_source_axis(a: f64, source: Event, event: Event) -> Option<OnTheSourceAxis> {
    let source = Event::new(0.0, source.x, source.y, source.z);
    let moved = Isometry::to_origin(a, source).apply(event);
    let here = 1e-12 * a;
    match (moved.r() > here, moved.z.abs() > here) {
        (true, _) => None,
        (false, false) => Some(OnTheSourceAxis::AtTheSource),
        (false, true) => Some(OnTheSourceAxis::OnItsAxis),
    }
}

/// [`on_the_source_axis`] in a Gödel-type member (to 10⁻¹² of its length scale); `None`
/// also where the source lies outside the chart (the caller's to refuse).
pub fn type_on_the_source_axis(
    member: GodelType,
    source: Event,
    event: Event,
) -> Option<OnTheSourceAxis> {
    let source = Event::new(0.0, source.x, source.y, source.z);
    let moved = TypeIsometry::to_origin(member, source)?.apply(event);
    let here = 1e-12 * Metric::GodelType(member).length_scale();
    match (moved.r() > here, moved.z.abs() > here) {
        (true, _) => None,
        (false, false) => Some(OnTheSourceAxis::AtTheSource),
        (false, true) => Some(OnTheSourceAxis::OnItsAxis),
    }
}

/// Local spatial components of `v` in the static frame at `at`, normalized.
fn local_direction(metric: &Metric, at: Event, v: FourVector) -> [f64; 3] {
    let frame = metric.static_frame(at);
    let [_, n @ ..] = vector_components(&metric.metric(at), &frame, v);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|c| c / len)
}

/// Every light ray, up to `windings` windings, from a source at rest at `source` (x, y, z;
/// its t ignored) to `event` in Gödel's universe of parameter `a`. The inputs are the
/// caller's to check (a > 0, finite coordinates, `windings` ≤ [`MAX_WINDINGS`], the event
/// not [`on_the_source_axis`]); `None` if a ray found has no closed form (it always has).
pub fn connections(a: f64, source: Event, event: Event, windings: u32) -> Option<Connections> {
    let source = Event::new(0.0, source.x, source.y, source.z);
    let rho = Isometry::to_origin(a, source).apply(event).r();
    let rays = shadow_rays(a, source, event, windings.min(MAX_WINDINGS));
    let end = |ray: &ShadowRay| {
        ExactGeodesic::new(a, ray.emission, ray.tangent).map(|g| g.at(ray.lambda))
    };
    let area = |ray: &ShadowRay| source_area_distance_sq(a, source, ray);
    let metric = Metric::Godel(Godel::new(a));
    let rays = measure_rays(metric, event, rays, end, area)?;
    Some(Connections {
        metric,
        event,
        source,
        rho,
        reach: Some(2.0 * a),
        rays,
    })
}

/// [`connections`] in a Gödel-type member: the rays of [`type_shadow_rays`]. The inputs are
/// the caller's to check (the member's constants, positions in the chart, the event not
/// [`type_on_the_source_axis`]); `None` if the source lies outside the chart or a ray found
/// has no closed form.
pub fn type_connections(
    member: GodelType,
    source: Event,
    event: Event,
    windings: u32,
) -> Option<Connections> {
    let source = Event::new(0.0, source.x, source.y, source.z);
    let rho = TypeIsometry::to_origin(member, source)?.apply(event).r();
    let rays = type_shadow_rays(member, source, event, windings.min(MAX_WINDINGS));
    let end = |ray: &ShadowRay| {
        TypeExactGeodesic::new(member, ray.emission, ray.tangent).map(|g| g.at(ray.lambda))
    };
    let area = |ray: &ShadowRay| type_source_area_distance_sq(member, source, ray);
    let metric = Metric::GodelType(member);
    let rays = measure_rays(metric, event, rays, end, area)?;
    Some(Connections {
        metric,
        event,
        source,
        rho,
        reach: member.critical_radius(),
        rays,
    })
}

/// What an observer measures of each ray: `end` is the closed form's event and tangent at the
/// ray's λ, `area` the source's area distance squared.
fn measure_rays(
    metric: Metric,
    event: Event,
    rays: Vec<ShadowRay>,
    end: impl Fn(&ShadowRay) -> Option<(Event, FourVector)>,
    area: impl Fn(&ShadowRay) -> f64,
) -> Option<Vec<Connection>> {
    let static_u = |at: Event| metric.static_frame(at).e[0];
    rays.into_iter()
        .map(|ray| {
            let (end_event, k_end) = end(&ray)?;
            let miss = (end_event - event)
                .to_array()
                .iter()
                .fold(0.0_f64, |m, d| m.max(d.abs()));
            let arrival = local_direction(&metric, event, k_end);
            let shift = frequency_ratio(
                static_u(event),
                metric.lower(event, k_end),
                static_u(ray.emission),
                metric.lower(ray.emission, ray.tangent),
            );
            Some(Connection {
                ray,
                travel_time: event.t - ray.emission.t,
                departure: local_direction(&metric, ray.emission, ray.tangent),
                look: arrival.map(|c| -c),
                area_distance: area(&ray).sqrt(),
                g: shift,
                miss,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_land_and_static_ends_see_no_shift() {
        let source = Event::new(0.0, 1.1, -0.6, 0.35);
        let event = Event::new(0.0, 0.4 * 2f64.cos(), 0.4 * 2f64.sin(), 0.1);
        let c = connections(1.0, source, event, 2).unwrap();
        assert!(c.within_horizon());
        assert!(c.rays.len() >= 4, "{}", c.rays.len());
        for ray in &c.rays {
            assert!(ray.miss < 1e-9, "{}", ray.miss);
            assert!((ray.g - 1.0).abs() < 1e-9, "{}", ray.g);
            assert!(ray.travel_time > 0.0);
        }
        // Beyond the horizon: no ray.
        let far = connections(
            1.0,
            Event::new(0.0, 2.2, 0.0, 0.0),
            Event::new(0.0, 0.0, 0.0, 0.0),
            2,
        );
        let far = far.unwrap();
        assert!(!far.within_horizon() && far.rays.is_empty());
    }

    /// The source's axis is the curve the source's isometry sends to the coordinate axis:
    /// off the coordinate axis it is not a vertical line, so the check must go through it.
    #[test]
    fn events_on_the_source_axis_are_found_through_its_isometry() {
        let a = 1.3;
        let source = Event::new(0.0, 1.1, -0.6, 0.35);
        let at = |t: f64, z: f64| Event::new(t, 1.1, -0.6, z);
        assert_eq!(
            on_the_source_axis(a, source, at(-7.0, 0.35)),
            Some(OnTheSourceAxis::AtTheSource)
        );
        // The axis maps to the axis with z shifted: the same x, y at another z is on it.
        assert_eq!(
            on_the_source_axis(a, source, at(2.0, 1.0)),
            Some(OnTheSourceAxis::OnItsAxis)
        );
        let off = Event::new(0.0, 1.1 + 1e-9, -0.6, 0.35);
        assert_eq!(on_the_source_axis(a, source, off), None);
        // An event a little off the axis still gets rays that land.
        let near = Event::new(0.0, 1.1 + 1e-3, -0.6, 0.35);
        let c = connections(a, source, near, 1).unwrap();
        assert!(!c.rays.is_empty());
        assert!(c.rays.iter().all(|r| r.miss < 1e-9 && r.travel_time > 0.0));
    }

    /// A member's rays land (re-evaluated by the closed form), see no shift between static
    /// ends, and the reach is ρ_c for m² < 4Ω², everything for causal members.
    #[test]
    fn members_rays_land_and_static_ends_see_no_shift() {
        let omega = 0.7;
        for ratio in [-1.0, 0.0, 2.0, 4.0, 6.0] {
            let member = GodelType::new(ratio * omega * omega, omega);
            let source = Event::new(0.0, 0.6, -0.3, 0.35);
            let event = Event::new(2.0, 0.2, 0.4, 1.1);
            assert_eq!(type_on_the_source_axis(member, source, event), None);
            let c = type_connections(member, source, event, 2).unwrap();
            assert!(c.within_horizon() && !c.rays.is_empty(), "m²/Ω² = {ratio}");
            assert_eq!(c.reach, member.critical_radius());
            for ray in &c.rays {
                assert!(ray.miss < 1e-9, "m²/Ω² = {ratio}: {}", ray.miss);
                assert!((ray.g - 1.0).abs() < 1e-9, "m²/Ω² = {ratio}: {}", ray.g);
                assert!(ray.area_distance > 0.0);
            }
            let above = Event::new(2.0, 0.6, -0.3, 1.0);
            assert_eq!(
                type_on_the_source_axis(member, source, above),
                Some(OnTheSourceAxis::OnItsAxis)
            );
        }
    }
}
