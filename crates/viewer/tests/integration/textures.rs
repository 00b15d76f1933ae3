//! Image textures a client names come only from the data file's folder or a folder the user
//! named at start (`--textures`): anything else — another image on the machine, a way out by
//! `..` or a symbolic link, a FIFO, a device — is refused with one message that tells nothing
//! about the file, and without blocking a worker. The embedded scene's textures obey the same
//! folders.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use crate::common::{data, error_of, post, scene, send_to, write_png};
use axum::http::StatusCode;
use shade::{ShadeSettings, ShaderKind, Shading, TextureChoice};
use viewer::{ViewerOptions, ViewerState, WorkLimit};

/// The texture layer with the ball's texture the image at `path` (as the client names it).
fn image_settings(path: &Path) -> ShadeSettings {
    let mut s = ShadeSettings::defaults_for(&data());
    s.shaders = vec![ShaderKind::Texture];
    s.objects.get_mut("ball").unwrap().texture = TextureChoice::Image {
        path: path.to_path_buf(),
    };
    s
}

/// The viewer of `data()` stored as `folder/view.exr`, with `extra` texture folders and one
/// shading worker (so that one blocked job would block every picture).
fn viewer_in(folder: &Path, extra: Vec<PathBuf>) -> Arc<ViewerState> {
    let options = ViewerOptions {
        texture_folders: extra,
        work: WorkLimit::new(1, 4),
    };
    Arc::new(ViewerState::new_with(&folder.join("view.exr"), data(), options).unwrap())
}

/// POSTs `settings` to `/api/png`; a deadline against hanging forever, not a speed check.
async fn png(state: &Arc<ViewerState>, settings: &ShadeSettings) -> (StatusCode, Vec<u8>) {
    let body = serde_json::to_string(settings).unwrap();
    let (status, _, answer) = tokio::time::timeout(
        Duration::from_secs(60),
        send_to(state.clone(), post("/api/png", &body)),
    )
    .await
    .expect("the request was answered");
    (status, answer)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn only_the_data_files_folder_and_named_folders_serve_textures() {
    let data_dir = tempfile::tempdir().unwrap();
    let named = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    write_png(&data_dir.path().join("map.png"), 200);
    write_png(&named.path().join("named.png"), 120);
    let secret = elsewhere.path().join("secret.png");
    write_png(&secret, 40);
    let state = viewer_in(data_dir.path(), Vec::new());

    // Inside the data file's folder, by name: the shade crate's picture of that image.
    let (status, body) = png(&state, &image_settings(Path::new("map.png"))).await;
    assert_eq!(status, StatusCode::OK);
    let want = Shading::new(&data(), &image_settings(&data_dir.path().join("map.png")))
        .unwrap()
        .image(&data());
    assert_eq!(image::load_from_memory(&body).unwrap().to_rgb8(), want);

    // Anything else is refused with the same words, whether or not a file is there.
    std::os::unix::fs::symlink(&secret, data_dir.path().join("link.png")).unwrap();
    let fifo = data_dir.path().join("pipe.png");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let escape = PathBuf::from("..")
        .join(elsewhere.path().file_name().unwrap())
        .join("secret.png");
    let refused = [
        secret.clone(),
        elsewhere.path().join("missing.png"),
        escape,
        PathBuf::from("link.png"),
        PathBuf::from("pipe.png"),
        PathBuf::from("/dev/zero"),
        PathBuf::from("/etc/passwd"),
        named.path().join("named.png"), // not named at start for this viewer
    ];
    for path in &refused {
        let (status, body) = png(&state, &image_settings(path)).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{path:?}");
        testkit::assert_texture_refused(&error_of(&body), path);
    }
    // The FIFOs blocked nothing: the one worker still shades.
    let (status, _) = png(&state, &image_settings(Path::new("map.png"))).await;
    assert_eq!(status, StatusCode::OK);

    // A folder named at start serves its images, by full path or by name.
    let state = viewer_in(data_dir.path(), vec![named.path().to_path_buf()]);
    for path in [named.path().join("named.png"), PathBuf::from("named.png")] {
        let (status, _) = png(&state, &image_settings(&path)).await;
        assert_eq!(status, StatusCode::OK, "{path:?}");
    }
    let (status, _) = png(&state, &image_settings(&secret)).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
}

#[test]
fn the_embedded_scenes_textures_come_from_the_same_folders() {
    let data_dir = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    write_png(&data_dir.path().join("scene-map.png"), 90);
    write_png(&elsewhere.path().join("far.png"), 30);
    let with_texture = |path: &str| {
        let mut d = data();
        d.header.scene_text = scene().replace(
            r#"{ kind = "uniform", color = [0.2, 0.4, 0.6] }"#,
            &format!(r#"{{ kind = "image", path = "{path}" }}"#),
        );
        d
    };
    let exr = data_dir.path().join("view.exr");
    // Beside the data file: served, whatever the current directory.
    assert!(ViewerState::new(&exr, with_texture("scene-map.png")).is_ok());
    // Elsewhere: refused at start, with a hint at --textures...
    let far = elsewhere.path().join("far.png");
    let e = ViewerState::new(&exr, with_texture(far.to_str().unwrap()))
        .err()
        .expect("refused");
    assert!(e.to_string().contains("--textures DIR"), "{e}");
    // ...which admits it.
    let options = ViewerOptions {
        texture_folders: vec![elsewhere.path().to_path_buf()],
        ..ViewerOptions::default()
    };
    assert!(ViewerState::new_with(&exr, with_texture(far.to_str().unwrap()), options).is_ok());
    // A texture folder that is not one is an error naming it.
    let options = ViewerOptions {
        texture_folders: vec![elsewhere.path().join("nope")],
        ..ViewerOptions::default()
    };
    let e = ViewerState::new_with(&exr, data(), options)
        .err()
        .expect("refused");
    assert!(matches!(e, viewer::LoadError::TextureFolder(_)), "{e:?}");
    assert!(e.to_string().contains("nope"), "{e}");
}
