//! `godel explore` in the browser, keeping what one flies (issue 23, point 4): "Render
//! exactly" of the view on screen downloads the PNG and data file that `godel render
//! --method exact` writes for a scene with the view's fields (the same records, the same
//! picture bytes); a recorded flight's sequence script, rendered by `godel sequence`, has at
//! each keyframe's frame the picture `godel render` makes of the view recorded there.

use std::path::Path;

use crate::browser_support::*;
use crate::common::records;

/// The reference scene (a ball in free fall past the observer) at 64×8 pixels, 4 rays each.
fn scene_text() -> String {
    std::fs::read_to_string(repo_root().join("scenes/reference.toml"))
        .unwrap()
        .replace("width = 880", "width = 64")
        .replace("height = 100", "height = 8")
}

/// A scene file written from a view of the page (its JSON): the reference scene's spacetime
/// and objects seen by the view's observer and camera, traced by the exact tracer.
fn scene_of_view(view: &serde_json::Value) -> String {
    let n = |v: &serde_json::Value| format!("{:?}", v.as_f64().unwrap());
    let vector = |v: &serde_json::Value| {
        let parts: Vec<String> = v.as_array().unwrap().iter().map(n).collect();
        format!("[{}]", parts.join(", "))
    };
    let (p, c) = (&view["position"], &view["camera"]);
    let text = scene_text();
    let objects = &text[text.find("[[object]]").unwrap()..];
    format!(
        "name = \"direct\"\n[spacetime]\nmetric = \"godel\"\na = 1.0\n[observer]\ntime = {}\n\
         position = {{ x = {}, y = {}, z = {} }}\n\
         velocity = {{ speed = {}, direction = {} }}\nforward = {}\nup = {}\n\
         [camera]\nkind = {}\nh_fov_deg = {}\nv_fov_deg = {}\nwidth = {}\nheight = {}\n\
         samples = {}\n[trace]\nmethod = \"exact\"\nmax_past = 30.0\n{objects}",
        n(&view["time"]),
        n(&p["x"]),
        n(&p["y"]),
        n(&p["z"]),
        n(&view["velocity"]["speed"]),
        vector(&view["velocity"]["direction"]),
        vector(&view["forward"]),
        vector(&view["up"]),
        c["kind"],
        n(&c["h_fov_deg"]),
        n(&c["v_fov_deg"]),
        c["width"],
        c["height"],
        c["samples"],
    )
}

/// `godel render --method exact` of the scene of `view`, written into `dir` as
/// `NAME.png`, `NAME.exr`; returns the two files' paths.
fn render_view(
    dir: &Path,
    name: &str,
    view: &serde_json::Value,
) -> (std::path::PathBuf, std::path::PathBuf) {
    let scene = dir.join(format!("{name}.toml"));
    std::fs::write(&scene, scene_of_view(view)).unwrap();
    let out = dir.join(name);
    let o = godel(&[
        "render",
        scene.to_str().unwrap(),
        "--method",
        "exact",
        "-q",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{o:?}");
    (out.join("direct.png"), out.join("direct.exr"))
}

#[test]
fn render_exactly_and_a_recorded_flight_are_the_views_on_screen() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("keep-test.toml");
    std::fs::write(&scene, scene_text()).unwrap();
    let (_server, url) = start_explore(&scene, dir.path(), &[]);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script(
        "keep.mjs",
        // On the server's frames (its script moves the event with the Explore panel's
        // fields); flying is tested in browser/fly.rs.
        &format!("{url}?trace=server"),
        &out,
        &["0.3".to_string(), "1.5".to_string()],
    );
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["console_errors"], serde_json::json!([]), "{seen}");
    assert_only_local_requests(&seen, &url);

    // Render exactly: the view moved to x = 0.3, at the scene's size and samples.
    let view = &seen["view"];
    assert_eq!(seen["exact"]["state"], "done", "{seen}");
    assert_eq!(view["position"]["x"], 0.3, "{seen}");
    assert_eq!(
        (&view["camera"]["width"], &view["camera"]["samples"]),
        (&serde_json::json!(64), &serde_json::json!(4)),
        "{seen}"
    );
    let (png, exr) = render_view(dir.path(), "exact-direct", view);
    assert_eq!(
        records(&out.join("exact.exr")),
        records(&exr),
        "the downloaded data file is not godel render's of the view"
    );
    assert!(std::fs::read(out.join("exact.png")).unwrap() == std::fs::read(png).unwrap());
    // Record: a keyframe at the start, after t moved, after x moved, and at Stop.
    let keyframes = seen["keyframes"].as_array().unwrap();
    assert!(keyframes.len() >= 4, "{seen}");
    let times: Vec<f64> = keyframes
        .iter()
        .map(|k| k["view"]["time"].as_f64().unwrap())
        .collect();
    assert_eq!((times[0], *times.last().unwrap()), (0.0, 1.5), "{seen}");
    assert_eq!(keyframes.last().unwrap()["view"]["position"]["x"], 0.0);
    let script = out.join("flight.toml");
    let o = godel(&["sequence", script.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{o:?}");
    let frames = out.join("reference-flight");
    let mut last_records = String::new();
    for (k, keyframe) in keyframes.iter().enumerate() {
        let frame = (keyframe["seconds"].as_f64().unwrap() * 24.0).round() as u32;
        let (png, key_exr) = render_view(dir.path(), &format!("key{k}"), &keyframe["view"]);
        assert!(
            std::fs::read(frames.join(format!("frame_{frame:04}.png"))).unwrap()
                == std::fs::read(png).unwrap(),
            "frame {frame} is not the view recorded at keyframe {k}: {seen}"
        );
        last_records = records(&key_exr);
    }
    // The flight went somewhere: its end (t = 1.5, x = 0) is not the view rendered exactly.
    assert_ne!(last_records, records(&exr));
}
