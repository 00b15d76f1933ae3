//! End-to-end tests of fly-through sequences (`godel sequence` with `[keyframe.observer]`
//! and `[keyframe.camera]`, docs/guide/src/sequences.md): at every keyframe a frame is the very
//! `godel render` of the scene with that observer and camera (the same PNG bytes and the
//! same data records); the observer's time eases between keyframes by the script's formula
//! (read back from each kept data file's header); stale data files of an earlier run are
//! removed; bad keyframes are refused with file:line and field, exit code 2 and no output.
//! Stereo fly-throughs: each frame is both eyes of its observer in the pair's layout, at a
//! keyframe the very preview `godel render` writes, with both eyes' data files kept.

use std::path::Path;

use datafile::DataFile;

use crate::common::{self, assert_refused, files_in, godel, records, sequence_within, stderr};

/// Long enough for any of these commands on a loaded machine.
const NEVER_HANGS: std::time::Duration = std::time::Duration::from_secs(300);

/// A ball falling freely past the origin, and a floor for orientation.
const OBJECTS: &str = r#"[[object]]
name = "ball"
radius = 0.3
texture = { kind = "checker", rows = 4, cols = 8 }
motion = { kind = "geodesic", time = 0.0, position = { x = 1.0, y = -0.5, z = 0.0 }, speed = 0.5, direction = [0, 1, 0] }
[[object]]
name = "floor"
frame = "coordinates"
shape = "plane"
height = -0.5
extent = 3.0
"#;

/// A scene of [`OBJECTS`] seen through a 40×8 panorama by the observer `observer` (the body
/// of an `[observer]` table) with the fields of view `fov` (camera keys).
fn scene_text(name: &str, observer: &str, fov: &str) -> String {
    format!(
        "name = \"{name}\"\n{}[observer]\n{observer}[camera]\nkind = \"panorama\"\n{fov}\
         width = 40\nheight = 8\n[trace]\nmax_past = 4.0\n{OBJECTS}",
        testkit::GODEL
    )
}

#[test]
fn keyframes_reproduce_direct_renders_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    // Three keyframes, each with a complete observer and panorama, moving, turning, boosting
    // and zooming between them.
    let keys: [(u32, &str, &str); 3] = [
        (
            0,
            "time = 0.0\nposition = { x = 0.0, y = 0.0, z = 0.0 }\n\
             velocity = { speed = 0.0, direction = [1.0, 0.0, 0.0] }\n\
             forward = [1.0, 0.0, 0.0]\nup = [0.0, 0.0, 1.0]\n",
            "h_fov_deg = 360.0\nv_fov_deg = 40.0\n",
        ),
        (
            2,
            "time = 0.75\nposition = { x = 0.2, y = -0.1, z = 0.05 }\n\
             velocity = { speed = 0.3, direction = [0.0, 1.0, 0.0] }\n\
             forward = [0.0, 1.0, 0.0]\nup = [0.0, 0.0, 1.0]\n",
            "h_fov_deg = 200.0\nv_fov_deg = 30.0\n",
        ),
        (
            4,
            "time = 1.5\nposition = { x = 0.1, y = 0.3, z = 0.0 }\n\
             velocity = { speed = 0.6, direction = [1.0, 1.0, 0.0] }\n\
             forward = [1.0, 1.0, 0.0]\nup = [0.0, 0.0, 2.0]\n",
            "h_fov_deg = 120.0\nv_fov_deg = 60.0\n",
        ),
    ];
    // The sequence's own scene has another observer and camera: the keyframes replace them.
    std::fs::write(
        dir.path().join("fly.toml"),
        scene_text(
            "fly",
            "time = -3.0\nposition = { r = 0.5, phi = 1.0, z = 0.2 }\n",
            "h_fov_deg = 90.0\nv_fov_deg = 20.0\n",
        ),
    )
    .unwrap();
    let mut script = String::from(
        "output = \"out\"\nframes = 5\nmp4 = false\n[trace]\nscene = \"fly.toml\"\nkeep_data = true\n",
    );
    for (frame, observer, fov) in keys {
        script +=
            &format!("[[keyframe]]\nframe = {frame}\n[keyframe.observer]\n{observer}[keyframe.camera]\n{fov}");
    }
    std::fs::write(dir.path().join("seq.toml"), script).unwrap();
    let seq = dir.path().join("seq.toml");
    let o = godel(&["sequence", seq.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = dir.path().join("out");
    assert_eq!(
        files_in(&out),
        std::iter::once(common::MANIFEST.to_string())
            .chain((0..5).flat_map(|i| [format!("frame_{i:04}.exr"), format!("frame_{i:04}.png")]))
            .collect::<Vec<_>>()
    );

    for (k, (frame, observer, fov)) in keys.into_iter().enumerate() {
        let name = format!("key{k}");
        let scene = dir.path().join(format!("{name}.toml"));
        std::fs::write(&scene, scene_text(&name, observer, fov)).unwrap();
        let direct = dir.path().join("direct");
        let o = godel(&[
            "render",
            scene.to_str().unwrap(),
            "-q",
            "-o",
            direct.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let png = |p: &Path| std::fs::read(p).unwrap();
        assert!(
            png(&out.join(format!("frame_{frame:04}.png")))
                == png(&direct.join(format!("{name}.png"))),
            "frame {frame}'s picture differs from the render of keyframe {k}"
        );
        assert_eq!(
            records(&out.join(format!("frame_{frame:04}.exr"))),
            records(&direct.join(format!("{name}.exr"))),
            "frame {frame}'s records differ from the render of keyframe {k}"
        );
    }
    // Between keyframes the frames are new pictures, not copies of a keyframe.
    let frame = |i: u32| records(&out.join(format!("frame_{i:04}.exr")));
    assert_ne!(frame(1), frame(0));
    assert_ne!(frame(1), frame(2));
}

/// Writes the scene `fly.toml` and the script `seq.toml` into `dir` and runs the sequence:
/// the script's top-level keys `top` (one line: its line 3), its `[trace]` table's keys
/// `trace` after `scene` (from line 6), then `keys`.
fn run_sequence(dir: &Path, top: &str, trace: &str, keys: &str) -> std::process::Output {
    std::fs::write(
        dir.join("fly.toml"),
        scene_text(
            "fly",
            "time = 0.0\n",
            "h_fov_deg = 360.0\nv_fov_deg = 40.0\n",
        ),
    )
    .unwrap();
    let script = dir.join("seq.toml");
    std::fs::write(
        &script,
        format!("output = \"out\"\nmp4 = false\n{top}[trace]\nscene = \"fly.toml\"\n{trace}{keys}"),
    )
    .unwrap();
    sequence_within(&script, NEVER_HANGS)
}

#[test]
fn time_eases_between_keyframes_by_the_formula() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    // Data files of an earlier, longer run (in its manifest): the one beyond this run's
    // frames goes; a file of the user's stays, and so does a numbered one no run of godel
    // wrote here.
    for name in [
        "frame_0003.exr",
        "frame_0012.exr",
        "frame_0013.exr",
        "notes.txt",
    ] {
        std::fs::write(out.join(name), b"old").unwrap();
    }
    common::record_as_sequence_output(&out, &["frame_0003.exr", "frame_0012.exr"]);
    let (t0, t1, last) = (0.5, 2.5, 8u32);
    let o = run_sequence(
        dir.path(),
        &format!("frames = {}\n", last + 1),
        "keep_data = true\n",
        &format!(
            "[[keyframe]]\nframe = 0\n[keyframe.observer]\ntime = {t0:?}\n\
             [[keyframe]]\nframe = {last}\n[keyframe.observer]\ntime = {t1:?}\n"
        ),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("frame_0012.exr"), "{}", stderr(&o));
    let mut times = Vec::new();
    for i in 0..=last {
        let data = DataFile::read(&out.join(format!("frame_{i:04}.exr"))).unwrap();
        let t = data.header.observer_time;
        // The script's default easing, "smooth": 3s² − 2s³.
        let s = f64::from(i) / f64::from(last);
        let want = t0 + s * s * (3.0 - 2.0 * s) * (t1 - t0);
        assert!((t - want).abs() < 1e-12, "frame {i}: time {t}, want {want}");
        times.push(t);
    }
    assert!(times.windows(2).all(|w| w[1] > w[0]), "{times:?}");
    // Smooth: the steps are small at both ends and largest in the middle.
    let steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(steps[0] < steps[3] && steps[7] < steps[4], "{steps:?}");
    let names = files_in(&out);
    assert!(!names.contains(&"frame_0012.exr".to_string()), "{names:?}");
    assert!(names.contains(&"notes.txt".to_string()), "{names:?}");
    assert!(names.contains(&"frame_0013.exr".to_string()), "{names:?}");

    // A re-run that keeps no data leaves no data file of the earlier run beside its frames.
    let o = run_sequence(
        dir.path(),
        "frames = 2\n",
        "",
        "[[keyframe]]\nframe = 1\n[keyframe.observer]\ntime = 1.0\n",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        files_in(&out),
        [
            common::MANIFEST,
            "frame_0000.png",
            "frame_0001.png",
            "frame_0013.exr",
            "notes.txt"
        ]
    );
}

/// `script` is refused with exit code 2, one line naming everything in `needles`, and
/// nothing written: a whole script (of a data file `syn.exr` that is not there) when
/// `traced` is `None`, else the pieces of a [`run_sequence`] script (`top`, `trace`).
fn refused(traced: Option<(&str, &str)>, script: &str, needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let o = if let Some((top, trace)) = traced {
        run_sequence(dir.path(), top, trace, script)
    } else {
        std::fs::write(dir.path().join("seq.toml"), script).unwrap();
        godel(&[
            "sequence",
            dir.path().join("seq.toml").to_str().unwrap(),
            "-q",
        ])
    };
    assert_refused(&o, needles, &dir.path().join("out"));
}

#[test]
fn bad_keyframes_are_refused_with_file_line_and_field() {
    // The observer of a sequence that only re-shades a data file cannot move (checked
    // before the data file is read).
    refused(
        None,
        "data = \"syn.exr\"\noutput = \"out\"\nframes = 3\n[[keyframe]]\nframe = 1\n\
         [keyframe.observer]\ntime = 1.0\n",
        &[
            "seq.toml:7",
            "keyframe[0].observer.time",
            "re-shades one data file",
        ],
    );
    refused(
        None,
        "data = \"syn.exr\"\noutput = \"out\"\nframes = 3\n[[keyframe]]\nframe = 1\n\
         [keyframe.camera]\nh_fov_deg = 90.0\n",
        &[
            "seq.toml:7",
            "keyframe[0].camera.h_fov_deg",
            "re-shades one data file",
        ],
    );
    let three = Some(("frames = 3\n", ""));
    // Time given twice.
    refused(
        Some(("frames = 3\n", "observer_time = [0.0, 1.0]\n")),
        "[[keyframe]]\nframe = 2\n[keyframe.observer]\ntime = 1.0\n",
        &["seq.toml:10", "keyframe[0].observer.time", "observer_time"],
    );
    // Unknown keys, in the observer (a velocity's own key at the top) and in the camera.
    refused(
        three,
        "[[keyframe]]\nframe = 1\n[keyframe.observer]\nspeed = 0.3\n",
        &[
            "seq.toml:9",
            "keyframe[0].observer.speed",
            "unknown field 'speed'",
        ],
    );
    refused(
        three,
        "[[keyframe]]\nframe = 1\n[keyframe.camera]\nzoom = 2.0\n",
        &[
            "seq.toml:9",
            "keyframe[0].camera.zoom",
            "unknown field 'zoom'",
        ],
    );
    // A field of view the scene's camera (a panorama) has not.
    refused(
        three,
        "[[keyframe]]\nframe = 1\n[keyframe.camera]\nfov_deg = 60.0\n",
        &[
            "seq.toml:9",
            "keyframe[0].camera.fov_deg",
            "unknown field 'fov_deg'",
        ],
    );
    // NaN.
    refused(
        three,
        "[[keyframe]]\nframe = 1\n[keyframe.observer]\nposition = { x = nan }\n",
        &["seq.toml:9", "keyframe[0].observer.position.x", "finite"],
    );
    // A keyframe that makes an invalid scene: faster than light.
    refused(
        three,
        "[[keyframe]]\nframe = 0\n[[keyframe]]\nframe = 2\n\
         [keyframe.observer]\nvelocity = { speed = 1.5, direction = [1, 0, 0] }\n",
        &["seq.toml:11", "keyframe[1].observer.velocity.speed"],
    );
    // Forward turning towards up and up away from it: halfway (frame 2) they are parallel.
    refused(
        Some(("frames = 5\n", "")),
        "[[keyframe]]\nframe = 0\n[keyframe.observer]\nforward = [1, 0, 0]\nup = [0, 0, 1]\n\
         [[keyframe]]\nframe = 4\n[keyframe.observer]\nforward = [0, 0, 1]\nup = [1, 0, 0]\n",
        &[
            "seq.toml:15",
            "keyframe[1].observer.up",
            "parallel",
            "frame 2",
        ],
    );
}

/// Issue 24: a sequence keeping its data whose `frame_0001.png` is a folder failed at frame 1
/// after writing `frame_0001.exr` (only frame 0 was checked before tracing). Every frame's
/// paths are checked first: refused with exit 2, nothing traced or written.
#[test]
fn every_frames_outputs_are_checked_before_tracing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir_all(out.join("frame_0001.png")).unwrap();
    let o = run_sequence(dir.path(), "frames = 2\n", "keep_data = true\n", "");
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("frame_0001.png: it is a directory"), "{e}");
    assert_eq!(files_in(&out), ["frame_0001.png"]);
}

/// A 40×8 panorama's fields of view (`h_fov` across) and `[camera] stereo` (camera keys of
/// [`scene_text`]).
fn stereo_camera(h_fov: f64, stereo: &str) -> String {
    format!("h_fov_deg = {h_fov:?}\nv_fov_deg = 40.0\nstereo = {{ {stereo} }}\n")
}

/// Issue 37, a stereo fly-through: each frame of a stereo scene's sequence is the two eyes
/// of that frame's observer in the pair's layout. At every keyframe the frame is the very
/// preview `godel render` writes of the scene with that observer and field of view (the eyes
/// move with the observer), and the kept `frame_NNNN.left.exr` / `.right.exr` hold that render's eyes'
/// records. A sequence shading one kept eye's data file shades both eyes into the layout:
/// the traced frame again.
#[test]
fn stereo_frames_are_both_eyes_of_each_frames_observer() {
    let dir = tempfile::tempdir().unwrap();
    let camera = |h_fov| stereo_camera(h_fov, "separation = 0.2, convergence = 2.0");
    let keys: [(u32, &str, f64); 2] = [
        (
            0,
            "time = 0.0\nposition = { x = 0.0, y = 0.0, z = 0.0 }\n",
            360.0,
        ),
        (
            2,
            "time = 0.75\nposition = { x = 0.2, y = -0.1, z = 0.05 }\n",
            200.0,
        ),
    ];
    std::fs::write(
        dir.path().join("fly.toml"),
        scene_text("fly", "time = -3.0\n", &camera(90.0)),
    )
    .unwrap();
    let mut script = String::from(
        "output = \"out\"\nframes = 3\nmp4 = false\n[trace]\nscene = \"fly.toml\"\nkeep_data = true\n",
    );
    for (frame, observer, h_fov) in keys {
        script += &format!(
            "[[keyframe]]\nframe = {frame}\n[keyframe.observer]\n{observer}\
             [keyframe.camera]\nh_fov_deg = {h_fov:?}\n"
        );
    }
    let seq = dir.path().join("seq.toml");
    std::fs::write(&seq, script).unwrap();
    let o = sequence_within(&seq, NEVER_HANGS);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = dir.path().join("out");
    assert_eq!(
        files_in(&out),
        std::iter::once(common::MANIFEST.to_string())
            .chain((0..3).flat_map(|i| {
                ["left.exr", "png", "right.exr"].map(|ext| format!("frame_{i:04}.{ext}"))
            }))
            .collect::<Vec<_>>()
    );
    let bytes = |p: &Path| std::fs::read(p).unwrap();
    for (k, (frame, observer, h_fov)) in keys.into_iter().enumerate() {
        let name = format!("key{k}");
        let scene = dir.path().join(format!("{name}.toml"));
        std::fs::write(&scene, scene_text(&name, observer, &camera(h_fov))).unwrap();
        let direct = dir.path().join("direct");
        let o = godel(&[
            "render",
            scene.to_str().unwrap(),
            "-q",
            "-o",
            direct.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(
            bytes(&out.join(format!("frame_{frame:04}.png")))
                == bytes(&direct.join(format!("{name}.png"))),
            "frame {frame}'s picture differs from the render of keyframe {k}"
        );
        for eye in ["left", "right"] {
            assert_eq!(
                records(&out.join(format!("frame_{frame:04}.{eye}.exr"))),
                records(&direct.join(format!("{name}.{eye}.exr"))),
                "frame {frame}'s {eye} eye differs from the render of keyframe {k}"
            );
        }
    }
    // Side by side: twice as wide as one eye; the eyes see different pictures, and the frame
    // between the keyframes is a new pair.
    let frame0 = common::png(&out.join("frame_0000.png"));
    assert_eq!(frame0.dimensions(), (80, 8));
    let eye = |i: u32, eye: &str| records(&out.join(format!("frame_{i:04}.{eye}.exr")));
    assert_ne!(eye(0, "left"), eye(0, "right"));
    assert_ne!(eye(1, "left"), eye(0, "left"));
    assert_ne!(eye(1, "left"), eye(2, "left"));

    // A sequence of one kept eye (either) shades both into the layout: frame 1 again.
    for given in ["left", "right"] {
        let shaded = dir.path().join(format!("from-{given}.toml"));
        std::fs::write(
            &shaded,
            format!("data = \"out/frame_0001.{given}.exr\"\noutput = \"{given}\"\nframes = 1\nmp4 = false\n"),
        )
        .unwrap();
        let o = sequence_within(&shaded, NEVER_HANGS);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(
            bytes(&dir.path().join(format!("{given}/frame_0000.png")))
                == bytes(&out.join("frame_0001.png")),
            "shading the {given} eye's data file differs from the traced frame"
        );
    }
    // Without the other eye's file it is refused, naming the script's field.
    std::fs::copy(
        out.join("frame_0001.left.exr"),
        dir.path().join("alone.left.exr"),
    )
    .unwrap();
    let alone = dir.path().join("alone.toml");
    std::fs::write(
        &alone,
        "data = \"alone.left.exr\"\noutput = \"alone\"\nframes = 1\nmp4 = false\n",
    )
    .unwrap();
    let o = sequence_within(&alone, NEVER_HANGS);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("alone.toml:1") && e.contains("alone.right.exr is missing"),
        "{e}"
    );
    assert!(!dir.path().join("alone/frame_0000.png").exists());
}

/// With separation 0 both eyes are the observer: the two halves of a side-by-side frame
/// are the same picture, frame after frame as the observer moves; over-under stacks them.
#[test]
fn stereo_frames_of_eyes_together_have_equal_halves() {
    for (layout, size) in [("side-by-side", (80, 8)), ("over-under", (40, 16))] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("fly.toml"),
            scene_text(
                "fly",
                "time = 0.0\n",
                &stereo_camera(360.0, &format!("separation = 0.0, layout = \"{layout}\"")),
            ),
        )
        .unwrap();
        let seq = dir.path().join("seq.toml");
        std::fs::write(
            &seq,
            "output = \"out\"\nframes = 2\nmp4 = false\n[trace]\nscene = \"fly.toml\"\n\
             [[keyframe]]\nframe = 0\n[keyframe.observer]\nposition = { x = 0.0, y = 0.0, z = 0.0 }\n\
             [[keyframe]]\nframe = 1\n[keyframe.observer]\ntime = 1.0\n\
             position = { x = 0.5, y = 0.5, z = 0.0 }\n",
        )
        .unwrap();
        let o = sequence_within(&seq, NEVER_HANGS);
        assert!(o.status.success(), "{}", stderr(&o));
        let frames: Vec<_> = (0..2)
            .map(|i| common::png(&dir.path().join(format!("out/frame_{i:04}.png"))))
            .collect();
        for (i, p) in frames.iter().enumerate() {
            assert_eq!(p.dimensions(), size, "{layout}");
            let (w, h) = match layout {
                "side-by-side" => (40, 0),
                _ => (0, 8),
            };
            for (x, y, px) in p.enumerate_pixels().filter(|(x, y, _)| *x < 40 && *y < 8) {
                assert_eq!(
                    *px,
                    *p.get_pixel(x + w, y + h),
                    "{layout} frame {i} at ({x}, {y})"
                );
            }
        }
        assert!(frames[0] != frames[1], "{layout}: the observer moved");
        assert_eq!(
            files_in(&dir.path().join("out")),
            [common::MANIFEST, "frame_0000.png", "frame_0001.png"]
        );
    }
}

/// A stereo frame keeping its data holds both eyes' data files until they are written
/// together: the memory check before the first frame counts both (refused with exit 2 and
/// nothing written where one eye's would fit), and one eye's without `keep_data`.
#[test]
fn a_stereo_frame_keeping_its_data_is_sized_for_both_eyes() {
    let dir = tempfile::tempdir().unwrap();
    let one_eye = 40 * 8 * datafile::memory::writing_bytes(0);
    let budget = (one_eye * 3 / 2).to_string();
    std::fs::write(
        dir.path().join("fly.toml"),
        scene_text(
            "fly",
            "time = 0.0\n",
            &stereo_camera(360.0, "separation = 0.1"),
        ),
    )
    .unwrap();
    let seq = dir.path().join("seq.toml");
    let run = |keep: bool| {
        std::fs::write(
            &seq,
            format!(
                "output = \"out\"\nframes = 1\nmp4 = false\n[trace]\nscene = \"fly.toml\"\n\
                 keep_data = {keep}\n"
            ),
        )
        .unwrap();
        common::run_within(
            std::process::Command::new(common::GODEL)
                .args(["sequence", seq.to_str().unwrap(), "-q"])
                .env("GODEL_MEMORY_BUDGET", &budget),
            NEVER_HANGS,
        )
    };
    let o = run(true);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("fly.toml: camera: both eyes' data files"), "{e}");
    assert!(files_in(&dir.path().join("out")).is_empty());
    let o = run(false);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        files_in(&dir.path().join("out")),
        [common::MANIFEST, "frame_0000.png"]
    );
}
