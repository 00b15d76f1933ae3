//! End-to-end tests of `godel shade`: the texture shader reproduces the render's preview, the
//! convenience flags reach the shaders (6504 K near white, time window by t_emit, light
//! switches), and bad input (truncated data file, not EXR, missing channel, unknown shader,
//! object or settings field, light shader without light channels) is a clear error with a
//! non-zero exit and no output file.

use std::path::{Path, PathBuf};

use datafile::DataFile;

use crate::common::{path_arg as s, png, render, shade, stderr};

/// The small scene rendered by the first test, also the scene text of the synthetic data
/// files.
fn small_scene() -> String {
    testkit::axis_panorama(
        "small",
        96,
        12,
        6.0,
        r#"[[object]]
name = "ball"
radius = 0.3
temperature = 4000.0
texture = { kind = "checker", rows = 4, cols = 8 }
motion = { kind = "rest", position = { r = 1.0, phi = 0.7, z = 0.0 } }
"#,
    )
}

/// A synthetic data file: 16 pixels of object "ball", g = 1, t_emit = −i/2, with `lights`
/// light planes of value 1.
fn synthetic(dir: &Path, lights: usize) -> PathBuf {
    let n = 16;
    let data = DataFile {
        header: testkit::godel_header("syn", &small_scene(), "panorama", &["ball"]),
        width: n,
        height: 1,
        records: (0..n)
            .map(|i| testkit::hit(0, 0.3, 0.3, 1.0, -(i as f32) / 2.0, 1.0))
            .collect(),
        lights: vec![vec![1.0; n]; lights],
        polarization: false,
    };
    let path = dir.join(format!("syn{lights}.exr"));
    data.write(&path).unwrap();
    path
}

#[test]
fn texture_shader_reproduces_the_render_preview() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("small.toml");
    std::fs::write(&scene, small_scene()).unwrap();
    let o = render(&scene, dir.path(), &["-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = dir.path().join("tex.png");
    let data = dir.path().join("small.exr");
    let o = shade(&data, &out, &["--shader", "texture"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (a, b) = (png(&out), png(&dir.path().join("small.png")));
    assert_eq!(a.dimensions(), b.dimensions());
    let mut hits = 0;
    for (p, q) in a.pixels().zip(b.pixels()) {
        for k in 0..3 {
            assert!(p[k].abs_diff(q[k]) <= 1, "{p:?} vs {q:?}");
        }
        hits += usize::from(p[0] > 40);
    }
    assert!(hits > 10, "the ball is in the picture");
    // The checker turned by one column (45°) changes the picture; the frequency shader too.
    let turned = dir.path().join("turned.png");
    let o = shade(&data, &turned, &["--rotate", "ball=45"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_ne!(png(&turned), a);
}

#[test]
fn frequency_flag_at_6504_kelvin_gives_near_white() {
    let dir = tempfile::tempdir().unwrap();
    let data = synthetic(dir.path(), 0);
    let out = dir.path().join("f.png");
    let frequency = |temperature: &str| {
        let flags = ["--shader", "frequency", "--no-reference"];
        let o = shade(
            &data,
            &out,
            &[&flags[..], &["--temperature", temperature]].concat(),
        );
        assert!(o.status.success(), "{}", stderr(&o));
        png(&out)
    };
    for p in frequency("6504").pixels() {
        assert!(p.0.iter().all(|&c| c >= 240), "{p:?}");
    }
    // 2000 K is red.
    let p = *frequency("ball=2000").get_pixel(5, 0);
    assert!(p[0] > p[1] && p[1] > p[2], "{p:?}");
}

#[test]
fn window_flag_switches_texture_by_t_emit() {
    let dir = tempfile::tempdir().unwrap();
    let data = synthetic(dir.path(), 0);
    let out = dir.path().join("w.png");
    let o = shade(
        &data,
        &out,
        &[
            "--shader",
            "time",
            "--window=-4,2",
            "--texture",
            "uniform:0,0,1",
            "--window-texture",
            "ball=uniform:1,0,0",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let img = png(&out);
    for i in 0..16u32 {
        let t = -(i as f64) / 2.0;
        let inside = (-4.0..=-2.0).contains(&t);
        let p = img.get_pixel(i, 0);
        assert_eq!(
            p.0,
            // Full colours through the display tone curve: 1.0 shows as 0.9 (sRGB 243).
            if inside { [243, 0, 0] } else { [0, 0, 243] },
            "t_emit = {t}"
        );
    }
}

#[test]
fn light_flags_switch_sources() {
    let dir = tempfile::tempdir().unwrap();
    let data = synthetic(dir.path(), 2);
    let (on, off) = (dir.path().join("on.png"), dir.path().join("off.png"));
    let base = [
        "--shader",
        "light",
        "--texture",
        "uniform:0.2,0.2,0.2",
        "--ambient",
        "0",
    ];
    let o = shade(&data, &on, &base);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = shade(
        &data,
        &off,
        &[&base[..], &["--light", "1=off", "--light", "0=0.5"]].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // 0.2 × (1 + 1) = 0.4 linear, then 0.2 × 0.5 = 0.1 linear.
    let srgb = |x: f64| (255.0 * (1.055 * x.powf(1.0 / 2.4) - 0.055)).round() as u8;
    assert_eq!(png(&on).get_pixel(3, 0)[1], srgb(0.4));
    assert_eq!(png(&off).get_pixel(3, 0)[1], srgb(0.1));
    let o = shade(&data, &off, &[&base[..], &["--light", "2=off"]].concat());
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("light 2 does not exist"),
        "{}",
        stderr(&o)
    );
}

/// Runs `godel shade` on bad input: non-zero exit `code`, stderr contains every needle, no
/// output file.
fn refused(data: &Path, extra: &[&str], out: &Path, code: i32, needles: &[&str]) {
    let o = shade(data, out, extra);
    let args = [&[s(data)], extra].concat();
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{args:?}: {e}");
    assert!(e.starts_with("error: "), "{e}");
    // The message is its first line (clap adds a hint line after it).
    let first = e.lines().next().unwrap_or("");
    for n in needles {
        assert!(first.contains(n), "{args:?}: expected {n:?} in {e}");
    }
    assert!(!out.exists(), "{args:?} left {}", out.display());
    let leftovers: Vec<_> = std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".png") || n.contains("tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn bad_data_files_are_clear_errors_with_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let good = synthetic(dir.path(), 0);
    let out = dir.path().join("out.png");
    // Truncated.
    let bytes = std::fs::read(&good).unwrap();
    let truncated = dir.path().join("truncated.exr");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    refused(&truncated, &[], &out, 1, &["truncated.exr"]);
    // Not EXR.
    let text = dir.path().join("notes.exr");
    std::fs::write(&text, "this is not an image\n").unwrap();
    refused(&text, &[], &out, 1, &["notes.exr", "not an OpenEXR file"]);
    // An EXR without the data channels.
    let rgb = dir.path().join("photo.exr");
    exr::prelude::write_rgb_file(&rgb, 4, 4, |_, _| (0.5f32, 0.5f32, 0.5f32)).unwrap();
    refused(&rgb, &[], &out, 1, &["photo.exr", "godel."]);
    // A data file lacking one channel: `t_emit` renamed in the header (same length, so the
    // file stays a valid EXR).
    let mut renamed = bytes.clone();
    let at = renamed
        .windows(7)
        .position(|w| w == b"t_emit\0")
        .expect("channel name in the header");
    renamed[at + 5] = b'q';
    let lacking = dir.path().join("lacking.exr");
    std::fs::write(&lacking, &renamed).unwrap();
    refused(&lacking, &[], &out, 1, &["lacking.exr", "t_emit"]);
    // Missing file.
    refused(&dir.path().join("none.exr"), &[], &out, 1, &["none.exr"]);
}

#[test]
fn bad_settings_are_usage_errors_with_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let data = synthetic(dir.path(), 0);
    let out = dir.path().join("out.png");
    refused(&data, &["--shader", "sepia"], &out, 2, &["sepia"]);
    refused(
        &data,
        &["--texture", "sun=checker:2x2"],
        &out,
        2,
        &["--texture", "unknown object 'sun'"],
    );
    refused(
        &data,
        &["--temperature", "ball=-3"],
        &out,
        2,
        &["--temperature", "positive"],
    );
    refused(
        &data,
        &["--texture", "checker:0x2"],
        &out,
        2,
        &["error: --texture: ", "objects.ball.texture"],
    );
    // Issue 10: these were blamed on --shader.
    refused(
        &data,
        &["--shader", "time", "--window-texture", "ball=checker:0x0"],
        &out,
        2,
        &["error: --window-texture: ", "objects.ball.window_texture"],
    );
    refused(
        &data,
        &["--texture", "ball=checker:0x0"],
        &out,
        2,
        &["error: --texture: ", "objects.ball.texture"],
    );
    refused(&data, &["--shader", "light"], &out, 2, &["light channels"]);
    let settings = dir.path().join("look.toml");
    std::fs::write(
        &settings,
        "exposure = 2.0\n\n[objects.ball]\ntemprature = 3.0\n",
    )
    .unwrap();
    refused(
        &data,
        &["--settings", s(&settings)],
        &out,
        2,
        &["look.toml:4", "objects.ball.temprature", "unknown field"],
    );
    // A bad value from the settings file is blamed on --settings, not on --shader.
    std::fs::write(
        &settings,
        "[objects.ball.texture]\nkind = \"checker\"\nrows = 0\ncols = 2\n",
    )
    .unwrap();
    refused(
        &data,
        &["--settings", s(&settings)],
        &out,
        2,
        &["error: --settings: ", "objects.ball.texture"],
    );
    // Issue 10: settings files are read with a bound; a device or FIFO is refused.
    refused(
        &data,
        &["--settings", "/dev/zero"],
        &out,
        2,
        &["error: --settings: ", "not a regular file"],
    );
    std::fs::write(&settings, "[objects.sun]\ntemperature = 3.0\n").unwrap();
    refused(
        &data,
        &["--settings", s(&settings)],
        &out,
        2,
        &["look.toml:1", "unknown object 'sun'"],
    );
}

#[test]
fn a_settings_file_sets_any_field() {
    let dir = tempfile::tempdir().unwrap();
    let data = synthetic(dir.path(), 0);
    let settings = dir.path().join("look.toml");
    std::fs::write(
        &settings,
        "shaders = [\"texture\"]\n[objects.ball]\ntexture = { kind = \"uniform\", color = [0, 1, 0] }\n",
    )
    .unwrap();
    let out = dir.path().join("out.png");
    let o = shade(&data, &out, &["--settings", s(&settings)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // 1.0 through the display tone curve (0.9) is sRGB 243.
    assert_eq!(png(&out).get_pixel(0, 0).0, [0, 243, 0]);
}

/// Issue 25: the polarization layer draws ticks over the texture layer where the scene
/// polarizes an object's light, and refuses a data file without the `pol_*` channels (one
/// written by the GPU tracer, or before them) with no output.
#[test]
fn polarization_layer_draws_ticks_and_needs_the_channels() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("small.toml");
    std::fs::write(
        &scene,
        small_scene() + "polarization = { axis = [0, 0, 1] }\n",
    )
    .unwrap();
    let o = render(&scene, dir.path(), &["-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let data = dir.path().join("small.exr");
    let (tex, pol) = (dir.path().join("tex.png"), dir.path().join("pol.png"));
    for (out, shader) in [(&tex, "texture"), (&pol, "texture,polarization")] {
        let o = shade(&data, out, &["--shader", shader]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let (a, b) = (png(&tex), png(&pol));
    let changed = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
    assert!(changed > 20, "{changed} pixels changed");
    // Alone, the layer draws over the texture layer.
    let alone = dir.path().join("alone.png");
    let o = shade(&data, &alone, &["--shader", "polarization"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(png(&alone), b);
    let old = synthetic(dir.path(), 0);
    let out = dir.path().join("sub").join("none.png");
    std::fs::create_dir(out.parent().unwrap()).unwrap();
    refused(&old, &["--shader", "polarization"], &out, 2, &["pol_x"]);
}
