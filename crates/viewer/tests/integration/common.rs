//! Helpers shared by the viewer's HTTP tests: a data file built in memory whose every pixel is
//! known, and requests sent straight into the router (tower's `oneshot`) carrying what the
//! page sends: `Host: 127.0.0.1:PORT`, and JSON bodies as `application/json`; small PNG
//! textures.

use std::path::Path;
use std::sync::Arc;

use axum::body::Body;
use axum::http::{HeaderMap, Request, StatusCode};
use datafile::record::PixelRecord;
use datafile::DataFile;
use http_body_util::BodyExt;
use shade::{ShadeSettings, ShaderKind};
use tower::ServiceExt;
use viewer::{Access, ViewerState};

/// The port the tests' server pretends to listen on.
pub const PORT: u16 = 8737;
/// The Host header a browser on this machine sends.
pub const HOST: &str = "127.0.0.1:8737";

pub const WIDTH: usize = 8;
pub const HEIGHT: usize = 4;

/// The scene the data file claims to come from: one ball with a uniform texture.
pub fn scene() -> String {
    testkit::ball_ahead(
        "api-test",
        &testkit::panorama(220.0, 25.0, WIDTH, HEIGHT),
        "ball",
        r#"{ kind = "uniform", color = [0.2, 0.4, 0.6] }"#,
    )
}

/// Left half: hits on the ball with u = col/8, v = row/4, g = 1 + col/10, t_emit = −(1 + row);
/// right half: nothing hit.
pub fn data() -> DataFile {
    let mut records = Vec::new();
    for row in 0..HEIGHT {
        for col in 0..WIDTH {
            records.push(if col < WIDTH / 2 {
                testkit::hit(
                    0,
                    col as f32 / 8.0,
                    row as f32 / 4.0,
                    1.0 + col as f32 / 10.0,
                    -(1.0 + row as f32),
                    1.0,
                )
            } else {
                PixelRecord::MISS
            });
        }
    }
    DataFile {
        header: testkit::godel_header("api-test", &scene(), "panorama", &["ball"]),
        width: WIDTH,
        height: HEIGHT,
        records,
        lights: Vec::new(),
        polarization: false,
    }
}

pub fn state() -> Arc<ViewerState> {
    Arc::new(ViewerState::new(Path::new("api-test.exr"), data()).unwrap())
}

/// Sends one request to the router of `state`; returns status, headers and body.
pub async fn send_to(
    state: Arc<ViewerState>,
    request: Request<Body>,
) -> (StatusCode, HeaderMap, Vec<u8>) {
    let response = viewer::router(state, Access::local(PORT))
        .oneshot(request)
        .await
        .unwrap();
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

/// Sends one request to the router of [`state`].
pub async fn send(request: Request<Body>) -> (StatusCode, HeaderMap, Vec<u8>) {
    send_to(state(), request).await
}

/// A POST as the page sends it: JSON body, same-origin.
pub fn post(path: &str, body: &str) -> Request<Body> {
    Request::post(path)
        .header("host", HOST)
        .header("origin", format!("http://{HOST}"))
        .header("content-type", "application/json")
        .body(Body::from(body.to_string()))
        .unwrap()
}

/// A GET as the page sends it.
pub fn get(path: &str) -> Request<Body> {
    Request::get(path)
        .header("host", HOST)
        .body(Body::empty())
        .unwrap()
}

/// The message of an `{"error": "..."}` answer.
pub fn error_of(body: &[u8]) -> String {
    let v: serde_json::Value = serde_json::from_slice(body).expect("error answers are JSON");
    v["error"].as_str().unwrap().to_string()
}

/// The data file's default settings with only the frequency layer at `temperature`.
pub fn frequency_settings(temperature: f64) -> ShadeSettings {
    let mut settings = ShadeSettings::defaults_for(&data());
    settings.shaders = vec![ShaderKind::Frequency];
    settings.objects.get_mut("ball").unwrap().temperature = temperature;
    settings
}

/// [`frequency_settings`] as the JSON the page sends.
pub fn frequency(temperature: f64) -> String {
    serde_json::to_string(&frequency_settings(temperature)).unwrap()
}

/// Writes a 4×2 PNG at `path` with distinct pixels, its red channel `seed`.
pub fn write_png(path: &Path, seed: u8) {
    image::RgbImage::from_fn(4, 2, |x, y| {
        image::Rgb([seed, (x * 60) as u8, (y * 120) as u8])
    })
    .save(path)
    .unwrap();
}

/// A view at the origin at rest, looking along x with z up, through an 8×4 camera of `kind`
/// with the fields of view `fov` (`fov_deg`, or `h_fov_deg` and `v_fov_deg` for a panorama).
pub fn view_at_origin(kind: &str, fov: [Option<f64>; 3]) -> viewer::view::View {
    use viewer::view::{CameraView, Position, Velocity, View};
    View {
        time: 0.0,
        position: Position {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
        velocity: Velocity {
            speed: 0.0,
            direction: [1.0, 0.0, 0.0],
        },
        forward: [1.0, 0.0, 0.0],
        up: [0.0, 0.0, 1.0],
        camera: CameraView {
            kind: kind.into(),
            fov_deg: fov[0],
            h_fov_deg: fov[1],
            v_fov_deg: fov[2],
            width: 8,
            height: 4,
            samples: 1,
        },
    }
}
