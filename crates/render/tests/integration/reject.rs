//! Whole-ray rejection of balls at rest (`render::reject`): the reach covers the renderer's
//! own ball, and a rejected ray never comes within the reach of the centre on any loop.

use crate::common::{norm, tracer, unit};
use proptest::prelude::*;
use render::circle::RayCircle;
use render::reject::{reach, static_distance, StaticBall, REACH_CURVATURE};
use render::target::Target;
use render::worldline::{Located, Worldline};
use scene::Motion;
use spacetime::{
    photon_tangent, Event, ExactGeodesic, Godel, LocalVelocity, Metric, Spacetime, TimeDirection,
};

/// Bound on ((static distance)/|ξ| − 1)/(|ξ|/a)² asserted below; the worst found while
/// writing the test was 0.104 (centres out to 40a; 0.03 within 2a of the axis, 0.07 to 3a).
const CURVATURE: f64 = 0.15;

fn ball(a: f64, c: [f64; 3], radius: f64) -> Target {
    let metric = Metric::Godel(Godel::new(a));
    let position = Event::new(0.0, c[0], c[1], c[2]);
    Target::LocalSphere {
        radius,
        worldline: Worldline::new(metric, &Motion::Rest { position }, -1.0, 1.0).unwrap(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, max_global_rejects: 100_000, ..ProptestConfig::default() })]

    /// The renderer's ball at rest is |ξ| ≤ R, ξ in second-order normal coordinates at the
    /// simultaneous centre, used wherever the first-order distance is within 0.25a + R
    /// (elsewhere its distance estimate stays above R). For every such point with
    /// |ξ| ≤ a/2 (the largest radius scene validation allows) the static distance from
    /// the centre is at most (1 + CURVATURE·(|ξ|/a)²)·|ξ|, inside the reach
    /// R·(1 + REACH_CURVATURE·(R/a)²) of a ball of radius R ≥ |ξ|. Centres out to 12a.
    #[test]
    fn a_static_ball_lies_within_its_reach(
        a in 0.1f64..10.0,
        r in 0.0f64..12.0, phi in 0.0f64..6.3, z in -3.0f64..3.0,
        dir in prop::array::uniform3(-1.0f64..1.0),
        len in 0.0f64..0.6, t in -50.0f64..50.0,
    ) {
        prop_assume!(norm(dir) > 1e-3);
        let metric = Metric::Godel(Godel::new(a));
        let c = [a * r * phi.cos(), a * r * phi.sin(), a * z];
        let Target::LocalSphere { worldline, .. } = ball(a, c, 0.1 * a) else { unreachable!() };
        // A coordinate displacement, scaled to proper lengths up to ~a at the centre.
        let s = (1.0 + (r / 2.0).powi(2)).sqrt();
        let d = unit(dir);
        let x = Event::new(t, c[0] + a * len * s * d[0], c[1] + a * len * s * d[1], c[2] + a * len * d[2]);
        let first = worldline.localize(&metric, x, t, 0.0).unwrap();
        let second = worldline.localize(&metric, x, t, f64::INFINITY).and_then(Located::near).unwrap();
        prop_assume!(first.distance() <= 0.75 * a && norm(second.xi) <= 0.5 * a);
        let dist = static_distance(a, c, [x.x, x.y, x.z]);
        let xi = norm(second.xi);
        prop_assert!(
            dist <= (1.0 + CURVATURE * (xi / a).powi(2)) * xi + 1e-12 * a,
            "static distance {dist} against |ξ| = {xi}"
        );
        prop_assert!(reach(xi, a) >= (1.0 + CURVATURE * (xi / a).powi(2)) * xi);
        prop_assert!(CURVATURE < REACH_CURVATURE);
    }

    /// Rays from random events in random directions (observers at rest or moving), balls at
    /// rest anywhere: where `misses` rejects the ray, the closed-form ray sampled over three
    /// loops and through its whole z window stays farther than the reach from the centre
    /// (less the distance light covers between samples).
    #[test]
    fn rejected_rays_stay_beyond_the_reach(
        a in 0.2f64..5.0,
        o in prop::array::uniform3(-2.5f64..2.5), t0 in -10.0f64..10.0,
        n in prop::array::uniform3(-1.0f64..1.0),
        v in 0.0f64..0.9, vdir in prop::array::uniform3(-1.0f64..1.0),
        c in prop::array::uniform3(-2.5f64..2.5),
        radius in 0.01f64..0.5,
    ) {
        prop_assume!(norm(n) > 1e-3 && norm(vdir) > 1e-3);
        let obs = Event::new(t0, a * o[0], a * o[1], a * o[2]);
        let geo = ray_from(a, obs, v, vdir, n);
        let centre = [a * c[0], a * c[1], a * c[2]];
        let target = ball(a, centre, radius * a);
        let b = StaticBall::new(a, obs, &target).unwrap();
        if b.misses(&geo.origin, f64::INFINITY) {
            let reach = reach(radius * a, a);
            for (l, dist, slack) in samples(a, &geo, centre, reach) {
                prop_assert!(
                    dist > reach - slack,
                    "rejected ray at λ = {l} is {dist} from the centre, reach {reach}"
                );
            }
        }
    }
}

/// The exact ray from `obs` in the direction `n` of an observer moving at `v` along `vdir`.
fn ray_from(a: f64, obs: Event, v: f64, vdir: [f64; 3], n: [f64; 3]) -> ExactGeodesic {
    let metric = Metric::Godel(Godel::new(a));
    let frame = metric.observer_frame(obs, LocalVelocity::new(v, vdir).unwrap());
    let k = photon_tangent(&frame, unit(n), TimeDirection::Past);
    ExactGeodesic::new(a, obs, k).unwrap()
}

/// Samples (λ, static distance from `centre`, slack) of the closed-form ray `geo` over three
/// loops and through its whole z window near a centre of the given reach; the slack is the
/// static distance light covers between samples (its static energy −k_t per λ).
fn samples(a: f64, geo: &ExactGeodesic, centre: [f64; 3], reach: f64) -> Vec<(f64, f64, f64)> {
    let metric = Metric::Godel(Godel::new(a));
    let (obs, k) = geo.at(0.0);
    let l_ret = geo.origin.return_parameter();
    let speed = metric.lower(obs, k).t.abs();
    let pz = geo.origin.pz;
    let end = 3.0 * l_ret
        + if pz != 0.0 {
            (centre[2] - obs.z).abs() / pz.abs() + 2.0 * reach / pz.abs()
        } else {
            0.0
        };
    let n = 3000;
    let step = end / n as f64;
    (0..=n)
        .map(|i| {
            let l = i as f64 * step;
            let (x, _) = geo.at(l);
            (
                l,
                static_distance(a, centre, [x.x, x.y, x.z]),
                0.5 * step * speed,
            )
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// The stretches of a ray near a ball at rest (`StaticBall::near`): every sample of the
    /// closed-form ray, over three loops and its whole z window, that lies within the reach
    /// (less the distance light covers between samples) is in a stretch.
    #[test]
    fn every_point_within_the_reach_is_in_a_stretch(
        a in 0.2f64..5.0,
        o in prop::array::uniform3(-2.5f64..2.5), t0 in -10.0f64..10.0,
        n in prop::array::uniform3(-1.0f64..1.0),
        v in 0.0f64..0.9, vdir in prop::array::uniform3(-1.0f64..1.0),
        c in prop::array::uniform3(-1.5f64..1.5),
        radius in 0.01f64..0.5,
    ) {
        prop_assume!(norm(n) > 1e-3 && norm(vdir) > 1e-3);
        let obs = Event::new(t0, a * o[0], a * o[1], 0.3 * a * o[2]);
        let geo = ray_from(a, obs, v, vdir, n);
        let centre = [a * c[0], a * c[1], 0.3 * a * c[2]];
        let b = StaticBall::new(a, obs, &ball(a, centre, radius * a)).unwrap();
        let near = b.near(&RayCircle::new(&geo.origin), f64::INFINITY);
        let reach = reach(radius * a, a);
        for (l, dist, slack) in samples(a, &geo, centre, reach) {
            if dist <= reach - slack {
                prop_assert!(
                    near.is_some_and(|s| s.meets(l, l)),
                    "λ = {l} is {dist} from the centre (reach {reach}) but in no stretch: {near:?}"
                );
            }
        }
    }
}

/// The aim of a shadow ray's occlusion test (`Stretches::deepest`): for rays of panoramas
/// from observers near balls at rest, every λ it gives lies within the ball's radius in
/// static distance (its claim), and wherever the ray's path (sampled densely over the same
/// λ) passes deeper than 0.8 radii within a copy of the arc, it gives a λ no more than 0.01
/// radii above that copy's least distance (found within 10⁻⁵ radii while writing the test;
/// 0.1 radii off with the height left out of the guess): where one probe tells whether the
/// ray is inside.
#[test]
fn the_deepest_point_is_found_where_a_ray_passes_deep() {
    let a = 1.0;
    let (mut deep, mut found, mut given) = (0, 0, 0);
    for (obs, centre, radius) in [
        (ORIGIN, [1.0, 0.0, 0.0], 0.2),
        (Event::new(0.0, 0.3, -0.2, 0.4), [0.2, 0.9, 0.1], 0.35),
        (Event::new(0.0, -0.5, 0.1, -0.3), [-1.1, -0.4, -0.5], 0.1),
    ] {
        let frame = Metric::Godel(Godel::new(a)).static_frame(obs);
        let b = StaticBall::new(a, obs, &ball(a, centre, radius)).unwrap();
        for i in 0..240 {
            for j in 0..120 {
                let (az, el) = (
                    (1.5 * i as f64).to_radians(),
                    (1.5 * j as f64 - 89.25).to_radians(),
                );
                let n = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
                let k = photon_tangent(&frame, n, TimeDirection::Past);
                let geo = ExactGeodesic::new(a, obs, k).unwrap();
                let until = 3.0 * geo.origin.return_parameter();
                let Some(near) = b.near(&RayCircle::new(&geo.origin), until) else {
                    continue;
                };
                let dist = |l: f64| {
                    let (x, _) = geo.at(l);
                    static_distance(a, centre, [x.x, x.y, x.z])
                };
                let aims: Vec<f64> = near.deepest(until, radius, 8).collect();
                for &l in &aims {
                    given += 1;
                    assert!(
                        dist(l) < radius * (1.0 + 1e-9),
                        "λ {l}: {} of radius {radius}",
                        dist(l)
                    );
                }
                // The least distance per copy of the arc, sampled every 1/4000 of a loop.
                let l_ret = geo.origin.return_parameter();
                let steps = 12_000;
                let mut copies: Vec<(f64, f64)> = Vec::new(); // (λ, distance) at each copy's least
                let mut in_copy = false;
                for s in 0..=steps {
                    let l = until * s as f64 / steps as f64;
                    let on = near.meets(l, l);
                    if on && !in_copy {
                        copies.push((l, f64::INFINITY));
                    }
                    in_copy = on;
                    if on {
                        let d = dist(l);
                        let last = copies.last_mut().unwrap();
                        if d < last.1 {
                            *last = (l, d);
                        }
                    }
                }
                for &(l_min, d_min) in &copies {
                    if d_min >= 0.8 * radius {
                        continue;
                    }
                    deep += 1;
                    // The aim within this copy: the one nearest its least.
                    let best = aims
                        .iter()
                        .filter(|&&l| (l - l_min).abs() < 0.25 * l_ret)
                        .map(|&l| dist(l))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        best <= d_min + 0.01 * radius,
                        "ray ({i}, {j}) from {obs:?}: least {d_min} at λ {l_min}, aimed {best}"
                    );
                    found += 1;
                }
            }
        }
    }
    assert!(
        deep > 200 && found == deep,
        "{found} of {deep} deep passes aimed"
    );
    assert!(given >= deep, "{given} aims for {deep} deep passes");
}

/// The stretches are not vacuous: for the rays of a panorama from the origin around a ball
/// at (1, 0, 0) that `misses` keeps, the stretches leave out most of each ray's first
/// three loops (each sampled at 64 points a loop).
#[test]
fn stretches_leave_out_most_of_a_kept_ray() {
    let a = 1.0;
    let b = StaticBall::new(a, ORIGIN, &ball(a, [1.0, 0.0, 0.0], 0.2)).unwrap();
    let (mut kept, mut samples, mut inside) = (0, 0, 0);
    for (_, geo) in panorama_rays(a) {
        if b.misses(&geo.origin, f64::INFINITY) {
            continue;
        }
        kept += 1;
        let near = b.near(&RayCircle::new(&geo.origin), f64::INFINITY);
        let l_ret = geo.origin.return_parameter();
        for s in 0..3 * 64 {
            let l = l_ret * s as f64 / 64.0;
            samples += 1;
            inside += usize::from(near.is_some_and(|st| st.meets(l, l)));
        }
    }
    assert!(kept > 100, "{kept} rays kept");
    assert!(
        inside * 4 < samples,
        "{inside} of {samples} samples in a stretch"
    );
}

/// The origin event: the observer of the panoramas below.
const ORIGIN: Event = Event::new(0.0, 0.0, 0.0, 0.0);

/// The rays of a 220°×25° panorama from the origin, one a degree, with their (azimuth,
/// elevation) in degrees.
fn panorama_rays(a: f64) -> impl Iterator<Item = ((f64, f64), ExactGeodesic)> {
    let frame = Metric::Godel(Godel::new(a)).static_frame(ORIGIN);
    (0..220).flat_map(move |i| {
        (0..25).map(move |j| {
            let (az, el) = (i as f64 - 110.0, j as f64 - 12.0);
            let (azr, elr) = (az.to_radians(), el.to_radians());
            let n = [elr.cos() * azr.cos(), elr.cos() * azr.sin(), elr.sin()];
            let k = photon_tangent(&frame, n, TimeDirection::Past);
            ((az, el), ExactGeodesic::new(a, ORIGIN, k).unwrap())
        })
    })
}

/// Rejection is not vacuous: of the rays of a panorama from the origin around a ball at
/// (1, 0, 0) (the benchmark scene), most that pass far from the ball are rejected, and
/// none that pass within the reach.
#[test]
fn most_rays_far_from_a_ball_are_rejected() {
    let a = 1.0;
    let centre = [1.0, 0.0, 0.0];
    let target = ball(a, centre, 0.2);
    let b = StaticBall::new(a, ORIGIN, &target).unwrap();
    let reach = reach(0.2, a);
    let (mut far, mut far_rejected) = (0, 0);
    for ((az, el), geo) in panorama_rays(a) {
        let l_ret = geo.origin.return_parameter();
        let nearest = (0..=2000)
            .map(|s| {
                let (x, _) = geo.at(5.0 * l_ret * s as f64 / 2000.0);
                static_distance(a, centre, [x.x, x.y, x.z])
            })
            .fold(f64::INFINITY, f64::min);
        let rejected = b.misses(&geo.origin, f64::INFINITY);
        assert!(!(rejected && nearest <= reach), "az {az}, el {el}");
        if nearest > 2.0 * reach {
            far += 1;
            far_rejected += rejected as usize;
        }
    }
    assert!(far > 2000, "{far}");
    assert!(far_rejected * 10 >= far * 9, "{far_rejected} of {far}");
}

/// A scene of balls at rest (and, with `falling`, one in free fall; with `floor`, a plane at
/// that height) seen by a full-sphere camera, as TOML.
#[allow(clippy::too_many_arguments)]
fn random_scene(
    a: f64,
    obs: [f64; 3],
    speed: f64,
    balls: &[([f64; 3], f64)],
    falling: bool,
    floor: Option<f64>,
    max_past: f64,
    method: &str,
) -> scene::Scene {
    let mut text = format!(
        "name = \"r\"\n[spacetime]\nmetric = \"godel\"\na = {a}\n\
         [observer]\ntime = 0.0\nposition = {{ x = {}, y = {}, z = {} }}\n\
         velocity = {{ speed = {speed}, direction = [0.3, 1, 0.2] }}\n\
         forward = [0, 1, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"sphere\"\nwidth = 48\nheight = 24\n\
         [trace]\nmethod = \"{method}\"\nmax_past = {max_past}\n",
        obs[0], obs[1], obs[2]
    );
    for (i, (c, r)) in balls.iter().enumerate() {
        text += &format!(
            "[[object]]\nname = \"b{i}\"\nradius = {r}\ntexture = {{ kind = \"checker\", rows = 4, cols = 8 }}\n\
             motion = {{ kind = \"rest\", position = {{ x = {}, y = {}, z = {} }} }}\n",
            c[0], c[1], c[2]
        );
    }
    if let Some(h) = floor {
        text += &format!(
            "[[object]]\nname = \"floor\"\nframe = \"coordinates\"\nshape = \"plane\"\nheight = {h}\nextent = {}\n\
             texture = {{ kind = \"checker\", rows = 4, cols = 4 }}\n",
            2.0 * a
        );
    }
    if falling {
        text += &format!(
            "[[object]]\nname = \"f\"\nradius = {}\ntexture = {{ kind = \"checker\", rows = 4, cols = 8 }}\n\
             motion = {{ kind = \"geodesic\", time = 0.0, position = {{ x = {}, y = 0.3, z = 0.0 }}, speed = 0.5, direction = [1, 0, 0] }}\n",
            0.2 * a,
            -a
        );
    }
    scene::Scene::from_str(&text, "random.toml").unwrap_or_else(|e| panic!("{e}\n{text}"))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The rejection changes nothing: every pixel's record (bit for bit) is the same with it
    /// as without it, for both tracers, moving observers, several balls at rest near and far
    /// (also around the observer), with and without a floor plane and a ball in free fall
    /// (rejected loop by loop; see also `tests/integration/falling.rs`). (That rejection happens at all
    /// is `most_rays_far_from_a_ball_are_rejected`; that hits survive it, every image test of
    /// the renderer, which run with it.)
    #[test]
    fn records_are_the_same_with_and_without_rejection(
        a in 0.5f64..2.0,
        obs in prop::array::uniform3(-1.0f64..1.0),
        speed in 0.0f64..0.6,
        centres in prop::collection::vec((prop::array::uniform3(-1.5f64..1.5), 0.05f64..0.5), 1..4),
        falling in any::<bool>(),
        floor in prop::option::of(-1.0f64..1.0),
        max_past in 2.0f64..12.0,
        exact in any::<bool>(),
    ) {
        let balls: Vec<([f64; 3], f64)> = centres
            .iter()
            .map(|(c, r)| ([a * c[0], a * c[1], 0.3 * a * c[2]], r * a))
            .collect();
        let obs = [a * obs[0], a * obs[1], 0.3 * a * obs[2]];
        let method = if exact { "exact" } else { "numeric" };
        let sc = random_scene(a, obs, speed, &balls, falling, floor.map(|h| h * a), max_past, method);
        let with = tracer(&sc);
        let without = tracer(&sc).without_rejection();
        let (mut s1, mut s2) = (with.scratch(), without.scratch());
        for row in 0..sc.camera.height() {
            for col in 0..sc.camera.width() {
                let n = sc.observer.pixel_direction(&sc.camera, col, row).unwrap();
                let r1 = with.trace(n, &mut s1).record;
                let r2 = without.trace(n, &mut s2).record;
                prop_assert_eq!(format!("{r1:?}"), format!("{r2:?}"), "pixel ({}, {})", col, row);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Shadow rays: the direct light at every hit is the same (bit for bit) with the
    /// rejection as without it, for lights anywhere among balls at rest, with and without a
    /// floor plane (lit from above or below).
    #[test]
    fn direct_light_is_the_same_with_and_without_rejection(
        a in 0.5f64..2.0,
        centres in prop::collection::vec((prop::array::uniform3(-1.5f64..1.5), 0.05f64..0.5), 1..4),
        lights in prop::collection::vec(prop::array::uniform3(-2.0f64..2.0), 1..3),
        floor in prop::option::of(-1.0f64..1.0),
        max_past in 2.0f64..8.0,
    ) {
        use render::lighting::{LightSource, Lighting};
        let balls: Vec<([f64; 3], f64)> = centres
            .iter()
            .map(|(c, r)| ([a * c[0], a * c[1], 0.3 * a * c[2]], r * a))
            .collect();
        let sc = random_scene(a, [0.0; 3], 0.0, &balls, false, floor.map(|h| h * a), max_past, "exact");
        let tr = tracer(&sc);
        let sources: Vec<LightSource> = lights
            .iter()
            .map(|l| LightSource { position: Event::new(0.0, a * l[0], a * l[1], 0.5 * a * l[2]), power: 1.0 })
            .collect();
        let with = Lighting::new(sources.clone(), max_past);
        let without = Lighting::new(sources, max_past).without_rejection();
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
