//! Tests of sequence scripts: keyframe interpolation (linear and smooth) at known fractions
//! against the formulas computed here, values held before the first and after the last
//! keyframe, non-numeric fields switching at keyframes, and located errors.

use std::path::Path;

use datafile::record::PixelRecord;
use datafile::DataFile;
use shade::{FrameSource, Interpolation, Script, Section, ShadeError, ShadeSettings, ShaderKind};

fn data() -> DataFile {
    DataFile {
        header: testkit::godel_header(
            "s",
            "name = \"s\"\n[[object]]\nname = \"ball\"\ntemperature = 5000.0\n",
            "panorama",
            &["ball"],
        ),
        width: 1,
        height: 1,
        records: vec![PixelRecord::MISS],
        lights: vec![],
        polarization: false,
    }
}

fn script(text: &str) -> Result<Script, ShadeError> {
    Script::parse(text, Path::new("dir/seq.toml"))
}

const TWO_KEYS: &str = r#"data = "d.exr"
frames = 21
interpolation = "linear"

[[keyframe]]
frame = 5
[keyframe.settings]
exposure = 1.0
objects.ball.temperature = 3000.0

[[keyframe]]
frame = 15
interpolation = "smooth"
[keyframe.settings]
exposure = 3
shaders = ["frequency"]
objects.ball.temperature = 9000.0

[[keyframe]]
frame = 20
[keyframe.settings]
exposure = 5.0
"#;

#[test]
fn linear_and_smooth_interpolation_at_known_fractions() {
    let s = script(TWO_KEYS).unwrap();
    assert_eq!(
        s.source,
        FrameSource::Data(Path::new("dir/d.exr").to_path_buf())
    );
    assert_eq!(s.output, Path::new("dir/frames"));
    assert_eq!(s.keyframes[0].interpolation, Interpolation::Linear);
    assert_eq!(s.keyframes[1].interpolation, Interpolation::Smooth);
    let tl = s.timeline(&ShadeSettings::defaults_for(&data())).unwrap();
    // Before the first keyframe its values hold.
    assert_eq!(tl.settings_at(0).objects["ball"].temperature, 3000.0);
    // Linear from frame 5 to 15: fraction (f − 5)/10.
    for f in 5..=15u32 {
        let x = f64::from(f - 5) / 10.0;
        let st = tl.settings_at(f);
        assert!((st.objects["ball"].temperature - (3000.0 + 6000.0 * x)).abs() < 1e-9);
        assert!((st.exposure - (1.0 + 2.0 * x)).abs() < 1e-12);
    }
    // Smooth from 15 to 20: 3x² − 2x³ of (f − 15)/5; temperature stays (carried forward).
    for f in 15..=20u32 {
        let x = f64::from(f - 15) / 5.0;
        let e = x * x * (3.0 - 2.0 * x);
        let st = tl.settings_at(f);
        assert!((st.exposure - (3.0 + 2.0 * e)).abs() < 1e-12, "frame {f}");
        assert_eq!(st.objects["ball"].temperature, 9000.0);
    }
    // Smooth at a quarter: 0.15625, not 0.25.
    assert!((Interpolation::Smooth.ease(0.25) - 0.156_25).abs() < 1e-15);
    assert!((Interpolation::Smooth.ease(0.5) - 0.5).abs() < 1e-15);
    // Non-numeric fields switch when the next keyframe is reached.
    assert_eq!(tl.settings_at(14).shaders, vec![ShaderKind::Texture]);
    assert_eq!(tl.settings_at(15).shaders, vec![ShaderKind::Frequency]);
}

/// Fuzzing found frame 0 of a script with `offset_u` going from −1e308 to 1e308 with
/// offset_u = NaN: the interpolation computed x + s·(y − x), and y − x overflows. Every
/// frame between two finite keyframe values is finite, between them, and exact at the
/// keyframes.
#[test]
fn regression_fuzz_interpolation_between_extreme_values_stays_finite() {
    let s = script(
        r#"data = "d.exr"
frames = 5
interpolation = "linear"
[[keyframe]]
frame = 0
[keyframe.settings]
objects.ball.offset_u = -1e308
objects.ball.offset_v = 1.7976931348623157e308
[[keyframe]]
frame = 4
[keyframe.settings]
objects.ball.offset_u = 1e308
objects.ball.offset_v = 1.7976931348623157e308
"#,
    )
    .unwrap();
    let tl = s.timeline(&ShadeSettings::defaults_for(&data())).unwrap();
    let at = |f: u32| {
        let o = &tl.settings_at(f).objects["ball"];
        (o.offset_u, o.offset_v)
    };
    assert_eq!(at(0), (-1e308, f64::MAX));
    assert_eq!(at(4), (1e308, f64::MAX));
    assert_eq!(at(2).0, 0.0);
    for f in 0..5 {
        let (u, v) = at(f);
        assert!((-1e308..=1e308).contains(&u), "frame {f}: offset_u = {u}");
        assert_eq!(v, f64::MAX, "frame {f}");
    }
    assert!(at(1).0 < at(2).0 && at(2).0 < at(3).0);
}

/// Fuzzing found a sequence that stops half-way: a texture flipped by keyframes
/// (scale_u from −1 to 1) passes through scale 0 at an in-between frame, which the settings
/// refused after earlier frames were written. A zero scale is a valid picture (one texel over
/// the whole body): every frame of the flip prepares.
#[test]
fn regression_fuzz_a_flip_through_zero_scale_shades_every_frame() {
    let s = script(
        r#"data = "d.exr"
frames = 3
interpolation = "linear"
[[keyframe]]
frame = 0
[keyframe.settings]
objects.ball.scale_u = -1.0
objects.ball.texture = { kind = "checker", rows = 2, cols = 4 }
[[keyframe]]
frame = 2
[keyframe.settings]
objects.ball.scale_u = 1.0
"#,
    )
    .unwrap();
    let tl = s.timeline(&ShadeSettings::defaults_for(&data())).unwrap();
    assert_eq!(tl.settings_at(1).objects["ball"].scale_u, 0.0);
    for f in 0..3 {
        shade::Shading::new(&data(), &tl.settings_at(f)).unwrap();
    }
}

#[test]
fn keyframes_out_of_order_are_refused_with_file_line_and_field() {
    let text =
        "data = \"d.exr\"\nframes = 30\n\n[[keyframe]]\nframe = 10\n\n[[keyframe]]\nframe = 4\n";
    let e = script(text).unwrap_err();
    let m = e.to_string();
    assert!(
        m.starts_with("dir/seq.toml:8: keyframe[1].frame: keyframes out of order"),
        "{m}"
    );
    // Equal frames too.
    let e = script(&text.replace("frame = 4", "frame = 10")).unwrap_err();
    assert!(e.to_string().contains("out of order"), "{e}");
    // Past the last frame.
    let e = script(&text.replace("frame = 4", "frame = 30")).unwrap_err();
    assert!(
        e.to_string()
            .contains("keyframe[1].frame: frame 30 is past"),
        "{e}"
    );
}

#[test]
fn unknown_fields_and_objects_are_located() {
    let e = script("data = \"d.exr\"\nframes = 3\nfrmaes = 2\n").unwrap_err();
    assert!(e.to_string().starts_with("dir/seq.toml:3"), "{e}");
    assert!(e.to_string().contains("frmaes"), "{e}");
    let text = "data = \"d.exr\"\nframes = 3\n[[keyframe]]\nframe = 1\n[keyframe.settings]\nobjects.sun.temperature = 3.0\n";
    let e = script(text)
        .unwrap()
        .timeline(&ShadeSettings::defaults_for(&data()))
        .unwrap_err();
    let m = e.to_string();
    assert!(
        m.starts_with("dir/seq.toml:6: keyframe[0].settings.objects.sun"),
        "{m}"
    );
    assert!(m.contains("unknown object 'sun'"), "{m}");
    let text = "data = \"d.exr\"\nframes = 3\n[settings]\nshaders = [\"sepia\"]\n";
    let e = script(text)
        .unwrap()
        .timeline(&ShadeSettings::defaults_for(&data()))
        .unwrap_err();
    assert!(e.to_string().contains("sepia"), "{e}");
}

#[test]
fn sources_frames_and_times_are_checked() {
    for (text, needle) in [
        ("frames = 3\n", "either `data"),
        (
            "frames = 3\ndata = \"a\"\n[trace]\nscene = \"b\"\n",
            "either `data",
        ),
        ("data = \"a\"\nframes = 0\n", "frames: must be at least 1"),
        (
            "data = \"a\"\nframes = 3\nfps = -1.0\n",
            "fps: must be positive",
        ),
        // Issue 24: a keyframe with neither was told "give either …, not both".
        (
            "data = \"a\"\nframes = 3\n[[keyframe]]\n",
            "keyframe[0]: says neither when it is: give `frame` (a frame number) or `time`",
        ),
        (
            "data = \"a\"\nframes = 3\n[[keyframe]]\nframe = 1\ntime = 0.5\n",
            "either `frame` or `time` (seconds), not both",
        ),
    ] {
        let e = script(text).unwrap_err();
        assert!(e.to_string().contains(needle), "{text}: {e}");
    }
    // time in seconds: frame = round(time·fps).
    let s = script("data = \"a\"\nframes = 100\nfps = 10.0\n[[keyframe]]\ntime = 2.46\n").unwrap();
    assert_eq!(s.keyframes[0].frame, 25);
    let s =
        script("frames = 3\n[trace]\nscene = \"s.toml\"\nobserver_time = [0.0, 2.0]\n").unwrap();
    assert_eq!(
        s.source,
        FrameSource::Trace {
            scene: Path::new("dir/s.toml").to_path_buf(),
            observer_time: Some([0.0, 2.0]),
            keep_data: false,
        }
    );
    let s = script("frames = 3\n[trace]\nscene = \"s.toml\"\nkeep_data = true\n").unwrap();
    assert!(matches!(
        s.source,
        FrameSource::Trace {
            keep_data: true,
            observer_time: None,
            ..
        }
    ));
}

const FLIGHT: &str = r#"frames = 11
interpolation = "linear"
[trace]
scene = "s.toml"

[[keyframe]]
frame = 2
[keyframe.observer]
time = 1
position = { x = 0.5 }
[keyframe.camera]
fov_deg = 60

[[keyframe]]
frame = 6
interpolation = "smooth"
[keyframe.observer]
position = { y = -1.0, z = 2 }
forward = [0, 1, 0]

[[keyframe]]
frame = 10
[keyframe.observer]
time = 3.0
"#;

fn start() -> toml::Table {
    toml::toml! {
        time = 0.0
        position = { x = 0.0, y = 0.0, z = 0.0 }
        forward = [1.0, 0.0, 0.0]
    }
}

fn number(v: &toml::Value, path: &[&str]) -> f64 {
    let mut v = v;
    for key in path {
        v = match key.parse::<usize>() {
            Ok(i) => &v.as_array().unwrap()[i],
            Err(_) => &v[*key],
        };
    }
    v.as_float().unwrap()
}

#[test]
fn observer_and_camera_tracks_follow_the_keyframes_with_the_easing() {
    let s = script(FLIGHT).unwrap();
    let track = s.track(Section::Observer, &start()).unwrap();
    // Integers became floats; fields hold until a keyframe changes them.
    let at = |f: u32, path: &[&str]| number(&track.at(f), path);
    assert_eq!(
        at(0, &["time"]),
        1.0,
        "before the first keyframe its values hold"
    );
    assert_eq!(at(2, &["position", "x"]), 0.5);
    assert_eq!(at(6, &["position", "x"]), 0.5);
    assert_eq!(at(6, &["position", "z"]), 2.0);
    assert_eq!(at(10, &["forward", "1"]), 1.0);
    // Linear from keyframe 0 to 1 (frames 2 → 6): a quarter of the way at frame 3.
    assert_eq!(at(3, &["position", "y"]), -0.25);
    assert_eq!(at(3, &["forward", "0"]), 1.0 - 0.25);
    // Smooth from keyframe 1 to 2 (frames 6 → 10): time 1 → 3 at s = 1/4.
    let e = 0.25 * 0.25 * (3.0 - 2.0 * 0.25);
    assert!((at(7, &["time"]) - (1.0 + e * 2.0)).abs() < 1e-15);
    assert_eq!(at(10, &["time"]), 3.0);
    // The camera: keys among CAMERA_KEYS; one the start lacks is located.
    let camera = s
        .track(Section::Camera, &toml::toml! { fov_deg = 90.0 })
        .unwrap();
    assert_eq!(number(&camera.at(0), &["fov_deg"]), 60.0);
    let e = s
        .track(Section::Camera, &toml::toml! { h_fov_deg = 90.0 })
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("seq.toml:12") && e.contains("keyframe[0].camera.fov_deg"),
        "{e}"
    );
    assert!(shade::CAMERA_KEYS.contains(&"v_fov_deg"));
    assert!(s.sets(Section::Observer) && s.sets(Section::Camera));
    assert!(!s.sets(Section::Settings));
    assert_eq!(s.keyframe_towards(0), Some(0));
    assert_eq!(s.keyframe_towards(7), Some(2));
    assert_eq!(s.keyframe_towards(10), Some(2));
}

#[test]
fn bad_observer_and_camera_keyframes_are_located() {
    let traced = "frames = 5\n[trace]\nscene = \"s.toml\"\n";
    for (text, line, field, needle) in [
        (
            format!("{traced}[[keyframe]]\nframe = 1\n[keyframe.observer]\nvelocity = {{ speed = nan }}\n"),
            7,
            "keyframe[0].observer.velocity.speed",
            "must be finite",
        ),
        (
            format!("{traced}[[keyframe]]\nframe = 1\n[keyframe.observer]\nposition = {{ r = 1.0 }}\n"),
            7,
            "keyframe[0].observer.position.r",
            "unknown field 'r' (expected one of: x, y, z)",
        ),
        (
            format!("{traced}[[keyframe]]\nframe = 1\n[keyframe.observer]\nforward = [1, 0]\n"),
            7,
            "keyframe[0].observer.forward",
            "array of 3 numbers",
        ),
        (
            format!("{traced}[[keyframe]]\nframe = 1\n[keyframe.camera]\nwidth = 10\n"),
            7,
            "keyframe[0].camera.width",
            "unknown field 'width'",
        ),
        (
            "frames = 5\n[trace]\nscene = \"s.toml\"\nobserver_time = [0.0, 1.0]\n\
             [[keyframe]]\nframe = 1\n[keyframe.observer]\ntime = 0.5\n"
                .to_string(),
            8,
            "keyframe[0].observer.time",
            "observer_time",
        ),
        (
            "data = \"d.exr\"\nframes = 5\n[[keyframe]]\nframe = 1\n[keyframe.camera]\nfov_deg = 10\n"
                .to_string(),
            6,
            "keyframe[0].camera.fov_deg",
            "re-shades one data file",
        ),
    ] {
        let e = script(&text).unwrap_err();
        let ShadeError::Script {
            line: l, field: f, ..
        } = &e
        else {
            panic!("{e}")
        };
        assert_eq!((*l, f.as_str()), (line, field), "{text}: {e}");
        assert!(e.to_string().contains(needle), "{text}: {e}");
    }
}
