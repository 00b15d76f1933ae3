//! The explore map (`render::map`) against independent computations: the horizon curve of an
//! observer off the axis against numerically integrated light rays from that observer; a
//! pixel's map ray against the tracer's record of that pixel; the tracks of balls against
//! their scene positions and the closed form of a timelike geodesic.

use crate::common;

use render::map::{light_ray, map, MapPoint, ObserverAxis, HORIZON_POINTS};
use scene::Scene;
use spacetime::{trace, Event, ExactGeodesic, Geodesic, Spacetime, TimeDirection, TraceLimits};

/// Distance from (px, py) to the segment from `a` to `b`.
fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let s = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - s * dx).hypot(p[1] - a[1] - s * dy)
}

/// Distance from `p` to the closed polygon `curve`.
fn curve_distance(p: [f64; 2], curve: &[[f64; 2]]) -> f64 {
    (0..curve.len())
        .map(|i| segment_distance(p, curve[i], curve[(i + 1) % curve.len()]))
        .fold(f64::INFINITY, f64::min)
}

/// Whether `p` is inside the closed polygon `curve` (even–odd rule).
fn inside(p: [f64; 2], curve: &[[f64; 2]]) -> bool {
    let mut inside = false;
    for i in 0..curve.len() {
        let (a, b) = (curve[i], curve[(i + 1) % curve.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

fn scene_with(observer: &str, method: &str, objects: &str) -> Scene {
    let text = format!(
        "name = \"map\"\n[spacetime]\nmetric = \"godel\"\na = 1.0\n{observer}\n{}\n{}\n{objects}",
        testkit::panorama(360.0, 60.0, 72, 12),
        testkit::trace(method, 12.0),
    );
    common::scene(&text)
}

const OFF_AXIS_OBSERVER: &str =
    "[observer]\ntime = 0.4\nposition = { x = 0.9, y = -0.5, z = 0.2 }\n\
    velocity = { speed = 0.6, direction = [0, 1, 0.3] }\nforward = [1, 0, 0]\nup = [0, 0, 1]\n";

/// Light rays leave an observer off the axis in every direction of its x–y plane (integrated
/// numerically, not by the closed form or the isometry): none leaves the horizon curve the
/// map draws for it, and each touches it.
#[test]
fn the_horizon_curve_bounds_and_touches_every_light_ray_of_the_observer_plane() {
    let s = scene_with(OFF_AXIS_OBSERVER, "exact", "");
    let observer = s.observer.event;
    let m = map(&s, observer).unwrap();
    assert_eq!(m.horizon.len(), HORIZON_POINTS);
    assert_eq!(m.horizon_radius, Some(2.0));
    let axis = ObserverAxis::new(s.metric, observer);
    assert_eq!(m.horizon, axis.horizon(HORIZON_POINTS));
    // Finely sampled, so that the polygon's chords are within 1e-6 of the curve.
    let horizon = axis.horizon(8192);
    // The curve is no circle about the observer: its extent differs by direction.
    let extent: Vec<f64> = m
        .horizon
        .iter()
        .map(|p| (p[0] - observer.x).hypot(p[1] - observer.y))
        .collect();
    let (lo, hi) = extent.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &d| {
        (lo.min(d), hi.max(d))
    });
    assert!(hi / lo > 1.2, "extent {lo}..{hi}");
    let frame = s.metric.static_frame(observer);
    for k in 0..24 {
        let az = std::f64::consts::TAU * (k as f64 + 0.3) / 24.0;
        let g = Geodesic::launch(
            &s.metric,
            observer,
            &frame,
            [az.cos(), az.sin(), 0.0],
            1.0,
            TimeDirection::Past,
        )
        .unwrap();
        let limits = TraceLimits {
            until_time: Some(2.0 * std::f64::consts::SQRT_2 * std::f64::consts::PI),
            ..TraceLimits::default()
        };
        let traced = trace(s.metric, &g, &limits);
        assert!(!traced.stop.is_failure(), "{:?}", traced.stop);
        let points: Vec<[f64; 2]> = traced
            .samples(2000)
            .iter()
            .map(|(_, st)| {
                assert!((st.x.z - observer.z).abs() < 1e-9, "the ray left its plane");
                [st.x.x, st.x.y]
            })
            .collect();
        let mut nearest = f64::INFINITY;
        for &p in &points[1..] {
            let d = curve_distance(p, &horizon);
            nearest = nearest.min(d);
            assert!(
                inside(p, &horizon) || d < 1e-6,
                "ray {k}: {p:?} outside, {d}"
            );
        }
        assert!(nearest < 1e-4, "ray {k} stays {nearest} from the horizon");
    }
}

/// For every traced pixel of a scene with a ball at rest and one in free fall, seen by a
/// moving observer off the axis, the map's ray starts at the observer and ends at the
/// emission event of the pixel's record (hits) or at the trace's past limit (misses).
#[test]
fn each_pixel_ray_runs_from_the_observer_to_its_emission_event() {
    let objects = testkit::ball_at_rest("still", 0.3, 1.2, 0.5)
        + "[[object]]\nname = \"falling\"\nradius = 0.25\n\
           motion = { kind = \"geodesic\", time = 0.0, position = { x = -0.6, y = 0.2, z = 0.0 }, speed = 0.7, direction = [1, 0, 0] }\n";
    for method in ["exact", "numeric"] {
        let s = scene_with(OFF_AXIS_OBSERVER, method, &objects);
        let observer = s.observer.event;
        let (data, _) = common::render_scene(&s);
        let (mut hits, mut misses) = (0, 0);
        for (i, record) in data.records.iter().enumerate() {
            let ray = light_ray(&s, observer, record);
            let first = ray.points[0];
            assert_eq!(
                (first.t, first.x, first.y, first.z),
                (observer.t, observer.x, observer.y, observer.z)
            );
            assert!(first.r < 1e-12, "{first:?}");
            let last = *ray.points.last().unwrap();
            let close = |p: MapPoint, q: MapPoint, tol: f64| {
                [p.t - q.t, p.x - q.x, p.y - q.y, p.z - q.z]
                    .iter()
                    .all(|d| d.abs() < tol)
            };
            if record.has_emission() {
                hits += 1;
                let e = ray.emission.unwrap();
                assert!(
                    close(last, e, 2e-4),
                    "{method} pixel {i}: {last:?} vs {e:?}"
                );
                assert_eq!(ray.travel_time, Some(-f64::from(record.t_emit)));
                assert!((e.t - (observer.t + f64::from(record.t_emit))).abs() < 1e-12);
            } else {
                misses += 1;
                assert!(ray.emission.is_none());
                let limit = observer.t - s.trace.max_past;
                assert!(
                    (last.t - limit).abs() < 1e-9,
                    "{method} pixel {i}: {last:?}"
                );
            }
            // No point of the ray is beyond the observer's horizon. (Coordinate time need not
            // fall monotonically along a ray that does not start on the axis: the isometry
            // to the observer shifts t by an amount that depends on the position.)
            for p in &ray.points {
                assert!(p.r <= 2.0 + 1e-9, "{method} pixel {i}: {p:?}");
            }
            assert!(last.t < first.t);
        }
        assert!(
            hits > 20 && misses > 40,
            "{method}: {hits} hits, {misses} misses"
        );
    }
}

/// The ball at rest is where the scene puts it at every time; the falling ball's track is
/// the closed-form timelike geodesic through its start event (independent of the
/// integrated worldline the map reads), and it is at its start position at the start time.
#[test]
fn balls_are_at_their_scene_positions_and_on_their_geodesics() {
    let objects = testkit::ball_at_rest("still", 0.3, 1.2, 0.5)
        + "[[object]]\nname = \"falling\"\nradius = 0.15\n\
           motion = { kind = \"geodesic\", time = -3.0, position = { x = 0.4, y = -0.3, z = 0.1 }, speed = 0.8, direction = [0.2, 1, 0.1] }\n";
    let s = scene_with(OFF_AXIS_OBSERVER, "exact", &objects);
    let observer = s.observer.event;
    let m = map(&s, observer).unwrap();
    assert_eq!(m.time_range, [observer.t - 12.0, observer.t]);
    assert_eq!(m.objects.len(), 2);
    let still = &m.objects[0];
    assert!(!still.moving && still.radius == 0.3 && still.index == 0);
    let (x, y) = (1.2 * 0.5f64.cos(), 1.2 * 0.5f64.sin());
    for p in still.track.iter().chain(still.at.iter()) {
        assert!((p.x - x).abs() < 1e-12 && (p.y - y).abs() < 1e-12 && p.z == 0.0);
    }
    assert_eq!(still.at.unwrap().t, observer.t);

    let falling = &m.objects[1];
    assert!(falling.moving && falling.index == 1);
    assert!(falling.track.len() > 500, "{}", falling.track.len());
    let Some(scene::Motion::Geodesic { start, velocity }) = s.objects.get(1).map(|o| o.motion)
    else {
        panic!("the falling ball's motion")
    };
    let u = s.metric.observer_frame(start, velocity).e[0];
    let closed = ExactGeodesic::new(1.0, start, u).unwrap();
    // The closed form at coordinate time t (t grows along it): bisection in τ.
    let at_time = |t: f64| {
        let (mut lo, mut hi) = (-40.0, 40.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if closed.at(mid).0.t < t {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        closed.at(0.5 * (lo + hi)).0
    };
    for p in falling.track.iter().step_by(16).chain(falling.at.iter()) {
        let e = at_time(p.t);
        let d = (e.x - p.x)
            .abs()
            .max((e.y - p.y).abs())
            .max((e.z - p.z).abs());
        assert!(d < 1e-6, "t = {}: map {p:?}, closed form {e:?}", p.t);
    }
    let start_point = render::map::position_at(
        &s.metric,
        &render::worldline::Worldline::new(s.metric, &s.objects[1].motion, -20.0, 2.0).unwrap(),
        start.t,
    )
    .unwrap();
    let e = Event::new(start.t, start.x, start.y, start.z);
    assert!((start_point.x - e.x).abs() < 1e-9 && (start_point.y - e.y).abs() < 1e-9);
}
