//! The viewer's HTTP interface without a browser: requests go straight into the router
//! (tower's `oneshot`), on a data file built in memory whose every pixel is known.

use crate::common;

use std::path::Path;

use crate::common::{
    data, error_of, frequency, frequency_settings, get, post, scene, send, HEIGHT, WIDTH,
};
use axum::http::StatusCode;
use shade::{ShadeSettings, Shading};
use viewer::ViewerState;
/// The picture the shade crate makes of `data()` for `settings`.
fn shaded(settings: &ShadeSettings) -> image::RgbImage {
    Shading::new(&data(), settings).unwrap().image(&data())
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
    assert_eq!(info["supersample"], 1);
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

#[tokio::test]
async fn pixel_record_says_where_the_pixel_looks() {
    // The test scene's camera: a 220°×25° panorama on 8×4 pixels, so pixel centres look at
    // azimuth 220·((col + ½)/8 − ½) and elevation 25·(½ − (row + ½)/4) (the closed form).
    for (col, row) in [(0, 0), (3, 2), (7, 3), (5, 1)] {
        let (status, _, body) = send(get(&format!("/api/pixel?col={col}&row={row}"))).await;
        assert_eq!(status, StatusCode::OK);
        let r: serde_json::Value = serde_json::from_slice(&body).unwrap();
        let az = 220.0 * ((col as f64 + 0.5) / 8.0 - 0.5);
        let el = 25.0 * (0.5 - (row as f64 + 0.5) / 4.0);
        assert!(
            (r["azimuth_deg"].as_f64().unwrap() - az).abs() < 1e-9,
            "{r}"
        );
        assert!(
            (r["elevation_deg"].as_f64().unwrap() - el).abs() < 1e-9,
            "{r}"
        );
    }
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
    d.header.scene_text = scene().replace(
        r#"{ kind = "uniform", color = [0.2, 0.4, 0.6] }"#,
        r#"{ kind = "image", path = "/nonexistent/texture.png" }"#,
    );
    let err = ViewerState::new(Path::new("x.exr"), d).err().unwrap();
    let message = err.to_string();
    assert!(message.contains("x.exr"), "{message}");
    assert!(message.contains("/nonexistent/texture.png"), "{message}");
}

#[tokio::test]
async fn a_sampled_file_is_shown_at_its_picture_size_and_hovers_the_centre_sample() {
    // The 8×4 records as 2×2 samples per pixel: a 4×2 picture.
    let mut sampled = data();
    sampled.header.supersample = 2;
    let state =
        std::sync::Arc::new(ViewerState::new(Path::new("aa.exr"), sampled.clone()).unwrap());
    let (_, _, body) = common::send_to(state.clone(), get("/api/info")).await;
    let info: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(
        (info["width"].clone(), info["height"].clone()),
        (4.into(), 2.into())
    );
    // The page learns the factor: the GPU channels are the 8×4 sample grid.
    assert_eq!(info["supersample"], 2);
    let (status, _, body) = common::send_to(state.clone(), get("/api/gpu/channel/u")).await;
    assert_eq!(status, StatusCode::OK);
    let size = |at: usize| u32::from_le_bytes(body[at..at + 4].try_into().unwrap());
    assert_eq!((size(4), size(8)), (8, 4));
    let (status, headers, body) =
        common::send_to(state.clone(), post("/api/image", &frequency(3000.0))).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(
        (&headers["x-image-width"], &headers["x-image-height"]),
        (&"4".parse().unwrap(), &"2".parse().unwrap())
    );
    // The shade crate's picture: each sample shaded, then the 2×2 blocks averaged.
    let want = Shading::new(&sampled, &frequency_settings(3000.0))
        .unwrap()
        .image(&sampled);
    assert_eq!(want.dimensions(), (4, 2));
    for (rgba, rgb) in body.chunks_exact(4).zip(want.pixels()) {
        assert_eq!(&rgba[..3], &rgb.0);
    }
    // Picture pixel (1, 0) is samples (2..4, 0..2); the hover shows sample (3, 1).
    let (_, _, body) = common::send_to(state.clone(), get("/api/pixel?col=1&row=0")).await;
    let r: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(r["u"].as_f64().unwrap(), 3.0 / 8.0);
    assert_eq!(r["v"].as_f64().unwrap(), 1.0 / 4.0);
    let (status, _, _) = common::send_to(state, get("/api/pixel?col=4&row=0")).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
}

#[tokio::test]
async fn overlay_is_the_shade_crates_layer_as_png_or_204() {
    // Nothing to draw (no marks, squares or legend): 204, no body.
    let none = altered(|v| {
        v["shaders"] = serde_json::json!(["texture"]);
    });
    let (status, _, body) = send(post("/api/overlay", &none)).await;
    assert_eq!(status, StatusCode::NO_CONTENT);
    assert!(body.is_empty());
    // Reference squares' labels: an RGBA PNG of the picture's size, equal to the layer.
    let (status, headers, body) = send(post("/api/overlay", &frequency(3000.0))).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(headers["content-type"], "image/png");
    let png = image::load_from_memory(&body).unwrap();
    assert_eq!(png.color(), image::ColorType::Rgba8);
    let want = Shading::new(&data(), &frequency_settings(3000.0))
        .unwrap()
        .overlay(WIDTH as u32, HEIGHT as u32)
        .unwrap();
    assert!(png.to_rgba8() == want);
    // Bad settings: 400 naming the field, as for the picture.
    let bad = altered(|v| v["ev"] = serde_json::json!(99.0));
    let (status, _, body) = send(post("/api/overlay", &bad)).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(error_of(&body).contains("ev"), "{}", error_of(&body));
}
