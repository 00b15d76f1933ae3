//! The page checks what it shows (issue 32, point 6; page/fly.js, viewer::page_check): explore
//! serves (`--kernel`) a GPU kernel with a fault — escaped rays written as failed — and the
//! page's first traced frame, checked against the server's CPU exact tracer, is refused: the
//! header names the renderer refused and why, and the frames shown then are the server's
//! (its channels fetched, coarse then full). The real kernel passing the same check is
//! asserted in fly.rs (at rest).

use super::explore::scene_text;
use crate::browser_support::*;

/// The kernel with a fault: escaped rays say `failed` (a constant read wrongly).
fn faulty_kernel() -> String {
    let (from, to) = ("const int ESCAPED = 1;", "const int ESCAPED = 3;");
    assert!(
        gpu::KERNEL.contains(from),
        "the kernel no longer has {from:?}"
    );
    gpu::KERNEL.replacen(from, to, 1)
}

#[test]
fn a_kernel_that_disagrees_with_the_cpu_is_refused_and_the_server_traces() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("check-test.toml");
    std::fs::write(&scene, scene_text()).unwrap();
    let kernel = dir.path().join("faulty.glsl");
    std::fs::write(&kernel, faulty_kernel()).unwrap();
    let (server, url) = start_explore(&scene, dir.path(), &["--kernel", kernel.to_str().unwrap()]);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script("fly-check.mjs", &super::fly::page_frames(&url), &out, &[]);
    drop(server);
    assert_eq!(seen["error"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["console_errors"], serde_json::json!([]), "{seen}");
    assert_only_local_requests(&seen, &url);

    // Refused on the CPU's word: the samples disagree in status.
    assert_eq!(seen["check"]["verdict"], "disagree", "{seen}");
    let reason = seen["check"]["reason"].as_str().unwrap();
    assert!(
        reason.contains("disagrees with the CPU exact tracer")
            && reason.contains("GPU failed, CPU escaped"),
        "{reason}"
    );
    // The header says the page's tracer was refused, why (naming its renderer), and who
    // traces now.
    let header = seen["header"].as_str().unwrap();
    assert!(
        header.contains(&format!("the page's tracer was refused: {reason}"))
            && reason.starts_with("the GPU (")
            && header.contains("frames traced on the server"),
        "{header}"
    );
    assert!(!header.contains("traced on the GPU in"), "{header}");
    // The frames then come from the server: its full frame at the scene's size, its channels
    // fetched after the refusal, and the page traces no more.
    assert_eq!(seen["fly"], serde_json::Value::Null, "{seen}");
    assert_eq!(seen["shown"]["level"], "full", "{seen}");
    assert_eq!(seen["size"], serde_json::json!([88, 10]), "{seen}");
    let after: Vec<&str> = (seen["requests_after"].as_array().unwrap().iter())
        .map(|r| r.as_str().unwrap())
        .collect();
    assert!(
        after
            .iter()
            .any(|r| r.contains("/api/explore/channels?") && r.contains("level=full")),
        "{after:?}"
    );
}
