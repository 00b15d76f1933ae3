//! One eye of a stereo pair (`NAME.left.exr`, issue 37): the viewer loads the other eye's file
//! beside it, `/api/info` says which eye and whether the other is there, and
//! `POST /api/stereo/png` answers both eyes shaded with the page's settings in the pair's
//! layout or the one asked for: the picture `shade::stereo::compose` makes of the two eyes
//! each shaded alone. A mono file, or an eye without its partner, gets 404.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use axum::http::StatusCode;
use datafile::DataFile;
use image::RgbImage;
use scene::Layout;
use shade::{ShadeSettings, Shading};
use viewer::ViewerState;

use crate::common::{self, get, post, send_to, HEIGHT, WIDTH};

/// `[camera] stereo` of a side-by-side pair 0.2 apart, marked as `eye`.
fn mark(eye: &str) -> String {
    format!("stereo = {{ separation = 0.2, layout = \"side-by-side\", eye = \"{eye}\" }}\n")
}

/// `common::data()` as the `eye` of a stereo pair: its scene marked so, and for the right eye
/// other frequency ratios (so that the two eyes' pictures differ).
pub fn eye_data(eye: &str) -> DataFile {
    let mut data = common::data();
    let camera = format!(
        "{}{}",
        testkit::panorama(220.0, 25.0, WIDTH, HEIGHT),
        mark(eye)
    );
    data.header.scene_text = testkit::ball_ahead(
        "api-test",
        &camera,
        "ball",
        r#"{ kind = "uniform", color = [0.2, 0.4, 0.6] }"#,
    );
    if eye == "right" {
        for r in &mut data.records {
            r.g *= 1.5;
            r.u = 1.0 - r.u;
        }
    }
    data
}

/// Writes both eyes' files (`s.left.exr`, `s.right.exr`) into `dir`; the left one's path.
pub fn pair(dir: &Path) -> PathBuf {
    eye_data("right").write(&dir.join("s.right.exr")).unwrap();
    let left = dir.join("s.left.exr");
    eye_data("left").write(&left).unwrap();
    left
}

fn load(path: &Path) -> Arc<ViewerState> {
    Arc::new(ViewerState::load(path).unwrap())
}

/// The data file's picture shaded alone with `settings` by the `shade` crate.
fn alone(data: &DataFile, settings: &ShadeSettings) -> RgbImage {
    Shading::new(data, settings).unwrap().image(data)
}

async fn info(state: &Arc<ViewerState>) -> serde_json::Value {
    let (status, _, body) = send_to(state.clone(), get("/api/info")).await;
    assert_eq!(status, StatusCode::OK);
    serde_json::from_slice(&body).unwrap()
}

/// `POST /api/stereo/png` with `query` and `settings`: status and body.
async fn stereo_png(
    state: &Arc<ViewerState>,
    query: &str,
    settings: &ShadeSettings,
) -> (StatusCode, Vec<u8>) {
    let body = serde_json::to_string(settings).unwrap();
    let (status, _, bytes) = send_to(
        state.clone(),
        post(&format!("/api/stereo/png{query}"), &body),
    )
    .await;
    (status, bytes)
}

#[tokio::test]
async fn the_picture_is_both_eyes_shaded_alone_in_the_layout() {
    let tmp = tempfile::tempdir().unwrap();
    let left = pair(tmp.path());
    let settings = common::frequency_settings(4500.0);
    let (l, r) = (
        alone(&eye_data("left"), &settings),
        alone(&eye_data("right"), &settings),
    );
    assert_ne!(l, r, "the eyes differ");
    for state in [load(&left), load(&tmp.path().join("s.right.exr"))] {
        for (query, layout, size) in [
            ("", Layout::SideBySide, (2 * WIDTH, HEIGHT)),
            (
                "?layout=side-by-side",
                Layout::SideBySide,
                (2 * WIDTH, HEIGHT),
            ),
            ("?layout=over-under", Layout::OverUnder, (WIDTH, 2 * HEIGHT)),
            ("?layout=anaglyph", Layout::Anaglyph, (WIDTH, HEIGHT)),
        ] {
            let (status, body) = stereo_png(&state, query, &settings).await;
            assert_eq!(
                status,
                StatusCode::OK,
                "{query}: {}",
                String::from_utf8_lossy(&body)
            );
            let got = image::load_from_memory(&body).unwrap().to_rgb8();
            let size = (size.0 as u32, size.1 as u32);
            assert_eq!(got.dimensions(), size, "{query}");
            assert_eq!(got, shade::stereo::compose(layout, &l, &r), "{query}");
        }
    }
}

#[tokio::test]
async fn info_says_which_eye_and_whether_the_other_is_there() {
    let tmp = tempfile::tempdir().unwrap();
    let left = pair(tmp.path());
    let stereo = &info(&load(&left)).await["stereo"];
    assert_eq!(
        *stereo,
        serde_json::json!({"eye": "left", "layout": "side-by-side", "partner": true})
    );
    let right = info(&load(&tmp.path().join("s.right.exr"))).await;
    assert_eq!(right["stereo"]["eye"], "right");
    std::fs::remove_file(&left).unwrap();
    let alone = load(&tmp.path().join("s.right.exr"));
    assert_eq!(info(&alone).await["stereo"]["partner"], false);
    let (status, body) = stereo_png(&alone, "", &common::frequency_settings(4500.0)).await;
    assert_eq!(status, StatusCode::NOT_FOUND);
    assert!(
        common::error_of(&body).contains("other eye"),
        "{}",
        common::error_of(&body)
    );
    // The one eye is still served.
    let (status, _, _) = send_to(alone, post("/api/png", &common::frequency(4500.0))).await;
    assert_eq!(status, StatusCode::OK);
}

#[tokio::test]
async fn a_mono_file_has_no_stereo_picture() {
    let state = common::state();
    assert!(info(&state).await["stereo"].is_null());
    let (status, body) = stereo_png(&state, "", &common::frequency_settings(4500.0)).await;
    assert_eq!(status, StatusCode::NOT_FOUND);
    assert!(common::error_of(&body).contains("not one eye of a stereo pair"));
}

#[tokio::test]
async fn a_bad_layout_or_settings_are_named() {
    let tmp = tempfile::tempdir().unwrap();
    let state = load(&pair(tmp.path()));
    let settings = common::frequency_settings(4500.0);
    let (status, body) = stereo_png(&state, "?layout=crossed", &settings).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    let why = common::error_of(&body);
    assert!(
        why.starts_with("stereo: ") && why.contains("crossed"),
        "{why}"
    );
    let mut bad = settings.clone();
    bad.objects.get_mut("ball").unwrap().temperature = -1.0;
    let (status, body) = stereo_png(&state, "", &bad).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(
        common::error_of(&body).contains("temperature"),
        "{}",
        common::error_of(&body)
    );
}

#[test]
fn a_file_beside_that_is_not_the_other_eye_is_refused_naming_it() {
    let tmp = tempfile::tempdir().unwrap();
    let left = pair(tmp.path());
    eye_data("left")
        .write(&tmp.path().join("s.right.exr"))
        .unwrap();
    let why = ViewerState::load(&left).err().unwrap().to_string();
    assert!(
        why.contains("s.right.exr") && why.contains("not the other eye"),
        "{why}"
    );
}
