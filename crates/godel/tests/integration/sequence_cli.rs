//! End-to-end tests of `godel sequence`: numbered frames from one data file with keyframed
//! settings (checked against the interpolation formula through the pictures), frames traced
//! from a scene with the observer time advancing, the ffmpeg note or MP4, and bad scripts
//! (keyframes out of order, unknown object, frame counts and rates out of bounds, an
//! unwritable output folder) refused with file, line and field and no frames; a run writes
//! only its own frames.

use std::path::{Path, PathBuf};
use std::process::Command;

use datafile::DataFile;

use crate::common::{self, assert_refused, files_in, godel, png, sequence_within, stderr};

/// Long enough for any of these commands on a loaded machine; they take well under a second.
const NEVER_HANGS: std::time::Duration = std::time::Duration::from_secs(120);

/// A 4×1 data file of one object "ball" with g = 1.
fn data_file(dir: &Path) -> PathBuf {
    let data = DataFile {
        header: testkit::godel_header(
            "syn",
            "name = \"syn\"\n[[object]]\nname = \"ball\"\n",
            "panorama",
            &["ball"],
        ),
        width: 4,
        height: 1,
        records: vec![testkit::hit(0, 0.0, 0.0, 1.0, -1.0, 1.0); 4],
        lights: vec![],
        polarization: false,
    };
    let path = dir.join("syn.exr");
    data.write(&path).unwrap();
    path
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
    // The guide's display curve (docs/guide/src/shading.md): identity to 0.8, then 0.8 + 0.2·y/(1 + y), y = (x − 0.8)/0.2.
    let tone = |x: f64| {
        if x <= 0.8 {
            x
        } else {
            let y = (x - 0.8) / 0.2;
            0.8 + 0.2 * y / (1.0 + y)
        }
    };
    let srgb = |x: f64| {
        let x = tone(x);
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
        testkit::axis_panorama(
            "fall",
            48,
            6,
            4.0,
            r#"[[object]]
name = "ball"
radius = 0.3
motion = { kind = "geodesic", time = 0.0, position = { x = 1.0, y = -0.5, z = 0.0 }, speed = 0.5, direction = [0, 1, 0] }
"#,
        ),
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

/// Runs `godel sequence` on each script text, which must be refused before any frame with a
/// message holding every needle.
fn refused_all(cases: &[(&str, &[&str])]) {
    for (script_text, needles) in cases {
        refused(script_text, needles);
    }
}

fn refused(script_text: &str, needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    data_file(dir.path());
    let script = dir.path().join("bad.toml");
    std::fs::write(&script, script_text).unwrap();
    // Bounded: before the frame count was bounded, `frames = 1e9` wrote until the disk
    // was full.
    let o = sequence_within(&script, NEVER_HANGS);
    assert_refused(&o, needles, &dir.path().join("frames"));
}

#[test]
fn bad_scripts_are_refused_before_any_frame() {
    refused_all(&[
        ("data = \"syn.exr\"\nframes = 9\n\n[[keyframe]]\nframe = 6\n\n[[keyframe]]\nframe = 2\n", &["bad.toml:8", "keyframe[1].frame", "out of order"]),
        ("data = \"syn.exr\"\nframes = 9\n[[keyframe]]\nframe = 1\n[keyframe.settings]\nobjects.sun.temperature = 3000.0\n", &["bad.toml:6", "keyframe[0].settings.objects.sun", "unknown object 'sun'"]),
        ("data = \"syn.exr\"\nframes = 9\n[settings]\nexposure = -1.0\n", &["exposure", "≥ 0"]),
        ("data = \"syn.exr\"\nframes = 9\nspeed = 3\n", &["bad.toml:3", "speed"]),
    ]);
}

/// Issue 10: `frames = 1000000000` wrote until the disk was full; `fps = 1e300` was accepted.
#[test]
fn frame_counts_and_rates_are_bounded() {
    refused_all(&[
        (
            "data = \"syn.exr\"\nframes = 1000000000\n",
            &["bad.toml:2", "frames", "at most 100000"],
        ),
        (
            "data = \"syn.exr\"\nframes = 100001\n",
            &["bad.toml:2", "frames", "at most 100000"],
        ),
        (
            "data = \"syn.exr\"\nframes = 9\nfps = 1e300\n",
            &["bad.toml:3", "fps", "at most 1000"],
        ),
    ]);
}

/// Issue 10: an unwritable output folder was found only after the work; a script or data
/// file that is not a regular file (a FIFO blocks on open) was read without a bound.
#[test]
fn unwritable_outputs_and_odd_inputs_are_refused_before_any_frame() {
    refused(
        "data = \"syn.exr\"\nframes = 2\n\noutput = \"/dev/null/frames\"\n[settings]\nshaders = [\"frequency\"]\n",
        &[
            "bad.toml:4",
            "output",
            "cannot create the folder /dev/null/frames",
        ],
    );
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("fifo");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let script = dir.path().join("s.toml");
    std::fs::write(&script, "data = \"fifo\"\nframes = 2\n").unwrap();
    for input in [&fifo, &script] {
        let o = sequence_within(input, NEVER_HANGS);
        let e = stderr(&o);
        assert!(!o.status.success(), "{e}");
        assert!(e.contains("not a regular file (a FIFO)"), "{e}");
        assert!(!dir.path().join("frames").exists());
    }
}

/// Issue 10: re-running a sequence with fewer frames into the same folder made an MP4 with
/// the old frames in it. The earlier run's extra frames and its MP4 are removed first — those
/// its manifest names (issue 24): a file of the user's named like a frame or the MP4 stays.
#[test]
fn a_shorter_rerun_leaves_only_its_own_frames() {
    let dir = tempfile::tempdir().unwrap();
    data_file(dir.path());
    let script = dir.path().join("s.toml");
    let run = |frames: u32| {
        std::fs::write(
            &script,
            format!(
                "data = \"syn.exr\"\noutput = \"out\"\nframes = {frames}\nmp4 = false\n\
                 [settings]\nshaders = [\"frequency\"]\n"
            ),
        )
        .unwrap();
        let o = godel(&["sequence", script.to_str().unwrap(), "-q"]);
        assert!(o.status.success(), "{}", stderr(&o));
        o
    };
    run(10);
    let out = dir.path().join("out");
    // An MP4 of the 10 frames as ffmpeg would have left it (recorded), and files of the
    // user's, one named like a frame beyond the count.
    std::fs::write(out.join("sequence.mp4"), b"old movie").unwrap();
    common::record_as_sequence_output(&out, &["sequence.mp4"]);
    std::fs::write(out.join("notes.txt"), b"mine").unwrap();
    std::fs::write(out.join("frame_0020.png"), b"mine too").unwrap();
    let o = run(4);
    let e = stderr(&o);
    assert!(e.contains("removed 7 file(s) of an earlier run"), "{e}");
    assert!(
        e.contains("frame_0004.png") && e.contains("sequence.mp4"),
        "{e}"
    );
    let expect: Vec<String> = [common::MANIFEST.to_string()]
        .into_iter()
        .chain((0..4).map(|i| format!("frame_{i:04}.png")))
        .chain(["frame_0020.png".to_string(), "notes.txt".to_string()])
        .collect();
    assert_eq!(files_in(&out), expect);
}

/// Issue 24: a sequence that re-shades a data file, its output folder being that file's
/// folder, removed the input and every traced `frame_NNNN.exr` there (and exited 0 with a
/// note). A sequence removes only what its manifest says an earlier sequence wrote, never its
/// input, never a file that changed since it was written.
#[test]
fn a_sequence_never_removes_its_input_or_files_it_did_not_write() {
    let dir = tempfile::tempdir().unwrap();
    let fly = dir.path().join("fly");
    std::fs::create_dir(&fly).unwrap();
    // The repro: a render named like a frame, re-shaded into its own folder.
    std::fs::copy(data_file(dir.path()), fly.join("frame_0002.exr")).unwrap();
    std::fs::write(fly.join("frame_0003.exr"), b"another render").unwrap();
    let script = dir.path().join("r.toml");
    let write_script = |data: &str, frames: u32| {
        let text = format!(
            "data = \"{data}\"\noutput = \"fly\"\nframes = {frames}\nmp4 = false\n\
             [settings]\nshaders = [\"frequency\"]\n"
        );
        std::fs::write(&script, text).unwrap();
    };
    let expected = [
        common::MANIFEST,
        "frame_0000.png",
        "frame_0001.png",
        "frame_0002.exr",
        "frame_0003.exr",
    ];
    write_script("fly/frame_0002.exr", 2);
    let o = godel(&["sequence", script.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("removed"), "{}", stderr(&o));
    let before = std::fs::read(fly.join("frame_0002.exr")).unwrap();
    assert_eq!(files_in(&fly), expected);
    // Even a data file an earlier sequence wrote is not removed while it is the input.
    common::record_as_sequence_output(&fly, &["frame_0002.exr"]);
    // And a frame the user replaced since its sequence wrote it stays, with a note.
    std::fs::write(fly.join("frame_0001.png"), b"the user's own picture now").unwrap();
    write_script("fly/frame_0002.exr", 1);
    let o = godel(&["sequence", script.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("changed since: frame_0001.png"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(fly.join("frame_0002.exr")).unwrap(), before);
    assert_eq!(files_in(&fly), expected);
}

/// Issue 24: an output of a sequence that is one of its inputs is refused before any frame.
#[test]
fn a_sequence_whose_output_is_its_input_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    std::fs::copy(data_file(dir.path()), out.join("frame_0001.png")).unwrap();
    let script = dir.path().join("s.toml");
    std::fs::write(
        &script,
        "data = \"out/frame_0001.png\"\noutput = \"out\"\nframes = 3\nmp4 = false\n\
         [settings]\nshaders = [\"frequency\"]\n",
    )
    .unwrap();
    let o = godel(&["sequence", script.to_str().unwrap(), "-q"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("s.toml") && e.contains("output"), "{e}");
    assert!(
        e.contains("frame_0001.png is the data file this run reads"),
        "{e}"
    );
    assert_eq!(files_in(&out), ["frame_0001.png"]);
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
