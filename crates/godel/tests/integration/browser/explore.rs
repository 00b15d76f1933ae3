//! `godel explore` in the browser: the Explore panel shows, moving the time slider sends the
//! new event, and the page swaps in the full frame traced for it (the ball in free fall has
//! moved, so the picture changes), at the scene's size; the map beside the picture
//! (issue 15) draws the hovered pixel's light ray from the observer to the pixel's emission
//! event, dragging the observer's marker on it moves the observer's event to the map's point
//! under the mouse, and "Save observer keyframe" saves a keyframe at that event; playing
//! takes coarse frames, each drawn before the next; with `--sphere` the page looks around
//! in the traced sphere and keeps the view across events.

use crate::browser_support::*;

/// The reference scene (a ball in free fall past the observer) at 88×10 pixels, one ray each.
pub(super) fn scene_text() -> String {
    std::fs::read_to_string(repo_root().join("scenes/reference.toml"))
        .unwrap()
        .replace("width = 880", "width = 88")
        .replace("height = 100", "height = 10")
        .replace("samples = 4", "samples = 1")
}

#[test]
fn moving_the_time_slider_shows_the_frame_traced_for_the_new_time() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("explore-test.toml");
    let text = scene_text();
    assert!(text.contains("width = 88\n") && text.contains("samples = 1"));
    std::fs::write(&scene, text).unwrap();
    let (_server, url) = start_explore(&scene, dir.path(), &[]);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script(
        "explore.mjs",
        &server_frames(&url),
        &out,
        &["1.5".to_string()],
    );
    assert_eq!(seen["panel_hidden"], false, "{seen}");
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["console_errors"], serde_json::json!([]), "{seen}");
    assert_eq!(seen["before"]["event"]["t"], 0.0, "{seen}");
    assert_eq!(seen["after"]["event"]["t"], 1.5, "{seen}");
    for frame in ["before", "after"] {
        assert_eq!(seen[frame]["width"], 88, "{seen}");
        assert_eq!(seen[frame]["height"], 10, "{seen}");
    }
    // Issue 24: Save PNG is the frame on screen's, at its size (it was the first coarse
    // frame's, 22×2).
    assert_eq!(
        seen["saved"],
        serde_json::json!({"width": 88, "height": 10}),
        "{seen}"
    );
    assert!(
        seen["after"]["generation"].as_u64() > seen["before"]["generation"].as_u64(),
        "{seen}"
    );
    assert!(
        seen["status"].as_str().unwrap().contains("t = 1.50"),
        "{seen}"
    );
    // Playing: coarse frames of later and later times, each drawn (a shading pass) before the
    // next is taken; Pause brings the full frame of where time stopped.
    let log = seen["play_log"].as_array().unwrap();
    assert!(log.len() >= 4, "{seen}");
    for pair in log.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        assert_eq!(b["level"], "coarse", "{seen}");
        assert!(
            b["generation"].as_u64() > a["generation"].as_u64(),
            "{seen}"
        );
        assert!(b["t"].as_f64() > a["t"].as_f64(), "{seen}");
        assert!(
            b["shadings"].as_u64() > a["shadings"].as_u64(),
            "a frame was taken before the last one was drawn: {seen}"
        );
    }
    assert_eq!(seen["paused"]["level"], "full", "{seen}");
    assert_eq!(seen["paused"]["event"]["t"], seen["paused_t"], "{seen}");
    assert!(seen["paused_t"].as_f64().unwrap() > 1.5, "{seen}");
    let (w, h, before) = read_rgba(&out.join("before.rgba"));
    let (w2, h2, after) = read_rgba(&out.join("after.rgba"));
    assert_eq!((w, h), (w2, h2));
    let changed = compare(&before, &after, w).off.len();
    assert!(changed > 0, "the picture did not change with t");
    assert_only_local_requests(&seen, &url);
}

/// The point `p` ({t, x, y, z, …}) is the event `want` (t, x, y, z) within `tol`.
fn same_event(p: &serde_json::Value, want: [f64; 4], tol: f64) -> bool {
    ["t", "x", "y", "z"]
        .iter()
        .zip(want)
        .all(|(k, w)| p[*k].as_f64().is_some_and(|v| (v - w).abs() <= tol))
}

fn event_of(e: &serde_json::Value) -> [f64; 4] {
    ["t", "x", "y", "z"].map(|k| e[k].as_f64().unwrap())
}

/// What the page showed while hovering a pixel at `event`: the map's ray runs from the
/// observer's event to the emission event of the pixel's record (`/api/pixel`), is drawn on
/// the map's canvas along its points, and is gone once the mouse leaves the picture.
fn check_hover(seen: &serde_json::Value, hover: &serde_json::Value, event: [f64; 4]) {
    let ray = &hover["ray"];
    let record = &hover["record"];
    let points = ray["points"].as_array().unwrap();
    assert!(points.len() >= 2, "{ray}");
    assert!(
        same_event(&points[0], event, 1e-3),
        "{} vs {event:?}",
        points[0]
    );
    assert_eq!(ray["status"], record["status"], "{seen}");
    if record["status"] == "hit" {
        let emission = [
            event[0] + record["t_emit"].as_f64().unwrap(),
            record["x"].as_f64().unwrap(),
            record["y"].as_f64().unwrap(),
            record["z"].as_f64().unwrap(),
        ];
        let last = points.last().unwrap();
        assert!(
            same_event(last, emission, 1e-3),
            "last point {last}, record {record}"
        );
        assert!(same_event(&ray["emission"], emission, 1e-3), "{ray}");
        let travel = ray["travel_time"].as_f64().unwrap();
        assert!((travel - record["travel_time"].as_f64().unwrap()).abs() <= 1e-3);
    }
    let before = &hover["ray_pixels_before"];
    let during = &hover["ray_pixels"];
    let after = &hover["ray_pixels_after"];
    assert_eq!(before["total"], 0, "ray colour on the map before hovering");
    let (inside, near) = (
        during["inside"].as_u64().unwrap(),
        during["near"].as_u64().unwrap(),
    );
    assert!(
        inside >= 10 && near * 10 >= inside * 8 && during["total"].as_u64().unwrap() > 50,
        "the ray is not drawn along its points: {during}"
    );
    assert_eq!(after["total"], 0, "the ray stays after leaving the picture");
}

#[test]
fn the_map_shows_the_hovered_pixels_ray_and_dragging_the_observer_moves_the_event() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let text = scene_text().replace("name = \"reference\"", "name = \"map-test\"");
    assert!(text.contains("name = \"map-test\""));
    // The ball's pixel whose light took longest: it loops around the observer's axis.
    let exr = render(dir.path(), "map-test", &text);
    let data = datafile::DataFile::read(&exr).unwrap();
    let (col, row) = (0..data.height)
        .flat_map(|row| (0..data.width).map(move |col| (col, row)))
        .filter(|&(c, r)| data.record(c, r).object == 0)
        .max_by(|&a, &b| {
            let t = |p: (usize, usize)| -data.record(p.0, p.1).t_emit;
            t(a).total_cmp(&t(b))
        })
        .expect("the test scene shows the ball");
    let scene = dir.path().join("map-test.toml");
    let (_server, url) = start_explore(&scene, dir.path(), &[]);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let (dx, dy) = (60, -40);
    let args = [col, row].map(|v| v.to_string());
    let seen = run_script(
        "map.mjs",
        &server_frames(&url),
        &out,
        &[
            args[0].clone(),
            args[1].clone(),
            dx.to_string(),
            dy.to_string(),
        ],
    );
    assert_eq!(seen["map_hidden"], false, "{seen}");
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    // While the observer is dragged, frames are superseded as their channels load: the
    // server answers 410 Gone (the page then takes the next frame). No other error.
    assert_eq!(seen["console_errors_before_drag"], serde_json::json!([]));
    for message in seen["console_errors"].as_array().unwrap() {
        assert!(
            message.as_str().unwrap().contains("410 (Gone)"),
            "{message}"
        );
    }
    assert_only_local_requests(&seen, &url);
    let map = &seen["map"];
    assert!(map["horizon_points"].as_u64().unwrap() > 100, "{map}");
    assert_eq!(map["objects"], serde_json::json!(["earth"]), "{map}");

    // Hovering the ball's pixel at the scene's event.
    let before = event_of(&seen["before"]["event"]);
    assert_eq!(before, [0.0; 4]);
    assert_eq!(seen["hover_before"]["record"]["object_name"], "earth");
    assert_eq!(seen["hover_before"]["record"]["status"], "hit");
    check_hover(&seen, &seen["hover_before"], before);
    // The Pixel panel's direction is the scene camera's for that pixel (the page knows the
    // full frame's size, though the server started on a coarse frame).
    let scene = scene::Scene::from_str(&text, "map-test").unwrap();
    let n = scene
        .observer
        .pixel_direction(&scene.camera, col as u32, row as u32)
        .unwrap();
    let shown = &seen["hover_before"]["direction"];
    assert_ne!(shown, "–", "no direction shown for pixel ({col}, {row})");
    let [az, el] = super::angles(shown);
    let [want_az, want_el] = super::azimuth_elevation(n);
    assert!(
        (az - want_az).abs() < 0.006 && (el - want_el).abs() < 0.006,
        "direction shown {az}°, {el}°; the camera's {want_az}°, {want_el}°"
    );

    // Dragging the observer's marker: the new event is the map's point under the drop, the
    // frame shown is traced there, the fields say so, and the picture changed.
    let after = event_of(&seen["after"]["event"]);
    let drop = &seen["drop"];
    let pixel = drop["pixel"].as_f64().unwrap();
    assert!(pixel > 0.0 && pixel < 0.1, "{drop}");
    for (k, i) in [("x", 1), ("y", 2)] {
        let want = drop[k].as_f64().unwrap();
        assert!(
            (after[i] - want).abs() <= pixel,
            "{k}: {} after the drag, the drop point is at {want}",
            after[i]
        );
        assert!((after[i] - before[i]).abs() > 10.0 * pixel, "{seen}");
    }
    assert_eq!((after[0], after[3]), (before[0], before[3]));
    assert!(
        same_event(&seen["after"]["frame_event"], after, 0.0),
        "{seen}"
    );
    assert!(same_event(&seen["map_after"], after, 0.0), "{seen}");
    let fields: Vec<f64> = seen["after"]["fields"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(fields, after[1..].to_vec(), "the x, y, z fields");
    assert!(seen["after"]["generation"].as_u64() > seen["before"]["generation"].as_u64());
    let (w, _, pic_before) = read_rgba(&out.join("before.rgba"));
    let (_, _, pic_after) = read_rgba(&out.join("after.rgba"));
    assert!(
        !compare(&pic_before, &pic_after, w).off.is_empty(),
        "the picture did not change with the observer's place"
    );
    // The same pixel hovered at the new event.
    check_hover(&seen, &seen["hover_after"], after);

    // "Save observer keyframe": a keyframe at the new event, shown and downloaded.
    let saved = std::fs::read_to_string(out.join("keyframe.toml")).unwrap();
    assert_eq!(seen["keyframe_shown"].as_str(), Some(saved.as_str()));
    assert!(seen["keyframe_name"].as_str().unwrap().ends_with(".toml"));
    let keyframe: toml::Value = toml::from_str(&saved).unwrap();
    let k = &keyframe["keyframe"][0];
    assert_eq!(k["frame"].as_integer(), Some(0), "{saved}");
    let observer = &k["observer"];
    let number = |v: &toml::Value| v.as_float().or(v.as_integer().map(|i| i as f64));
    assert_eq!(number(&observer["time"]), Some(after[0]), "{saved}");
    for (k, i) in [("x", 1), ("y", 2), ("z", 3)] {
        assert_eq!(number(&observer["position"][k]), Some(after[i]), "{saved}");
    }
}

/// `godel explore --sphere 96`: the page looks around in the traced sphere (a drag turns the
/// view on the GPU and asks the server for no new trace), and a new time is traced and shown
/// in the same turned view.
#[test]
fn with_sphere_the_page_looks_around_and_keeps_the_view_across_events() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("explore-test.toml");
    std::fs::write(&scene, scene_text()).unwrap();
    let (_server, url) = start_explore(&scene, dir.path(), &["--sphere", "96"]);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script(
        "explore-look.mjs",
        &server_frames(&url),
        &out,
        &["1.5".to_string()],
    );
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["console_errors"], serde_json::json!([]), "{seen}");
    assert!(seen["look"].is_object(), "not looking around: {seen}");
    let yaw = seen["drag"]["yaw"].as_f64().unwrap();
    assert!(yaw.abs() > 5.0, "the drag did not turn the view: {seen}");
    assert!(
        seen["drag"]["pixels_changed"].as_u64() > Some(100),
        "{seen}"
    );
    let asked: Vec<&str> = seen["drag"]["requests"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_str().unwrap())
        .collect();
    assert!(
        asked.iter().all(|r| !r.contains("/api/explore/event")),
        "turning re-traced: {asked:?}"
    );
    assert_eq!(seen["after"]["event"]["t"], 1.5, "{seen}");
    assert_eq!(seen["after"]["level"], "full", "{seen}");
    assert_eq!(seen["after"]["look"], true, "{seen}");
    assert_eq!(seen["after"]["yaw"].as_f64(), Some(yaw), "{seen}");
    assert!(seen["pixels_changed_by_t"].as_u64() > Some(0), "{seen}");
}

/// The page on the server's frames (`?trace=server`): what these tests check. The page's own
/// GPU frames are tested in browser/fly.rs.
fn server_frames(url: &str) -> String {
    format!("{url}?trace=server")
}
