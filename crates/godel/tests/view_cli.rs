//! `godel view` on bad input: every failure comes before anything is served, as one
//! `error:` line naming the file or flag, with a non-zero exit (2 for flags).

use std::process::{Command, Output};

fn godel(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_godel"))
        .args(args)
        .output()
        .expect("run godel")
}

fn fails_with(o: &Output, code: i32, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(code), "{stderr}");
    assert!(o.stdout.is_empty(), "nothing served: {:?}", o.stdout);
    for needle in needles {
        assert!(stderr.contains(needle), "{needle:?} not in {stderr}");
    }
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// Renders a 48×8 view of scenes/static-sphere.toml into `dir`; returns the data file.
fn small_data_file(dir: &std::path::Path) -> std::path::PathBuf {
    let scene = dir.join("s.toml");
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/static-sphere.toml"),
    )
    .unwrap()
    .replace("width = 720", "width = 48")
    .replace("height = 120", "height = 8");
    std::fs::write(&scene, text).unwrap();
    let o = godel(&[
        "render",
        scene.to_str().unwrap(),
        "-q",
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{o:?}");
    let exr = dir.join("static-sphere.exr");
    exr
}

#[test]
fn missing_data_file_is_refused_before_serving() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nope.exr");
    let o = godel(&["view", path.to_str().unwrap(), "--port", "0"]);
    fails_with(&o, 1, &["error: data file", "nope.exr", "No such file"]);
}

#[test]
fn file_that_is_not_exr_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fake.exr");
    std::fs::write(&path, "P3\n1 1\n255\n0 0 0\n").unwrap();
    let o = godel(&["view", path.to_str().unwrap(), "--port", "0"]);
    fails_with(&o, 1, &["fake.exr", "not an OpenEXR file"]);
}

/// A real data file cut in half.
#[test]
fn truncated_data_file_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let exr = small_data_file(dir.path());
    let bytes = std::fs::read(&exr).unwrap();
    std::fs::write(&exr, &bytes[..bytes.len() / 2]).unwrap();
    let o = godel(&["view", exr.to_str().unwrap(), "--port", "0"]);
    fails_with(&o, 1, &["static-sphere.exr"]);
}

#[test]
fn port_in_use_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let exr = small_data_file(dir.path());
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let o = godel(&["view", exr.to_str().unwrap(), "--port", &port]);
    fails_with(&o, 2, &["--port", &port, "already in use"]);
}

#[test]
fn bad_host_names_the_flag() {
    let o = godel(&["view", "whatever.exr", "--host", "not an address"]);
    fails_with(&o, 2, &["--host", "not an address"]);
}
