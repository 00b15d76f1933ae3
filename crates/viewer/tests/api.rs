//! The viewer's HTTP interface without a browser: requests go straight into the router
//! (tower's `oneshot`), on a data file built in memory whose every pixel is known.

use std::path::Path;
use std::sync::Arc;

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use render::datafile::{DataFile, DataHeader, FORMAT_VERSION};
use render::record::{PixelRecord, RayStatus};
use shade::{ShadeSettings, ShaderKind, Shading};
use tower::ServiceExt;
use viewer::ViewerState;

const SCENE: &str = r#"
name = "api-test"
[spacetime]
metric = "godel"
a = 1.0
[observer]
time = 0.0
position = { r = 0.0, phi = 0.0, z = 0.0 }
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "panorama"
h_fov_deg = 220.0
v_fov_deg = 25.0
width = 8
height = 4
[trace]
method = "numeric"
max_past = 10.0
[[object]]
name = "ball"
radius = 0.2
texture = { kind = "uniform", color = [0.2, 0.4, 0.6] }
temperature = 5800.0
motion = { kind = "rest", position = { r = 1.0, phi = 0.0, z = 0.0 } }
"#;

const WIDTH: usize = 8;
const HEIGHT: usize = 4;

/// Left half: hits on the ball with u = col/8, v = row/4, g = 1 + col/10, t_emit = −(1 + row);
/// right half: nothing hit.
fn data() -> DataFile {
    let mut records = Vec::new();
    for row in 0..HEIGHT {
        for col in 0..WIDTH {
            records.push(if col < WIDTH / 2 {
                PixelRecord {
                    object: 0,
                    status: RayStatus::Hit,
                    u: col as f32 / 8.0,
                    v: row as f32 / 4.0,
                    g: 1.0 + col as f32 / 10.0,
                    t_emit: -(1.0 + row as f32),
                    cos_i: 1.0,
                    ..PixelRecord::MISS
                }
            } else {
                PixelRecord::MISS
            });
        }
    }
    DataFile {
        header: DataHeader {
            format_version: FORMAT_VERSION,
            scene_name: "api-test".into(),
            scene_text: SCENE.into(),
            camera: "panorama".into(),
            observer_time: 0.0,
            metric: "godel".into(),
            godel_a: 1.0,
            method: "numeric".into(),
            object_names: vec!["ball".into()],
        },
        width: WIDTH,
        height: HEIGHT,
        records,
        lights: Vec::new(),
    }
}

fn state() -> Arc<ViewerState> {
    Arc::new(ViewerState::new(Path::new("api-test.exr"), data()).unwrap())
}

/// Sends one request; returns status, headers and body.
async fn send(request: Request<Body>) -> (StatusCode, axum::http::HeaderMap, Vec<u8>) {
    let response = viewer::router(state()).oneshot(request).await.unwrap();
    let status = response.status();
    let headers = response.headers().clone();
    let body = response
        .into_body()
        .collect()
        .await
        .unwrap()
        .to_bytes()
        .to_vec();
    (status, headers, body)
}

fn post(path: &str, body: &str) -> Request<Body> {
    Request::post(path)
        .body(Body::from(body.to_string()))
        .unwrap()
}

fn get(path: &str) -> Request<Body> {
    Request::get(path).body(Body::empty()).unwrap()
}

/// The data file's default settings with only the frequency layer at `temperature`.
fn frequency_settings(temperature: f64) -> ShadeSettings {
    let mut settings = ShadeSettings::defaults_for(&data());
    settings.shaders = vec![ShaderKind::Frequency];
    settings.objects.get_mut("ball").unwrap().temperature = temperature;
    settings
}

fn frequency(temperature: f64) -> String {
    serde_json::to_string(&frequency_settings(temperature)).unwrap()
}

/// The picture the shade crate makes of `data()` for `settings`.
fn shaded(settings: &ShadeSettings) -> image::RgbImage {
    Shading::new(&data(), settings).unwrap().image(&data())
}

fn error_of(body: &[u8]) -> String {
    let v: serde_json::Value = serde_json::from_slice(body).expect("error answers are JSON");
    v["error"].as_str().unwrap().to_string()
}

#[tokio::test]
async fn page_is_served_from_the_binary() {
    for (path, kind, marker) in [
        ("/", "text/html", "<canvas id=\"image\""),
        ("/viewer.js", "text/javascript", "/api/image"),
        ("/viewer.css", "text/css", "#image"),
    ] {
        let (status, headers, body) = send(get(path)).await;
        assert_eq!(status, StatusCode::OK, "{path}");
        assert!(headers["content-type"].to_str().unwrap().starts_with(kind));
        assert!(String::from_utf8(body).unwrap().contains(marker), "{path}");
    }
}

#[tokio::test]
async fn info_describes_the_file_and_its_defaults() {
    let (status, _, body) = send(get("/api/info")).await;
    assert_eq!(status, StatusCode::OK);
    let info: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(info["width"], WIDTH);
    assert_eq!(info["height"], HEIGHT);
    assert_eq!(info["objects"], serde_json::json!(["ball"]));
    assert_eq!(info["defaults"]["objects"]["ball"]["temperature"], 5800.0);
    assert_eq!(info["defaults"]["shaders"], serde_json::json!(["texture"]));
}

#[tokio::test]
async fn image_is_the_shade_crates_picture_as_rgba() {
    let (status, headers, body) = send(post("/api/image", &frequency(3000.0))).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(headers["x-image-width"], "8");
    assert_eq!(headers["x-image-height"], "4");
    assert!(headers["server-timing"]
        .to_str()
        .unwrap()
        .contains("shade;dur="));
    let want = shaded(&frequency_settings(3000.0));
    assert_eq!(body.len(), WIDTH * HEIGHT * 4);
    for (rgba, rgb) in body.chunks_exact(4).zip(want.pixels()) {
        assert_eq!(&rgba[..3], &rgb.0);
        assert_eq!(rgba[3], 255);
    }
    // A different temperature is a different picture.
    let (_, _, other) = send(post("/api/image", &frequency(9000.0))).await;
    assert_ne!(body, other);
}

#[tokio::test]
async fn png_download_decodes_to_the_same_picture() {
    let (status, headers, body) = send(post("/api/png", &frequency(4000.0))).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(headers["content-type"], "image/png");
    assert!(headers["content-disposition"]
        .to_str()
        .unwrap()
        .contains("api-test.png"));
    let img = image::load_from_memory(&body).unwrap().to_rgb8();
    assert_eq!(
        img,
        shade::shade_frequency(&data(), &[4000.0], shade::Brightness::Normalized)
    );
}

#[tokio::test]
async fn keyframe_is_toml_with_the_settings() {
    let (status, _, body) = send(post("/api/keyframe?frame=12", &frequency(4321.0))).await;
    assert_eq!(status, StatusCode::OK);
    let text = std::str::from_utf8(&body).unwrap();
    let v: toml::Value = toml::from_str(text).unwrap();
    let frame = &v["keyframe"][0];
    assert_eq!(frame["frame"].as_integer(), Some(12), "{text}");
    let settings: ShadeSettings = frame["settings"].clone().try_into().unwrap();
    assert_eq!(settings, frequency_settings(4321.0));
}

#[tokio::test]
async fn pixel_record_comes_from_the_data_in_memory() {
    let (status, _, body) = send(get("/api/pixel?col=3&row=2")).await;
    assert_eq!(status, StatusCode::OK);
    let r: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(r["object_name"], "ball");
    assert_eq!(r["status"], "hit");
    assert_eq!(r["u"].as_f64().unwrap(), 3.0 / 8.0);
    assert_eq!(r["v"].as_f64().unwrap(), 2.0 / 4.0);
    assert!((r["g"].as_f64().unwrap() - 1.3).abs() < 1e-6);
    assert_eq!(r["t_emit"].as_f64().unwrap(), -3.0);
    assert_eq!(r["travel_time"].as_f64().unwrap(), 3.0);

    let (_, _, body) = send(get("/api/pixel?col=6&row=1")).await;
    let r: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(r["object"], -1);
    assert_eq!(r["object_name"], serde_json::Value::Null);
    assert_eq!(r["status"], "escaped");
}

/// `frequency_settings(5000)` as JSON with `change` applied.
fn altered(change: impl FnOnce(&mut serde_json::Value)) -> String {
    let mut v = serde_json::to_value(frequency_settings(5000.0)).unwrap();
    change(&mut v);
    v.to_string()
}

#[tokio::test]
async fn bad_settings_get_400_naming_the_field() {
    let cases = [
        ("{not json".to_string(), "settings"),
        (String::new(), "settings"),
        (
            altered(|v| v["shaders"] = serde_json::json!(["sepia"])),
            "sepia",
        ),
        (altered(|v| v["extra"] = 1.into()), "extra"),
        (altered(|v| v["exposure"] = "x".into()), "exposure"),
        (
            altered(|v| v["objects"]["ball"]["temperature"] = (-5.0).into()),
            "objects.ball.temperature",
        ),
        (
            altered(|v| v["objects"]["moon"] = v["objects"]["ball"].clone()),
            "moon",
        ),
        (altered(|v| v["shaders"] = serde_json::json!([])), "shaders"),
        (
            altered(|v| v["shaders"] = serde_json::json!(["light"])),
            "light",
        ),
        (
            altered(|v| {
                v["shaders"] = serde_json::json!(["texture"]);
                v["objects"]["ball"]["texture"] =
                    serde_json::json!({"kind": "image", "path": "/nonexistent/map.png"})
            }),
            "/nonexistent/map.png",
        ),
    ];
    for route in ["/api/image", "/api/png", "/api/keyframe"] {
        for (body, needle) in &cases {
            let (status, _, answer) = send(post(route, body)).await;
            assert_eq!(status, StatusCode::BAD_REQUEST, "{route} {body}");
            let message = error_of(&answer);
            assert!(message.contains(needle), "{needle:?} not in {message:?}");
        }
    }
}

#[tokio::test]
async fn bad_pixel_queries_get_400() {
    for (query, needle) in [
        ("col=8&row=0", "outside the 8×4 image"),
        ("col=0&row=4", "outside"),
        ("col=-1&row=0", "pixel"),
        ("col=x&row=0", "pixel"),
        ("row=0", "col"),
    ] {
        let (status, _, body) = send(get(&format!("/api/pixel?{query}"))).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{query}");
        let message = error_of(&body);
        assert!(message.contains(needle), "{needle:?} not in {message:?}");
    }
}

#[test]
fn a_data_file_whose_scene_texture_cannot_load_is_refused() {
    let mut d = data();
    d.header.scene_text = SCENE.replace(
        r#"{ kind = "uniform", color = [0.2, 0.4, 0.6] }"#,
        r#"{ kind = "image", path = "/nonexistent/texture.png" }"#,
    );
    let err = ViewerState::new(Path::new("x.exr"), d).err().unwrap();
    let message = err.to_string();
    assert!(message.contains("x.exr"), "{message}");
    assert!(message.contains("/nonexistent/texture.png"), "{message}");
}
