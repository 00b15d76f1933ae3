//! End-to-end tests of `godel sequence`: numbered frames from one data file with keyframed
//! settings (checked against the interpolation formula through the pictures), frames traced
//! from a scene with the observer time advancing, the ffmpeg note or MP4, and bad scripts
//! (keyframes out of order, unknown object) refused with file, line and field and no frames.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use render::datafile::{DataFile, DataHeader, FORMAT_VERSION};
use render::record::{PixelRecord, RayStatus};

fn godel(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_godel"))
        .args(args)
        .output()
        .expect("run godel")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A 4×1 data file of one object "ball" with g = 1.
fn data_file(dir: &Path) -> PathBuf {
    let data = DataFile {
        header: DataHeader {
            format_version: FORMAT_VERSION,
            scene_name: "syn".into(),
            scene_text: "name = \"syn\"\n[[object]]\nname = \"ball\"\n".into(),
            camera: "panorama".into(),
            observer_time: 0.0,
            metric: "godel".into(),
            godel_a: 1.0,
            method: "numeric".into(),
            object_names: vec!["ball".into()],
        },
        width: 4,
        height: 1,
        records: vec![
            PixelRecord {
                object: 0,
                status: RayStatus::Hit,
                g: 1.0,
                t_emit: -1.0,
                cos_i: 1.0,
                ..PixelRecord::MISS
            };
            4
        ],
        lights: vec![],
    };
    let path = dir.join("syn.exr");
    data.write(&path).unwrap();
    path
}

fn png(path: &Path) -> image::RgbImage {
    image::open(path).unwrap().to_rgb8()
}

#[test]
fn keyframed_frames_follow_the_interpolation() {
    let dir = tempfile::tempdir().unwrap();
    data_file(dir.path());
    // Uniform texture whose green channel goes 0 → 1 linearly over frames 0..4, on a body
    // with cos_i = 1 (Lambert factor 1).
    let script = dir.path().join("seq.toml");
    std::fs::write(
        &script,
        r#"data = "syn.exr"
output = "frames"
frames = 5
interpolation = "linear"
mp4 = true

[[keyframe]]
frame = 0
[keyframe.settings.objects.ball]
texture = { kind = "uniform", color = [0.0, 0.0, 0.0] }

[[keyframe]]
frame = 4
[keyframe.settings.objects.ball]
texture = { kind = "uniform", color = [0.0, 1.0, 0.0] }
"#,
    )
    .unwrap();
    let o = godel(&["sequence", script.to_str().unwrap(), "-q"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    let srgb = |x: f64| {
        let s = if x <= 0.003_130_8 {
            12.92 * x
        } else {
            1.055 * x.powf(1.0 / 2.4) - 0.055
        };
        (255.0 * s).round() as u8
    };
    for i in 0..5u32 {
        let p = png(&dir.path().join(format!("frames/frame_{i:04}.png")));
        let expect = srgb(f64::from(i) / 4.0);
        assert!(p.get_pixel(2, 0)[1].abs_diff(expect) <= 1, "frame {i}");
    }
    assert!(!dir.path().join("frames/frame_0005.png").exists());
    // Either an MP4 or the note saying how to get one.
    let mp4 = dir.path().join("frames/sequence.mp4");
    assert!(
        mp4.exists()
            || (e.contains("ffmpeg is not on PATH") && e.contains("apt-get install ffmpeg")),
        "{e}"
    );
}

#[test]
fn a_scene_traced_with_the_observer_time_advancing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("fall.toml"),
        r#"name = "fall"
[observer]
position = { r = 0.0, phi = 0.0, z = 0.0 }
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "panorama"
h_fov_deg = 360.0
v_fov_deg = 40.0
width = 48
height = 6
[trace]
max_past = 4.0
[[object]]
name = "ball"
radius = 0.3
motion = { kind = "geodesic", time = 0.0, position = { x = 1.0, y = -0.5, z = 0.0 }, speed = 0.5, direction = [0, 1, 0] }
"#,
    )
    .unwrap();
    let script = dir.path().join("seq.toml");
    std::fs::write(
        &script,
        "output = \"out\"\nframes = 2\nmp4 = false\n[trace]\nscene = \"fall.toml\"\nobserver_time = [0.0, 1.5]\n",
    )
    .unwrap();
    let o = godel(&["sequence", script.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let a = png(&dir.path().join("out/frame_0000.png"));
    let b = png(&dir.path().join("out/frame_0001.png"));
    assert_eq!(a.dimensions(), (48, 6));
    assert_ne!(
        a, b,
        "the falling ball moved between observer times 0 and 1.5"
    );
    assert!(!dir.path().join("out/sequence.mp4").exists());
}

fn refused(script_text: &str, needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    data_file(dir.path());
    let script = dir.path().join("bad.toml");
    std::fs::write(&script, script_text).unwrap();
    let o = godel(&["sequence", script.to_str().unwrap(), "-q"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    for n in needles {
        assert!(e.contains(n), "expected {n:?} in {e}");
    }
    assert!(
        !dir.path().join("frames").exists(),
        "no frames for a bad script"
    );
}

#[test]
fn bad_scripts_are_refused_before_any_frame() {
    refused(
        "data = \"syn.exr\"\nframes = 9\n\n[[keyframe]]\nframe = 6\n\n[[keyframe]]\nframe = 2\n",
        &["bad.toml:8", "keyframe[1].frame", "out of order"],
    );
    refused(
        "data = \"syn.exr\"\nframes = 9\n[[keyframe]]\nframe = 1\n[keyframe.settings]\nobjects.sun.temperature = 3000.0\n",
        &["bad.toml:6", "keyframe[0].settings.objects.sun", "unknown object 'sun'"],
    );
    refused(
        "data = \"syn.exr\"\nframes = 9\n[settings]\nexposure = -1.0\n",
        &["exposure", "≥ 0"],
    );
    refused(
        "data = \"syn.exr\"\nframes = 9\nspeed = 3\n",
        &["bad.toml:3", "speed"],
    );
}

#[test]
fn example_scripts_parse() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../sequences");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let script = shade::Script::from_file(&path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert!(script.frames > 0);
            n += 1;
        }
    }
    assert!(n >= 2, "the examples are in sequences/");
}
