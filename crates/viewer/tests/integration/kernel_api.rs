//! The routes that let the page trace on the GPU (`viewer::kernel_routes`): the kernel's source
//! as the `gpu` crate embeds it, and the input of the data file's embedded scene as the `gpu`
//! crate packs it, with the slot layout and the defines for the page's render targets; a data
//! file whose scene does not trace its own grid, and bad queries, are refused saying why.

use std::path::Path;
use std::sync::Arc;

use axum::http::StatusCode;
use gpu::input::OBJECT_TEXELS;
use gpu::KernelInput;
use scene::Scene;
use viewer::ViewerState;

use crate::common;

fn json(body: &[u8]) -> serde_json::Value {
    serde_json::from_slice(body).expect("a JSON answer")
}

/// A data file of `common::data()`'s records whose embedded scene is `scene`, with one zero
/// light plane per light of that scene.
fn state_with(scene: &str, lights: usize) -> Arc<ViewerState> {
    let mut data = common::data();
    data.header.scene_text = scene.to_string();
    data.lights = vec![vec![0.0; common::WIDTH * common::HEIGHT]; lights];
    Arc::new(ViewerState::new(Path::new("kernel-test.exr"), data).unwrap())
}

#[tokio::test]
async fn the_kernel_is_the_gpu_crates_source_as_text() {
    let (status, headers, body) = common::send(common::get("/api/gpu/kernel")).await;
    assert_eq!(status, StatusCode::OK);
    assert!(headers["content-type"]
        .to_str()
        .unwrap()
        .starts_with("text/plain"));
    assert_eq!(String::from_utf8(body).unwrap(), gpu::KERNEL);
}

#[tokio::test]
async fn the_input_is_the_embedded_scene_packed_by_the_gpu_crate() {
    let scene = Scene::from_str(&common::scene(), "api-test.toml").unwrap();
    // As text, as the route sends it (f32 in its shortest form).
    let want = json(
        serde_json::to_string(&KernelInput::new(&scene))
            .unwrap()
            .as_bytes(),
    );
    let (status, _, body) = common::send(common::get("/api/gpu/input?draw_buffers=8")).await;
    assert_eq!(status, StatusCode::OK);
    let got = json(&body);
    for field in [
        "uniforms",
        "table",
        "table_rows",
        "objects",
        "light_count",
        "supersample",
    ] {
        assert!(
            got[field] == want[field],
            "{field}: {} against {}",
            got[field],
            want[field]
        );
    }
    assert_eq!(
        got["uniforms"]["size"],
        serde_json::json!([common::WIDTH, common::HEIGHT])
    );
    // No light: five fixed slots (the fifth: view_z and the polarization).
    assert_eq!(got["slots"], 5);
    assert_eq!(got["light_channels"], serde_json::json!([]));
    // Eight render targets asked for, eight used: one draw a round writes the record and the
    // three slots of the sample's progress (docs/physics.md, "Rounds"), no finishing draw.
    assert_eq!(got["draw_buffers"], 8);
    assert_eq!(
        got["plan"],
        serde_json::json!({"rounds": {"start": 0, "end": 8}, "finish": null, "layers": 8})
    );
    assert_eq!(got["defines"], KernelInput::new(&scene).defines(8));
    assert!(got["defines"]
        .as_str()
        .unwrap()
        .contains("#define DRAW_BUFFERS 8\n"));
    // Without the page's count: four, what every WebGL2 has; with two, two.
    for (query, buffers) in [("", 4), ("?draw_buffers=2", 2), ("?draw_buffers=16", 8)] {
        let (status, _, body) = common::send(common::get(&format!("/api/gpu/input{query}"))).await;
        assert_eq!(status, StatusCode::OK, "{query}");
        let got = json(&body);
        assert_eq!(got["draw_buffers"], buffers, "{query}");
        let defines = got["defines"].as_str().unwrap();
        assert!(
            defines.contains(&format!("#define DRAW_BUFFERS {buffers}\n")),
            "{defines}"
        );
    }
}

#[tokio::test]
async fn light_channels_follow_the_records_slots() {
    // Five lights: light k is channel k counted from slot 5's first component.
    let lights: String = (0..5)
        .map(|k| format!("[[light]]\nposition = {{ x = 1.0, y = {k}.0, z = 0.0 }}\npower = 2.0\n"))
        .collect();
    let state = state_with(&format!("{}{lights}", common::scene()), 5);
    let (status, _, body) = common::send_to(state, common::get("/api/gpu/input")).await;
    assert_eq!(status, StatusCode::OK);
    let got = json(&body);
    assert_eq!(got["light_count"], 5);
    assert_eq!(got["uniforms"]["lights"], 5);
    assert_eq!(got["slots"], 7);
    assert_eq!(
        got["light_channels"],
        serde_json::json!([[5, 0], [5, 1], [5, 2], [5, 3], [6, 0]])
    );
    // Each light's position and power in the table, after the object's texels.
    let table = got["table"].as_array().unwrap();
    for k in 0..5 {
        let texel: Vec<f64> = (0..4)
            .map(|c| table[(OBJECT_TEXELS + k) * 4 + c].as_f64().unwrap())
            .collect();
        assert_eq!(texel, [1.0, k as f64, 0.0, 2.0], "light {k}");
    }
}

#[tokio::test]
async fn a_file_whose_scene_traces_another_grid_is_refused_saying_so() {
    // The scene says 16×4 pixels, the file holds 8×4.
    let scene = testkit::ball_ahead(
        "api-test",
        &testkit::panorama(220.0, 25.0, 16, common::HEIGHT),
        "ball",
        r#"{ kind = "uniform", color = [0.2, 0.4, 0.6] }"#,
    );
    let state = state_with(&scene, 0);
    let (status, _, body) = common::send_to(state, common::get("/api/gpu/input")).await;
    assert_eq!(status, StatusCode::NOT_FOUND);
    let message = common::error_of(&body);
    assert!(
        message.contains("cannot trace") && message.contains("16×4") && message.contains("8×4"),
        "{message}"
    );
}

#[tokio::test]
async fn bad_queries_are_refused_naming_the_field() {
    for (query, needle) in [
        ("draw_buffers=0", "draw_buffers"),
        ("draw_buffers=many", "draw_buffers"),
        ("buffers=4", "buffers"),
    ] {
        let (status, _, body) = common::send(common::get(&format!("/api/gpu/input?{query}"))).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{query}");
        let message = common::error_of(&body);
        assert!(message.contains(needle), "{query}: {message}");
    }
}
