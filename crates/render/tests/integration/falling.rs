//! Rejection of balls in free fall loop by loop (`render::falling`, docs/physics.md "Balls
//! in free fall" and "Occlusion"): the reach and time slack cover the renderer's own ball,
//! no loop stretch where a ray is inside a falling ball is left out, and records and direct
//! light are the same, bit for bit, with and without the rejection (and an over-eager bound
//! is caught by that comparison).

use crate::common::{self, norm, tracer, unit};
use proptest::prelude::*;
use render::circle::RayCircle;
use render::falling::{FallingBall, LoopWindow, REACH_PER_RADIUS};
use render::reject::static_distance;
use render::target::Target;
use render::tracer::Tracer;
use render::worldline::{Located, Worldline};
use scene::Motion;
use spacetime::{
    photon_tangent, Event, ExactGeodesic, GeodesicState, Godel, LocalVelocity, Metric, Spacetime,
    TimeDirection,
};

/// Bound asserted below on (static distance)/|ξ| and on the time offset over √2·|ξ|, below
/// [`REACH_PER_RADIUS`].
const RATIO: f64 = 1.05;

/// A ball of `radius` falling freely from `start` with `speed` along `dir`, its worldline
/// covering coordinate times [t_min, t_max].
fn falling(a: f64, start: Event, speed: f64, dir: [f64; 3], radius: f64, t: (f64, f64)) -> Target {
    let metric = Metric::Godel(Godel::new(a));
    let motion = Motion::Geodesic {
        start,
        velocity: LocalVelocity::new(speed, dir).unwrap(),
    };
    Target::LocalSphere {
        radius,
        worldline: Worldline::new(metric, &motion, t.0, t.1).unwrap(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, max_global_rejects: 100_000, ..ProptestConfig::default() })]

    /// The renderer's falling ball is |ξ| ≤ R at the simultaneous centre P (second-order
    /// normal coordinates). For every point X with |ξ| ≤ a/2 (the largest radius allowed),
    /// the centre's point Q that the static observer at X counts as simultaneous (X − Q
    /// orthogonal to ∂t, found by bisection on the worldline) lies within static distance
    /// RATIO·|ξ| of X and within coordinate time RATIO·√2·|ξ| of it, within the reach and slack
    /// the rejection uses.
    #[test]
    fn a_falling_ball_lies_within_its_reach(
        a in 0.2f64..5.0,
        s in prop::array::uniform3(-3.0f64..3.0),
        speed in 0.0f64..0.95, dir in prop::array::uniform3(-1.0f64..1.0),
        tau in -3.0f64..3.0,
        xi in prop::array::uniform3(-1.0f64..1.0), len in 0.0f64..0.55,
    ) {
        prop_assume!(norm(dir) > 1e-3 && norm(xi) > 1e-3);
        let metric = Metric::Godel(Godel::new(a));
        let start = Event::new(0.0, a * s[0], a * s[1], a * s[2]);
        let Target::LocalSphere { worldline, .. } =
            falling(a, start, speed, dir, 0.1 * a, (-20.0 * a, 20.0 * a)) else { unreachable!() };
        let p = worldline.at(&metric, tau * a);
        prop_assume!(p.is_some());
        let p = p.unwrap();
        // A displacement of proper length ~len·a in the ball's rest frame.
        let d = unit(xi);
        let e = p.frame.e.map(|v| v.to_array());
        let c = |k: usize| a * len * (d[0] * e[1][k] + d[1] * e[2][k] + d[2] * e[3][k]);
        let x = Event::new(
            p.event.t + c(0), p.event.x + c(1), p.event.y + c(2), p.event.z + c(3),
        );
        let lp = worldline.localize(&metric, x, tau * a, f64::INFINITY).and_then(Located::near).unwrap();
        let r = norm(lp.xi);
        prop_assume!(r <= 0.5 * a && r > 1e-6 * a);
        // g(Q − X, ∂t) = −Δt + g_ti Δx^i at X (g_tt = −1): at P at most about
        // γ|ξ|(v + 2√2) in size, growing along the worldline at about γ a unit of proper
        // time, so it changes sign within about 4|ξ| of P's proper time (bracketed by 6|ξ|).
        let g = metric.metric(x);
        let q_at = |t: f64| worldline.at(&metric, t).unwrap().event;
        let tilt = |t: f64| {
            let q = q_at(t);
            (q.t - x.t) - g[0][1] * (q.x - x.x) - g[0][2] * (q.y - x.y)
        };
        let (mut lo, mut hi) = (lp.at.tau - 6.0 * r, lp.at.tau + 6.0 * r);
        prop_assert!(tilt(lo) < 0.0 && tilt(hi) > 0.0, "no static-simultaneous point bracketed");
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if tilt(mid) < 0.0 { lo = mid } else { hi = mid }
        }
        let q = q_at(0.5 * (lo + hi));
        let dist = static_distance(a, [q.x, q.y, q.z], [x.x, x.y, x.z]);
        prop_assert!(dist <= RATIO * r + 1e-12 * a, "static distance {dist} against |ξ| = {r}");
        let dt = (x.t - q.t).abs();
        prop_assert!(
            dt <= RATIO * std::f64::consts::SQRT_2 * r + 1e-12 * a,
            "time offset {dt} against √2·|ξ| = {}", std::f64::consts::SQRT_2 * r
        );
        prop_assert!(RATIO < REACH_PER_RADIUS);
    }

    /// Rays from random events near a falling ball's path, past-directed from the test's
    /// event (a pixel ray's) or from the same place earlier, either way (a shadow ray's, whose
    /// test is made at the light's event): wherever the ray (sampled over its loops) is inside
    /// the renderer's ball, its loop searches the ball there.
    #[test]
    fn no_stretch_inside_a_falling_ball_is_left_out(
        a in 0.5f64..2.0,
        o in prop::array::uniform3(-0.5f64..0.5), t0 in -2.0f64..2.0,
        n in prop::array::uniform3(-1.0f64..1.0),
        s in prop::array::uniform3(-1.0f64..1.0),
        speed in 0.0f64..0.9, dir in prop::array::uniform3(-1.0f64..1.0),
        radius in 0.1f64..0.5,
        earlier in prop::sample::select(vec![0.0, 0.0, 0.5, 3.0, 8.0]),
        future in any::<bool>(),
    ) {
        prop_assume!(norm(n) > 1e-3 && norm(dir) > 1e-3);
        let metric = Metric::Godel(Godel::new(a));
        let obs = Event::new(t0, a * o[0], a * o[1], 0.2 * a * o[2]);
        let from = Event::new(t0 - earlier * a, obs.x, obs.y, obs.z);
        let start = Event::new(0.0, a * s[0], a * s[1], 0.2 * a * s[2]);
        let target = falling(a, start, speed, dir, radius * a, (t0 - 12.0 * a, t0 + 2.0 * a));
        let way = if future && earlier > 0.0 { TimeDirection::Future } else { TimeDirection::Past };
        let k = photon_tangent(&metric.static_frame(from), unit(n), way);
        let geo = ExactGeodesic::new(a, from, k).unwrap();
        let ball = FallingBall::new(a, &metric, obs, &target).unwrap();
        let circle = RayCircle::new(&geo.origin);
        let mut loops = Vec::new();
        prop_assert!(ball.loops(&circle, from.t - obs.t, f64::INFINITY, false, &mut loops));
        let l_ret = geo.origin.return_parameter();
        let samples = 4000;
        let end = 4.0 * l_ret;
        for i in 0..=samples {
            let l = end * i as f64 / samples as f64;
            let (x, k) = geo.at(l);
            if x.t < t0 - 10.0 * a || x.t > t0 + 1.5 * a {
                break;
            }
            let st = GeodesicState { x, p: metric.lower(x, k) };
            if target.probe(&metric, &st, f64::NAN).f <= 0.0 {
                let lp = (l / l_ret).floor() as usize;
                let window = loops.get(lp).copied().unwrap_or(LoopWindow::NONE);
                // (At a loop's start the difference can round below 0: λ = 3·λ_ret sampled as
                // 4·λ_ret·3000/4000, with floor(λ/λ_ret) = 3.)
                let at = (l - lp as f64 * l_ret).max(0.0);
                prop_assert!(
                    window.meets(at, at),
                    "inside at λ = {l} (loop {lp}), but searched only over {window:?}"
                );
            }
        }
    }
}

/// A random scene of falling balls (start place, speed, direction, radius) and maybe one
/// at rest, seen by a full-sphere camera from the origin.
fn scene_text(
    a: f64,
    balls: &[([f64; 3], f64, [f64; 3], f64)],
    max_past: f64,
    method: &str,
) -> String {
    let mut text = format!(
        "name = \"f\"\n[spacetime]\nmetric = \"godel\"\na = {a}\n\
         [observer]\ntime = 0.0\nposition = {{ x = 0.0, y = 0.0, z = 0.0 }}\n\
         forward = [-1, 0, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"sphere\"\nwidth = 48\nheight = 24\n\
         [trace]\nmethod = \"{method}\"\nmax_past = {max_past}\n"
    );
    for (i, (p, speed, d, r)) in balls.iter().enumerate() {
        text += &format!(
            "[[object]]\nname = \"b{i}\"\nradius = {r}\ntexture = {{ kind = \"checker\", rows = 4, cols = 8 }}\n\
             motion = {{ kind = \"geodesic\", time = 0.0, position = {{ x = {}, y = {}, z = {} }}, \
             speed = {speed}, direction = [{}, {}, {}] }}\n",
            p[0], p[1], p[2], d[0], d[1], d[2]
        );
    }
    text
}

/// Falling balls from random places near the observer, random speeds and directions, and
/// radii as fractions of the largest one allowed.
fn balls() -> impl Strategy<Value = Vec<([f64; 3], f64, [f64; 3], f64)>> {
    prop::collection::vec(
        (
            prop::array::uniform3(-1.2f64..1.2),
            0.0f64..0.9,
            prop::array::uniform3(-1.0f64..1.0),
            0.1f64..0.9,
        ),
        1..3,
    )
    .prop_filter("a direction", |v| v.iter().all(|b| norm(b.2) > 1e-2))
}

/// Every pixel's record, as text, of `tracer` on `sc`.
fn records(tracer: &Tracer, sc: &scene::Scene) -> Vec<String> {
    let mut scratch = tracer.scratch();
    let mut out = Vec::new();
    for row in 0..sc.camera.height() {
        for col in 0..sc.camera.width() {
            let n = sc.observer.pixel_direction(&sc.camera, col, row).unwrap();
            out.push(format!("{:?}", tracer.trace(n, &mut scratch).record));
        }
    }
    out
}

fn scaled_balls(
    a: f64,
    b: &[([f64; 3], f64, [f64; 3], f64)],
) -> Vec<([f64; 3], f64, [f64; 3], f64)> {
    b.iter()
        // Radius a fraction of the largest allowed, a/(2γ²).
        .map(|(p, s, d, r)| {
            (
                [a * p[0], a * p[1], 0.3 * a * p[2]],
                *s,
                *d,
                0.5 * r * a * (1.0 - s * s),
            )
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Every pixel's record is the same, bit for bit, with the rejection as without it, for
    /// both tracers and one or two balls in free fall anywhere near the observer.
    #[test]
    fn records_with_falling_balls_are_the_same_with_and_without_rejection(
        a in 0.5f64..2.0,
        b in balls(),
        max_past in 2.0f64..14.0,
        exact in any::<bool>(),
    ) {
        let method = if exact { "exact" } else { "numeric" };
        let text = scene_text(a, &scaled_balls(a, &b), max_past * a, method);
        let sc = scene::Scene::from_str(&text, "falling.toml").unwrap();
        let with = records(&tracer(&sc), &sc);
        let without = records(&tracer(&sc).without_rejection(), &sc);
        for (i, (r1, r2)) in with.iter().zip(&without).enumerate() {
            prop_assert_eq!(r1, r2, "pixel {}", i);
        }
    }

    /// Shadow rays: the direct light at every hit is the same, bit for bit, with the
    /// rejection as without it, with balls in free fall between the lights and the hits.
    #[test]
    fn direct_light_with_falling_balls_is_the_same_with_and_without_rejection(
        a in 0.5f64..2.0,
        b in balls(),
        lights in prop::collection::vec(prop::array::uniform3(-1.5f64..1.5), 1..3),
        max_past in 2.0f64..8.0,
    ) {
        use render::lighting::{LightSource, Lighting};
        let text = scene_text(a, &scaled_balls(a, &b), max_past * a, "exact");
        let sc = scene::Scene::from_str(&text, "falling.toml").unwrap();
        let tr = tracer(&sc);
        let sources: Vec<LightSource> = lights
            .iter()
            .map(|l| LightSource { position: Event::new(0.0, a * l[0], a * l[1], 0.3 * a * l[2]), power: 1.0 })
            .collect();
        let with = Lighting::new(sources.clone(), max_past * a);
        let without = Lighting::new(sources, max_past * a).without_rejection();
        let mut scratch = tr.scratch();
        let (mut o1, mut o2) = (vec![0.0f32; lights.len()], vec![0.0f32; lights.len()]);
        for row in 0..sc.camera.height() {
            for col in 0..sc.camera.width() {
                let n = sc.observer.pixel_direction(&sc.camera, col, row).unwrap();
                let Some(hit) = tr.trace(n, &mut scratch).hit else { continue };
                with.illuminate(&tr.objects, Some(&hit), &mut scratch.probes, &mut o1);
                without.illuminate(&tr.objects, Some(&hit), &mut scratch.probes, &mut o2);
                prop_assert_eq!(format!("{o1:?}"), format!("{o2:?}"), "pixel ({}, {})", col, row);
            }
        }
    }
}

/// A lit floor with a ball falling between it and the light, seen by an observer moving off
/// the axis (the second live scene), its shadow rays 25 time units long: several
/// loops each, the ball near only in some. The direct light at every hit is the same, bit
/// for bit, with the rejection as without it, and the ball shadows some of the floor.
#[test]
fn direct_light_on_a_lit_floor_is_the_same_with_and_without_rejection() {
    use render::lighting::{LightSource, Lighting};
    let sc = common::scene(
        "name = \"lit-floor\"\n\
         [spacetime]\nmetric = \"godel\"\na = 1.5\n\
         [observer]\ntime = 2.0\nposition = { r = 0.6, phi = 0.8, z = 0.4 }\n\
         velocity = { speed = 0.6, direction = [0.2, -1, 0.1] }\nforward = [1, 0, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"panorama\"\nh_fov_deg = 360.0\nv_fov_deg = 90.0\nwidth = 72\nheight = 14\n\
         [trace]\nmethod = \"exact\"\nmax_past = 25\n\
         [[object]]\nname = \"falling\"\nradius = 0.15\n\
         motion = { kind = \"geodesic\", time = 0.0, position = { x = -0.5, y = 0.5, z = 0.0 }, speed = 0.8, direction = [1, 0, 0.2] }\n\
         [[object]]\nname = \"floor\"\nframe = \"coordinates\"\nshape = \"plane\"\nheight = -0.5\nextent = 3.0\n",
    );
    let tr = tracer(&sc);
    let light = LightSource {
        position: Event::new(0.0, 0.5 * 2f64.cos(), 0.5 * 2f64.sin(), 0.6),
        power: 2.0,
    };
    let with = Lighting::new(vec![light], sc.trace.max_past);
    let without = Lighting::new(vec![light], sc.trace.max_past).without_rejection();
    let ball_free = Lighting::new(vec![light], sc.trace.max_past);
    let no_ball = common::scene(&sc.source_text.replace("radius = 0.15", "radius = 0.000001"));
    let tr_free = tracer(&no_ball);
    let mut scratch = tr.scratch();
    let mut scratch_free = tr_free.scratch();
    let (mut o1, mut o2, mut o3) = ([0.0f32], [0.0f32], [0.0f32]);
    let mut shadowed = 0;
    for row in 0..sc.camera.height() {
        for col in 0..sc.camera.width() {
            let n = sc.observer.pixel_direction(&sc.camera, col, row).unwrap();
            let Some(hit) = tr.trace(n, &mut scratch).hit else {
                continue;
            };
            with.illuminate(&tr.objects, Some(&hit), &mut scratch.probes, &mut o1);
            without.illuminate(&tr.objects, Some(&hit), &mut scratch.probes, &mut o2);
            assert_eq!(format!("{o1:?}"), format!("{o2:?}"), "pixel ({col}, {row})");
            if hit.target == 1 {
                ball_free.illuminate(
                    &tr_free.objects,
                    Some(&hit),
                    &mut scratch_free.probes,
                    &mut o3,
                );
                shadowed += usize::from(o3[0] > o1[0]);
            }
        }
    }
    assert!(shadowed > 0, "the ball shadows none of the floor");
}

/// The reference scene (a ball falling past the observer at 0.7 c) at 88×10, both tracers.
fn reference(method: &str) -> scene::Scene {
    common::reference_scene(method, 88, 10)
}

/// The comparison can fail: with the reach and time slack of the falling ball cut to a
/// tenth, rays that do meet the ball leave it out of their search, and records differ;
/// with the rejection as it is, the records are the same and most loops of most rays
/// search the ball for less than the whole loop, and their later starts leave out a quarter of
/// what they would search from their start (the rejection is not vacuous).
#[test]
fn an_over_eager_falling_bound_changes_the_reference_scene() {
    for method in ["exact", "numeric"] {
        let sc = reference(method);
        let without = records(&tracer(&sc).without_rejection(), &sc);
        assert_eq!(records(&tracer(&sc), &sc), without, "{method}");
        let eager = records(&tracer(&sc).with_falling_reach_scaled(0.1), &sc);
        let differ = eager.iter().zip(&without).filter(|(p, q)| p != q).count();
        assert!(differ > 10, "{method}: {differ} records differ");
    }
    // Not vacuous: count the loop stretches left out for the reference scene's rays.
    let sc = reference("exact");
    let a = 1.0;
    let metric = Metric::Godel(Godel::new(a));
    let tr = tracer(&sc);
    let obs = sc.observer.event;
    let ball = FallingBall::new(a, &metric, obs, &tr.objects.targets[0]).unwrap();
    let frame = metric.observer_frame(obs, sc.observer.velocity);
    let (mut loops_total, mut loops_cut) = (0, 0);
    // The λ the searched loops search up to, and of it what their later start leaves out.
    let (mut up_to, mut before) = (0.0, 0.0);
    let mut out = Vec::new();
    for row in 0..sc.camera.height() {
        for col in 0..sc.camera.width() {
            let n = sc.observer.pixel_direction(&sc.camera, col, row).unwrap();
            let k = photon_tangent(&frame, n, TimeDirection::Past);
            let geo = ExactGeodesic::new(a, obs, k).unwrap();
            let c = RayCircle::new(&geo.origin);
            assert!(ball.loops(&c, 0.0, f64::INFINITY, false, &mut out));
            // Loops within the traced 30 time units.
            let n_loops = (sc.trace.max_past / c.dt_loop.abs()).ceil() as usize;
            loops_total += n_loops;
            loops_cut += (0..n_loops)
                .filter(|&k| out.get(k).is_none_or(|w| w.from > 0.0 || w.until < c.l_ret))
                .count();
            for w in out.iter().take(n_loops).filter(|w| w.until >= w.from) {
                up_to += w.until;
                before += w.from;
            }
        }
    }
    assert!(
        loops_cut * 10 >= loops_total * 8,
        "{loops_cut} of {loops_total}"
    );
    assert!(
        before >= 0.25 * up_to,
        "the later starts leave out {before} of the searched loops' {up_to} (λ)"
    );
}
