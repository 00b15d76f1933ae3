//! The live viewer in a real browser: renders small scenes with `godel render`, serves their
//! data files with `godel view --port 0`, and drives Debian's chromium through
//! playwright-core (tests/browser/*.mjs), with WebGL2 on SwiftShader (software rendering; a
//! browser without WebGL2 fails these tests). Checked here against the data files, the
//! `shade` crate and `godel look`:
//!
//! - the slider redraws on the GPU without asking the server, hover shows the file's record
//!   and direction, the save buttons download the server's PNG and keyframe, errors show;
//! - every layer combination shaded on the GPU equals the `shade` crate within one 8-bit step;
//! - looking around a full sphere (drag, projections, velocity) equals `godel look` then
//!   `godel shade` within one step, and a boost turns the ball ahead blue, the one behind red;
//! - the polarization layer's ticks equal `godel shade`'s, on the file's frame and on a frame
//!   traced in the page, and its axis control re-shades without tracing or asking anything;
//! - one eye of a stereo pair shows both eyes' picture (the server's) in the Stereo panel, in
//!   the pair's layout and as an anaglyph on request;
//! - the page asks nothing of any server but its own.
//!
//! Chromium and the npm packages are installed by `bash scripts/test.sh`; without them these
//! tests fail and say so.

use crate::browser_support::*;
use datafile::record::RayStatus;
use datafile::DataFile;
use scene::Scene;
use shade::{ShadeSettings, ShaderKind, Shading};

/// A 96×48 pinhole view of a checkered ball at rest inside the horizon.
fn scene_text() -> String {
    testkit::ball_ahead(
        "viewer-test",
        &testkit::pinhole(60.0, 96, 48),
        "ball",
        r#"{ kind = "checker", rows = 8, cols = 16 }"#,
    )
}

pub fn number(text: &serde_json::Value) -> f64 {
    text.as_str()
        .unwrap_or_else(|| panic!("{text} is not text"))
        .parse()
        .unwrap_or_else(|_| panic!("{text} is not a number"))
}

/// "AZ°, EL°" as the page writes a direction.
pub fn angles(text: &serde_json::Value) -> [f64; 2] {
    let t = text.as_str().unwrap().replace('°', "");
    let v: Vec<f64> = t.split(',').map(|x| x.trim().parse().unwrap()).collect();
    [v[0], v[1]]
}

/// Azimuth (x towards y) and elevation (towards z) of a unit direction, degrees.
pub fn azimuth_elevation(n: [f64; 3]) -> [f64; 2] {
    [
        n[1].atan2(n[0]).to_degrees(),
        n[2].clamp(-1.0, 1.0).asin().to_degrees(),
    ]
}

#[test]
fn browser_moves_slider_reads_record_saves_and_shows_errors() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let exr = render(dir.path(), "viewer-test", &scene_text());
    let data = DataFile::read(&exr).unwrap();

    // The hit pixel nearest the centre of the ball's image.
    let hits: Vec<(usize, usize)> = (0..data.height)
        .flat_map(|row| (0..data.width).map(move |col| (col, row)))
        .filter(|&(col, row)| data.record(col, row).status == RayStatus::Hit)
        .collect();
    assert!(hits.len() > 20, "the test scene shows the ball");
    let mean = |f: fn(&(usize, usize)) -> usize| {
        hits.iter().map(f).sum::<usize>() as f64 / hits.len() as f64
    };
    let (cx, cy) = (mean(|p| p.0), mean(|p| p.1));
    let &(col, row) = hits
        .iter()
        .min_by(|a, b| {
            let d = |p: &(usize, usize)| (p.0 as f64 - cx).powi(2) + (p.1 as f64 - cy).powi(2);
            d(a).total_cmp(&d(b))
        })
        .unwrap();

    let (server, url) = start_viewer(&exr, dir.path());
    let out = dir.path().join("browser");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script(
        "viewer.mjs",
        &url,
        &out,
        &[col.to_string(), row.to_string()],
    );
    drop(server);

    assert_eq!(seen["title"], "godel view");
    assert_eq!(seen["canvas"], serde_json::json!([data.width, data.height]));

    // The slider moved down, and the picture followed, shaded on the GPU: no request but
    // for the overlay layer.
    let t_before = seen["temperature"][0].as_f64().unwrap();
    let t_after = seen["temperature"][1].as_f64().unwrap();
    assert_eq!(
        t_before, 5800.0,
        "the slider starts at the scene's temperature"
    );
    assert!(
        t_after < 4000.0,
        "the drag moved the slider down: {t_after}"
    );
    assert!(seen["shadings_for_drag"].as_u64().unwrap() >= 1);
    // Only the overlay layer (the reference squares' labels name the temperature) is asked
    // of the server.
    for r in seen["requests_for_drag"].as_array().unwrap() {
        assert!(r.as_str().unwrap().ends_with("/api/overlay"), "{r}");
    }
    let changed = seen["pixels_changed"].as_u64().unwrap() as usize;
    assert!(
        changed * 10 >= hits.len() * 9 && changed < data.width * data.height,
        "{changed} pixels changed; the ball has {} pixels",
        hits.len()
    );

    // The page's settings are the file's defaults with the frequency layer alone at the
    // slider's temperature, and its picture is the shade crate's within one 8-bit step.
    let mut want_settings = ShadeSettings::defaults_for(&data);
    want_settings.shaders = vec![ShaderKind::Frequency];
    want_settings.objects.get_mut("ball").unwrap().temperature = t_after;
    let settings: ShadeSettings = serde_json::from_value(seen["settings"].clone()).unwrap();
    assert_eq!(settings, want_settings);
    let want = Shading::new(&data, &want_settings).unwrap().image(&data);
    let (_, _, gpu) = read_rgba(&out.join("slider.rgba"));
    let c = compare(&gpu, want.as_raw(), data.width);
    assert!(c.max <= 1, "GPU vs shade: max {}, {:?}", c.max, c.off);

    // The record shown on hover is the data file's, with the pixel's direction.
    let shown = &seen["record_shown"];
    assert_eq!(shown["pixel"], format!("{col}, {row}"));
    assert_eq!(shown["object"], "ball");
    assert_eq!(shown["status"], "hit");
    let expected = *data.record(col, row);
    for (field, value) in [
        ("u", expected.u),
        ("v", expected.v),
        ("g", expected.g),
        ("t_emit", expected.t_emit),
        ("travel_time", -expected.t_emit),
    ] {
        let got = number(&shown[field]);
        assert!(
            (got - f64::from(value)).abs() <= 6e-5,
            "{field}: page shows {got}, file has {value}"
        );
    }
    assert!(expected.t_emit < 0.0);
    let scene = Scene::from_str(&scene_text(), "ball").unwrap();
    let n = scene
        .observer
        .pixel_direction(&scene.camera, col as u32, row as u32)
        .unwrap();
    let [az, el] = angles(&shown["direction"]);
    let [want_az, want_el] = azimuth_elevation(n);
    assert!(
        (az - want_az).abs() < 0.006 && (el - want_el).abs() < 0.006,
        "direction shown {az}°, {el}°; the camera's {want_az}°, {want_el}°"
    );
    assert_eq!(number(&shown["doppler"]), 1.0);

    // "Save PNG" downloads the server's shading of those settings, as `godel shade` makes it.
    assert_eq!(seen["png_name"], "viewer-test.png");
    let saved = image::open(out.join("saved.png")).unwrap().to_rgb8();
    assert!(saved == want, "the saved PNG is not the shaded view");

    // "Save keyframe" downloads a sequence-script keyframe holding those settings.
    assert_eq!(seen["keyframe_name"], "viewer-test.keyframe.toml");
    let keyframe: toml::Value =
        toml::from_str(&std::fs::read_to_string(out.join("keyframe.toml")).unwrap()).unwrap();
    let saved_settings: ShadeSettings = keyframe["keyframe"][0]["settings"]
        .clone()
        .try_into()
        .unwrap();
    assert_eq!(saved_settings, want_settings);

    // Bad settings sent to the server: its 400 message is shown on the page.
    assert_eq!(seen["error_shown"], true);
    let error = seen["error_text"].as_str().unwrap();
    assert!(
        error.contains("shader") && error.contains("sepia"),
        "{error}"
    );
    for message in seen["console_errors"].as_array().unwrap() {
        assert!(message.as_str().unwrap().contains("400"), "{message}");
    }
    assert_only_local_requests(&seen, &url);

    // Zoomed in with the wheel on the textured ball, the canvas shows blends between
    // neighbouring pixels (linear filtering): most of the ball's canvas pixels have colours
    // that are nowhere in the picture, where blocky enlargement would show only its own.
    assert!(seen["zoom"].as_f64().unwrap() > 6.0);
    assert_eq!(seen["requests_for_zoom"], serde_json::json!([]));
    let (_, _, textured) = read_rgba(&out.join("textured.rgba"));
    let palette: std::collections::HashSet<&[u8]> = textured.chunks_exact(3).collect();
    let (_, _, zoomed) = read_rgba(&out.join("zoomed.rgba"));
    let mut counts = std::collections::HashMap::new();
    zoomed
        .chunks_exact(3)
        .for_each(|p| *counts.entry(p).or_insert(0) += 1);
    let background = counts
        .iter()
        .max_by_key(|(_, n)| **n)
        .map(|(p, _)| *p)
        .unwrap();
    let ball: Vec<&[u8]> = zoomed
        .chunks_exact(3)
        .filter(|p| *p != background)
        .collect();
    let blended = ball.iter().filter(|p| !palette.contains(*p)).count();
    assert!(
        ball.len() > 1000 && blended * 2 > ball.len(),
        "{blended} of {} canvas pixels off the background are blends",
        ball.len()
    );

    let screenshot = image::open(out.join("screenshot.png")).unwrap();
    assert!(screenshot.width() >= 800 && screenshot.height() >= 400);
}

mod explore;
mod faster;
mod fly;
mod gpu_trace;
mod keep;
mod layers;
mod look;
mod page_check;
mod polarization;
mod stereo;
