//! Helpers shared by the renderer's integration tests: scenes from TOML text, rendering,
//! connected groups of hit pixels, the panorama's pixel geometry (docs/physics.md, "Pixels
//! and cameras"), and an independent numeric shoot-and-solve for the light rays connecting
//! the observer on the Gödel axis with a static point (built on `spacetime::trace` only, not
//! on the renderer); the tracer of a scene, built as the renderer builds it; lengths and
//! unit vectors of 3-vectors.

use datafile::DataFile;
use render::driver::{render, NoProgress, RenderStats};
use scene::Scene;
use spacetime::{
    trace, Event, Geodesic, Godel, Metric, Spacetime, TimeDirection, TraceLimits, TracedGeodesic,
};
use std::f64::consts::{PI, TAU};

/// A validated scene from TOML text (panics with the located error otherwise).
pub fn scene(text: &str) -> Scene {
    Scene::from_str(text, "test.toml").unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The example scene `scenes/NAME` with its camera resized to `width` × `height`, one ray per
/// pixel (the tracers are compared ray by ray: samples add only cost), traced by `method`.
pub fn scene_file(name: &str, method: &str, width: u32, height: u32) -> scene::Scene {
    scene(&scene_text(name, method, width, height))
}

/// The text of [`scene_file`]'s scene.
pub fn scene_text(name: &str, method: &str, width: u32, height: u32) -> String {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name);
    let text = std::fs::read_to_string(p).unwrap();
    // The table each line is in: only the camera's width and height are its size (a plane's
    // `height` is its place).
    let mut table = String::new();
    text.lines()
        .map(|l| {
            if l.trim_start().starts_with('[') {
                table = l.trim().to_string();
            }
            let camera = table == "[camera]";
            match l.split('=').next().map(str::trim) {
                Some("width") if camera => format!("width = {width}"),
                Some("height") if camera => format!("height = {height}"),
                Some("method") if table == "[trace]" => String::new(),
                // One ray per pixel: the tracers are compared ray by ray, samples add only
                // cost.
                Some("samples") if camera => String::new(),
                _ => l.to_string(),
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
        .replace("[trace]", &format!("[trace]\nmethod = \"{method}\""))
}

/// Renders on the current rayon pool.
pub fn render_scene(s: &Scene) -> (DataFile, RenderStats) {
    render(s, &NoProgress).expect("render")
}

/// Every pixel of the data file `d` rendered from `s`, row by row, as (column, row, the
/// direction its ray leaves the observer in the observer's frame).
pub fn pixel_directions(s: &Scene, d: &DataFile) -> Vec<(usize, usize, [f64; 3])> {
    let mut out = Vec::with_capacity(d.width * d.height);
    for row in 0..d.height {
        for col in 0..d.width {
            let n = s
                .observer
                .pixel_direction(&s.camera, col as u32, row as u32)
                .unwrap();
            out.push((col, row, n));
        }
    }
    out
}

/// A root of an increasing-or-decreasing `f` on [lo, hi] with a sign change, by
/// `iterations` halvings.
pub fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, iterations: usize) -> f64 {
    let flo = f(lo);
    assert!(
        (flo > 0.0) != (f(hi) > 0.0),
        "no sign change on [{lo}, {hi}]"
    );
    for _ in 0..iterations {
        let m = 0.5 * (lo + hi);
        if (f(m) > 0.0) == (flo > 0.0) {
            lo = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo + hi)
}

/// Connected groups of hit pixels (8-connectivity). With `wrap`, column 0 and column
/// W − 1 are neighbours (a 360° panorama). Each group is a list of (col, row).
pub fn groups(d: &DataFile, wrap: bool) -> Vec<Vec<(usize, usize)>> {
    let (w, h) = (d.width, d.height);
    let mut label = vec![usize::MAX; w * h];
    let mut out = Vec::new();
    for start in 0..w * h {
        if !d.records[start].is_hit() || label[start] != usize::MAX {
            continue;
        }
        let id = out.len();
        let mut group = Vec::new();
        let mut stack = vec![start];
        label[start] = id;
        while let Some(i) = stack.pop() {
            let (c, r) = (i % w, i / w);
            group.push((c, r));
            for dr in -1i64..=1 {
                for dc in -1i64..=1 {
                    let rr = r as i64 + dr;
                    let mut cc = c as i64 + dc;
                    if rr < 0 || rr >= h as i64 {
                        continue;
                    }
                    if cc < 0 || cc >= w as i64 {
                        if !wrap {
                            continue;
                        }
                        cc = cc.rem_euclid(w as i64);
                    }
                    let j = rr as usize * w + cc as usize;
                    if d.records[j].is_hit() && label[j] == usize::MAX {
                        label[j] = id;
                        stack.push(j);
                    }
                }
            }
        }
        out.push(group);
    }
    out
}

/// Wraps an angle into [−π, π).
pub fn wrap_pi(a: f64) -> f64 {
    (a + PI).rem_euclid(TAU) - PI
}

/// Fractional column of the panorama direction with camera azimuth `alpha` (radians,
/// positive to the right): the pixel containing it is `floor`, its centre is at `+ 0.5`
/// (docs/physics.md, "Pixels and cameras": α = h_fov·((col + ½)/W − ½)).
pub fn panorama_col(alpha: f64, h_fov: f64, width: usize) -> f64 {
    width as f64 * (alpha / h_fov + 0.5)
}

/// Circular distance between two columns of a 360° panorama.
pub fn col_dist_wrapped(a: f64, b: f64, width: usize) -> f64 {
    let w = width as f64;
    let d = (a - b).rem_euclid(w);
    d.min(w - d)
}

/// Circular mean of the pixel-centre columns of a group (360° panorama).
pub fn circular_mean_col(group: &[(usize, usize)], width: usize) -> f64 {
    let (mut s, mut c) = (0.0, 0.0);
    for &(col, _) in group {
        let a = TAU * (col as f64 + 0.5) / width as f64;
        s += a.sin();
        c += a.cos();
    }
    (s.atan2(c).rem_euclid(TAU)) * width as f64 / TAU
}

/// The Gödel metric with parameter a.
pub fn godel(a: f64) -> Metric {
    Metric::Godel(Godel::new(a))
}

/// The backward (past-directed) light ray leaving the origin event along the in-plane local
/// direction with azimuth `az` (counter-clockwise from e_x), integrated for one loop.
pub fn backward_ray(metric: Metric, a: f64, az: f64) -> TracedGeodesic {
    let o = Event::new(0.0, 0.0, 0.0, 0.0);
    let frame = metric.static_frame(o);
    let g = Geodesic::launch(
        &metric,
        o,
        &frame,
        [az.cos(), az.sin(), 0.0],
        1.0,
        TimeDirection::Past,
    )
    .unwrap();
    let t = trace(metric, &g, &TraceLimits::one_loop(a));
    assert!(!t.stop.is_failure(), "{:?}", t.stop);
    t
}

/// Closest approach of a ray to the point (cx, cy, 0), on the outbound (`first_half`) or
/// inbound half of the loop (split at the largest r): (signed distance, λ there). The sign
/// is that of the z component of (X − C) × Ẋ, so it changes sign as the ray sweeps across C.
pub fn closest_approach(
    metric: Metric,
    ray: &TracedGeodesic,
    c: [f64; 2],
    first_half: bool,
) -> (f64, f64) {
    let n = 800;
    let samples = ray.samples(n);
    let imax = (0..n)
        .max_by(|&i, &j| {
            let ri = samples[i].1.x.r();
            let rj = samples[j].1.x.r();
            ri.total_cmp(&rj)
        })
        .unwrap();
    let range = if first_half { 0..imax + 1 } else { imax..n };
    let d2 = |l: f64| {
        let s = ray.state_at(l).x;
        (s.x - c[0]).powi(2) + (s.y - c[1]).powi(2)
    };
    let best = range
        .clone()
        .min_by(|&i, &j| d2(samples[i].0).total_cmp(&d2(samples[j].0)))
        .unwrap();
    // Golden-section refinement between the neighbouring samples.
    let mut lo = samples[best.saturating_sub(1)].0;
    let mut hi = samples[(best + 1).min(n - 1)].0;
    let gr = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..200 {
        let m1 = hi - gr * (hi - lo);
        let m2 = lo + gr * (hi - lo);
        if d2(m1) < d2(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    let l = 0.5 * (lo + hi);
    let s = ray.state_at(l);
    let v = metric.raise(s.x, s.p);
    let cross = (s.x.x - c[0]) * v.y - (s.x.y - c[1]) * v.x;
    let dist = d2(l).sqrt();
    (dist * cross.signum(), l)
}

/// All in-plane azimuths (in [0, 2π)) whose backward ray from the origin passes through
/// (cx, cy, 0) on the given half of its first loop: a scan in azimuth for sign changes of
/// the signed closest approach, each refined by bisection and kept if the distance
/// vanishes. Returns (azimuth, coordinate time at the crossing).
pub fn connecting_rays(a: f64, c: [f64; 2], first_half: bool) -> Vec<(f64, f64)> {
    let m = godel(a);
    let f = |az: f64| closest_approach(m, &backward_ray(m, a, az), c, first_half).0;
    let n = 72;
    let azs: Vec<f64> = (0..=n).map(|i| TAU * i as f64 / n as f64).collect();
    let fs: Vec<f64> = azs.iter().map(|&az| f(az)).collect();
    let mut out = Vec::new();
    for i in 0..n {
        if (fs[i] > 0.0) == (fs[i + 1] > 0.0) {
            continue;
        }
        let az = bisect(f, azs[i], azs[i + 1], 60);
        let ray = backward_ray(m, a, az);
        let (d, l) = closest_approach(m, &ray, c, first_half);
        if d.abs() < 1e-7 {
            out.push((az.rem_euclid(TAU), ray.state_at(l).x.t));
        }
    }
    out
}

/// docs/physics.md, "Closed forms": Φ(θ) = arctan(q tan θ), continuous in θ.
pub fn big_phi(q: f64, theta: f64) -> f64 {
    let (s, c) = theta.sin_cos();
    theta + ((q - 1.0) * s * c).atan2(c * c + q * s * s)
}

/// docs/physics.md, "Images of a point": image azimuths (counter-clockwise from e_x) and
/// delays of a static point at (ρ, φ_c, 0) seen from the origin: [(az_1, Δt_1), (az_2, Δt_2)].
pub fn closed_form_images(a: f64, rho: f64, phi_c: f64) -> [(f64, f64); 2] {
    let th1 = (rho / (2.0 * a)).asin();
    let th2 = PI - th1;
    let q = 2f64.sqrt();
    let img = |th: f64| {
        let p = big_phi(q, th);
        (
            (phi_c + p).rem_euclid(TAU),
            2.0 * 2f64.sqrt() * a * p - 2.0 * a * th,
        )
    };
    [img(th1), img(th2)]
}

/// The scene's tracer, built as the renderer builds it (worldlines one time unit beyond the
/// traced range on both sides).
pub fn tracer(sc: &Scene) -> render::tracer::Tracer {
    use render::intersect::Intersector;
    use render::target::Target;
    use render::tracer::{TraceOptions, Tracer};
    let m = sc.metric;
    let o = sc.observer;
    let t_min = o.event.t - sc.trace.max_past - 1.0;
    let targets = sc
        .objects
        .iter()
        .map(|ob| Target::new(m, ob, t_min, o.event.t + 1.0).unwrap())
        .collect();
    Tracer::new(
        Intersector::new(m, targets),
        &o,
        TraceOptions {
            max_past: sc.trace.max_past,
            tolerance: sc.trace.tolerance,
            max_steps: sc.trace.max_steps,
            exact: sc.trace.method == scene::TraceMethod::Exact,
        },
    )
}

/// The built-in reference scene at `width`×`height` (one ray per pixel), traced by `method`.
pub fn reference_scene(method: &str, width: u32, height: u32) -> Scene {
    let text = scene::BUILTIN_SCENE_TEXT
        .replace("width = 880", &format!("width = {width}"))
        .replace("height = 100", &format!("height = {height}"))
        .replace("samples = 4", "samples = 1")
        .replace("method = \"numeric\"", &format!("method = \"{method}\""));
    Scene::from_str(&text, "reference.toml").unwrap()
}

/// The Euclidean length of a 3-vector.
pub fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// `v` scaled to unit length.
pub fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = norm(v);
    [v[0] / n, v[1] / n, v[2] / n]
}

/// The Gödel-type family's Gödel member's event (m² = 1/a², Ω = 1/(√2 a), r the proper
/// radius ρ) of the Gödel event `e`: (x, y) scaled from r to ρ = 2a asinh(r/2a), t and z
/// unchanged (docs/physics.md, "The Gödel-type family").
pub fn carried(a: f64, e: Event) -> Event {
    let r = e.x.hypot(e.y);
    let s = if r == 0.0 {
        1.0
    } else {
        2.0 * a * (r / (2.0 * a)).asinh() / r
    };
    Event::new(e.t, s * e.x, s * e.y, e.z)
}

/// A local ball of `radius` with `motion` in `metric`, ready to be searched, its worldline
/// covering coordinate times [t_min, t_max].
pub fn local_ball(
    metric: Metric,
    radius: f64,
    motion: scene::Motion,
    (t_min, t_max): (f64, f64),
) -> render::target::Target {
    let object = scene::Object {
        name: "ball".into(),
        frame: scene::ObjectFrame::Local,
        shape: scene::Shape::Sphere { radius },
        texture: scene::TextureSpec::Gradient,
        temperature: 5800.0,
        motion,
        polarization: None,
    };
    render::target::Target::new(metric, &object, t_min, t_max).unwrap()
}

/// A small seeded generator: the same cases on every run.
pub struct Cases(pub u64);

impl Cases {
    pub fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn signed(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }
    pub fn direction(&mut self) -> [f64; 3] {
        loop {
            let d = [self.signed(), self.signed(), self.signed()];
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if n > 0.1 && n <= 1.0 {
                return [d[0] / n, d[1] / n, d[2] / n];
            }
        }
    }
}

/// A random local ball in Gödel's universe for the search's property tests, and its a, its
/// metric, speed and radius: a from 0.5 to 2, at rest when `at_rest`, else falling at up to
/// `max_speed`; radius up to a/2, up to 1.8a from the axis and 0.3a off the plane z = 0; its
/// worldline over coordinate times ±`span`·a.
pub fn random_ball(
    rng: &mut Cases,
    at_rest: bool,
    max_speed: f64,
    span: f64,
) -> (f64, Metric, f64, f64, render::target::Target) {
    let a = 0.5 + 1.5 * rng.unit();
    let m = Metric::Godel(spacetime::Godel::new(a));
    let speed = if at_rest { 0.0 } else { max_speed * rng.unit() };
    let radius = (0.02 + 0.48 * rng.unit()) * a;
    let (r, phi) = (1.8 * a * rng.unit(), TAU * rng.unit());
    let position = Event::new(0.0, r * phi.cos(), r * phi.sin(), 0.3 * a * rng.signed());
    let motion = if speed == 0.0 {
        scene::Motion::Rest { position }
    } else {
        scene::Motion::Geodesic {
            start: position,
            velocity: spacetime::LocalVelocity::new(speed, rng.direction()).unwrap(),
        }
    };
    let target = local_ball(m, radius, motion, (-span * a, span * a));
    (a, m, speed, radius, target)
}
