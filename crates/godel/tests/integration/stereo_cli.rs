//! `godel render` of a stereo scene (`[camera] stereo`, issue 37): each eye's data file is the
//! mono render from that eye's event (docs/physics.md, "Stereo eyes"), the preview puts the
//! two pictures in the scene's layout, and bad stereo settings are refused naming the field.

use crate::common::{assert_refused, png, records, render, stderr, write_scene};
use datafile::{DataFile, RayStatus};
use spacetime::{LocalVelocity, Metric, Viewpoint};
use std::path::Path;

/// A scene named `s` with `metric` (TOML lines), the observer's `observer` lines, a pinhole
/// camera of `fov`° on `width`×`height` with the extra camera `lines`, and `objects`.
fn scene(metric: &str, observer: &str, camera: (f64, u32, u32, &str), objects: &str) -> String {
    let (fov, width, height, lines) = camera;
    // The closed forms are Gödel's; flat space is traced numerically.
    let method = if metric == MINKOWSKI {
        "numeric"
    } else {
        "exact"
    };
    format!(
        "name = \"s\"\n[spacetime]\n{metric}[observer]\n{observer}[camera]\nkind = \"pinhole\"\n\
         fov_deg = {fov}\nwidth = {width}\nheight = {height}\n{lines}[trace]\nmethod = \"{method}\"\n\
         max_past = 8.0\n{objects}"
    )
}

const GODEL: &str = "metric = \"godel\"\na = 1.0\n";
const MINKOWSKI: &str = "metric = \"minkowski\"\n";
const AT_ORIGIN: &str = "time = 0.0\nposition = { x = 0.0, y = 0.0, z = 0.0 }\n\
                         forward = [1, 0, 0]\nup = [0, 0, 1]\n";
const BALLS: &str = "[[object]]\nname = \"still\"\nradius = 0.15\n\
    motion = { kind = \"rest\", position = { x = 0.9, y = 0.2, z = 0.0 } }\n\
    [[object]]\nname = \"falling\"\nradius = 0.1\n\
    motion = { kind = \"geodesic\", time = -0.5, position = { x = 0.7, y = -0.4, z = 0.05 }, \
    speed = 0.5, direction = [0, 1, 0] }\n";

/// Renders `text` (written as `file` in `dir`) into `dir/out`, asserting success.
fn render_ok(dir: &Path, file: &str, text: &str) {
    let path = write_scene(dir, file, text);
    let o = render(Path::new(&path), &dir.join("out"), &["-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn with_separation_zero_each_eye_is_the_mono_render() {
    let tmp = tempfile::tempdir().unwrap();
    let observer = "time = 0.5\nposition = { r = 0.3, phi = 1.0, z = 0.0 }\n\
        velocity = { speed = 0.4, direction = [0, 1, 0] }\nforward = [1, 0, 0]\nup = [0, 0, 1]\n";
    let mono = scene(GODEL, observer, (70.0, 48, 16, ""), BALLS);
    let stereo = scene(
        GODEL,
        observer,
        (70.0, 48, 16, "stereo = { separation = 0.0 }\n"),
        BALLS,
    );
    let (a, b) = (tmp.path().join("mono"), tmp.path().join("stereo"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    render_ok(&a, "s.toml", &mono);
    render_ok(&b, "s.toml", &stereo);
    let mono_records = records(&a.join("out/s.exr"));
    for eye in ["left", "right"] {
        let data = b.join(format!("out/s.{eye}.exr"));
        assert_eq!(records(&data), mono_records, "{eye} eye");
    }
    // Side by side (the default layout): the mono preview twice.
    let (one, both) = (png(&a.join("out/s.png")), png(&b.join("out/s.png")));
    assert_eq!(both.dimensions(), (2 * one.width(), one.height()));
    for (x, y, p) in one.enumerate_pixels() {
        assert_eq!(both.get_pixel(x, y), p);
        assert_eq!(both.get_pixel(x + one.width(), y), p);
    }
    assert!(
        !b.join("out/s.exr").exists(),
        "no mono data file beside the eyes'"
    );
}

/// In flat space the eyes are the observer's event moved by ∓separation/2 along the right
/// axis (forward × up = −y here): their records are those of mono renders from there.
#[test]
fn in_flat_space_each_eye_is_the_mono_render_from_its_displaced_event() {
    let tmp = tempfile::tempdir().unwrap();
    let balls = "[[object]]\nname = \"near\"\nradius = 0.3\n\
        motion = { kind = \"rest\", position = { x = 2.0, y = 0.4, z = 0.0 } }\n\
        [[object]]\nname = \"far\"\nradius = 0.5\n\
        motion = { kind = \"rest\", position = { x = 5.0, y = -1.0, z = 0.3 } }\n";
    let camera = (
        60.0,
        64,
        24,
        "stereo = { separation = 0.2, layout = \"anaglyph\" }\n",
    );
    render_ok(
        tmp.path(),
        "s.toml",
        &scene(MINKOWSKI, AT_ORIGIN, camera, balls),
    );
    for (eye, y) in [("left", "0.1"), ("right", "-0.1")] {
        let dir = tmp.path().join(eye);
        std::fs::create_dir_all(&dir).unwrap();
        let observer = AT_ORIGIN.replace("y = 0.0", &format!("y = {y}"));
        render_ok(
            &dir,
            "s.toml",
            &scene(MINKOWSKI, &observer, (60.0, 64, 24, ""), balls),
        );
        let stereo = records(&tmp.path().join(format!("out/s.{eye}.exr")));
        assert_eq!(stereo, records(&dir.join("out/s.exr")), "{eye} eye");
    }
    // An anaglyph is one picture of the camera's size.
    assert_eq!(png(&tmp.path().join("out/s.png")).dimensions(), (64, 24));
}

/// In Gödel's universe the left eye's records are those of a mono render from the left eye's
/// event, velocity and axes (`spacetime::Viewpoint::eye`, written into a scene by hand), and
/// its data file embeds a scene that says so.
#[test]
fn in_godels_universe_the_left_eye_is_the_mono_render_from_its_event() {
    let tmp = tempfile::tempdir().unwrap();
    let observer = "time = 1.0\nposition = { x = 0.4, y = -0.3, z = 0.1 }\n\
        velocity = { speed = 0.5, direction = [0.6, 0.8, 0.0] }\nforward = [1, 0, 0]\nup = [0, 0, 1]\n";
    let camera = (
        80.0,
        48,
        20,
        "stereo = { separation = 0.3, layout = \"over-under\" }\n",
    );
    render_ok(tmp.path(), "s.toml", &scene(GODEL, observer, camera, BALLS));
    let here = Viewpoint {
        event: spacetime::Event::new(1.0, 0.4, -0.3, 0.1),
        velocity: LocalVelocity::new(0.5, [0.6, 0.8, 0.0]).unwrap(),
        forward: [1.0, 0.0, 0.0],
        up: [0.0, 0.0, 1.0],
    };
    let eye = here
        .eye(&Metric::Godel(spacetime::Godel::new(1.0)), -0.15)
        .expect("a Gödel eye");
    let e = eye.event;
    let v = eye.velocity;
    let by_hand = format!(
        "time = {}\nposition = {{ x = {}, y = {}, z = {} }}\n\
         velocity = {{ speed = {}, direction = {:?} }}\nforward = {:?}\nup = {:?}\n",
        e.t, e.x, e.y, e.z, v.speed, v.direction, eye.forward, eye.up
    );
    let dir = tmp.path().join("mono");
    std::fs::create_dir_all(&dir).unwrap();
    render_ok(
        &dir,
        "s.toml",
        &scene(GODEL, &by_hand, (80.0, 48, 20, ""), BALLS),
    );
    let left = tmp.path().join("out/s.left.exr");
    assert_eq!(records(&left), records(&dir.join("out/s.exr")));
    let header = DataFile::read(&left).unwrap().header;
    let embedded = scene::Scene::from_str(&header.scene_text, "embedded").unwrap();
    let mark = embedded.stereo.and_then(|s| s.eye);
    assert_eq!(
        (embedded.name.as_str(), mark),
        ("s.left", Some(scene::Eye::Left))
    );
    assert_eq!(embedded.observer.event, e);
    // That scene traces the eye again, as one picture under the eye's name.
    let again = tmp.path().join("again");
    std::fs::create_dir_all(&again).unwrap();
    render_ok(&again, "eye.toml", &header.scene_text);
    assert_eq!(records(&again.join("out/s.left.exr")), records(&left));
    assert!(!again.join("out/s.left.left.exr").exists());
    // Over-under: the left eye's picture on top.
    assert_eq!(png(&tmp.path().join("out/s.png")).dimensions(), (48, 40));
}

/// The mean column of the samples that hit object 0.
fn ball_column(path: &Path) -> f64 {
    let data = DataFile::read(path).unwrap();
    let (mut sum, mut n) = (0.0, 0usize);
    for row in 0..data.height {
        for col in 0..data.width {
            let r = &data.records[data.index(col, row)];
            if r.status == RayStatus::Hit && r.object == 0 {
                sum += col as f64 + 0.5;
                n += 1;
            }
        }
    }
    assert!(n > 50, "the ball covers {n} samples");
    sum / n as f64
}

/// A ball at rest a distance D straight ahead, eyes S apart with S ≪ D: the left eye sees it
/// to the right of the right eye's view, by the flat-space disparity W·(S/2D)/tan(fov/2)
/// pixels (each eye sees it atan(S/2D) off its axis). So it is in flat space (to 2 %), and in
/// Gödel's universe at D = 0.1a (to 10 %; at D = 0.3a its light bends so much that the
/// disparity is half the flat one). Eyes converging at the ball's distance see no disparity.
#[test]
fn a_near_balls_disparity_has_the_flat_space_sign_and_size() {
    let (s, d, fov, width) = (0.01, 0.1, 30.0f64, 600u32);
    let want = f64::from(width) * (s / (2.0 * d)) / (fov.to_radians() / 2.0).tan();
    let ball = format!(
        "[[object]]\nname = \"near\"\nradius = 0.012\n\
         motion = {{ kind = \"rest\", position = {{ x = {d}, y = 0.0, z = 0.0 }} }}\n"
    );
    for (metric, tolerance) in [(MINKOWSKI, 0.02), (GODEL, 0.1)] {
        let disparity = |stereo: &str| {
            let tmp = tempfile::tempdir().unwrap();
            let camera = (fov, width, 60, stereo);
            render_ok(
                tmp.path(),
                "s.toml",
                &scene(metric, AT_ORIGIN, camera, &ball),
            );
            let left = ball_column(&tmp.path().join("out/s.left.exr"));
            left - ball_column(&tmp.path().join("out/s.right.exr"))
        };
        let got = disparity(&format!("stereo = {{ separation = {s} }}\n"));
        assert!(
            got > 0.0 && (got - want).abs() < tolerance * want,
            "{metric}: disparity {got:.2} px, flat-space estimate {want:.2} px"
        );
        let converged = disparity(&format!(
            "stereo = {{ separation = {s}, convergence = {d} }}\n"
        ));
        assert!(
            converged.abs() < tolerance * want,
            "{metric}: {converged:.2} px"
        );
    }
}

#[test]
fn bad_stereo_settings_are_refused_naming_the_field() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    for (stereo, needles) in [
        (
            "stereo = { separation = -1.0 }\n",
            &["camera.stereo.separation", "must not be negative"][..],
        ),
        (
            "stereo = { separation = 2.0 }\n",
            &["camera.stereo.separation", "at most 1"],
        ),
        (
            "stereo = { separation = 0.1, layout = \"cross-eyed\" }\n",
            &["camera.stereo.layout", "cross-eyed"],
        ),
        (
            "stereo = { separation = 0.1, convergence = 0.0 }\n",
            &["camera.stereo.convergence", "positive"],
        ),
        (
            "stereo = { separation = 0.1, baseline = 2 }\n",
            &["camera.stereo", "baseline"],
        ),
    ] {
        let text = scene(GODEL, AT_ORIGIN, (60.0, 16, 8, stereo), BALLS);
        let path = write_scene(tmp.path(), "bad.toml", &text);
        let o = render(Path::new(&path), &out, &["-q"]);
        let mut all = vec!["bad.toml:"];
        all.extend_from_slice(needles);
        assert_refused(&o, &all, &out);
    }
    let text = scene(
        GODEL,
        AT_ORIGIN,
        (60.0, 16, 8, "stereo = { separation = 0.1 }\n"),
        BALLS,
    );
    let path = write_scene(tmp.path(), "s.toml", &text);
    let o = render(Path::new(&path), &out, &["-q", "--part", "1/2"]);
    assert_refused(&o, &["--part", "stereo"], &out);
}

/// `godel shade` of one eye's data file re-colours the pair into its layout: the picture is
/// the two eyes shaded alone (`--one-eye`) put side by side, whichever eye is named; with the
/// other eye's file gone it says so.
#[test]
fn shade_colours_both_eyes_into_the_pairs_layout() {
    let tmp = tempfile::tempdir().unwrap();
    let camera = (60.0, 40, 16, "stereo = { separation = 0.1 }\n");
    render_ok(
        tmp.path(),
        "s.toml",
        &scene(GODEL, AT_ORIGIN, camera, BALLS),
    );
    let out = tmp.path().join("out");
    let shade = |data: &str, png: &str, extra: &[&str]| {
        let o = crate::common::shade(
            &out.join(data),
            &out.join(png),
            &[&["--shader", "frequency"], extra].concat(),
        );
        assert!(o.status.success(), "{}", stderr(&o));
    };
    shade("s.left.exr", "left.png", &["--one-eye"]);
    shade("s.right.exr", "right.png", &["--one-eye"]);
    shade("s.left.exr", "pair.png", &[]);
    shade("s.right.exr", "pair-from-right.png", &[]);
    let (left, right) = (png(&out.join("left.png")), png(&out.join("right.png")));
    let pair = png(&out.join("pair.png"));
    assert_eq!(pair, png(&out.join("pair-from-right.png")));
    assert_eq!(pair.dimensions(), (80, 16));
    assert_ne!(left, right, "the eyes see differently");
    for (x, y, p) in left.enumerate_pixels() {
        assert_eq!(pair.get_pixel(x, y), p);
        assert_eq!(pair.get_pixel(x + 40, y), right.get_pixel(x, y));
    }
    std::fs::remove_file(out.join("s.right.exr")).unwrap();
    let o = crate::common::shade(&out.join("s.left.exr"), &out.join("again.png"), &[]);
    assert_refused(
        &o,
        &["s.right.exr", "missing", "--one-eye"],
        &out.join("again.png"),
    );
}
