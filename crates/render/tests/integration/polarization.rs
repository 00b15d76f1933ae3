//! The records' polarization channels (`pol`, docs/physics.md "Polarization") against
//! independent computations:
//!
//! - the exact tracer (closed-form transport) and the numeric tracer (the propagator
//!   integrated with the ray) on the example scenes, loops and falling balls included;
//! - in flat spacetime, the special-relativistic closed form: the moving observer's screen-up
//!   boosted to the emitter's rest frame (aberration of the polarization), for emitters at
//!   rest and moving;
//! - in Gödel's universe, the transport integrated here from the Christoffel symbols along
//!   each pixel's ray (an off-axis, moving observer; rays over many loops), which a tracer
//!   that dropped the transport fails.

use crate::common::{render_scene, scene, scene_file, tracer, unit};
use spacetime::measure::vector_components;
use spacetime::{
    photon_tangent, Dop853, Event, FourVector, Metric, OdeSystem, Spacetime, StepOutcome,
    TimeDirection, Tolerances,
};

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn f64s(v: [f32; 3]) -> [f64; 3] {
    v.map(f64::from)
}

fn max_diff(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).fold(0.0, |m, i| f64::max(m, (a[i] - b[i]).abs()))
}

/// The pixel's screen-up, written out here: the camera's up projected orthogonal to the
/// direction `n` the pixel looks along, normalized.
fn screen_up(up: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    let a = dot(up, n);
    unit([0, 1, 2].map(|i| up[i] - a * n[i]))
}

/// `v` with its part along the unit vector `d` taken out, normalized.
fn across(v: [f64; 3], d: [f64; 3]) -> [f64; 3] {
    let a = dot(v, d);
    unit([0, 1, 2].map(|i| v[i] - a * d[i]))
}

/// Exact and numeric tracers on the example scenes: wherever both hit the same object, the
/// three channels agree to 1e-5, and every hit's `pol` is a unit vector orthogonal to `dir`.
#[test]
fn exact_and_numeric_tracers_agree_on_the_polarization() {
    let mut worst: f64 = 0.0;
    let mut later_loops = 0;
    for (name, w, h) in [
        ("static-sphere.toml", 180, 30),
        ("reference.toml", 330, 40),
        ("moving-sphere-long.toml", 660, 31),
        ("floor-grid.toml", 120, 40),
        ("surroundings.toml", 60, 30),
        ("lit-shadow.toml", 180, 20),
    ] {
        let (num, _) = render_scene(&scene_file(name, "numeric", w, h));
        let (exa, _) = render_scene(&scene_file(name, "exact", w, h));
        assert!(num.polarization && exa.polarization);
        let mut both = 0;
        for (a, b) in num.records.iter().zip(&exa.records) {
            for r in [a, b].into_iter().filter(|r| r.is_hit()) {
                let (pol, dir) = (f64s(r.pol), f64s(r.dir));
                assert!((dot(pol, pol) - 1.0).abs() < 1e-6, "{name}: |pol| {pol:?}");
                assert!(
                    dot(pol, dir).abs() < 1e-6,
                    "{name}: pol·dir {pol:?} {dir:?}"
                );
            }
            if a.is_hit() && a.object == b.object {
                both += 1;
                // Emitted more than a shortest loop (2πa(√2 − 1)) ago: a later loop.
                later_loops += usize::from(b.t_emit < -2.61);
                let d = max_diff(f64s(a.pol), f64s(b.pol));
                worst = worst.max(d);
                assert!(d <= 1e-5, "{name}: numeric {:?}, exact {:?}", a.pol, b.pol);
            }
        }
        assert!(both > 50, "{name}: only {both} common hits");
    }
    assert!(later_loops > 500, "only {later_loops} hits on later loops");
    eprintln!("exact against numeric: largest |Δpol| {worst:e}");
}

/// A Minkowski scene: an observer moving at 0.8 c looks at the whole sky, a ball at rest and
/// a ball moving at 0.6 c.
fn flat_scene() -> scene::Scene {
    scene(
        r#"
name = "flat-polarization"
[spacetime]
metric = "minkowski"
[observer]
position = { x = 0.0, y = 0.0, z = 0.0 }
velocity = { speed = 0.8, direction = [0.3, 1.0, 0.2] }
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "sphere"
width = 240
height = 120
[trace]
max_past = 20.0
[[object]]
name = "resting"
radius = 1.0
motion = { kind = "rest", position = { x = 2.0, y = 0.5, z = 0.2 } }
[[object]]
name = "moving"
radius = 1.0
motion = { kind = "geodesic", time = 0.0, position = { x = 0.5, y = -2.0, z = 0.0 }, speed = 0.6, direction = [0.2, 1.0, 0.4] }
"#,
    )
}

/// The standard boost of the four-vector (x⁰, x) into the frame moving with velocity
/// `speed`·`dir` (components in the moving frame); `speed` < 0 boosts the other way.
fn boost_into(speed: f64, dir: [f64; 3], x0: f64, x: [f64; 3]) -> (f64, [f64; 3]) {
    let g = 1.0 / (1.0 - speed * speed).sqrt();
    let along = dot(dir, x);
    (
        g * (x0 - speed * along),
        [0, 1, 2].map(|i| x[i] + (g - 1.0) * along * dir[i] - g * speed * x0 * dir[i]),
    )
}

/// In flat spacetime transport is trivial and the channels are special relativity: the
/// moving observer's screen-up s′ (and the photon (1, −n′)) carried into the static frame
/// and on into the emitter's rest frame by Lorentz boosts, then taken orthogonal to the
/// photon there: pol = the emitter-frame screen-up minus its part along dir. Every hit pixel
/// of both balls, to 1e-5.
#[test]
fn in_flat_spacetime_the_channels_are_the_boosted_screen_up() {
    let s = flat_scene();
    let (data, _) = render_scene(&s);
    let obs = s.observer;
    let v = obs.velocity;
    let mut counts = [0; 2];
    let mut boosted = 0;
    let mut worst: f64 = 0.0;
    for r in data.records.iter().filter(|r| r.is_hit()) {
        let n = unit(f64s(r.view));
        let su = screen_up(obs.up, n);
        // Observer's frame → static frame (the inverse boost).
        let (f0, f) = boost_into(-v.speed, v.direction, 0.0, su);
        let (k0, k) = boost_into(-v.speed, v.direction, 1.0, n.map(|c| -c));
        // Static frame → the emitter's rest frame.
        let (f0, f, k0, k) = match s.objects[r.object as usize].motion {
            scene::Motion::Rest { .. } => (f0, f, k0, k),
            scene::Motion::Geodesic { velocity: b, .. } => {
                let (f0, f) = boost_into(b.speed, b.direction, f0, f);
                let (k0, k) = boost_into(b.speed, b.direction, k0, k);
                (f0, f, k0, k)
            }
        };
        let _ = f0;
        let dir = k.map(|c| c / k0);
        let pol = across(f, dir);
        let (dd, dp) = (max_diff(dir, f64s(r.dir)), max_diff(pol, f64s(r.pol)));
        worst = worst.max(dp);
        assert!(dd < 1e-5, "dir {:?}, expected {dir:?}", r.dir);
        assert!(dp < 1e-5, "pol {:?}, expected {pol:?} (dir {dir:?})", r.pol);
        counts[r.object as usize] += 1;
        // The boosts matter: the observer's screen-up taken as if it were the static
        // observer's is another vector (but where it is orthogonal to the velocity).
        boosted += usize::from(max_diff(across(su, dir), pol) > 1e-3);
    }
    assert!(counts.iter().all(|&c| c > 100), "hits per ball {counts:?}");
    let hits: usize = counts.iter().sum();
    assert!(
        boosted * 2 > hits,
        "the boosts change only {boosted} of {hits}"
    );
    eprintln!("flat spacetime: largest |Δpol| {worst:e} over {counts:?} hits");
}

/// Geodesic and transported vector: dx/dλ = k, dk/dλ = −Γ(k, k), dW/dλ = −Γ(k, W), straight
/// from the Christoffel symbols.
struct Transport(Metric);

impl OdeSystem<12> for Transport {
    fn rhs(&self, s: &[f64; 12]) -> [f64; 12] {
        let gam = self.0.christoffel(Event::new(s[0], s[1], s[2], s[3]));
        let mut out = [0.0; 12];
        for mu in 0..4 {
            out[mu] = s[4 + mu];
            for a in 0..4 {
                for b in 0..4 {
                    out[4 + mu] -= gam[mu][a][b] * s[4 + a] * s[4 + b];
                    out[8 + mu] -= gam[mu][a][b] * s[4 + a] * s[8 + b];
                }
            }
        }
        out
    }
}

/// The transported vector W where the ray from `x0` with tangent `k0` passes the event
/// `hit`, carrying `w0`: integrated past the record's λ (f32), then λ refined on the dense
/// output to the point nearest `hit`.
fn integrate_to(
    metric: Metric,
    x0: Event,
    k0: FourVector,
    w0: FourVector,
    lambda: f64,
    hit: Event,
) -> (Event, FourVector, FourVector) {
    let mut s0 = [0.0; 12];
    s0[..4].copy_from_slice(&x0.to_array());
    s0[4..8].copy_from_slice(&k0.to_array());
    s0[8..].copy_from_slice(&w0.to_array());
    let tol = Tolerances {
        rtol: 1e-12,
        atol: 1e-12,
        h_max: 0.2,
        h_min: 1e-14,
    };
    let mut ode = Dop853::new(Transport(metric), 0.0, s0, tol, None);
    let end = lambda * (1.0 + 1e-5) + 1e-5;
    let mut steps = Vec::new();
    while ode.lambda() < end {
        assert_eq!(ode.step(), StepOutcome::Accepted);
        steps.push(ode.dense());
        assert!(steps.len() < 100_000);
    }
    let at = |l: f64| {
        let i = steps
            .partition_point(|d| d.lambda1() < l)
            .min(steps.len() - 1);
        steps[i].eval(l)
    };
    let mut l = lambda;
    for _ in 0..4 {
        let s = at(l);
        let d: f64 = (0..4).map(|i| (hit.to_array()[i] - s[i]) * s[4 + i]).sum();
        let kk: f64 = (0..4).map(|i| s[4 + i] * s[4 + i]).sum();
        l += d / kk;
    }
    let s = at(l);
    (
        Event::new(s[0], s[1], s[2], s[3]),
        FourVector::new(s[4], s[5], s[6], s[7]),
        FourVector::new(s[8], s[9], s[10], s[11]),
    )
}

/// Gödel's universe, an observer off the axis moving at 0.5 c between a floor and a ceiling,
/// with a coordinate sphere beside it: each sampled pixel's `pol` against the screen-up transported here from the
/// Christoffel symbols and measured by the static observer at the hit (the coordinate
/// objects' frame), to 1e-5, on rays up to fifteen loops long. The same comparison of what a
/// tracer without transport would write (the screen-up's components kept) fails.
#[test]
fn in_godel_the_channels_are_the_screen_up_transported_along_the_ray() {
    let s = scene(
        r#"
name = "godel-polarization"
[spacetime]
metric = "godel"
a = 1.0
[observer]
time = 0.0
position = { x = 0.3, y = -0.2, z = 0.1 }
velocity = { speed = 0.5, direction = [1.0, 1.0, 0.0] }
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "panorama"
h_fov_deg = 360.0
v_fov_deg = 40.0
width = 60
height = 16
[trace]
method = "exact"
max_past = 40.0
[[object]]
name = "globe"
frame = "coordinates"
shape = "sphere"
center = { x = 1.0, y = 0.8, z = 0.1 }
radius = 0.3
[[object]]
name = "floor"
frame = "coordinates"
shape = "plane"
height = -0.45
[[object]]
name = "ceiling"
frame = "coordinates"
shape = "plane"
height = 0.6
"#,
    );
    let tr = tracer(&s);
    let metric = s.metric;
    let obs = s.observer;
    let frame = metric.observer_frame(obs.event, obs.velocity);
    let mut scratch = tr.scratch();
    let (mut checked, mut late, mut caught) = (0, 0, 0);
    let mut worst: f64 = 0.0;
    for row in 0..s.camera.height() {
        for col in 0..s.camera.width() {
            let n = obs.pixel_direction(&s.camera, col, row).unwrap();
            let traced = tr.trace(n, &mut scratch);
            let Some(hit) = traced.hit else { continue };
            let r = traced.record;
            let k0 = photon_tangent(&frame, n, TimeDirection::Past);
            let su = screen_up(obs.up, n);
            let w0 = frame.vector([0.0, su[0], su[1], su[2]]);
            let (x, k, w) =
                integrate_to(metric, obs.event, k0, w0, f64::from(r.lambda), hit.state.x);
            assert!(
                max_diff(
                    [x.x, x.y, x.z],
                    [hit.state.x.x, hit.state.x.y, hit.state.x.z]
                ) < 1e-7
            );
            // Measured by the static observer at the hit, orthogonal to the photon.
            let g = metric.metric(x);
            let sf = metric.static_frame(x);
            let kc = vector_components(&g, &sf, k);
            let dir = unit([-kc[1], -kc[2], -kc[3]]);
            let wc = vector_components(&g, &sf, w);
            let expected = across([wc[1], wc[2], wc[3]], dir);
            let d = max_diff(expected, f64s(r.pol));
            worst = worst.max(d);
            assert!(
                d < 1e-5,
                "pixel ({col}, {row}): pol {:?}, transported {expected:?}",
                r.pol
            );
            checked += 1;
            late += usize::from(r.t_emit < -2.61);
            // Without transport: the screen-up's and screen-right's components measured at
            // the hit.
            let sr = [
                n[1] * su[2] - n[2] * su[1],
                n[2] * su[0] - n[0] * su[2],
                n[0] * su[1] - n[1] * su[0],
            ];
            let r0 = frame.vector([0.0, sr[0], sr[1], sr[2]]);
            let target = &tr.objects.targets[hit.target];
            let dropped = target
                .surface(&metric, &hit.state, hit.tau, [w0, r0])
                .expect("a surface");
            caught += usize::from(max_diff(expected, dropped.pol) > 1e-2);
        }
    }
    assert!(
        checked > 300 && late > 100,
        "{checked} hits, {late} on later loops"
    );
    assert!(
        caught * 10 > checked * 9,
        "a dropped transport differs on only {caught} of {checked}"
    );
    eprintln!("Gödel: largest |Δpol| against the integrated transport {worst:e} ({checked} hits, {late} on later loops)");
}

/// The propagator integrated along a numeric ray has its own fixed step budget, a few times
/// the ray's: a scene whose every ray hits the ball around the observer within one step keeps
/// the hits found within them (found by the fuzz test: with the ray's budget of 1 or 2 steps,
/// they were marked failed), each with a unit `pol` orthogonal to `dir`.
#[test]
fn a_tiny_step_budget_keeps_the_hits_of_a_ball_around_the_observer() {
    let s = scene(
        r#"
name = "inside"
[spacetime]
metric = "godel"
a = 1.0
[observer]
time = 0.0
position = { x = 0.0, y = 0.0, z = 0.4 }
velocity = { speed = 0.7, direction = [1.0, 0.0, -0.2] }
[camera]
kind = "sphere"
width = 16
height = 8
[trace]
method = "numeric"
max_past = 6.0
max_steps = 2
[[object]]
name = "around"
radius = 0.24
motion = { kind = "geodesic", time = 0.0, position = { x = 0.0, y = 0.0, z = 0.4 }, speed = 0.7, direction = [0.7, 0.4, -0.6] }
"#,
    );
    let (data, _) = render_scene(&s);
    let mut hits = 0;
    for r in &data.records {
        // A ray may run out of its own steps, but no hit is lost to the transport.
        assert_ne!(r.status, datafile::RayStatus::Failed);
        if r.is_hit() {
            hits += 1;
            let (pol, dir) = (f64s(r.pol), f64s(r.dir));
            assert!((dot(pol, pol) - 1.0).abs() < 1e-6 && dot(pol, dir).abs() < 1e-6);
        }
    }
    assert!(hits > 10, "{hits} hits");
}
