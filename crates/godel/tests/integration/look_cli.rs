//! End-to-end tests of `godel look`: from a full-sphere render it writes VIEW.exr (the very
//! records of `look::look`, or of `look::look_with` for `--samples` and `--filter`, with a
//! header and scene describing the new view) and
//! VIEW.png, and reports the source's resolution; the scene it embeds renders the same
//! view when traced; negative flag values are accepted; a file that is not a static
//! observer's full sphere, a part file and bad flags are refused with the file or flag
//! named, exit 2 (1 for unreadable files), and no output.

use crate::common::{self, files_in, godel, path_arg as s, stderr};
use datafile::DataFile;
use look::{look, look_with, Filter, LookView, Sampling};
use scene::{Camera, Scene};
use spacetime::LocalVelocity;
use std::path::{Path, PathBuf};
use std::process::Output;

/// A ball at rest at r = 1, its first image 39.2° to the left of +x, traced over the
/// whole sphere (or another camera).
fn scene_text(name: &str, camera: &str, observer_extra: &str) -> String {
    let ball = testkit::textured_ball_at("ball", 0.3, &testkit::checker(4, 8), 5800.0, 1.0, 0.0);
    format!(
        "name = \"{name}\"\n{}{observer_extra}\n[camera]\n{camera}\n{}{ball}",
        testkit::OBSERVER_AT_ORIGIN,
        testkit::trace("exact", 6.0),
    )
}

const SPHERE: &str = "kind = \"sphere\"\nwidth = 240\nheight = 120";

/// Renders `text` into `dir`, returns the data file's path.
fn render(dir: &Path, name: &str, text: &str, extra: &[&str]) -> PathBuf {
    let scene = dir.join(format!("{name}.toml"));
    std::fs::write(&scene, text).unwrap();
    let o = common::render(&scene, dir, &[&["-q"], extra].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    dir.join(format!("{name}.exr"))
}

/// Renders the full sphere of [`scene_text`] into `dir`; returns the data file's path.
fn sphere_source(dir: &Path) -> PathBuf {
    render(dir, "sphere", &scene_text("sphere", SPHERE, ""), &[])
}

/// Runs `godel look DATA -o OUT` followed by `flags` (separated by spaces) and asserts that it
/// succeeds; returns its standard error.
fn look_ok(data: &Path, out: &Path, flags: &str) -> String {
    let o = run_look(data, out, &flags.split(' ').collect::<Vec<_>>());
    assert!(o.status.success(), "{}", stderr(&o));
    stderr(&o)
}

/// Runs `godel look DATA -o OUT` followed by `extra` to its end.
fn run_look(data: &Path, out: &Path, extra: &[&str]) -> Output {
    godel(&[&["look", s(data), "-o", s(out)], extra].concat())
}

#[test]
fn look_writes_the_view_and_its_preview_and_reports_resolution() {
    let tmp = tempfile::tempdir().unwrap();
    let sphere = sphere_source(tmp.path());
    let out = tmp.path().join("views/fast.exr");
    let e = look_ok(
        &sphere,
        &out,
        "--camera pinhole --fov 90 --width 64 --height 48 --forward 0.7746,0.6325,0 --up 0,0,1 \
         --velocity 0.9,0,1,0",
    );
    assert!(e.contains("a source pixel spans 1.5000°"), "{e}");
    assert!(e.contains("of the static observer's sky"), "{e}");
    let data = DataFile::read(&out).expect("a data file");
    let png = image::open(out.with_extension("png")).expect("a preview");
    assert_eq!((png.width(), png.height()), (64, 48));
    // The records are the library's.
    let velocity = LocalVelocity::new(0.9, [0.0, 1.0, 0.0]).unwrap();
    let cam = Camera::Pinhole {
        fov_deg: 90.0,
        width: 64,
        height: 48,
    };
    let view = LookView::new(cam, [0.7746, 0.6325, 0.0], [0.0, 0.0, 1.0], velocity).unwrap();
    let want = look(&DataFile::read(&sphere).unwrap(), &view).unwrap();
    assert_eq!(data, want);
    assert!(data.records.iter().any(|r| r.is_hit() && r.g > 1.0));
    // The header describes the view, and its scene is the sphere's with the view replaced.
    assert_eq!(data.header.camera, "pinhole 90°, 64×48");
    let (observer, camera) = Scene::read_view(&data.header.scene_text, "x").unwrap();
    assert_eq!((camera, observer.velocity), (cam, velocity));
    // Issue 36: `-o` takes `.exr` in any case, as render's, the preview in the same case
    // (look refused `VIEW.EXR`).
    let upper = tmp.path().join("upper/VIEW.EXR");
    look_ok(
        &sphere,
        &upper,
        "--camera pinhole --fov 90 --width 16 --height 12",
    );
    assert_eq!(
        files_in(&tmp.path().join("upper")),
        ["VIEW.EXR", "VIEW.PNG"]
    );
}

#[test]
fn samples_and_filter_give_the_librarys_records() {
    let tmp = tempfile::tempdir().unwrap();
    let sphere = sphere_source(tmp.path());
    let source = DataFile::read(&sphere).unwrap();
    let cam = Camera::Pinhole {
        fov_deg: 90.0,
        width: 64,
        height: 48,
    };
    let view = LookView::new(
        cam,
        [0.7746, 0.6325, 0.0],
        [0.0, 0.0, 1.0],
        LocalVelocity::REST,
    )
    .unwrap();
    let flags = "--camera pinhole --fov 90 --width 64 --height 48 --forward 0.7746,0.6325,0";
    for (filter, extra) in [(Filter::Nearest, " --filter nearest"), (Filter::Smooth, "")] {
        let out = tmp.path().join(format!("{filter:?}.exr"));
        look_ok(&sphere, &out, &format!("{flags} --samples 4{extra}"));
        let data = DataFile::read(&out).unwrap();
        let want = look_with(&source, &view, Sampling { filter, samples: 4 }).unwrap();
        assert_eq!(data, want, "{filter:?}");
        assert_eq!(
            (data.width, data.height, data.header.supersample),
            (128, 96, 2)
        );
        // The preview is the picture's size: the samples are averaged.
        let png = image::open(out.with_extension("png")).unwrap();
        assert_eq!((png.width(), png.height()), (64, 48));
    }
    // The two filters differ inside the ball (smooth blends, nearest copies).
    let [nearest, smooth] = ["Nearest", "Smooth"]
        .map(|f| DataFile::read(&tmp.path().join(format!("{f}.exr"))).unwrap());
    let differ = nearest
        .records
        .iter()
        .zip(&smooth.records)
        .filter(|(a, b)| a.is_hit() && a.object == b.object && a.u != b.u)
        .count();
    assert!(differ > 1000, "{differ}");
}

#[test]
fn the_embedded_scene_traces_the_same_view() {
    let tmp = tempfile::tempdir().unwrap();
    let sphere = sphere_source(tmp.path());
    let out = tmp.path().join("pano.exr");
    look_ok(
        &sphere,
        &out,
        "--camera panorama --h-fov 360 --v-fov 60 --width 240 --height 40 --velocity 0.6,0,-1,0",
    );
    let looked = DataFile::read(&out).unwrap();
    let traced = render(
        tmp.path(),
        "again",
        &looked
            .header
            .scene_text
            .replace("name = \"sphere\"", "name = \"again\""),
        &[],
    );
    let traced = DataFile::read(&traced).unwrap();
    assert_eq!((traced.width, traced.height), (240, 40));
    let same = looked
        .records
        .iter()
        .zip(&traced.records)
        .filter(|(a, b)| a.object == b.object)
        .count();
    let hits = traced.records.iter().filter(|r| r.is_hit()).count();
    // Only pixels at the ball's edges may differ (the sphere's pixels are 1.5°).
    assert!(hits > 200, "{hits}");
    assert!(same as f64 > 0.97 * (240.0 * 40.0), "{same}");
}

#[test]
fn negative_values_are_flag_values() {
    let tmp = tempfile::tempdir().unwrap();
    let sphere = sphere_source(tmp.path());
    let run = |name: &str, flags: &[&str]| -> DataFile {
        let out = tmp.path().join(format!("{name}.exr"));
        let base = ["--camera", "fisheye", "--width", "40"];
        let o = run_look(&sphere, &out, &[&base[..], flags].concat());
        assert!(o.status.success(), "{flags:?}: {}", stderr(&o));
        DataFile::read(&out).unwrap()
    };
    let a = run("a", &["--forward", "-1,0,0", "--velocity", "-0.5,1,0,0"]);
    let b = run("b", &["--forward=-1,0,0", "--velocity=0.5,-1,0,0"]);
    assert_eq!(a.records, b.records);
    let (observer, _) = Scene::read_view(&a.header.scene_text, "a").unwrap();
    assert_eq!(observer.velocity.direction, [-1.0, 0.0, 0.0]);
    assert_eq!(observer.forward, [-1.0, 0.0, 0.0]);
}

/// Runs `godel look` expecting a refusal: exit `code`, every needle in the first line of
/// stderr, and no file left in `dir` besides `keep`.
fn refused(dir: &Path, keep: &[&str], args: &[&str], code: i32, needles: &[&str]) {
    let o = godel(args);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{args:?}: {e}");
    let first = e.lines().next().unwrap_or("");
    for n in needles {
        assert!(first.contains(n), "{args:?}: expected {n:?} in {e}");
    }
    let mut left: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| !keep.contains(&n.as_str()))
        .collect();
    left.sort();
    assert!(left.is_empty(), "{args:?} left {left:?}");
}

#[test]
fn bad_sources_and_flags_are_refused_with_nothing_written() {
    let tmp = tempfile::tempdir().unwrap();
    let src = tmp.path().join("src");
    std::fs::create_dir(&src).unwrap();
    let sphere = sphere_source(&src);
    let pinhole = render(
        &src,
        "pinhole",
        &scene_text(
            "pinhole",
            "kind = \"pinhole\"\nfov_deg = 60\nwidth = 16\nheight = 8",
            "",
        ),
        &[],
    );
    let moving = render(
        &src,
        "moving",
        &scene_text(
            "moving",
            SPHERE,
            "velocity = { speed = 0.5, direction = [0, 1, 0] }",
        ),
        &[],
    );
    render(
        &src,
        "sphere",
        &scene_text("sphere", SPHERE, ""),
        &["--part", "1/2"],
    );
    let part = src.join("sphere.part-1-of-2.exr");
    assert!(part.exists());
    let out_dir = tmp.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let out = out_dir.join("v.exr");
    let o = s(&out);
    let look = |file: &Path, flags: &[&str]| -> Vec<String> {
        let mut v = vec!["look".to_string(), s(file).to_string()];
        v.extend(flags.iter().map(|f| f.to_string()));
        v.extend(["-o".to_string(), o.to_string()]);
        v
    };
    let pin = [
        "--camera", "pinhole", "--fov", "60", "--width", "16", "--height", "8",
    ];
    let check = |args: Vec<String>, code: i32, needles: &[&str]| {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&out_dir, &[], &args, code, needles);
    };
    // Sources.
    check(
        look(&pinhole, &pin),
        2,
        &["pinhole.exr", "not a full-sphere", "pinhole 60°, 16×8"],
    );
    check(
        look(&moving, &pin),
        2,
        &["moving.exr", "0.5 c", "static observer"],
    );
    check(
        look(&part, &pin),
        1,
        &["sphere.part-1-of-2.exr", "part 1/2", "godel merge"],
    );
    check(look(&src.join("missing.exr"), &pin), 1, &["missing.exr"]);
    // Flags: each case replaces (or adds) one flag of a good pinhole view.
    let bad: [(&str, &str, &[&str]); 18] = [
        ("--samples", "3", &["--samples", "square number"]),
        ("--samples", "0", &["--samples", "1..=256"]),
        ("--filter", "cubic", &["--filter", "cubic"]),
        ("--velocity", "1,1,0,0", &["--velocity", "below 1"]),
        ("--velocity", "-1.5,1,0,0", &["--velocity", "below 1"]),
        ("--velocity", "0.5,0,0,0", &["--velocity", "direction"]),
        (
            "--velocity",
            "0.5,1,0",
            &["--velocity", "4 comma-separated"],
        ),
        ("--velocity", "NaN,1,0,0", &["--velocity"]),
        ("--forward", "0,0,0", &["--forward", "non-zero"]),
        ("--up", "1,0,0.5", &["--up", "orthogonal"]),
        ("--up", "1,0", &["--up"]),
        (
            "--forward",
            "0,0,1",
            &["--up", "the sphere's up", "give --up"],
        ),
        ("--fov", "180", &["--fov", "(0, 180)"]),
        ("--fov", "-10", &["--fov"]),
        ("--h-fov", "90", &["--h-fov", "not used"]),
        ("--width", "0", &["--width"]),
        ("--height", "30000", &["--height"]),
        ("--camera", "orthographic", &["--camera", "orthographic"]),
    ];
    for (flag, value, needles) in bad {
        let mut all: Vec<&str> = Vec::new();
        for pair in pin.chunks(2).filter(|p| p[0] != flag) {
            all.extend_from_slice(pair);
        }
        all.extend([flag, value]);
        check(look(&sphere, &all), 2, needles);
    }
    check(
        look(
            &sphere,
            &["--camera", "pinhole", "--width", "16", "--height", "8"],
        ),
        2,
        &["--fov", "required"],
    );
    check(
        look(
            &sphere,
            &[
                "--camera", "panorama", "--h-fov", "90", "--width", "16", "--height", "8",
            ],
        ),
        2,
        &["--v-fov", "required"],
    );
    check(
        look(
            &sphere,
            &["--camera", "fisheye", "--width", "16", "--height", "8"],
        ),
        2,
        &["--height", "square"],
    );
    check(
        look(
            &sphere,
            &["--camera", "sphere", "--fov", "90", "--width", "16"],
        ),
        2,
        &["--fov", "not used"],
    );
    let png_out = [
        "look",
        s(&sphere),
        "--camera",
        "sphere",
        "--width",
        "16",
        "-o",
    ];
    let target = out_dir.join("v.png");
    refused(
        &out_dir,
        &[],
        &[&png_out[..], &[s(&target)]].concat(),
        2,
        &["--output", ".exr"],
    );
}

/// Issue 24: `godel look S.exr … -o S.exr` replaced the sphere with a small view; a negative
/// `--width` got clap's misleading `-- -5` tip; an overflowing velocity direction was called
/// zero and printed with 300 digits; a damaged embedded scene exited 2, not the documented 1.
#[test]
fn inputs_are_kept_and_odd_values_get_accurate_messages() {
    let tmp = tempfile::tempdir().unwrap();
    let sphere = sphere_source(tmp.path());
    let bytes = std::fs::read(&sphere).unwrap();
    let pin = [
        "--camera", "pinhole", "--fov", "60", "--width", "16", "--height", "8",
    ];
    let o = run_look(&sphere, &sphere, &pin);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("--output") && e.contains("the sphere this run reads"),
        "{e}"
    );
    assert_eq!(std::fs::read(&sphere).unwrap(), bytes);

    let out = tmp.path().join("v.exr");
    for (flag, value) in [("--width", "-5"), ("--height", "-5")] {
        let mut args: Vec<&str> = pin
            .chunks(2)
            .filter(|p| p[0] != flag)
            .flatten()
            .copied()
            .collect();
        args.extend([flag, value]);
        let o = run_look(&sphere, &out, &args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{e}");
        assert!(
            e.starts_with(&format!("error: {flag}: must be at least 1 pixel, got -5")),
            "{e}"
        );
        assert!(!e.contains("-- -5"), "{e}");
    }
    // A direction whose length overflows is still a direction: that of (1, 1, 0).
    let o = run_look(
        &sphere,
        &out,
        &[&pin[..], &["--velocity", "0.5,1e308,1e308,0"]].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let (observer, _) =
        Scene::read_view(&DataFile::read(&out).unwrap().header.scene_text, "v").unwrap();
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (c, want) in observer.velocity.direction.iter().zip([h, h, 0.0]) {
        assert!(
            (c - want).abs() < 1e-12,
            "{:?}",
            observer.velocity.direction
        );
    }
    let o = run_look(
        &sphere,
        &out,
        &[&pin[..], &["--velocity", "1e300,1,0,0"]].concat(),
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("got 1e300") && e.len() < 200, "{e}");

    // A data file whose embedded scene is damaged: exit 1 naming the file.
    let mut damaged = DataFile::read(&sphere).unwrap();
    damaged.header.scene_text = "name = \"sphere\"\n[camera]\nkind = ".into();
    let broken = tmp.path().join("broken.exr");
    damaged.write(&broken).unwrap();
    let o = run_look(&broken, &out, &pin);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("broken.exr"), "{e}");
}
