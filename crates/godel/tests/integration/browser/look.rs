//! Looking around a full-sphere data file in the browser, against `godel look` then
//! `godel shade` of the same view, samples per pixel and settings: within one 8-bit step per
//! channel. Excused: output pixels with a sample whose direction falls within 0.01 of a source
//! pixel's width of its edge or of the line through its centre, where the choice of the
//! pixel (nearest neighbour) or of the four pixels (smooth reading) made by the GPU's
//! single-precision trigonometry (SwiftShader's is good to about 1e-3 pixel here) may differ
//! from the CPU's f64: both are right to within rounding. Also: dragging turns the view
//! without asking the server, and a boost along +x turns the ball ahead blue and the one
//! behind red.

use std::path::Path;

use super::{angles, azimuth_elevation, number};
use crate::browser_support::*;
use datafile::DataFile;
use look::{pixel_look, LookView, SphereSource};
use scene::Camera;
use serde_json::{json, Value};
use shade::{BrightnessMode, ShadeSettings, ShaderKind, TimeMode};
use spacetime::LocalVelocity;

/// The full sphere of directions of a static observer in flat spacetime (fast to trace):
/// equal checkered balls ahead (+x) and behind (−x), the earth to the left (+y), a ball
/// passing below at 0.6 c.
const SCENE: &str = r#"
name = "sky"
[spacetime]
metric = "minkowski"
[observer]
time = 0.0
position = { x = 0.0, y = 0.0, z = 0.0 }
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "sphere"
width = 256
height = 128
[trace]
method = "numeric"
max_past = 10.0
[[object]]
name = "front"
radius = 0.8
texture = { kind = "checker", rows = 8, cols = 16 }
temperature = 5800.0
motion = { kind = "rest", position = { x = 2.0, y = 0.0, z = 0.0 } }
[[object]]
name = "back"
radius = 0.8
texture = { kind = "checker", rows = 8, cols = 16 }
temperature = 5800.0
motion = { kind = "rest", position = { x = -2.0, y = 0.0, z = 0.0 } }
[[object]]
name = "earth"
radius = 0.7
texture = { kind = "image", builtin = "earth" }
temperature = 4000.0
motion = { kind = "rest", position = { x = 0.0, y = 2.0, z = 0.3 } }
[[object]]
name = "runner"
radius = 0.4
texture = { kind = "gradient" }
temperature = 7000.0
motion = { kind = "geodesic", time = 0.0, position = { x = -1.0, y = -1.0, z = -1.0 }, speed = 0.6, direction = [1, 0, 0] }
"#;

fn vector(v: &Value) -> [f64; 3] {
    [0, 1, 2].map(|i| v[i].as_f64().unwrap())
}

/// The view of a saved body ({"settings", "view"}) as `look` reads it.
fn look_view(view: &Value) -> LookView {
    let c = &view["camera"];
    let (w, h) = (
        c["width"].as_u64().unwrap() as u32,
        c["height"].as_u64().unwrap() as u32,
    );
    let f = |k: &str| c[k].as_f64().unwrap();
    let camera = match c["kind"].as_str().unwrap() {
        "pinhole" => Camera::Pinhole {
            fov_deg: f("fov_deg"),
            width: w,
            height: h,
        },
        "panorama" => Camera::Panorama {
            h_fov_deg: f("h_fov_deg"),
            v_fov_deg: f("v_fov_deg"),
            width: w,
            height: h,
        },
        "sphere" => Camera::Sphere {
            width: w,
            height: h,
        },
        _ => Camera::Fisheye {
            fov_deg: f("fov_deg"),
            size: w,
        },
    };
    let v = &view["velocity"];
    let velocity =
        LocalVelocity::new(v["speed"].as_f64().unwrap(), vector(&v["direction"])).unwrap();
    LookView::new(
        camera,
        vector(&view["forward"]),
        vector(&view["up"]),
        velocity,
    )
    .unwrap()
}

/// The samples per pixel of a saved view.
fn samples(view: &Value) -> u64 {
    view["samples"].as_u64().unwrap_or(1)
}

/// `godel look` of `view` then `godel shade` with `settings`: the picture and the looked data.
fn godel_look(
    sphere: &Path,
    view: &Value,
    settings: &ShadeSettings,
    out: &Path,
) -> (image::RgbImage, DataFile) {
    let c = &view["camera"];
    let list = |v: [f64; 3]| format!("{},{},{}", v[0], v[1], v[2]);
    let s = &view["velocity"];
    let d = vector(&s["direction"]);
    let mut args = vec![
        "look".to_string(),
        sphere.display().to_string(),
        format!("--camera={}", c["kind"].as_str().unwrap()),
        format!("--forward={}", list(vector(&view["forward"]))),
        format!("--up={}", list(vector(&view["up"]))),
        format!("--width={}", c["width"]),
        format!("--height={}", c["height"]),
        format!(
            "--velocity={},{},{},{}",
            s["speed"].as_f64().unwrap(),
            d[0],
            d[1],
            d[2]
        ),
        format!("--samples={}", samples(view)),
        format!("--output={}", out.with_extension("exr").display()),
    ];
    for (field, flag) in [
        ("fov_deg", "--fov"),
        ("h_fov_deg", "--h-fov"),
        ("v_fov_deg", "--v-fov"),
    ] {
        if let Some(x) = c[field].as_f64() {
            args.push(format!("{flag}={x}"));
        }
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let looked = godel(&args);
    assert!(looked.status.success(), "{looked:?}");
    let toml = out.with_extension("toml");
    std::fs::write(&toml, settings.to_toml()).unwrap();
    let png = out.with_extension("png");
    let shaded = godel(&[
        "shade",
        out.with_extension("exr").to_str().unwrap(),
        "--settings",
        toml.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(shaded.status.success(), "{shaded:?}");
    (
        image::open(&png).unwrap().to_rgb8(),
        DataFile::read(&out.with_extension("exr")).unwrap(),
    )
}

/// Whether a sample of output pixel (col, row) (s×s of them) looks within 0.01 pixel of a
/// source pixel's edge or of the line through its centre.
fn near_source_edge(
    view: &LookView,
    s: u32,
    sphere: &SphereSource,
    col: usize,
    row: usize,
) -> bool {
    let samples = LookView {
        camera: view.camera.supersampled(s),
        ..*view
    };
    (0..s * s).any(|k| {
        let (c, r) = (s * col as u32 + k % s, s * row as u32 + k / s);
        let Some(p) = pixel_look(&samples, c, r) else {
            return false;
        };
        let pos = sphere.position(p.static_dir);
        pos.iter()
            .any(|x| (2.0 * x - (2.0 * x).round()).abs() < 2e-2)
    })
}

/// Compares a browser picture with `godel look` + `godel shade` of its body; returns
/// (largest difference outside excused pixels, excused pixels, pixels).
fn check_against_godel(sphere: &Path, picture: &Path, out: &Path) -> (u8, usize, usize) {
    let meta: Value =
        serde_json::from_slice(&std::fs::read(picture.with_extension("json")).unwrap()).unwrap();
    let body = &meta["body"];
    let settings: ShadeSettings = serde_json::from_value(body["settings"].clone()).unwrap();
    let (want, _) = godel_look(sphere, &body["view"], &settings, out);
    let (w, h, gpu) = read_rgba(picture);
    assert_eq!(
        (w as u32, h as u32),
        want.dimensions(),
        "{}",
        picture.display()
    );
    let view = look_view(&body["view"]);
    let s = (samples(&body["view"]) as f64).sqrt().round() as u32;
    let source = SphereSource::of(&DataFile::read(sphere).unwrap()).unwrap();
    let c = compare(&gpu, want.as_raw(), w);
    for &(col, row) in &c.off {
        assert!(
            near_source_edge(&view, s, &source, col, row),
            "{}: pixel ({col}, {row}) differs by more than one step from godel look: GPU {:?}, \
             CPU {:?}, source position {:?}",
            picture.display(),
            &gpu[(row * w + col) * 3..][..3],
            want.get_pixel(col as u32, row as u32),
            pixel_look(&view, col as u32, row as u32).map(|p| source.position(p.static_dir))
        );
    }
    (c.within, c.off.len(), w * h)
}

/// Mean blue minus red (8-bit) of the picture's pixels whose static direction lies within
/// 20° of `axis` (the balls ahead and behind span 23.6°).
fn blue_minus_red(picture: &Path, axis: [f64; 3]) -> f64 {
    let meta: Value =
        serde_json::from_slice(&std::fs::read(picture.with_extension("json")).unwrap()).unwrap();
    let view = look_view(&meta["body"]["view"]);
    let (w, h, rgb) = read_rgba(picture);
    let (mut sum, mut n) = (0.0, 0);
    for row in 0..h {
        for col in 0..w {
            let Some(p) = pixel_look(&view, col as u32, row as u32) else {
                continue;
            };
            let cos = (0..3).map(|i| p.static_dir[i] * axis[i]).sum::<f64>();
            if cos > 20f64.to_radians().cos() {
                let px = &rgb[(row * w + col) * 3..][..3];
                sum += f64::from(px[2]) - f64::from(px[0]);
                n += 1;
            }
        }
    }
    assert!(n >= 10, "{n} pixels near {axis:?}");
    sum / n as f64
}

#[test]
fn looking_around_on_the_gpu_equals_godel_look() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let exr = render(dir.path(), "sky", SCENE);
    let data = DataFile::read(&exr).unwrap();
    let sphere = SphereSource::of(&data).unwrap();
    let defaults = ShadeSettings::defaults_for(&data);
    let with = |shaders: &[ShaderKind], change: &dyn Fn(&mut ShadeSettings)| {
        let mut s = defaults.clone();
        s.shaders = shaders.to_vec();
        change(&mut s);
        s
    };
    use ShaderKind::*;
    let cases = vec![
        json!({"look": {"projection": "pinhole", "fov": 90, "yaw": 30, "pitch": 10, "speed": 0},
               "settings": with(&[Texture], &|s| s.grid = true)}),
        json!({"look": {"projection": "pinhole", "fov": 40, "yaw": 0, "pitch": 0, "speed": 0.5,
                        "preset": "+x", "samples": "1"},
               "settings": with(&[Texture], &|_| {})}),
        json!({"look": {"projection": "pinhole", "fov": 40, "yaw": 90, "pitch": 0, "speed": 0,
                        "samples": "16"},
               "settings": with(&[Texture, Frequency], &|_| {})}),
        json!({"look": {"projection": "pinhole", "fov": 60, "yaw": -20, "pitch": -5,
                 "speed": 0.6, "preset": "+x", "samples": "4"},
        "settings": with(&[Texture, Frequency], &|s| {
            s.brightness = BrightnessMode::Physical;
        })}),
        json!({"look": {"projection": "panorama", "fov": 220, "yaw": 0, "pitch": 0,
                        "speed": 0.5, "preset": "object:2"},
               "settings": with(&[Frequency, Time], &|s| s.time.mode = TimeMode::Travel)}),
        json!({"look": {"projection": "fisheye", "fov": 180, "yaw": 10, "pitch": 60,
                        "speed": 0.3, "preset": "-z"},
               "settings": with(&[Texture, Time], &|s| s.grid = true)}),
        json!({"look": {"projection": "sphere", "fov": 360, "yaw": 0, "pitch": 0, "speed": 0,
                        "preset": "+x"},
               "settings": with(&[Frequency], &|s| s.reference_squares = false)}),
        json!({"look": {"projection": "sphere", "fov": 360, "yaw": 0, "pitch": 0,
                        "speed": 0.8, "preset": "+x"},
               "settings": with(&[Frequency], &|s| s.reference_squares = false)}),
    ];
    let cases_file = dir.path().join("cases.json");
    std::fs::write(&cases_file, serde_json::to_vec(&cases).unwrap()).unwrap();
    let (server, url) = start_viewer(&exr, dir.path());
    let out = dir.path().join("browser");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script("look.mjs", &url, &out, &[cases_file.display().to_string()]);
    drop(server);

    // The page starts looking along the file's own axes, at rest.
    assert_eq!(seen["look"]["yaw"], 0);
    assert_eq!(seen["look"]["speed"], 0);

    // Dragging left by 40 of 160 pixels at 90° turns the view 22.5° to the right, redrawn
    // on the GPU without asking the server anything.
    let drag = &seen["drag"];
    let yaw = drag["yaw"].as_f64().unwrap();
    assert!((yaw - 22.5).abs() < 1.0, "yaw after the drag: {yaw}");
    assert!(drag["pixels_changed"].as_u64().unwrap() > 160 * 120 / 10);
    assert!(drag["frames"].as_u64().unwrap() >= 1);
    assert_eq!(drag["requests"], json!([]));

    // Every picture (the canvas after the drag, and each case) is godel look's.
    let mut pictures = vec![out.join("drag-after.rgba")];
    pictures.extend((0..cases.len()).map(|k| out.join(format!("case-{k}.rgba"))));
    let (mut worst, mut excused, mut total) = (0, 0, 0);
    for (k, picture) in pictures.iter().enumerate() {
        assert!(
            k == 0 || seen["errors"][k - 1].is_null(),
            "case {k}: {}",
            seen["errors"][k - 1]
        );
        let (within, off, pixels) =
            check_against_godel(&exr, picture, &dir.path().join(format!("godel-{k}")));
        worst = worst.max(within);
        excused += off;
        total += pixels;
    }
    eprintln!(
        "GPU look vs godel look + shade over {} pictures: max difference {worst} (8-bit steps) \
         outside {excused} pixels excused at source-pixel edges, of {total}",
        pictures.len()
    );
    assert!(excused * 50 <= total, "{excused} of {total} pixels excused");

    // The boost along +x: at rest the balls ahead and behind look alike; moving, the one
    // ahead is blue (D = γ(1 + v) = 3 at its centre), the one behind red (D = 1/3).
    let rest = out.join(format!("case-{}.rgba", cases.len() - 2));
    let boost = out.join(format!("case-{}.rgba", cases.len() - 1));
    let (ahead, behind) = ([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]);
    let (ahead_rest, behind_rest) = (blue_minus_red(&rest, ahead), blue_minus_red(&rest, behind));
    assert!(
        (ahead_rest - behind_rest).abs() < 1.0,
        "{ahead_rest} {behind_rest}"
    );
    let (ahead_boost, behind_boost) = (
        blue_minus_red(&boost, ahead),
        blue_minus_red(&boost, behind),
    );
    eprintln!(
        "blue minus red (8-bit): ahead {ahead_rest:.1} at rest, {ahead_boost:.1} at 0.8 c; \
         behind {behind_rest:.1} at rest, {behind_boost:.1} at 0.8 c"
    );
    assert!(
        ahead_boost > 40.0 && ahead_boost > ahead_rest + 60.0,
        "{ahead_boost}"
    );
    assert!(
        behind_boost < -60.0 && behind_boost < behind_rest - 60.0,
        "{behind_boost}"
    );

    // Hover at the centre of the boosted sphere view: the record of the sphere pixel it shows,
    // its frequency shift times D, its direction.
    let meta: Value =
        serde_json::from_slice(&std::fs::read(boost.with_extension("json")).unwrap()).unwrap();
    let view = look_view(&meta["body"]["view"]);
    let record = &seen["record"];
    let view_px: Vec<usize> = seen["record_shown"]["pixel"]
        .as_str()
        .unwrap()
        .split("view ")
        .nth(1)
        .unwrap()
        .trim_end_matches(')')
        .split(", ")
        .map(|x| x.parse().unwrap())
        .collect();
    let p = pixel_look(&view, view_px[0] as u32, view_px[1] as u32).unwrap();
    let i = sphere.nearest(sphere.position(p.static_dir));
    assert_eq!(
        (
            record["col"].as_u64().unwrap() as usize,
            record["row"].as_u64().unwrap() as usize
        ),
        (i % data.width, i / data.width)
    );
    let g = f64::from(data.records[i].g) * p.doppler;
    assert!((number(&seen["record_shown"]["g"]) - g).abs() < 6e-5);
    assert!((number(&seen["record_shown"]["doppler"]) - p.doppler).abs() < 6e-5);
    let [az, el] = angles(&seen["record_shown"]["direction"]);
    let want = azimuth_elevation(p.own);
    assert!((az - want[0]).abs() < 0.006 && (el - want[1]).abs() < 0.006);
    let [az, el] = angles(&seen["record_shown"]["static_direction"]);
    let want = azimuth_elevation(p.static_dir);
    assert!((az - want[0]).abs() < 0.006 && (el - want[1]).abs() < 0.006);

    // "Save PNG" of a boosted view is the server's look + shade: godel look's picture exactly.
    assert_eq!(seen["png_name"], "sky.look.png");
    let saved = image::open(out.join("saved-look.png")).unwrap().to_rgb8();
    let godel_png = image::open(dir.path().join(format!("godel-{}.png", cases.len())))
        .unwrap()
        .to_rgb8();
    assert!(saved == godel_png, "the saved PNG is not godel look's");

    assert!(seen["console_errors"].as_array().unwrap().is_empty());
    assert_only_local_requests(&seen, &url);
}
