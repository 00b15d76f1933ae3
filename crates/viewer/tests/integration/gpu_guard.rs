//! The GPU and look routes keep every promise of the viewer's other routes: they answer only
//! requests that name this server and come from its own page (403), JSON bodies (415) within
//! the body cap (413); their work waits for the bound on concurrent work (503 beyond it);
//! a look picture has a bounded size; image textures come only from the data file's folder
//! (the embedded scene's through the viewer's texture source, a client's through the same
//! check as `/api/png`), with the same words whatever the reason.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::common::{error_of, write_png};
use crate::gpu_common::*;
use axum::http::StatusCode;
use shade::{ShadeSettings, ShaderKind, TextureChoice};
use viewer::{ViewerOptions, ViewerState, WorkLimit, MAX_BODY_BYTES};

/// A look request body: `settings` and a small pinhole view at rest.
fn look_body(settings: &ShadeSettings) -> String {
    serde_json::json!({
        "settings": settings,
        "view": {
            "camera": {"kind": "pinhole", "fov_deg": 60.0, "width": 8, "height": 6},
            "forward": [1.0, 0.0, 0.0],
            "up": [0.0, 0.0, 1.0],
            "velocity": {"speed": 0.0, "direction": [1.0, 0.0, 0.0]},
        },
    })
    .to_string()
}

fn texture_settings() -> ShadeSettings {
    let mut s = ShadeSettings::defaults_for(&data());
    s.shaders = vec![ShaderKind::Texture];
    s
}

/// Every GET route of the GPU page and the look routes.
const GETS: [&str; 6] = [
    "/api/gpu/channel/u",
    "/api/gpu/textures",
    "/api/gpu/image/earth",
    "/api/gpu/blackbody",
    "/api/gpu/blackbody/gt",
    "/api/view",
];
const POSTS: [&str; 2] = ["/api/look/image", "/api/look/png"];

#[tokio::test]
async fn gpu_and_look_routes_pass_the_guard() {
    let body = look_body(&texture_settings());
    for path in GETS {
        let (status, _) = send(data(), get(path)).await;
        assert_eq!(status, StatusCode::OK, "{path}");
        // A DNS-rebinding page reaches the server under its own name.
        let mut request = get(path);
        request
            .headers_mut()
            .insert("host", "evil.example".parse().unwrap());
        let (status, answer) = send(data(), request).await;
        assert_eq!(status, StatusCode::FORBIDDEN, "{path}");
        assert!(error_of(&answer).contains("evil.example"), "{path}");
    }
    for path in POSTS {
        let (status, _) = send(data(), post(path, body.clone())).await;
        assert_eq!(status, StatusCode::OK, "{path}");
        // Another site's page; a form post (it needs no CORS preflight), refused for not
        // being JSON.
        for (name, value, refused) in [
            ("origin", "http://evil.example", StatusCode::FORBIDDEN),
            (
                "content-type",
                "text/plain",
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
            ),
        ] {
            let mut request = post(path, body.clone());
            request.headers_mut().insert(name, value.parse().unwrap());
            let (status, _) = send(data(), request).await;
            assert_eq!(status, refused, "{path} {name}");
        }
        // One byte over the cap.
        let padded = format!("{body}{}", " ".repeat(MAX_BODY_BYTES + 1 - body.len()));
        let (status, answer) = send(data(), post(path, padded)).await;
        assert_eq!(status, StatusCode::PAYLOAD_TOO_LARGE, "{path}");
        assert!(error_of(&answer).contains("4 MiB"), "{path}");
    }
}

fn viewer_with(folder: &Path, work: WorkLimit) -> Arc<ViewerState> {
    let options = ViewerOptions {
        texture_folders: Vec::new(),
        work,
    };
    Arc::new(ViewerState::new_with(&folder.join("gpu-test.exr"), data(), options).unwrap())
}

#[tokio::test]
async fn gpu_and_look_work_waits_for_the_work_limit() {
    let dir = tempfile::tempdir().unwrap();
    let state = viewer_with(dir.path(), WorkLimit::new(1, 1));
    // One working and one waiting fill the limit.
    let tickets = (state.work().admit().unwrap(), state.work().admit().unwrap());
    let body = look_body(&texture_settings());
    let busy = [
        get("/api/gpu/channel/u"),
        get("/api/gpu/image/earth"),
        get("/api/view"),
        post("/api/look/image", body.clone()),
        post("/api/look/png", body.clone()),
    ];
    for request in busy {
        let path = request.uri().to_string();
        let (status, answer) = send_to(state.clone(), request).await;
        assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE, "{path}");
        assert!(error_of(&answer).contains("busy"), "{path}");
    }
    // Tables already in memory are no work: answered meanwhile.
    for path in ["/api/gpu/textures", "/api/gpu/blackbody", "/api/info"] {
        let (status, _) = send_to(state.clone(), get(path)).await;
        assert_eq!(status, StatusCode::OK, "{path}");
    }
    drop(tickets);
    let (status, _) = send_to(state.clone(), post("/api/look/image", body)).await;
    assert_eq!(status, StatusCode::OK);
    let (status, _) = send_to(state, get("/api/gpu/channel/u")).await;
    assert_eq!(status, StatusCode::OK);
}

#[tokio::test]
async fn look_pictures_have_a_bounded_size() {
    // The data file has 128 pixels: the bound is a 4K screen's 3840×2160.
    let mut body: serde_json::Value =
        serde_json::from_str(&look_body(&texture_settings())).unwrap();
    body["view"]["camera"] = serde_json::json!({"kind": "sphere", "width": 4000, "height": 2200});
    let (status, answer) = send(data(), post("/api/look/image", body.to_string())).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    let message = error_of(&answer);
    assert!(
        message.contains("view: camera") && message.contains("8800000 pixels"),
        "{message}"
    );
    assert!(message.contains("godel look"), "{message}");
    // Samples count: 1930×1080 is within the bound, with 4 samples per pixel it is not; and
    // samples are a square number.
    body["view"]["camera"] = serde_json::json!({"kind": "sphere", "width": 1930, "height": 1080});
    body["view"]["samples"] = serde_json::json!(4);
    let (status, answer) = send(data(), post("/api/look/png", body.to_string())).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(
        error_of(&answer).contains("8337600 pixels"),
        "{}",
        error_of(&answer)
    );
    body["view"]["camera"] = serde_json::json!({"kind": "sphere", "width": 16, "height": 8});
    body["view"]["samples"] = serde_json::json!(3);
    let (status, answer) = send(data(), post("/api/look/png", body.to_string())).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(
        error_of(&answer).starts_with("view: camera.samples: must be a square number"),
        "{}",
        error_of(&answer)
    );
    body["view"]["samples"] = serde_json::json!(1);
    // The scene's own limits hold too (a side beyond 20000).
    body["view"]["camera"] = serde_json::json!({"kind": "sphere", "width": 40000, "height": 1});
    let (status, answer) = send(data(), post("/api/look/png", body.to_string())).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(error_of(&answer).contains("camera"));
}

#[tokio::test]
async fn look_settings_read_textures_only_from_the_allowed_folders() {
    let dir = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    write_png(&dir.path().join("map.png"), 200);
    let secret = elsewhere.path().join("secret.png");
    write_png(&secret, 200);
    let state = viewer_with(dir.path(), WorkLimit::new(1, 4));
    let with_image = |path: &Path| {
        let mut s = texture_settings();
        s.objects.get_mut("ball").unwrap().texture = TextureChoice::Image {
            path: path.to_path_buf(),
        };
        s
    };
    let (status, _) = send_to(
        state.clone(),
        post(
            "/api/look/image",
            look_body(&with_image(Path::new("map.png"))),
        ),
    )
    .await;
    assert_eq!(status, StatusCode::OK);
    for path in [
        secret.clone(),
        elsewhere.path().join("missing.png"),
        PathBuf::from("/etc/passwd"),
    ] {
        let body = look_body(&with_image(&path));
        let (status, answer) = send_to(state.clone(), post("/api/look/png", body)).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{path:?}");
        testkit::assert_texture_refused(&error_of(&answer), &path);
    }
}

#[tokio::test]
async fn the_scenes_image_textures_come_from_the_data_files_folder() {
    // The globe's texture is an image file named relative to the data file's folder: the
    // GPU page gets exactly that image (the current directory plays no part).
    let dir = tempfile::tempdir().unwrap();
    write_png(&dir.path().join("globe.png"), 200);
    let mut d = data();
    d.header.scene_text = scene_text().replace(
        r#"texture = { kind = "image", builtin = "earth" }"#,
        r#"texture = { kind = "image", path = "globe.png" }"#,
    );
    assert_ne!(d.header.scene_text, scene_text());
    let state = Arc::new(ViewerState::new(&dir.path().join("gpu-test.exr"), d.clone()).unwrap());
    let (status, body) = send_to(state.clone(), get("/api/gpu/textures")).await;
    assert_eq!(status, StatusCode::OK);
    let globe = &json(&body)["objects"][1];
    assert_eq!(
        *globe,
        serde_json::json!({"kind": "image", "image": "scene-1", "width": 4, "height": 2})
    );
    let (status, body) = send_to(state, get("/api/gpu/image/scene-1")).await;
    assert_eq!(status, StatusCode::OK);
    let pixels = &body[viewer::wire::HEADER_LEN..];
    let want: Vec<u8> = (0..2u32)
        .flat_map(|y| (0..4u32).flat_map(move |x| [200, (x * 60) as u8, (y * 120) as u8]))
        .collect();
    assert_eq!(pixels, &want[..]);

    // The same file served from another folder no longer finds its image: refused at loading.
    let other = tempfile::tempdir().unwrap();
    let refused = ViewerState::new(&other.path().join("gpu-test.exr"), d);
    assert!(refused.is_err());
}
