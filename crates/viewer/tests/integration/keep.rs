//! The routes of explore's *Render exactly* and *Record* (`viewer::keep_routes`) with a keeper
//! whose renders wait at a gate: bad views and recordings are refused with 400 naming the
//! field, one render runs at a time (429 for a second), a render can be cancelled and is
//! cancelled when the server's routes are dropped, only the newest render's files are served
//! (410 for an older one), and a recording's frames are its seconds at 24 frames per second.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use tower::ServiceExt;
use viewer::keep::{ExactJob, Keeper, Recording, Rendered, MAX_KEYFRAMES};
use viewer::view::View;
use viewer::{Access, WorkLimit};

use crate::common;

/// A keeper whose renders wait (at most ten seconds) until the gate opens or they are
/// cancelled; views wider than 100 pixels are refused as a scene would refuse them.
#[derive(Clone, Default)]
struct Fake {
    gate: Arc<AtomicBool>,
    /// Whether each render begun saw its cancel flag.
    cancelled: Arc<Mutex<Vec<bool>>>,
}

fn own() -> View {
    common::view_at_origin("pinhole", [Some(60.0), None, None])
}

impl Keeper for Fake {
    fn name(&self) -> String {
        "fake scene".into()
    }
    fn own_view(&self) -> View {
        own()
    }
    fn check(&self, view: &View) -> Result<(), String> {
        if view.camera.width > 100 {
            return Err(format!(
                "view.camera.width: at most 100, got {}",
                view.camera.width
            ));
        }
        Ok(())
    }
    fn render(&self, view: &View, job: &ExactJob) -> Result<Option<Rendered>, String> {
        let until = Instant::now() + Duration::from_secs(10);
        while !self.gate.load(Ordering::SeqCst) && !job.cancelled() && Instant::now() < until {
            std::thread::sleep(Duration::from_millis(5));
        }
        self.cancelled.lock().unwrap().push(job.cancelled());
        if job.cancelled() {
            return Ok(None);
        }
        Ok(Some(Rendered {
            name: "fake scene".into(),
            png: format!("png of t = {}", view.time).into_bytes(),
            exr: b"exr".to_vec(),
            summary: "done".into(),
        }))
    }
    fn script(&self, recording: &Recording, frames: &[u32]) -> Result<String, String> {
        Ok(format!(
            "{} keyframes at {frames:?}",
            recording.keyframes.len()
        ))
    }
}

fn app(fake: &Fake) -> axum::Router {
    viewer::keep_routes::router(
        fake.clone(),
        WorkLimit::new(1, 1),
        Access::local(common::PORT),
    )
}

async fn send(app: &axum::Router, request: Request<Body>) -> (StatusCode, Vec<u8>, String) {
    let response = app.clone().oneshot(request).await.unwrap();
    let status = response.status();
    let disposition = response
        .headers()
        .get("content-disposition")
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let body = response.into_body().collect().await.unwrap().to_bytes();
    (status, body.to_vec(), disposition)
}

fn view_json(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let mut v = serde_json::to_value(own()).unwrap();
    edit(&mut v);
    v.to_string()
}

/// Asks for the newest render's state until it is not `rendering` (ten seconds at most).
async fn settled(app: &axum::Router) -> serde_json::Value {
    let until = Instant::now() + Duration::from_secs(10);
    loop {
        let (_, body, _) = send(app, common::get("/api/explore/exact")).await;
        let job: serde_json::Value = serde_json::from_slice(&body).unwrap();
        if job["job"]["state"] != "rendering" || Instant::now() > until {
            return job["job"].clone();
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

#[tokio::test]
async fn bad_views_are_refused_naming_the_field() {
    let fake = Fake::default();
    let app = app(&fake);
    let cases: [(String, &str); 6] = [
        (
            view_json(|v| v["zoom"] = 2.into()),
            "view.zoom: unknown field",
        ),
        (
            view_json(|v| v["time"] = serde_json::Value::Null),
            "view.time: invalid type: null",
        ),
        (
            view_json(|v| v["camera"]["width"] = (-1).into()),
            "view.camera.width: invalid value",
        ),
        (
            view_json(|v| v["camera"]["width"] = 1000.into()),
            "view.camera.width: at most 100",
        ),
        (
            view_json(|v| {
                v["position"]
                    .as_object_mut()
                    .unwrap()
                    .remove("y")
                    .map(drop)
                    .unwrap()
            }),
            "view.position: missing field `y`",
        ),
        (
            view_json(|v| v["up"] = serde_json::json!([0, 0])),
            "view.up: invalid length 2",
        ),
    ];
    for (body, want) in cases {
        let (status, answer, _) = send(&app, common::post("/api/explore/exact", &body)).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{body}");
        let error = common::error_of(&answer);
        assert!(error.starts_with(want), "{error} (wanted {want})");
    }
    // A number JSON cannot hold as a finite f64.
    let body = view_json(|v| v["time"] = 0.into()).replace("\"time\":0", "\"time\":1e999");
    let (status, answer, _) = send(&app, common::post("/api/explore/exact", &body)).await;
    assert_eq!(status, StatusCode::BAD_REQUEST, "{body}");
    assert!(common::error_of(&answer).starts_with("view.time"));
    assert!(
        fake.cancelled.lock().unwrap().is_empty(),
        "nothing was rendered"
    );
}

#[tokio::test]
async fn one_render_at_a_time_cancelled_or_kept_and_only_the_newest_served() {
    let fake = Fake::default();
    let app = app(&fake);
    let body = view_json(|_| {});
    let (status, answer, _) = send(&app, common::post("/api/explore/exact", &body)).await;
    assert_eq!(status, StatusCode::ACCEPTED);
    assert_eq!(
        serde_json::from_slice::<serde_json::Value>(&answer).unwrap()["job"],
        1
    );
    let (status, answer, _) = send(&app, common::post("/api/explore/exact", &body)).await;
    assert_eq!(status, StatusCode::TOO_MANY_REQUESTS);
    assert!(common::error_of(&answer).contains("under way"));
    let (status, _, _) = send(&app, common::post("/api/explore/exact/cancel", "{}")).await;
    assert_eq!(status, StatusCode::OK);
    let job = settled(&app).await;
    assert_eq!(job["state"], "cancelled", "{job}");
    assert_eq!(job["png"], serde_json::Value::Null, "{job}");
    let (status, _, _) = send(&app, common::get("/api/explore/exact/1/png")).await;
    assert_eq!(status, StatusCode::NOT_FOUND);

    fake.gate.store(true, Ordering::SeqCst);
    let later = view_json(|v| v["time"] = 2.5.into());
    let (status, _, _) = send(&app, common::post("/api/explore/exact", &later)).await;
    assert_eq!(status, StatusCode::ACCEPTED);
    let job = settled(&app).await;
    assert_eq!(
        (&job["state"], &job["id"]),
        (&"done".into(), &2.into()),
        "{job}"
    );
    assert_eq!(job["png"], "/api/explore/exact/2/png");
    let (status, png, disposition) = send(&app, common::get("/api/explore/exact/2/png")).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(png, b"png of t = 2.5");
    assert_eq!(disposition, "attachment; filename=\"fake_scene.png\"");
    let (status, exr, _) = send(&app, common::get("/api/explore/exact/2/exr")).await;
    assert_eq!(
        (status, exr.as_slice()),
        (StatusCode::OK, b"exr".as_slice())
    );
    for (path, want) in [
        ("/api/explore/exact/1/png", StatusCode::GONE),
        ("/api/explore/exact/2/tiff", StatusCode::NOT_FOUND),
    ] {
        let (status, _, _) = send(&app, common::get(path)).await;
        assert_eq!(status, want, "{path}");
    }
    assert_eq!(*fake.cancelled.lock().unwrap(), [true, false]);
}

#[tokio::test]
async fn the_server_stopping_cancels_the_render_under_way() {
    let fake = Fake::default();
    let routes = app(&fake);
    let (status, _, _) = send(
        &routes,
        common::post("/api/explore/exact", &view_json(|_| {})),
    )
    .await;
    assert_eq!(status, StatusCode::ACCEPTED);
    drop(routes);
    let until = Instant::now() + Duration::from_secs(5);
    while fake.cancelled.lock().unwrap().is_empty() && Instant::now() < until {
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!(*fake.cancelled.lock().unwrap(), [true]);
}

fn recording(seconds: &[serde_json::Value]) -> String {
    let keyframes: Vec<serde_json::Value> = seconds
        .iter()
        .map(|s| serde_json::json!({ "seconds": s, "view": own() }))
        .collect();
    serde_json::json!({ "keyframes": keyframes }).to_string()
}

#[tokio::test]
async fn recordings_are_bounded_and_their_keyframes_on_increasing_frames() {
    let fake = Fake::default();
    let app = app(&fake);
    let (status, script, disposition) = send(
        &app,
        common::post(
            "/api/explore/record",
            &recording(&[0.into(), 0.25.into(), 1.0.into()]),
        ),
    )
    .await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(
        String::from_utf8(script).unwrap(),
        "3 keyframes at [0, 6, 24]"
    );
    assert_eq!(
        disposition,
        "attachment; filename=\"fake_scene-flight.toml\""
    );
    let many: Vec<serde_json::Value> = (0..=MAX_KEYFRAMES).map(|i| (i as f64).into()).collect();
    let cases = [
        (recording(&[]), "recording.keyframes: a recording has 1 to"),
        (
            recording(&many),
            "recording.keyframes: a recording has 1 to",
        ),
        (
            recording(&[0.into(), 0.5.into(), 0.51.into()]),
            "recording.keyframes[2].seconds: 0.51 s is frame 12, not after keyframe 1's frame 12",
        ),
        (
            recording(&[(-1).into()]),
            "recording.keyframes[0].seconds: must be from 0",
        ),
        (
            recording(&[serde_json::Value::Null]),
            "recording.keyframes[0].seconds: invalid type",
        ),
        (
            recording(&[0.into()]).replace("\"kind\"", "\"kinds\""),
            "recording.keyframes[0].view.camera.kinds: unknown field",
        ),
    ];
    for (body, want) in cases {
        let (status, answer, _) = send(&app, common::post("/api/explore/record", &body)).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{want}");
        let error = common::error_of(&answer);
        assert!(error.starts_with(want), "{error} (wanted {want})");
    }
}

/// Issue 36: a body cut short was named `view.?` or `recording.keyframes[0].?`, 1e308 seconds
/// printed with 309 digits, and a render's number that is not one got axum's plain-text
/// answer. Now the name stops at the last field the request wrote, numbers are short, and
/// every refusal is JSON naming the route.
#[tokio::test]
async fn refusals_name_what_the_request_wrote_in_short() {
    let fake = Fake::default();
    let app = app(&fake);
    let cases = [
        (
            "/api/explore/exact",
            r#"{"time": 1, "position": {"x": 1"#.to_string(),
            "view.position: EOF while parsing an object",
        ),
        (
            "/api/explore/record",
            r#"{"keyframes": [{"seconds": 0, "vi"#.to_string(),
            "recording.keyframes[0]: EOF while parsing a string",
        ),
        (
            "/api/explore/record",
            r#"{"keyf"#.to_string(),
            "recording: EOF while parsing a string",
        ),
        (
            "/api/explore/record",
            recording(&[1e308.into()]),
            "recording.keyframes[0].seconds: must be from 0 to 3600, got 1e308",
        ),
    ];
    for (url, body, want) in cases {
        let (status, answer, _) = send(&app, common::post(url, &body)).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{want}");
        let error = common::error_of(&answer);
        assert!(error.starts_with(want), "{error} (wanted {want})");
    }
    for (url, want) in [
        (
            "/api/explore/exact/abc/png",
            "exact: `abc` is not the number of a render",
        ),
        ("/api/explore/exact/1/%FF", "exact: Invalid URL"),
    ] {
        let (status, answer, _) = send(&app, common::get(url)).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{url}");
        let error = common::error_of(&answer);
        assert!(error.starts_with(want), "{url}: {error}");
    }
}
