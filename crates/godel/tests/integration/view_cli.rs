//! `godel view` on bad input: every failure comes before anything is served, as one
//! `error:` line naming the file or flag, with a non-zero exit (2 for flags).

use std::process::Output;

use crate::common::{self, godel};

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
    let text = std::fs::read_to_string(testkit::scenes_dir().join("static-sphere.toml"))
        .unwrap()
        .replace("width = 720", "width = 48")
        .replace("height = 120", "height = 8");
    std::fs::write(&scene, text).unwrap();
    let o = common::render(&scene, dir, &["-q"]);
    assert!(o.status.success(), "{o:?}");
    dir.join("static-sphere.exr")
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

#[test]
fn a_texture_folder_that_is_not_one_names_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let exr = small_data_file(dir.path());
    let missing = dir.path().join("no-such-folder");
    let o = godel(&[
        "view",
        exr.to_str().unwrap(),
        "--port",
        "0",
        "--textures",
        missing.to_str().unwrap(),
    ]);
    fails_with(&o, 2, &["--textures", "no-such-folder"]);
}

/// One HTTP/1.1 request over a fresh connection; returns the status code and the body.
fn http(port: u16, request: &str) -> (u16, String) {
    use std::io::{Read, Write};
    let mut stream = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
    // A deadline against hanging forever, not a speed check.
    stream
        .set_read_timeout(Some(std::time::Duration::from_secs(60)))
        .unwrap();
    stream.write_all(request.as_bytes()).unwrap();
    let mut answer = String::new();
    stream.read_to_string(&mut answer).unwrap();
    let status = answer
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no status in {answer:?}"));
    let body = answer
        .split_once("\r\n\r\n")
        .map(|(_, b)| b.to_string())
        .unwrap_or_default();
    (status, body)
}

/// The running server checks Host against the port it really listens on, and wants JSON.
#[test]
fn the_server_answers_only_requests_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let exr = small_data_file(dir.path());
    let (_server, url) = common::start_server("view", &exr, dir.path());
    let port = common::port_of(&url);
    let get = |host: &str| {
        http(
            port,
            &format!("GET /api/info HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n\r\n"),
        )
    };
    let (status, body) = get(&format!("127.0.0.1:{port}"));
    assert_eq!(status, 200, "{body}");
    assert!(body.contains("\"file\":\"static-sphere.exr\""), "{body}");
    assert!(!body.contains(&dir.path().display().to_string()), "{body}");
    let (status, body) = get(&format!("localhost:{port}"));
    assert_eq!(status, 200, "{body}");
    let (status, body) = get(&format!("evil.example:{port}"));
    assert_eq!(status, 403, "{body}");
    assert!(body.contains("\"error\""), "{body}");
    let (status, _) = get(&format!("127.0.0.1:{}", port.wrapping_add(1)));
    assert_eq!(status, 403);
    // A cross-site form post: text/plain, refused before shading.
    let settings = "{}";
    let (status, body) = http(
        port,
        &format!(
            "POST /api/png HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: text/plain\r\n\
             Content-Length: {}\r\nConnection: close\r\n\r\n{settings}",
            settings.len()
        ),
    );
    assert_eq!(status, 415, "{body}");
}
