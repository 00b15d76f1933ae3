//! What the explore map draws (docs/guide/src/explore.md; docs/physics.md, "The explore map"):
//! for an observer's event, its optical horizon in the x–y plane, the scene's balls where
//! they are at the observer's time and their worldline tracks, and one pixel's light ray from
//! the observer back to where it was emitted.
//!
//! - The horizon: an observer on the axis sees nothing beyond r = 2a ("Conventions"); for any
//!   other event it is that circle carried by the isometry T_P⁻¹ that takes the origin to the
//!   event ("Isometries"). The curve is drawn at the observer's z (T_P moves z only by a shift).
//!   In a Gödel-type member ("The Gödel-type family") the circle is ρ = ρ_c, where closed
//!   timelike curves begin and where the in-plane light rays from the axis turn back, carried
//!   by the member's T_P⁻¹ ("Isometries of the family"); a causal member (m² ≥ 4Ω²) has none.
//! - Every point of the map also carries r, its distance from the *observer's* axis: the
//!   cylindrical radius after T_P (so the horizon is r = 2a in the side view, t against r); in
//!   a member the proper radius ρ after the member's T_P.
//! - A ball at rest stays at its position; a ball in free fall is on its worldline
//!   (`worldline`), at the proper time whose coordinate time is the one asked (Newton on
//!   t(τ), dt/dτ = u^t > 0).
//! - A pixel's light ray is the exact geodesic ("Isometries", exact geodesics from any event;
//!   in a member "Closed-form geodesics of the family") with the tangent the tracer launched (`photon_tangent` of the record's `view` in the
//!   observer's frame), sampled from λ = 0 (the observer) to the record's affine parameter
//!   at the hit; a ray that hit nothing is drawn until it reaches the trace's past limit, or
//!   in a member with m² > 0 until it is as far from the axis as scenes' positions may be.
//!   In Minkowski space the rays are straight and there is no horizon.

use crate::worldline::{Worldline, WorldlineError};
use datafile::PixelRecord;
use scene::{Motion, Scene, Shape};
use spacetime::{
    photon_tangent, Event, ExactGeodesic, FourVector, Isometry, Metric, Spacetime, TimeDirection,
    TypeExactGeodesic, TypeIsometry,
};

/// Points of the horizon curve.
pub const HORIZON_POINTS: usize = 256;
/// Points of an object's track.
pub const TRACK_POINTS: usize = 512;
/// The most points of a light ray.
pub const MAX_RAY_POINTS: usize = 4096;
/// Points per loop of a light ray (a loop returns to the observer's axis).
const POINTS_PER_LOOP: f64 = 96.0;
/// Newton steps for the proper time of a coordinate time on a worldline.
const MAX_NEWTON_STEPS: usize = 40;
/// Doublings and halvings in the search for the parameter where a ray reaches a time.
const MAX_SEARCH_STEPS: usize = 200;

/// An event with its distance from the observer's axis.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MapPoint {
    pub t: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
    /// Cylindrical radius about the observer's axis (after the isometry to the origin).
    pub r: f64,
}

/// A ball on the map.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MapObject {
    /// Index in the scene file (as the data file's `object`).
    pub index: usize,
    pub name: String,
    /// Proper radius of a ball; coordinate radius of a coordinate sphere.
    pub radius: f64,
    /// Whether it falls freely (else at rest).
    pub moving: bool,
    /// Where it is at the observer's time (`None` outside its computed worldline).
    pub at: Option<MapPoint>,
    /// Its worldline over the map's time range, t increasing.
    pub track: Vec<MapPoint>,
}

/// A Gödel-type member on the map: its constants, and the unit the page sizes its view by.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MemberMap {
    pub m2: f64,
    pub omega: f64,
    /// The member's length scale, min(1/(√2 Ω), 1/|m|) (`Metric::length_scale`): what a is
    /// to Gödel's map.
    pub unit: f64,
}

/// The map of an observer's event.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Map {
    /// Gödel's parameter (`None` in Minkowski space and in a Gödel-type member).
    pub a: Option<f64>,
    pub event: MapPoint,
    /// The horizon's radius about the observer's axis: 2a in Gödel's universe, ρ_c in a
    /// Gödel-type member; `None` without a horizon.
    pub horizon_radius: Option<f64>,
    /// The horizon in the x–y plane, a closed curve (first point not repeated); empty in
    /// Minkowski space and in a causal member.
    pub horizon: Vec<[f64; 2]>,
    /// The span of the tracks: from the trace's past limit to the observer's time.
    pub time_range: [f64; 2],
    /// The scene's balls (planes are left out).
    pub objects: Vec<MapObject>,
    /// The Gödel-type member, if the scene is one. Left out of the JSON otherwise, so that
    /// Gödel's and Minkowski's maps read as before.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub member: Option<MemberMap>,
}

/// One pixel's light ray.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct LightRay {
    /// From the observer (first) into the past: to the emission event (last) for a hit,
    /// to the trace's past limit otherwise (or where a member's escaping ray leaves the reach
    /// of scenes' positions).
    pub points: Vec<MapPoint>,
    /// The emission event of the record (a hit only).
    pub emission: Option<MapPoint>,
    /// −t_emit (a hit only).
    pub travel_time: Option<f64>,
}

/// T_P, the isometry that takes the observer's event to the origin.
#[derive(Clone, Copy, Debug)]
enum ToOrigin {
    Godel(Isometry),
    Member(TypeIsometry),
    /// Minkowski space; also a member's event outside its chart (at or beyond the pole of the
    /// sphere m² < 0, where scenes keep no observer): distances in the x–y plane, no horizon.
    Flat,
}

/// Distances from the axis of an observer at `observer`.
#[derive(Clone, Copy, Debug)]
pub struct ObserverAxis {
    observer: Event,
    to_origin: ToOrigin,
    /// The horizon's radius about the axis (2a; ρ_c in a member).
    horizon_radius: Option<f64>,
}

impl ObserverAxis {
    pub fn new(metric: Metric, observer: Event) -> ObserverAxis {
        let (to_origin, horizon_radius) = match metric {
            Metric::Godel(g) => (
                ToOrigin::Godel(Isometry::to_origin(g.a, observer)),
                Some(2.0 * g.a),
            ),
            Metric::GodelType(member) => match TypeIsometry::to_origin(member, observer) {
                Some(to) => (ToOrigin::Member(to), member.critical_radius()),
                None => (ToOrigin::Flat, None),
            },
            Metric::Minkowski(_) => (ToOrigin::Flat, None),
        };
        ObserverAxis {
            observer,
            to_origin,
            horizon_radius,
        }
    }

    /// The horizon's radius about the observer's axis: 2a in Gödel's universe, ρ_c in a
    /// Gödel-type member; `None` in Minkowski space and in a causal member.
    pub fn horizon_radius(&self) -> Option<f64> {
        self.horizon_radius
    }

    /// `e` with its radius from the observer's axis.
    pub fn point(&self, e: Event) -> MapPoint {
        let r = match self.to_origin {
            ToOrigin::Godel(iso) => iso.apply(e).r(),
            ToOrigin::Member(iso) => iso.apply(e).r(),
            ToOrigin::Flat => (e.x - self.observer.x).hypot(e.y - self.observer.y),
        };
        MapPoint {
            t: e.t,
            x: e.x,
            y: e.y,
            z: e.z,
            r,
        }
    }

    /// The observer's optical horizon in the x–y plane: the circle of the horizon's radius
    /// about the axis carried to the observer, in `points` points; empty without a horizon.
    pub fn horizon(&self, points: usize) -> Vec<[f64; 2]> {
        let Some(radius) = self.horizon_radius else {
            return Vec::new();
        };
        let back = |e: Event| match self.to_origin {
            ToOrigin::Godel(to) => to.inverse().apply(e),
            ToOrigin::Member(to) => to.inverse().apply(e),
            // Not reached: flat distances come with no horizon radius.
            ToOrigin::Flat => e,
        };
        (0..points)
            .map(|k| {
                let phi = std::f64::consts::TAU * k as f64 / points as f64;
                let e = back(Event::new(0.0, radius * phi.cos(), radius * phi.sin(), 0.0));
                [e.x, e.y]
            })
            .collect()
    }
}

/// The map of `scene` seen from `observer`: horizon, balls at the observer's time, tracks
/// over the scene's `max_past` before it.
pub fn map(scene: &Scene, observer: Event) -> Result<Map, (String, WorldlineError)> {
    let metric = scene.metric;
    let axis = ObserverAxis::new(metric, observer);
    let (t0, t1) = (observer.t - scene.trace.max_past, observer.t);
    let mut objects = Vec::new();
    for (index, o) in scene.objects.iter().enumerate() {
        let radius = match o.shape {
            Shape::Sphere { radius } | Shape::CoordinateSphere { radius, .. } => radius,
            Shape::Plane { .. } => continue,
        };
        let line = Worldline::new(metric, &o.motion, t0 - 1.0, t1 + 1.0)
            .map_err(|e| (o.name.clone(), e))?;
        let at_time = |t: f64| position_at(&metric, &line, t).map(|e| axis.point(e));
        let track = (0..TRACK_POINTS)
            .filter_map(|k| at_time(t0 + (t1 - t0) * k as f64 / (TRACK_POINTS - 1) as f64))
            .collect();
        objects.push(MapObject {
            index,
            name: o.name.clone(),
            radius,
            moving: matches!(o.motion, Motion::Geodesic { .. }),
            at: at_time(t1),
            track,
        });
    }
    Ok(Map {
        a: metric.godel_a(),
        event: axis.point(observer),
        horizon_radius: axis.horizon_radius(),
        horizon: axis.horizon(HORIZON_POINTS),
        time_range: [t0, t1],
        objects,
        member: metric.godel_type().map(|m| MemberMap {
            m2: m.m2,
            omega: m.omega,
            unit: metric.length_scale(),
        }),
    })
}

/// Where the worldline is at coordinate time `t` (`None` outside its computed range or if
/// Newton's method does not settle).
pub fn position_at(metric: &Metric, line: &Worldline, t: f64) -> Option<Event> {
    if let Worldline::Rest { position, .. } = line {
        return Some(Event::new(t, position.x, position.y, position.z));
    }
    let mut tau = line.tau_guess(t);
    for _ in 0..MAX_NEWTON_STEPS {
        let p = line.at(metric, tau)?;
        let dt = p.event.t - t;
        if dt.abs() <= 1e-12 * (1.0 + t.abs()) {
            return Some(p.event);
        }
        let ut = p.frame.e[0].t;
        if !(ut > 0.0) {
            return None;
        }
        tau -= dt / ut;
    }
    None
}

/// The light ray of a pixel whose record is `record`, for an observer at `observer` moving
/// with the scene observer's velocity; `max_past` ends a ray that hit nothing. A pixel that
/// was not traced (zero `view`) has no ray: empty points.
pub fn light_ray(scene: &Scene, observer: Event, record: &PixelRecord) -> LightRay {
    let none = LightRay {
        points: Vec::new(),
        emission: None,
        travel_time: None,
    };
    // The stored direction is rounded to f32: made a unit vector again, so that the tangent
    // is null (the closed form refuses a spacelike one).
    let n = record.view.map(f64::from);
    let len = n.iter().map(|c| c * c).sum::<f64>().sqrt();
    if !(len > 0.0 && len.is_finite()) {
        return none;
    }
    let n = n.map(|c| c / len);
    let metric = scene.metric;
    let axis = ObserverAxis::new(metric, observer);
    let frame = metric.observer_frame(observer, scene.observer.velocity);
    let k = photon_tangent(&frame, n, TimeDirection::Past);
    let ray = Ray::new(metric, observer, k);
    let hit = record.has_emission() && record.lambda.is_finite();
    let lambda_end = if hit {
        f64::from(record.lambda)
    } else {
        let past = observer.t - scene.trace.max_past;
        // A member's escaping ray (m² > 0) runs out as e^{mρ}: it ends where scenes' positions
        // end (mρ = 30, `scene::ranges::check_member_radius`), beyond which the coordinates
        // lose the precision of f64. On the sphere (m² < 0) every ray returns.
        let far = |e: Event| match metric.godel_type() {
            Some(member) if member.m2 > 0.0 => {
                scene::ranges::check_member_radius(member, e.r()).is_err()
            }
            _ => false,
        };
        ray.parameter_where(|e| e.t <= past || far(e))
    };
    let count = (ray.loops(lambda_end) * POINTS_PER_LOOP).ceil();
    let count = (count.max(2.0) as usize).min(MAX_RAY_POINTS - 1);
    // The first point is the observer's event itself (the isometries' round trip would
    // move it by rounding).
    let points = std::iter::once(axis.point(observer))
        .chain((1..=count).map(|i| axis.point(ray.at(lambda_end * i as f64 / count as f64))))
        .collect();
    let emission = hit.then(|| {
        axis.point(Event::new(
            observer.t + f64::from(record.t_emit),
            f64::from(record.x),
            f64::from(record.y),
            f64::from(record.z),
        ))
    });
    LightRay {
        points,
        emission,
        travel_time: hit.then(|| -f64::from(record.t_emit)),
    }
}

/// A light ray from the observer: the exact geodesic in Gödel's universe and in a Gödel-type
/// member, a straight line in Minkowski space (and where a closed form refuses the event).
enum Ray {
    Godel(ExactGeodesic),
    Member(TypeExactGeodesic),
    Straight(Event, FourVector),
}

impl Ray {
    fn new(metric: Metric, at: Event, k: FourVector) -> Ray {
        let exact = match metric {
            Metric::Godel(g) => ExactGeodesic::new(g.a, at, k).map(Ray::Godel),
            Metric::GodelType(m) => TypeExactGeodesic::new(m, at, k).map(Ray::Member),
            Metric::Minkowski(_) => None,
        };
        exact.unwrap_or(Ray::Straight(at, k))
    }

    fn at(&self, lambda: f64) -> Event {
        match self {
            Ray::Godel(g) => g.at(lambda).0,
            Ray::Member(g) => g.at(lambda).0,
            Ray::Straight(at, k) => at.offset(*k, lambda),
        }
    }

    /// How many returns to the observer's axis the ray makes up to `lambda` (at least 1, so
    /// that a short ray still gets enough points to look smooth; 1 for a member's ray that
    /// escapes).
    fn loops(&self, lambda: f64) -> f64 {
        match self {
            Ray::Godel(g) => (lambda / g.origin.return_parameter()).max(1.0),
            Ray::Member(g) => g
                .origin
                .return_parameter()
                .map_or(1.0, |period| (lambda / period).max(1.0)),
            Ray::Straight(..) => 1.0,
        }
    }

    /// The parameter at which the past-directed ray first has `ended` (reached the past limit,
    /// t decreasing along it; or left the coordinates' reach): doubling, then bisection, each
    /// bounded.
    fn parameter_where(&self, ended: impl Fn(Event) -> bool) -> f64 {
        let mut hi = 1.0;
        for _ in 0..MAX_SEARCH_STEPS {
            if ended(self.at(hi)) {
                break;
            }
            hi *= 2.0;
        }
        let mut lo = 0.0;
        for _ in 0..MAX_SEARCH_STEPS {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if !ended(self.at(mid)) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }
}
