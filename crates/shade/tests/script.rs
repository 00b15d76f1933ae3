//! Tests of sequence scripts: keyframe interpolation (linear and smooth) at known fractions
//! against the formulas computed here, values held before the first and after the last
//! keyframe, non-numeric fields switching at keyframes, and located errors.

use std::path::Path;

use datafile::{DataFile, DataHeader, FORMAT_VERSION};
use datafile::record::PixelRecord;
use shade::{FrameSource, Interpolation, Script, ShadeError, ShadeSettings, ShaderKind};

fn data() -> DataFile {
    DataFile {
        header: DataHeader {
            format_version: FORMAT_VERSION,
            scene_name: "s".into(),
            scene_text: "name = \"s\"\n[[object]]\nname = \"ball\"\ntemperature = 5000.0\n".into(),
            camera: "panorama".into(),
            observer_time: 0.0,
            metric: "godel".into(),
            godel_a: 1.0,
            method: "numeric".into(),
            object_names: vec!["ball".into()],
        },
        width: 1,
        height: 1,
        records: vec![PixelRecord::MISS],
        lights: vec![],
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
        (
            "data = \"a\"\nframes = 3\n[[keyframe]]\n",
            "either `frame` or `time`",
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
            observer_time: Some([0.0, 2.0])
        }
    );
}
