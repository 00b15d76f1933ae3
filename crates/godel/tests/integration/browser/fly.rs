//! Flying in `godel explore` (issue 23, page/fly.js), in headless Chromium (WebGL2 on
//! SwiftShader): the page traces its own frames with the GPU kernel, and
//!
//! - its kernel uniforms for the view on screen are the server's for that view
//!   (`POST /api/explore/input`, from the scene file's fields: one home for them);
//! - with "fall freely" on, holding R moves the observer along its up axis (+z here) by γ v τ in γ τ of coordinate
//!   time for the proper time τ it moved, at the speed v of the speed control
//!   (spacetime::worldline: exact along z in Gödel's universe);
//! - while it moves, a frame is traced and drawn in every animation frame (counted by the
//!   test's own requestAnimationFrame loop), at fewer pixels than the full frame;
//! - at rest the frame reaches the scene's full size, and equals `godel render --gpu` of a
//!   scene with the view's fields within issue 22's tolerances (crates/gpu/tests/integration/common.rs);
//! - "Save observer keyframe" gives the view flown (the velocity it fell with);
//! - hovering a pixel of the frame at rest (a hit, and one that hit nothing) shows its
//!   record, the one `godel render --gpu` writes, and draws on the map the light ray that
//!   render::map makes from that record, both made in the page (no server call);
//! - a touch drag turns the view about its up axis by the drag's share of the field of
//!   view, and a wheel step zooms.

use super::explore::scene_text;
use super::gpu_trace::{kernel_agreement, traced_file};
use crate::browser_support::*;
use datafile::DataFile;

/// The page with every frame on its own kernel (`?trace=page`): what these tests check; the
/// choice of the faster tracer is tested in browser/faster.rs.
pub(super) fn page_frames(url: &str) -> String {
    format!("{url}?trace=page")
}

/// The scene with the observer and camera fields of a view (`viewer.explore.view()`).
fn scene_of_view(text: &str, view: &serde_json::Value) -> String {
    let mut table: toml::Table = text.parse().unwrap();
    let as_toml =
        |v: &serde_json::Value| -> toml::Value { serde_json::from_value(v.clone()).unwrap() };
    let observer = table["observer"].as_table_mut().unwrap();
    for key in ["time", "position", "velocity", "forward", "up"] {
        observer.insert(key.into(), as_toml(&view[key]));
    }
    table.insert("camera".into(), as_toml(&view["camera"]));
    toml::to_string(&table).unwrap()
}

#[test]
fn flying_moves_the_observer_by_its_speed_and_proper_time_and_traces_what_render_gpu_traces() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("fly-test.toml");
    let text = scene_text();
    assert!(text.contains("width = 88\n") && text.contains("samples = 1"));
    std::fs::write(&scene, &text).unwrap();
    let (server, url) = start_explore(&scene, dir.path(), &[]);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script("fly.mjs", &page_frames(&url), &out, &[]);
    drop(server);
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["console_errors"], serde_json::json!([]), "{seen}");
    assert_only_local_requests(&seen, &url);

    // One home for the uniforms: the page's are the server's for the same view.
    assert_eq!(seen["uniforms_page"], seen["uniforms_server"], "{seen}");

    // Holding R: along +z (the observer's up) by γ v τ, in γ τ.
    let (start, moved) = (&seen["start"], &seen["moved"]);
    assert_eq!(start["up"], serde_json::json!([0, 0, 1]));
    let tau = seen["tau"].as_f64().unwrap();
    let v = seen["speed"].as_f64().unwrap();
    assert!(tau > 0.0 && v > 0.0, "{seen}");
    let gamma = 1.0 / (1.0 - v * v).sqrt();
    let f =
        |w: &serde_json::Value, path: &[&str]| path.iter().fold(w, |w, k| &w[*k]).as_f64().unwrap();
    let dz = f(moved, &["position", "z"]) - f(start, &["position", "z"]);
    let dt = f(moved, &["time"]) - f(start, &["time"]);
    assert!(
        (dz - gamma * v * tau).abs() < 1e-9 * (1.0 + dz.abs()),
        "Δz {dz}, γvτ {}",
        gamma * v * tau
    );
    assert!(
        (dt - gamma * tau).abs() < 1e-9 * (1.0 + dt.abs()),
        "Δt {dt}, γτ {}",
        gamma * tau
    );
    for k in ["x", "y"] {
        assert_eq!(moved["position"][k], start["position"][k], "{seen}");
    }
    // Falling freely, it keeps the velocity R gave it (along z, the geodesic's own): the
    // frame at rest below is a moving observer's (aberration and Doppler).
    assert!(
        (f(moved, &["velocity", "speed"]) - v).abs() < 1e-9,
        "{seen}"
    );
    let d = &moved["velocity"]["direction"];
    assert!((d[2].as_f64().unwrap() - 1.0).abs() < 1e-9, "{seen}");

    // Every animation frame while moving draws a traced frame, smaller than the full one.
    let rafs = seen["rafs"].as_u64().unwrap();
    let traced = seen["traced_moving"].as_u64().unwrap();
    let drawn = seen["drawn"].as_u64().unwrap();
    assert!(rafs >= 40, "{seen}");
    assert!(
        traced + 2 >= rafs && traced <= rafs + 2,
        "{traced} traced in {rafs} animation frames"
    );
    assert!(
        drawn + 2 >= rafs,
        "{drawn} pictures drawn in {rafs} animation frames"
    );
    for size in seen["moving_sizes"].as_array().unwrap() {
        assert_eq!(size[2], "moving", "{seen}");
        assert!(
            size[0].as_u64().unwrap() < 88 || size[1].as_u64().unwrap() <= 10,
            "{seen}"
        );
    }
    assert!(
        seen["moving_header"]
            .as_str()
            .unwrap()
            .contains("traced on the GPU · "),
        "{seen}"
    );

    // At rest: the full size, and what `godel render --gpu` traces for the view.
    assert_eq!(seen["rest"]["width"], 88, "{seen}");
    assert_eq!(seen["rest"]["height"], 10, "{seen}");
    assert_eq!(seen["rest"]["traced"]["level"], "full", "{seen}");
    assert!(
        seen["header"]
            .as_str()
            .unwrap()
            .contains("88×10 traced on the GPU in"),
        "{seen}"
    );
    let slots = saved_slots(&out, "fly", seen["rest"]["slots"].as_u64().unwrap());
    let data = compare_with_render_gpu(dir.path(), "fly", &scene_of_view(&text, moved), &slots);

    // Save observer keyframe while flying: the view on screen, the velocity it fell with.
    let keyframe: toml::Table = seen["keyframe"].as_str().unwrap().parse().unwrap();
    let observer = &keyframe["keyframe"][0]["observer"];
    let number = |v: &toml::Value| v.as_float().unwrap();
    assert_eq!(number(&observer["time"]), moved["time"].as_f64().unwrap());
    assert_eq!(
        number(&observer["position"]["z"]),
        moved["position"]["z"].as_f64().unwrap()
    );
    let speed = moved["velocity"]["speed"].as_f64().unwrap();
    assert!(speed > 0.0, "{moved}");
    assert_eq!(number(&observer["velocity"]["speed"]), speed, "{keyframe}");

    // Hovering a pixel of the frame traced in the page: the map's light ray, traced in the
    // page by the kernel, is the one render::map makes from `godel render --gpu`'s record of
    // that pixel, seen from the view; for a hit and for a ray that hit nothing (drawn to the
    // past limit). No ray was asked of the server.
    for r in seen["requests"].as_array().unwrap() {
        let r = r.as_str().unwrap();
        assert!(
            !r.contains("/api/explore/ray") && !r.contains("/api/pixel"),
            "{r}"
        );
    }
    let scene = scene::Scene::from_str(&scene_of_view(&text, moved), "fly-view.toml").unwrap();
    let close = |a: &serde_json::Value, b: f64| (a.as_f64().unwrap() - b).abs() < 2e-3;
    for (hovered, ray, record, status) in [
        ("hovered", "ray", "record", "hit"),
        ("hovered_miss", "ray_miss", "record_miss", "escaped"),
    ] {
        let hovered = &seen[hovered];
        let (col, row) = (
            hovered["col"].as_u64().unwrap() as usize,
            hovered["row"].as_u64().unwrap() as usize,
        );
        assert_eq!(hovered["at"], serde_json::json!([col, row]), "{seen}");
        let ray = &seen[ray];
        assert_eq!(ray["status"], status, "{seen}");
        let expected_record = &data.records[data.index(col, row)];
        // The record panel's record, read in the page from the frame it traced.
        let shown = &seen[record];
        assert_eq!(shown["status"], status, "{seen}");
        assert_eq!(shown["object"], expected_record.object, "{seen}");
        if status == "hit" {
            let name = &data.header.object_names[expected_record.object as usize];
            assert_eq!(shown["object_name"], name.as_str(), "{seen}");
            let relative = |a: &serde_json::Value, b: f32| {
                (a.as_f64().unwrap() - f64::from(b)).abs() <= 1e-3 * (1.0 + f64::from(b).abs())
            };
            assert!(relative(&shown["g"], expected_record.g), "{shown}");
            assert!(
                relative(&shown["t_emit"], expected_record.t_emit),
                "{shown}"
            );
            assert!(relative(&shown["u"], expected_record.u), "{shown}");
        }
        let expected = render::map::light_ray(&scene, scene.observer.event, expected_record);
        let points = ray["points"].as_array().unwrap();
        assert!(expected.points.len() > 2, "{expected:?}");
        assert_eq!(points.len(), expected.points.len(), "{status}: {seen}");
        for (p, e) in points.iter().zip(&expected.points) {
            assert!(
                close(&p["t"], e.t)
                    && close(&p["x"], e.x)
                    && close(&p["y"], e.y)
                    && close(&p["z"], e.z)
                    && close(&p["r"], e.r),
                "{status}: {p} against {e:?}"
            );
        }
        match expected.emission {
            Some(emission) => {
                assert!(close(&ray["emission"]["t"], emission.t), "{seen}");
                assert!(close(&ray["emission"]["r"], emission.r), "{seen}");
                assert!(
                    close(&ray["travel_time"], expected.travel_time.unwrap()),
                    "{seen}"
                );
            }
            None => assert_eq!(ray["emission"], serde_json::Value::Null, "{seen}"),
        }
    }

    // A touch drag of dx CSS pixels to the right (pointer events of type touch) turns the
    // view left about its up axis by dx times the field of view per pixel; one wheel step of
    // 100 zooms out by e^0.1 (fly.js), keeping the panorama's aspect.
    let vector = |v: &serde_json::Value| -> [f64; 3] {
        let v = v.as_array().unwrap();
        [0, 1, 2].map(|i| v[i].as_f64().unwrap())
    };
    let (before, touch) = (&seen["before_touch"], &seen["touch"]);
    let (f0, up) = (vector(&before["forward"]), vector(&before["up"]));
    let f1 = vector(&touch["after"]["forward"]);
    let angle = touch["dx"].as_f64().unwrap() * before["camera"]["h_fov_deg"].as_f64().unwrap()
        / touch["width"].as_f64().unwrap()
        * std::f64::consts::PI
        / 180.0;
    // Rodrigues: f0 turned by `angle` about `up` (f0 ⟂ up).
    let cross = [
        up[1] * f0[2] - up[2] * f0[1],
        up[2] * f0[0] - up[0] * f0[2],
        up[0] * f0[1] - up[1] * f0[0],
    ];
    for i in 0..3 {
        let expected = f0[i] * angle.cos() + cross[i] * angle.sin();
        assert!(
            (f1[i] - expected).abs() < 1e-9,
            "{f1:?} against turned {f0:?}: {seen}"
        );
    }
    assert!(angle > 0.1, "{seen}");
    let fov = |v: &serde_json::Value, k: &str| v["camera"][k].as_f64().unwrap();
    let zoomed = &seen["wheel"];
    for k in ["h_fov_deg", "v_fov_deg"] {
        let ratio = fov(zoomed, k) / fov(&touch["after"], k);
        assert!((ratio - 0.1f64.exp()).abs() < 1e-9, "{k}: {ratio}");
    }
}

/// Renders `scene_text` (a view flown) with `godel render --gpu` into `dir/NAME-rendered` and
/// asserts that the page's `slots` of that view agree with it within issue 22's tolerances,
/// on a view that shows the ball; returns the rendered data file.
fn compare_with_render_gpu(
    dir: &std::path::Path,
    name: &str,
    scene_text: &str,
    slots: &[Vec<f32>],
) -> DataFile {
    let view_scene = dir.join(format!("{name}-view.toml"));
    std::fs::write(&view_scene, scene_text).unwrap();
    let rendered_dir = dir.join(format!("{name}-rendered"));
    std::fs::create_dir(&rendered_dir).unwrap();
    let rendered = godel(&[
        "render",
        "--gpu",
        view_scene.to_str().unwrap(),
        "-q",
        "-o",
        rendered_dir.to_str().unwrap(),
    ]);
    assert!(rendered.status.success(), "{rendered:?}");
    let data = DataFile::read(&rendered_dir.join("reference.exr")).unwrap();
    let page = traced_file(&data, slots);
    let a = kernel_agreement::compare(name, &page, &data);
    assert!(a.seen > 50, "the view shows the ball: {a:?} {scene_text}");
    assert!(a.holds(), "{a:?}");
    data
}

/// Reads the `count` slots a script saved as `OUT/PREFIX-slot-S.f32` (RGBA32F).
fn saved_slots(out: &std::path::Path, prefix: &str, count: u64) -> Vec<Vec<f32>> {
    (0..count)
        .map(|s| {
            std::fs::read(out.join(format!("{prefix}-slot-{s}.f32")))
                .unwrap()
                .chunks_exact(4)
                .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                .collect()
        })
        .collect()
}

/// At rest on a scene of 4 samples a pixel whose observer moves (0.6 c, sideways), the
/// page's first full frame is `godel render --gpu` of the scene itself: flying starts from
/// the scene's observer, velocity included (issue 32, point 7: it was flown at rest); Stop
/// (X) then stops it. The page shows half the size first (at the scene's own view, before it knows the kernel's
/// speed), then the full size at one sample a pixel, which is what `godel render --gpu`
/// traces for the view at one sample, and then the full samples; the canvas shows each while
/// the next is traced, also while the server's own first frame, held back by the script,
/// still loads (its channels are dropped then).
#[test]
fn at_rest_the_full_size_comes_at_one_sample_before_the_full_samples() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("rest-test.toml");
    let still = "velocity = { speed = 0.0, direction = [1, 0, 0] }";
    let moving = "velocity = { speed = 0.6, direction = [0, 1, 0] }";
    let text = scene_text()
        .replace("samples = 1", "samples = 4")
        .replace(still, moving);
    assert!(text.contains("width = 88\n") && text.contains("samples = 4"));
    assert!(text.contains(moving), "{text}");
    std::fs::write(&scene, &text).unwrap();
    let (server, url) = start_explore(&scene, dir.path(), &[]);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script("fly-rest.mjs", &page_frames(&url), &out, &[]);
    drop(server);
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["console_errors"], serde_json::json!([]), "{seen}");

    // The first full frame is the scene's own view, its observer moving: what `godel render
    // --gpu` traces for the scene (176×20 samples).
    let start_view = &seen["start_view"];
    assert_eq!(start_view["velocity"]["speed"], 0.6, "{seen}");
    assert_eq!(
        (&seen["start"]["width"], &seen["start"]["height"]),
        (&176.into(), &20.into()),
        "{seen}"
    );
    let slots = saved_slots(&out, "start-full", seen["start"]["slots"].as_u64().unwrap());
    compare_with_render_gpu(dir.path(), "start", &text, &slots);
    // Stop (X) sets the speed to 0, the direction kept; the rest is at rest.
    let stopped = &seen["stopped_view"]["velocity"];
    assert_eq!(stopped["speed"], 0.0, "{seen}");
    assert_eq!(stopped["direction"], serde_json::json!([0, 1, 0]), "{seen}");
    assert_eq!(seen["view"]["velocity"]["speed"], 0.0, "{seen}");

    // The page checked its tracer against the CPU exact tracer: the real kernel agrees.
    let check = &seen["check"];
    assert!(check["done"].as_u64().unwrap() >= 1, "{seen}");
    assert_eq!(check["last"]["verdict"], "agree", "{seen}");
    assert!(check["last"]["checked"].as_u64().unwrap() >= 8, "{seen}");
    assert_eq!(check["refused"], serde_json::Value::Null, "{seen}");

    // The frames at rest, in the order shown: (level, width, height) of each.
    let frames = |log: &serde_json::Value| -> Vec<(String, u64, u64)> {
        let log = log.as_array().unwrap();
        for pair in log.windows(2) {
            assert!(pair[0]["at"].as_f64() <= pair[1]["at"].as_f64(), "{seen}");
        }
        (log.iter())
            .map(|l| {
                let n = |k: &str| l[k].as_u64().unwrap();
                (l["level"].as_str().unwrap().into(), n("width"), n("height"))
            })
            .collect()
    };
    let (half, size, full) = (
        ("half".to_string(), 44, 5),
        ("size".to_string(), 88, 10),
        ("full".to_string(), 88, 10),
    );
    // The scene's own view, before the kernel's speed is known: half the size first.
    assert_eq!(
        frames(&seen["start_log"]),
        [half.clone(), size.clone(), full.clone()]
    );
    // After the wheel: half the size only where the full size would take over QUICK_MS
    // (fly.js, 1 s) at the speed measured before.
    let rays_per_ms = seen["rays_per_ms"].as_f64().unwrap();
    let mut expected = vec![size, full];
    if 88.0 * 10.0 / rays_per_ms > 1000.0 {
        expected.insert(0, half);
    }
    assert_eq!(frames(&seen["log"]), expected, "{seen}");
    // The slots of the last two frames: one sample a pixel, then 2×2.
    let shown = &seen["shown"].as_array().unwrap()[expected.len() - 2..];
    assert_eq!(shown[0]["level"], "size", "{seen}");
    assert_eq!(
        (&shown[0]["width"], &shown[0]["height"]),
        (&88.into(), &10.into())
    );
    assert_eq!(shown[1]["level"], "full", "{seen}");
    assert_eq!(
        (&shown[1]["width"], &shown[1]["height"]),
        (&176.into(), &20.into())
    );
    let header = seen["header"].as_str().unwrap();
    assert!(
        header.contains("88×10 · 4 samples a pixel traced on the GPU in"),
        "{header}"
    );
    // The one-sample frame is on the canvas while the full samples are traced: the canvas
    // then is near the final one, not the one before the wheel (the page's picture drawn
    // between the tracer's tiles was once clipped to the tile).
    let canvas = &seen["canvas"];
    assert_eq!(canvas["drawn_while_refining"], true, "{seen}");
    let n = |k: &str| canvas[k].as_u64().unwrap();
    assert!(
        n("full_to_before") > 100,
        "the wheel changed the picture: {canvas}"
    );
    assert!(
        n("size_to_full") * 2 < n("size_to_before"),
        "the canvas while refining: {canvas}"
    );

    // The one-sample frame is `godel render --gpu` of the view at one sample a pixel.
    let mut view = seen["view"].clone();
    assert_eq!(view["camera"]["samples"], 4, "{seen}");
    view["camera"]["samples"] = 1.into();
    let slots = saved_slots(&out, "rest-size", shown[0]["slots"].as_u64().unwrap());
    compare_with_render_gpu(dir.path(), "rest", &scene_of_view(&text, &view), &slots);
}
