//! `godel explore` in the browser: the Explore panel shows, moving the time slider sends the
//! new event, and the page swaps in the full frame traced for it (the ball in free fall has
//! moved, so the picture changes), at the scene's size.

use super::browser_support::*;

/// The reference scene (a ball in free fall past the observer) at 88×10 pixels, one ray each.
fn scene_text() -> String {
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
    let (_server, url) = start_explore(&scene, dir.path());
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script("explore.mjs", &url, &out, &["1.5".to_string()]);
    assert_eq!(seen["panel_hidden"], false, "{seen}");
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["console_errors"], serde_json::json!([]), "{seen}");
    assert_eq!(seen["before"]["event"]["t"], 0.0, "{seen}");
    assert_eq!(seen["after"]["event"]["t"], 1.5, "{seen}");
    for frame in ["before", "after"] {
        assert_eq!(seen[frame]["width"], 88, "{seen}");
        assert_eq!(seen[frame]["height"], 10, "{seen}");
    }
    assert!(
        seen["after"]["generation"].as_u64() > seen["before"]["generation"].as_u64(),
        "{seen}"
    );
    assert!(
        seen["status"].as_str().unwrap().contains("t = 1.50"),
        "{seen}"
    );
    let (w, h, before) = read_rgba(&out.join("before.rgba"));
    let (w2, h2, after) = read_rgba(&out.join("after.rgba"));
    assert_eq!((w, h), (w2, h2));
    let changed = compare(&before, &after, w).off.len();
    assert!(changed > 0, "the picture did not change with t");
    assert_only_local_requests(&seen, &url);
}
