//! Shared by the GPU and look route tests: a 16×8 full-sphere data file built in memory whose
//! every pixel is known, and requests as the page sends them.

use std::path::Path;
use std::sync::Arc;

use axum::body::Body;
use axum::http::{Request, StatusCode};
use datafile::{DataFile, DataHeader, PixelRecord, RayStatus, FORMAT_VERSION};
use http_body_util::BodyExt;
use scene::Camera;
use tower::ServiceExt;
use viewer::{Access, ViewerState};

/// A full sphere (16×8) of a static observer in flat spacetime: a uniform ball and the earth.
pub fn scene_text() -> String {
    format!(
        "name = \"gpu-test\"\n[spacetime]\nmetric = \"minkowski\"\n{}{}{}{}{}",
        testkit::OBSERVER_AT_ORIGIN,
        testkit::sphere(W, H),
        testkit::trace("numeric", 10.0),
        testkit::textured_ball(
            "ball",
            0.2,
            "{ kind = \"uniform\", color = [0.2, 0.4, 0.6] }",
            5800.0,
            "{ x = 0.0, y = -1.0, z = 0.0 }"
        ),
        testkit::textured_ball(
            "globe",
            0.2,
            "{ kind = \"image\", builtin = \"earth\" }",
            4000.0,
            "{ x = 1.0, y = 0.0, z = 0.0 }"
        ),
    )
}

pub const W: usize = 16;
pub const H: usize = 8;

/// Columns 11, 12 of rows 3, 4 show the ball (azimuth 360°((col + ½)/16 − ½) = 78.75° and
/// 101.25° to the right: around right = forward × up = −y), columns 7, 8 the globe (∓11.25°:
/// around +x), where the scene puts them; one pixel of each other status; the rest escaped. (`godel look` refuses object ids the file does not name; the
/// channel test adds one.)
pub fn data() -> DataFile {
    let mut records = vec![PixelRecord::MISS; W * H];
    for row in 3..5 {
        for (col, object) in [(11, 0), (12, 0), (7, 1), (8, 1)] {
            let k = row * W + col;
            records[k] = PixelRecord {
                object,
                status: RayStatus::Hit,
                u: 0.1 + 0.037 * k as f32,
                v: 0.9 - 0.011 * k as f32,
                g: 0.5 + 0.013 * k as f32,
                t_emit: -1.0 - 0.1 * k as f32,
                cos_i: [0.3, 1.7, -0.2, f32::NAN][k % 4],
                ..PixelRecord::MISS
            };
        }
    }
    records[0] = PixelRecord::miss(RayStatus::Failed);
    records[1] = PixelRecord::miss(RayStatus::StepBudget);
    records[2] = PixelRecord::miss(RayStatus::NotTraced);
    let light = (0..W * H).map(|i| i as f32 * 0.25 - 3.0).collect();
    DataFile {
        header: DataHeader {
            format_version: FORMAT_VERSION,
            scene_name: "gpu-test".into(),
            scene_text: scene_text(),
            camera: Camera::Sphere {
                width: W as u32,
                height: H as u32,
            }
            .describe(),
            observer_time: 0.0,
            metric: "minkowski".into(),
            godel_a: 1.0,
            member: None,
            method: "numeric".into(),
            object_names: vec!["ball".into(), "globe".into()],
            supersample: 1,
        },
        width: W,
        height: H,
        records,
        lights: vec![light],
        polarization: false,
    }
}

/// The same pixels seen by a 60° pinhole camera: not a full sphere.
pub fn flat() -> DataFile {
    let mut flat = data();
    flat.header.scene_text =
        scene_text().replace("kind = \"sphere\"", "kind = \"pinhole\"\nfov_deg = 60.0");
    flat.header.camera = Camera::Pinhole {
        fov_deg: 60.0,
        width: W as u32,
        height: H as u32,
    }
    .describe();
    flat
}

/// The server's answer to `request` on `state`, which answers Host `127.0.0.1` (port 80).
pub async fn send_to(state: Arc<ViewerState>, request: Request<Body>) -> (StatusCode, Vec<u8>) {
    let router = viewer::router(state, Access::local(80));
    let response = router.oneshot(request).await.unwrap();
    let status = response.status();
    let body = response.into_body().collect().await.unwrap().to_bytes();
    (status, body.to_vec())
}

/// The viewer of `data` with the default options.
pub fn state_of(data: DataFile) -> Arc<ViewerState> {
    Arc::new(ViewerState::new(Path::new("gpu-test.exr"), data).unwrap())
}

/// The answer to `request` by the viewer of `data`.
pub async fn send(data: DataFile, request: Request<Body>) -> (StatusCode, Vec<u8>) {
    send_to(state_of(data), request).await
}

pub fn get(path: &str) -> Request<Body> {
    Request::get(path)
        .header("host", "127.0.0.1")
        .body(Body::empty())
        .unwrap()
}

pub fn post(path: &str, body: String) -> Request<Body> {
    Request::post(path)
        .header("host", "127.0.0.1")
        .header("content-type", "application/json")
        .body(Body::from(body))
        .unwrap()
}

pub fn json(body: &[u8]) -> serde_json::Value {
    serde_json::from_slice(body).expect("a JSON answer")
}
