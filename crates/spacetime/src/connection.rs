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

use crate::measure::{frequency_ratio, vector_components};
use crate::{
    shadow_rays, source_area_distance_sq, Event, ExactGeodesic, FourVector, Godel, Isometry,
    ShadowRay, Spacetime,
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
    pub a: f64,
    pub event: Event,
    /// The source's position (t = 0).
    pub source: Event,
    /// The event's distance from the source's axis in the source's frame (horizon at 2a).
    pub rho: f64,
    /// Latest emission first.
    pub rays: Vec<Connection>,
}

impl Connections {
    /// Whether the event lies within the source's horizon (else there is no ray).
    pub fn within_horizon(&self) -> bool {
        self.rho < 2.0 * self.a
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

/// Local spatial components of `v` in the static frame at `at`, normalized.
fn local_direction(metric: &Godel, at: Event, v: FourVector) -> [f64; 3] {
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
    let metric = Godel::new(a);
    let rho = Isometry::to_origin(a, source).apply(event).r();
    let static_u = |at: Event| metric.static_frame(at).e[0];
    let rays = shadow_rays(a, source, event, windings.min(MAX_WINDINGS))
        .into_iter()
        .map(|ray| {
            let g = ExactGeodesic::new(a, ray.emission, ray.tangent)?;
            let (end, k_end) = g.at(ray.lambda);
            let miss = (end - event)
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
                area_distance: source_area_distance_sq(a, source, &ray).sqrt(),
                g: shift,
                miss,
            })
        })
        .collect::<Option<Vec<_>>>()?;
    Some(Connections {
        a,
        event,
        source,
        rho,
        rays,
    })
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
}
