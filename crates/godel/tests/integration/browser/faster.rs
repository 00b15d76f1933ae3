//! Explore on the faster tracer (issue 33, page/fly.js), in headless Chromium (WebGL2 on
//! SwiftShader, a software GPU): the page measures its kernel's rays a millisecond on a frame
//! of a quarter of the width and height at rest (at most 2,048 rays) and the server's CPU exact tracer's on the
//! frames the server traced, and from then on each frame, at rest and moving, comes from the
//! faster one. On this software GPU
//! that is the CPU, and
//!
//! - the speeds the page measured say so (the CPU's above the kernel's), the kernel's
//!   measuring frame has at most 2,048 rays, every frame after it is the CPU's, and the header names the tracer and both
//!   speeds;
//! - the full frame at rest is the scene's view at its size and samples, and the hovered
//!   pixel's record is the one `godel render --method exact` writes (the page reads it from
//!   the server's frame), its light ray on the map ends at that record's emission event;
//! - flying forward, the moving frames are the CPU's too (one ray a pixel), and so is the
//!   full frame at rest after letting go;
//! - a moving frame fills a canvas of at most the full frame's pixels, of its box's shape,
//!   which the browser scales to the box; at rest the canvas has the box's pixels again; while
//!   flying the map is fetched at most four times a second (map.js, MAP_GAP_MS).
//!
//! That the server's frame of a view holds `godel render`'s records bit for bit is
//! `explore_cli::the_frame_of_a_flown_view_is_godel_render_of_that_view`; the kernel's frames,
//! with `?trace=page`, are browser/fly.rs's.

use super::explore::scene_text;
use crate::browser_support::*;
use datafile::DataFile;

#[test]
fn each_frame_comes_from_the_faster_tracer_here_the_cpu() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    // The reference scene at 440×80 pixels of 2×2 rays, by the exact tracer (as explore's
    // server traces it): its own view gives a hit pixel to hover (its centre sample). A
    // quarter of its width and height is more than the kernel's measuring frame may have.
    let (width, height) = (440, 80);
    let text = scene_text()
        .replace("width = 88\n", &format!("width = {width}\n"))
        .replace("height = 10\n", &format!("height = {height}\n"))
        .replace("samples = 1", "samples = 4")
        .replace("method = \"numeric\"", "method = \"exact\"");
    assert!(text.contains("width = 440\n") && text.contains("samples = 4"));
    assert!(text.contains("method = \"exact\""), "{text}");
    let rendered = DataFile::read(&render(dir.path(), "reference", &text)).unwrap();
    let scene = dir.path().join("reference.toml");
    let sample =
        |col: usize, row: usize| rendered.records[rendered.index(2 * col + 1, 2 * row + 1)];
    let (col, row) = (0..height)
        .flat_map(|row| (0..width).map(move |col| (col, row)))
        .find(|&(col, row)| sample(col, row).has_emission())
        .expect("the scene shows the earth");

    let (server, url) = start_explore(&scene, dir.path(), &[]);
    let browser_out = dir.path().join("out");
    std::fs::create_dir(&browser_out).unwrap();
    let seen = run_script(
        "fly-faster.mjs",
        &url,
        &browser_out,
        &[col.to_string(), row.to_string()],
    );
    drop(server);
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["console_errors"], serde_json::json!([]), "{seen}");
    assert_only_local_requests(&seen, &url);

    // Both speeds measured here; the CPU's the higher on this software GPU.
    let rest = &seen["rest"];
    let (cpu, gpu) = (rest["cpu"].as_f64().unwrap(), rest["gpu"].as_f64().unwrap());
    assert!(cpu > gpu && gpu > 0.0, "{seen}");
    // The kernel traced until its speed was known (a frame of a quarter of the width and
    // height at rest, 110×20, cut to at most 2,048 rays in the scene's proportions:
    // √(2048·440/80) = 106.1 → 106×19), the CPU after.
    let log = rest_log(&seen["rest_log"]);
    let first_cpu = log
        .iter()
        .position(|(_, by)| by == "cpu")
        .expect("a CPU frame");
    assert!(first_cpu > 0, "{seen}");
    assert!(log[..first_cpu].iter().all(|(_, by)| by == "gpu"), "{seen}");
    assert!(log[first_cpu..].iter().all(|(_, by)| by == "cpu"), "{seen}");
    let measured = &seen["rest_log"][first_cpu - 1];
    assert_eq!(
        (&measured["level"], &measured["width"], &measured["height"]),
        (&"moving".into(), &106.into(), &19.into()),
        "{seen}"
    );
    let traced = &rest["traced"];
    assert_eq!(
        (
            &traced["level"],
            &traced["by"],
            &traced["width"],
            &traced["height"]
        ),
        (&"full".into(), &"cpu".into(), &width.into(), &height.into()),
        "{seen}"
    );
    let header = rest["header"].as_str().unwrap();
    assert!(
        header.contains("440×80 · 4 samples a pixel traced on the server\u{2019}s CPU")
            && header.contains(&format!("the CPU {} rays/ms", cpu.round()))
            && header.contains(&format!("the GPU {}", gpu.round())),
        "{header}"
    );
    // The hovered pixel's record is godel render's, and its ray ends where the light left.
    let (record, want) = (&seen["record"], sample(col, row));
    assert_eq!(seen["hovered"], serde_json::json!([col, row]), "{seen}");
    assert_eq!(record["status"], "hit", "{seen}");
    // (the record's f32 numbers as JSON writes them: the shortest that reads back the same)
    let f32_of = |k: &str| record[k].as_f64().map(|x| x as f32);
    assert_eq!(f32_of("t_emit"), Some(want.t_emit), "{seen}");
    assert_eq!(f32_of("g"), Some(want.g), "{seen}");
    assert_eq!(f32_of("u"), Some(want.u), "{seen}");
    let ray = &seen["ray"];
    let emission = ray["emission"].clone();
    assert!(
        (emission["t"].as_f64().unwrap() - f64::from(want.t_emit)).abs() < 1e-9
            && (emission["x"].as_f64().unwrap() - f64::from(want.x)).abs() < 1e-6,
        "{ray}"
    );
    // Flying: every moving frame (one ray a pixel) is the CPU's.
    let moving: Vec<_> = rest_log(&seen["moving_log"])
        .into_iter()
        .filter(|(level, _)| level == "moving")
        .collect();
    assert!(moving.len() >= 10, "{seen}");
    assert!(moving.iter().all(|(_, by)| by == "cpu"), "{seen}");
    let moving_header = seen["moving_header"].as_str().unwrap();
    assert!(
        moving_header.contains("traced on the server\u{2019}s CPU · "),
        "{moving_header}"
    );
    // Moving: the canvas holds at most the full frame's pixels, in the box's shape; at rest
    // (before and after) the box's.
    let pixels = |c: &serde_json::Value| {
        let n = |v: &serde_json::Value| v.as_u64().unwrap();
        (
            n(&c["width"]),
            n(&c["height"]),
            n(&c["box"][0]),
            n(&c["box"][1]),
        )
    };
    let moving_canvas = &seen["moving_canvas"];
    assert_eq!(moving_canvas["level"], "moving", "{seen}");
    let (w, h, bw, bh) = pixels(moving_canvas);
    assert!(
        bw > width as u64,
        "the box is wider than the full frame: {seen}"
    );
    assert!(w <= width as u64 && h <= height as u64, "{seen}");
    assert!(w == width as u64 || h == height as u64, "{seen}");
    let shape = (w as f64 / h as f64) / (bw as f64 / bh as f64);
    assert!((shape - 1.0).abs() < 0.02, "the box's shape: {seen}");
    for c in [&rest["canvas"], &seen["again"]["canvas"]] {
        assert_eq!(c["level"], "full", "{seen}");
        let (w, h, bw, bh) = pixels(c);
        // (the box's device pixels as the browser rounds its CSS size: within one)
        assert!(w.abs_diff(bw) <= 1 && h.abs_diff(bh) <= 1, "{seen}");
    }
    // The map while flying: fetched, at most once every 250 ms.
    let maps = seen["moving_map"]["requests"].as_u64().unwrap();
    let ms = seen["moving_map"]["ms"].as_f64().unwrap();
    assert!(maps >= 1 && maps as f64 <= ms / 250.0 + 1.0, "{seen}");
    // Drawn in the animation frame of a picture (one composition of the page for both), or
    // alone only for a map fetched when no move followed it soon: at most once a fetch.
    let alone = seen["moving_map"]["alone"].as_u64().unwrap();
    assert!(alone <= maps, "{seen}");
    // While the server traces a moving frame, the observer is moved at most every 100 ms
    // (fly.js MOVE_GAP_MS, timed from animation frames, so within a few ms of it).
    if let Some(gap) = seen["moving_moves"].as_f64() {
        assert!(gap >= 90.0, "moves {gap} ms apart: {seen}");
    }
    // At rest again, after moving forward: the CPU's full frame of the new view.
    let again = &seen["again"];
    assert_eq!(again["traced"]["level"], "full", "{seen}");
    assert_eq!(again["traced"]["by"], "cpu", "{seen}");
    assert!(
        rest_log(&seen["again_log"])
            .iter()
            .all(|(_, by)| by == "cpu"),
        "{seen}"
    );
    assert_ne!(
        again["view"]["position"], rest["view"]["position"],
        "{seen}"
    );
}

/// (level, tracer) of each frame of a log.
fn rest_log(log: &serde_json::Value) -> Vec<(String, String)> {
    log.as_array()
        .unwrap()
        .iter()
        .map(|l| {
            (
                l["level"].as_str().unwrap().to_string(),
                l["by"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}
