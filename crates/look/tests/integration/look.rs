//! `look` (docs/physics.md, "Observers at one event: aberration and Doppler") against independent
//! computations: direct renders of the same camera and observer velocity (the tracer with a
//! boosted frame), read by nearest neighbour and smoothly, with one and several samples per
//! pixel; the identity view, the Doppler factor's two closed forms, the shrinking and blue
//! shift of a ball the observer moves towards, the magnification of the static sky
//! (dθ = D dθ′). Refusals and the output header: `look_input.rs`.

use crate::common::{FISHEYE, PANORAMA, PINHOLE};
use datafile::{DataFile, PixelRecord, RayStatus};
use look::{look, look_with, pixel_look, resolution, Filter, LookView, Sampling, SphereSource};
use render::driver::{render, NoProgress};
use scene::{replace_view, Camera, Scene};
use spacetime::LocalVelocity;
use std::sync::OnceLock;

/// A validated scene from TOML text (panics with the located error otherwise).
fn scene(text: &str) -> Scene {
    Scene::from_str(text, "test.toml").unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The data file of a direct render.
fn render_scene(s: &Scene) -> DataFile {
    render(s, &NoProgress).expect("render").0
}

/// A ball at rest at r = 1 (seen twice, g = 1 for the static observer) and a ball falling
/// past at 0.7 c (several images, g ≠ 1), seen from the axis over the full sphere.
fn sphere_scene() -> String {
    testkit::sphere_scene(
        "two-balls",
        720,
        360,
        &format!(
            "{}{}[[object]]\nname = \"falling\"\nradius = 0.25\nmotion = {{ kind = \"geodesic\", \
             time = 0.0, position = {{ x = -1.0, y = 0.3, z = 0.2 }}, speed = 0.7, \
             direction = [1, 0, 0] }}\n",
            testkit::trace("exact", 10.0),
            testkit::ball_at_rest("resting", 0.3, 1.0, 0.0),
        ),
    )
}
const RESTING: i32 = 0;
const FALLING: i32 = 1;
/// Twice the larger ball's diameter: within one image of a ball, neighbouring pixels'
/// emission times differ by far less; a larger step is a boundary between two images.
const JUMP: f32 = 1.2;

fn sphere() -> &'static DataFile {
    static SPHERE: OnceLock<DataFile> = OnceLock::new();
    SPHERE.get_or_init(|| render_scene(&scene(&sphere_scene())))
}

/// The direction of the resting ball's first image from the axis (docs/physics.md, "Images
/// of a point": tan az = √2 ρ/√(4a² − ρ²) for ρ = 1, a = 1): 39.23° from e_x.
fn towards_resting() -> [f64; 3] {
    let az = (2f64.sqrt() / 3f64.sqrt()).atan();
    [az.cos(), az.sin(), 0.0]
}

fn view(camera: Camera, forward: [f64; 3], speed: f64, direction: [f64; 3]) -> LookView {
    let velocity = LocalVelocity::new(speed, direction).expect("velocity");
    LookView::new(camera, forward, [0.0, 0.0, 1.0], velocity).expect("view")
}

/// A direct trace of `view` at the sphere's event.
fn direct(view: &LookView) -> DataFile {
    let text = replace_view(
        &sphere_scene(),
        "test.toml",
        &view.camera,
        view.velocity,
        view.forward,
        view.up,
    )
    .expect("edit");
    let s = scene(&text);
    // The comparison means something only if the direct render really has this view.
    assert_eq!(s.camera, view.camera);
    assert_eq!(s.observer.velocity.speed, view.velocity.speed);
    for (a, b) in [
        (s.observer.velocity.direction, view.velocity.direction),
        (s.observer.forward, view.forward),
        (s.observer.up, view.up),
    ] {
        assert!((0..3).all(|i| (a[i] - b[i]).abs() < 1e-15), "{a:?} {b:?}");
    }
    render_scene(&s)
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let s = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    s.atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
}

/// The static direction of source pixel centre (col, row) (docs/physics.md, "Pixels and
/// cameras": the sphere is the 360°×180° panorama), columns wrapped.
fn centre(src: &SphereSource, col: i64, row: i64) -> [f64; 3] {
    let cam = Camera::Sphere {
        width: src.width as u32,
        height: src.height as u32,
    };
    let col = col.rem_euclid(src.width as i64) as u32;
    let d = cam.pixel_direction(col, row as u32).expect("inside");
    let r = [
        src.forward[1] * src.up[2] - src.forward[2] * src.up[1],
        src.forward[2] * src.up[0] - src.forward[0] * src.up[2],
        src.forward[0] * src.up[1] - src.forward[1] * src.up[0],
    ];
    [0, 1, 2].map(|i| d[0] * src.forward[i] + d[1] * r[i] + d[2] * src.up[i])
}

/// What the source knows around a static direction: whether the 3×3 block of pixels
/// around the one containing it mixes objects or statuses (an edge pixel) or images of one
/// object (a t_emit jump), the largest finite-difference gradients of g, t_emit, λ and the
/// polarization channels there (per radian), and the angle δ from the direction to the
/// containing pixel's centre.
struct Around {
    edge: bool,
    jump: bool,
    grad_g: f64,
    grad_t: f64,
    grad_l: f64,
    /// Of pol and of pol × dir (the transported screen-right, which the turn mixes in).
    grad_pol: f64,
    delta: f64,
}

fn pol(r: &PixelRecord) -> [f64; 3] {
    r.pol.map(f64::from)
}

/// pol × dir: the transported screen-right.
fn right(r: &PixelRecord) -> [f64; 3] {
    let (p, d) = (pol(r), r.dir.map(f64::from));
    [
        p[1] * d[2] - p[2] * d[1],
        p[2] * d[0] - p[0] * d[2],
        p[0] * d[1] - p[1] * d[0],
    ]
}

fn around(src: &SphereSource, data: &DataFile, n: [f64; 3]) -> Around {
    let pos = src.position(n);
    let (c0, r0) = (
        pos[0].floor() as i64,
        (pos[1].floor() as i64).clamp(0, src.height as i64 - 1),
    );
    let me = data.records[src.nearest(pos)];
    let here = centre(src, c0, r0);
    let mut a = Around {
        edge: false,
        jump: false,
        grad_g: 0.0,
        grad_t: 0.0,
        grad_l: 0.0,
        grad_pol: 0.0,
        delta: angle(n, here),
    };
    for dr in -1..=1i64 {
        for dc in -1..=1i64 {
            let r = r0 + dr;
            if (dr, dc) == (0, 0) || r < 0 || r >= src.height as i64 {
                continue;
            }
            let j = r as usize * src.width + (c0 + dc).rem_euclid(src.width as i64) as usize;
            let o: PixelRecord = data.records[j];
            a.edge |= o.object != me.object || o.status != me.status;
            a.jump |= (o.t_emit - me.t_emit).abs() > JUMP;
            let ang = angle(here, centre(src, c0 + dc, r));
            a.grad_g = a.grad_g.max((o.g - me.g).abs() as f64 / ang);
            a.grad_t = a.grad_t.max((o.t_emit - me.t_emit).abs() as f64 / ang);
            a.grad_l = a.grad_l.max((o.lambda - me.lambda).abs() as f64 / ang);
            let (po, pm, ro, rm) = (pol(&o), pol(&me), right(&o), right(&me));
            let dp = (0..3).fold(0.0f64, |m, i| m.max((po[i] - pm[i]).abs()));
            let dr = (0..3).fold(0.0f64, |m, i| m.max((ro[i] - rm[i]).abs()));
            a.grad_pol = a.grad_pol.max(dp.max(dr) / ang);
        }
    }
    a
}

/// The views compared with direct renders: a pinhole turned towards the resting ball at
/// rest and moving towards it at 0.5 c, a panorama and a dome fisheye moving sideways at
/// 0.9 c.
fn compared_views() -> Vec<(&'static str, LookView)> {
    let t = towards_resting();
    let side = [-t[1], t[0], 0.0];
    vec![
        ("pinhole at rest", view(PINHOLE, t, 0.0, t)),
        ("pinhole 0.5c towards", view(PINHOLE, t, 0.5, t)),
        (
            "panorama 0.9c sideways",
            view(PANORAMA, [1.0, 0.0, 0.0], 0.9, side),
        ),
        ("fisheye 0.9c sideways", view(FISHEYE, t, 0.9, side)),
    ]
}

const NEAREST: Sampling = Sampling {
    filter: Filter::Nearest,
    samples: 1,
};

/// Median of some errors.
fn median(mut e: Vec<f64>) -> f64 {
    e.sort_by(f64::total_cmp);
    e.get(e.len() / 2).copied().unwrap_or(0.0)
}

/// Both filters stay within the nearest-neighbour bound inside objects, and the smooth look
/// is closer: its median t_emit error at most half the nearest one's in every view (24 times
/// smaller in the pinhole views, 3.5 times in the panorama at 0.9 c), its mean g error over
/// all views at most half as large.
#[test]
fn look_agrees_with_direct_renders_within_the_stated_bound() {
    let data = sphere();
    let src = SphereSource::of(data).expect("a sphere");
    let mut falling_checked = 0;
    let mut g_errors = [Vec::new(), Vec::new()];
    for (name, v) in compared_views() {
        let traced = direct(&v);
        let mut t_errors = [Vec::new(), Vec::new()];
        for (k, sampling) in [NEAREST, Sampling::default()].into_iter().enumerate() {
            let looked = look_with(data, &v, sampling).expect("look");
            assert_eq!((looked.width, looked.height), (traced.width, traced.height));
            let (inner, hits, resting) = compare_inside_objects(
                &src,
                &v,
                &looked,
                &traced,
                &format!("{name} {sampling:?}"),
                &mut |a, b, resting_ball| {
                    t_errors[k].push((a.t_emit - b.t_emit).abs() as f64);
                    g_errors[k].push((a.g - b.g).abs() as f64);
                    falling_checked +=
                        (!resting_ball && a.object == FALLING && a.g != b.g) as usize;
                },
            );
            // Enough of each picture is compared for the test to mean something.
            assert!(
                inner > 10_000 && hits > 200 && resting > 100,
                "{name}: {inner} {hits} {resting}"
            );
        }
        let [nearest, smooth] = t_errors.map(median);
        assert!(
            smooth <= 0.5 * nearest,
            "{name}: median t_emit error {smooth} smooth, {nearest} nearest"
        );
    }
    let [nearest, smooth] = g_errors.map(|e| e.iter().sum::<f64>() / e.len() as f64);
    assert!(
        smooth <= 0.5 * nearest,
        "mean g error {smooth} smooth, {nearest} nearest"
    );
    // The falling ball's g varies, so its comparison exercises the bound.
    assert!(falling_checked > 200, "{falling_checked}");
}

/// Compares `looked` with `traced` (the same view) on every output pixel that is not an edge
/// pixel of the source: the same object and status, and on hits within one image g, t_emit
/// and λ within the nearest-neighbour bound D·|∇f|·δ (with a margin of 1.5 for the
/// finite-difference gradient); `each` sees every compared hit (looked, traced, whether it is
/// the resting ball). Returns the counts of inner pixels, compared hits, resting-ball hits.
fn compare_inside_objects(
    src: &SphereSource,
    v: &LookView,
    looked: &DataFile,
    traced: &DataFile,
    name: &str,
    each: &mut dyn FnMut(&PixelRecord, &PixelRecord, bool),
) -> (usize, usize, usize) {
    let data = sphere();
    let (mut inner, mut hits, mut resting) = (0, 0, 0);
    for row in 0..v.camera.height() {
        for col in 0..v.camera.width() {
            let i = traced.index(col as usize, row as usize);
            let (a, b) = (looked.records[i], traced.records[i]);
            let Some(p) = pixel_look(v, col, row) else {
                assert_eq!(a.status, RayStatus::NotTraced);
                assert_eq!(b.status, RayStatus::NotTraced);
                continue;
            };
            let s = around(src, data, p.static_dir);
            if s.edge {
                continue;
            }
            inner += 1;
            // The same object (and status) on every pixel that is not an edge pixel.
            assert_eq!(
                (a.object, a.status),
                (b.object, b.status),
                "{name}: pixel ({col}, {row})"
            );
            if !a.is_hit() || s.jump {
                continue;
            }
            hits += 1;
            // |Δf| ≤ D·|∇f|·δ, with the gradient estimated from the source's neighbours (a
            // finite difference, hence the margin of 1.5).
            let bound_g = 1.5 * p.doppler * s.grad_g * s.delta + 2e-6 * b.g as f64;
            let bound_t = 1.5 * s.grad_t * s.delta + 2e-6 * (b.t_emit as f64).abs();
            let (dg, dt) = ((a.g - b.g).abs() as f64, (a.t_emit - b.t_emit).abs() as f64);
            assert!(
                dg <= bound_g,
                "{name} ({col}, {row}): |Δg| {dg} > {bound_g}"
            );
            assert!(
                dt <= bound_t,
                "{name} ({col}, {row}): |Δt| {dt} > {bound_t}"
            );
            // λ belongs to the photon normalized to unit energy in the observer's frame: it
            // scales with D like g.
            let bound_l = 1.5 * p.doppler * s.grad_l * s.delta + 2e-6 * b.lambda as f64;
            let dl = (a.lambda - b.lambda).abs() as f64;
            assert!(
                dl <= bound_l,
                "{name} ({col}, {row}): |Δλ| {dl} > {bound_l}"
            );
            // The polarization channels: the source's screen-up and screen-right transported
            // (pol, pol × dir), mixed by the turn between the two observers' screen-up at the
            // pixel's own direction (docs/physics.md, "Polarization"): off by their
            // gradients times δ.
            let bound_p = 1.5 * s.grad_pol * s.delta + 2e-6;
            let dp = (0..3).fold(0.0f32, |m, i| m.max((a.pol[i] - b.pol[i]).abs())) as f64;
            assert!(
                dp <= bound_p,
                "{name} ({col}, {row}): |Δpol| {dp} > {bound_p}: {:?} {:?}",
                a.pol,
                b.pol
            );
            let resting_ball = a.object == RESTING;
            if resting_ball {
                // At rest, the static observer sees g = 1 exactly: g′ is the Doppler factor
                // alone, with no interpolation error.
                resting += 1;
                assert!((b.g as f64 - p.doppler).abs() <= 2e-6 * p.doppler);
                assert!((a.g as f64 - p.doppler).abs() <= 2e-6 * p.doppler);
            }
            each(&a, &b, resting_ball);
        }
    }
    (inner, hits, resting)
}

/// s×s samples per pixel are the pixels of the camera s times wider and taller, kept as a
/// render keeps its samples (header and embedded scene say so), and they agree with a direct
/// render with as many rays per pixel.
#[test]
fn samples_are_the_finer_cameras_pixels_as_a_render_keeps_them() {
    let data = sphere();
    let (name, v) = compared_views().remove(1);
    let four = Sampling {
        filter: Filter::Smooth,
        samples: 4,
    };
    let looked = look_with(data, &v, four).expect("look");
    let finer = LookView {
        camera: v.camera.supersampled(2),
        ..v
    };
    let fine = look(data, &finer).expect("look");
    assert_eq!(looked.records, fine.records);
    assert_eq!((looked.width, looked.height), (480, 320));
    assert_eq!(looked.header.supersample, 2);
    assert_eq!(looked.header.camera, v.camera.describe());
    let embedded = scene(&looked.header.scene_text);
    assert_eq!((embedded.camera, embedded.samples), (v.camera, 4));
    // Against a direct render with 4 rays per pixel, sample by sample.
    let text = scene::replace_samples(&looked.header.scene_text, "test.toml", 4).unwrap();
    let traced = render_scene(&scene(&text));
    assert_eq!(traced.header.supersample, 2);
    let src = SphereSource::of(data).expect("a sphere");
    let (inner, hits, _) =
        compare_inside_objects(&src, &finer, &looked, &traced, name, &mut |_, _, _| {});
    assert!(inner > 40_000 && hits > 1_000, "{inner} {hits}");
    // The pictures: with 4 samples, the look is closer to a direct render with 16 rays per
    // pixel than the nearest-neighbour look with one, and than the smooth look with one (mean
    // 8-bit difference per channel 0.28, 0.73 and 0.56 here).
    let truth = {
        let text = scene::replace_samples(&looked.header.scene_text, "test.toml", 16).unwrap();
        let s = scene(&text);
        shade::preview(&render_scene(&s), &s).expect("preview")
    };
    let error = |looked: &DataFile| {
        let s = scene(&looked.header.scene_text);
        let img = shade::preview(looked, &s).expect("preview");
        let diff: u64 = img
            .as_raw()
            .iter()
            .zip(truth.as_raw())
            .map(|(a, b)| u64::from(a.abs_diff(*b)))
            .sum();
        diff as f64 / img.as_raw().len() as f64
    };
    let sampled = error(&looked);
    let nearest = error(&look_with(data, &v, NEAREST).unwrap());
    let smooth = error(&look(data, &v).unwrap());
    eprintln!("mean 8-bit error: {sampled} with 4 samples, {smooth} smooth, {nearest} nearest");
    assert!(
        sampled < 0.6 * nearest && sampled < 0.8 * smooth && smooth < nearest,
        "mean 8-bit error: {sampled} with 4 samples, {smooth} smooth, {nearest} nearest"
    );
    // A bad count is refused, naming the field.
    for bad in [2, 0, 289] {
        let e = look_with(
            data,
            &v,
            Sampling {
                filter: Filter::Smooth,
                samples: bad,
            },
        )
        .unwrap_err();
        assert!(e.to_string().starts_with("camera.samples: "), "{e}");
    }
}

#[test]
fn the_identity_view_reproduces_the_source_exactly() {
    let data = sphere();
    let src = SphereSource::of(data).expect("a sphere");
    let cam = Camera::Sphere {
        width: data.width as u32,
        height: data.height as u32,
    };
    let v = LookView::new(cam, src.forward, src.up, LocalVelocity::REST).expect("view");
    let same = look(data, &v).expect("look");
    assert_eq!(same.records, data.records);
    assert_eq!(same.lights, data.lights);
    assert_eq!(same.header.camera, data.header.camera);
    // The output is itself a static full sphere, and reads back as a data file.
    let again = DataFile::from_bytes(&same.to_bytes().expect("encode")).expect("decode");
    assert_eq!(SphereSource::of(&again).expect("still a sphere"), src);
    let r = resolution(&src, &v);
    let pixel = std::f64::consts::PI / data.height as f64;
    assert!((r.source_pixel - pixel).abs() < 1e-12);
    for o in [r.output_pixel_min, r.output_pixel_max] {
        assert!((o - pixel).abs() < 1e-9 * pixel, "{r:?}");
    }
}

#[test]
fn doppler_factor_has_both_closed_forms_and_scales_g() {
    let data = sphere();
    let src = SphereSource::of(data).expect("a sphere");
    let (_, v) = compared_views().remove(2);
    let looked = look_with(data, &v, NEAREST).expect("look");
    let (gamma, speed, d) = (v.velocity.gamma(), v.velocity.speed, v.velocity.direction);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut hits = 0;
    for row in 0..v.camera.height() {
        for col in 0..v.camera.width() {
            let p = pixel_look(&v, col, row).expect("a panorama shows every pixel");
            // g′/g = γ(1 + n·v) with n the static direction, = 1/(γ(1 − n′·v)) with the
            // moving observer's own direction n′.
            let forward_form = gamma * (1.0 + speed * dot(p.static_dir, d));
            let own_form = 1.0 / (gamma * (1.0 - speed * dot(p.own, d)));
            assert!((forward_form - own_form).abs() < 1e-12 * own_form);
            assert!((p.doppler - own_form).abs() < 1e-12 * own_form);
            let i = looked.index(col as usize, row as usize);
            let (a, s) = (
                looked.records[i],
                data.records[src.nearest(src.position(p.static_dir))],
            );
            if s.is_hit() {
                hits += 1;
                assert!((a.g as f64 - s.g as f64 * own_form).abs() <= 1e-6 * a.g as f64);
                assert!(
                    (a.lambda as f64 - s.lambda as f64 * own_form).abs() <= 1e-6 * a.lambda as f64
                );
                let unchanged = |r: PixelRecord| {
                    (
                        r.object, r.u, r.v, r.t_emit, r.x, r.y, r.z, r.dir, r.cos_i, r.status,
                    )
                };
                assert_eq!(unchanged(a), unchanged(s));
            }
        }
    }
    assert!(hits > 1000, "{hits}");
}

#[test]
fn a_ball_moved_towards_is_blue_shifted_and_shrinks() {
    let data = sphere();
    let t = towards_resting();
    let cam = Camera::Pinhole {
        fov_deg: 120.0,
        width: 240,
        height: 160,
    };
    // The pixels of the resting ball's first image: within 45° of the axis (its second
    // image is 101.5° away in the static sky, at least 70° in the views below).
    let first_image = |d: &DataFile| -> Vec<(PixelRecord, f64)> {
        let mut out = Vec::new();
        for row in 0..d.height {
            for col in 0..d.width {
                let dir = cam.pixel_direction(col as u32, row as u32).expect("inside");
                if d.record(col, row).object == RESTING && dir[0] > 0.5f64.sqrt() {
                    out.push((*d.record(col, row), dir[0]));
                }
            }
        }
        out
    };
    // The solid angle it covers: a pinhole pixel spans cos³ of its angle from the axis (in
    // units of a pixel at the centre).
    let solid_angle = |d: &DataFile| -> f64 { first_image(d).iter().map(|p| p.1.powi(3)).sum() };
    let at_rest = look(data, &view(cam, t, 0.0, t)).expect("look");
    assert!(solid_angle(&at_rest) > 1000.0);
    let speed: f64 = 0.5;
    // Along the motion D = √((1 + v)/(1 − v)); a solid angle at angle θ from it shrinks by
    // 1/D(θ)², D(θ) = γ(1 + v cos θ): between 1/3 (θ = 0) and 0.347 (θ = 20°, the ball's
    // angular radius) for v = 0.5.
    let d = ((1.0 + speed) / (1.0 - speed)).sqrt();
    let towards = look(data, &view(cam, t, speed, t)).expect("look");
    let ratio = solid_angle(&towards) / solid_angle(&at_rest);
    assert!(
        (0.95..1.1).contains(&(ratio * d * d)),
        "solid angle ratio {ratio}, 1/D² = {}",
        1.0 / (d * d)
    );
    for (r, _) in first_image(&towards) {
        assert!(r.g > 1.6 && r.g as f64 <= d * 1.000_001, "g′ {}", r.g);
    }
    // Moving away, the same ball is red-shifted and grows by D(θ)² (3 to 2.67).
    let away = look(data, &view(cam, t, speed, t.map(|c| -c))).expect("look");
    let ratio = solid_angle(&away) / solid_angle(&at_rest);
    assert!(
        (0.85..1.02).contains(&(ratio / (d * d))),
        "solid angle ratio {ratio}"
    );
    for (r, _) in first_image(&away) {
        assert!(
            r.g < 0.62 && r.g as f64 >= 1.0 / d * 0.999_999,
            "g′ {}",
            r.g
        );
    }
}

#[test]
fn the_static_sky_is_magnified_by_the_doppler_factor() {
    // dθ = D dθ′: along the motion, an output pixel covers D times its own angle of the
    // static observer's sky (so the source's pixels limit the output D times sooner).
    let src = SphereSource::of(sphere()).expect("a sphere");
    let cam = Camera::Pinhole {
        fov_deg: 1.0,
        width: 100,
        height: 100,
    };
    let f = [1.0, 0.0, 0.0];
    let rest = resolution(&src, &view(cam, f, 0.0, f));
    let own = 2.0 * 0.5f64.to_radians().tan() / 100.0;
    assert!((rest.output_pixel_max / own - 1.0).abs() < 1e-3, "{rest:?}");
    for speed in [0.5f64, 0.9] {
        let d = ((1.0 + speed) / (1.0 - speed)).sqrt();
        let towards = resolution(&src, &view(cam, f, speed, f));
        let away = resolution(&src, &view(cam, f, speed, [-1.0, 0.0, 0.0]));
        assert!(
            (towards.output_pixel_max / own / d - 1.0).abs() < 1e-3,
            "{towards:?}"
        );
        assert!(
            (away.output_pixel_max / own * d - 1.0).abs() < 1e-3,
            "{away:?}"
        );
    }
}
