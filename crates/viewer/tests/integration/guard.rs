//! Only the user's own browser tab gets answers: requests must name this server in `Host`
//! (against DNS rebinding), come from its own origin when they say where from, and send JSON
//! as `application/json` (a page on another site can POST `text/plain` without a CORS
//! preflight); bodies are capped; `/api/info` does not show where the data file lies.

use std::net::SocketAddr;
use std::sync::Arc;

use crate::common::{data, error_of, frequency, get, post, send, send_to};
use axum::body::Body;
use axum::http::{Request, StatusCode};
use viewer::{Access, ViewerState, MAX_BODY_BYTES};

fn get_with_host(path: &str, host: Option<&str>) -> Request<Body> {
    let mut r = Request::get(path);
    if let Some(h) = host {
        r = r.header("host", h);
    }
    r.body(Body::empty()).unwrap()
}

#[tokio::test]
async fn requests_must_name_this_server() {
    for host in [
        "127.0.0.1:8737",
        "localhost:8737",
        "LocalHost:8737",
        "[::1]:8737",
    ] {
        for path in ["/", "/api/info", "/api/pixel?col=0&row=0"] {
            let (status, _, _) = send(get_with_host(path, Some(host))).await;
            assert_eq!(status, StatusCode::OK, "{host} {path}");
        }
    }
    let refused = [
        Some("evil.example:8737"), // DNS rebinding: another name for 127.0.0.1
        Some("localhost.evil.example:8737"),
        Some("127.0.0.1:9999"), // another port
        Some("127.0.0.1"),      // no port, and the server is not on 80
        Some("192.168.1.5:8737"),
        Some("[::1"),
        Some(""),
        None,
    ];
    for host in refused {
        for path in ["/", "/api/info", "/api/pixel?col=0&row=0"] {
            let (status, _, body) = send(get_with_host(path, host)).await;
            assert_eq!(status, StatusCode::FORBIDDEN, "{host:?} {path}");
            let message = error_of(&body);
            assert!(
                message.contains("localhost, 127.0.0.1 or [::1]"),
                "{message}"
            );
        }
    }
    // A POST with a foreign Host is refused before its body is looked at.
    let mut request = post("/api/image", &frequency(5000.0));
    request
        .headers_mut()
        .insert("host", "evil.example:8737".parse().unwrap());
    request
        .headers_mut()
        .insert("origin", "http://evil.example:8737".parse().unwrap());
    let (status, _, _) = send(request).await;
    assert_eq!(status, StatusCode::FORBIDDEN);
}

#[test]
fn other_addresses_are_named_with_host() {
    let addr = |s: &str| s.parse::<SocketAddr>().unwrap();
    // The default: this machine only.
    let local = Access::listening_on(addr("127.0.0.1:8737"));
    assert!(local.allows_host("localhost:8737"));
    assert!(!local.allows_host("192.168.1.5:8737"));
    assert!(!local.allows_host("127.0.0.2:8737"));
    // Another loopback address, as printed in the URL.
    let other_loopback = Access::listening_on(addr("127.0.0.2:8737"));
    assert!(other_loopback.allows_host("127.0.0.2:8737"));
    assert!(other_loopback.allows_host("[::1]:8737"));
    // A given address: that address too, nothing else.
    let lan = Access::listening_on(addr("192.168.1.5:8737"));
    assert!(lan.allows_host("192.168.1.5:8737"));
    assert!(lan.allows_host("127.0.0.1:8737"));
    assert!(!lan.allows_host("192.168.1.6:8737"));
    assert!(!lan.allows_host("evil.example:8737"));
    let v6 = Access::listening_on(addr("[fe80::1]:8737"));
    assert!(v6.allows_host("[fe80::1]:8737"));
    assert!(!v6.allows_host("[fe80::2]:8737"));
    // Every interface: any address literal, but no other names (DNS rebinding).
    let all = Access::listening_on(addr("0.0.0.0:8737"));
    assert!(all.allows_host("192.168.1.5:8737"));
    assert!(all.allows_host("[fe80::1]:8737"));
    assert!(!all.allows_host("evil.example:8737"));
    assert!(!all.allows_host("192.168.1.5:8738"));
    // Port 80 may be left out, as browsers do.
    let web = Access::local(80);
    assert!(web.allows_host("localhost"));
    assert!(web.allows_host("localhost:80"));
}

#[tokio::test]
async fn posts_from_other_origins_are_refused() {
    let body = frequency(5000.0);
    for origin in [
        "http://evil.example",
        "http://evil.example:8737",
        "https://127.0.0.1:8737",
        "http://127.0.0.1:9999",
        "null",
    ] {
        for route in ["/api/image", "/api/png", "/api/keyframe"] {
            let mut request = post(route, &body);
            request
                .headers_mut()
                .insert("origin", origin.parse().unwrap());
            let (status, _, answer) = send(request).await;
            assert_eq!(status, StatusCode::FORBIDDEN, "{origin} {route}");
            assert!(error_of(&answer).contains(origin), "{origin}");
        }
    }
    // The server's own origin, or none (same-origin GETs and non-browser clients), pass.
    let (status, _, _) = send(post("/api/image", &body)).await;
    assert_eq!(status, StatusCode::OK);
    let mut request = post("/api/image", &body);
    request.headers_mut().remove("origin");
    let (status, _, _) = send(request).await;
    assert_eq!(status, StatusCode::OK);
    // A GET with a foreign origin (a cross-site fetch) is refused too.
    let mut request = get("/api/info");
    request
        .headers_mut()
        .insert("origin", "http://evil.example".parse().unwrap());
    let (status, _, _) = send(request).await;
    assert_eq!(status, StatusCode::FORBIDDEN);
}

#[tokio::test]
async fn posts_must_be_json() {
    let body = frequency(5000.0);
    // What a form or a no-preflight fetch from another page can send, and nothing at all.
    for content_type in [
        Some("text/plain"),
        Some("text/plain;charset=UTF-8"),
        Some("application/x-www-form-urlencoded"),
        Some("multipart/form-data; boundary=x"),
        Some("application/jsonx"),
        None,
    ] {
        for route in ["/api/image", "/api/png", "/api/keyframe"] {
            let mut request = post(route, &body);
            match content_type {
                Some(t) => {
                    request
                        .headers_mut()
                        .insert("content-type", t.parse().unwrap());
                }
                None => {
                    request.headers_mut().remove("content-type");
                }
            }
            let (status, _, answer) = send(request).await;
            assert_eq!(
                status,
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                "{content_type:?} {route}"
            );
            assert!(error_of(&answer).contains("application/json"));
        }
    }
    let mut request = post("/api/image", &body);
    request.headers_mut().insert(
        "content-type",
        "Application/JSON; charset=utf-8".parse().unwrap(),
    );
    let (status, _, _) = send(request).await;
    assert_eq!(status, StatusCode::OK);
}

#[tokio::test]
async fn bodies_are_capped() {
    // Valid settings padded with whitespace to just under the cap are read (more than axum's
    // default 2 MB limit), one byte more is refused with a JSON message.
    let settings = frequency(5000.0);
    let pad = |total: usize| format!("{settings}{}", " ".repeat(total - settings.len()));
    let (status, _, _) = send(post("/api/image", &pad(MAX_BODY_BYTES))).await;
    assert_eq!(status, StatusCode::OK);
    let over = pad(MAX_BODY_BYTES + 1);
    // Refused from the declared length and, without one, while reading.
    for declared in [true, false] {
        let mut request = post("/api/image", &over);
        if declared {
            request
                .headers_mut()
                .insert("content-length", over.len().to_string().parse().unwrap());
        }
        let (status, _, answer) = send(request).await;
        assert_eq!(
            status,
            StatusCode::PAYLOAD_TOO_LARGE,
            "declared: {declared}"
        );
        assert!(error_of(&answer).contains("4 MiB"), "declared: {declared}");
    }
}

#[tokio::test]
async fn info_names_the_file_without_its_folder() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("secret-project").join("view.exr");
    std::fs::create_dir(path.parent().unwrap()).unwrap();
    let state = Arc::new(ViewerState::new(&path, data()).unwrap());
    let (status, _, body) = send_to(state, get("/api/info")).await;
    assert_eq!(status, StatusCode::OK);
    let info: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(info["file"], "view.exr");
    let text = String::from_utf8(body).unwrap();
    assert!(!text.contains("secret-project"), "{text}");
    assert!(!text.contains(&dir.path().display().to_string()));
}
