//! The scene files shipped in `scenes/`: every good one parses, every one in `scenes/bad/`
//! is rejected with an error naming the right field and line.
//!
//! Bad scenes declare what they expect: a line `# expect field: PATH` (empty for TOML
//! syntax errors, which have no field of their own) and the marker `# <- error here` on
//! the line the error must point at.

use scene::{Camera, Motion, Scene, SceneError, Shape, TextureSpec};
use std::path::Path;

use testkit::{bad_scene_expectation as expectation, scenes_dir, toml_files};

#[test]
fn every_good_scene_parses() {
    let files = toml_files(&scenes_dir());
    assert!(files.len() >= 7, "{files:?}");
    for f in files {
        let s = Scene::from_file(&f).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.source_path.as_deref(), Some(f.as_path()));
        assert!(!s.objects.is_empty(), "{}", f.display());
    }
}

#[test]
fn builtin_is_the_reference_file() {
    let file = Scene::from_file(scenes_dir().join("reference.toml")).unwrap();
    let builtin = Scene::builtin();
    assert_eq!(builtin.source_text, file.source_text);
    assert_eq!(builtin.objects, file.objects);
    assert_eq!(
        builtin.camera,
        Camera::Panorama {
            h_fov_deg: 220.0,
            v_fov_deg: 25.0,
            width: 880,
            height: 100
        }
    );
    assert!(matches!(builtin.objects[0].motion, Motion::Geodesic { .. }));
}

#[test]
fn bench_static_is_as_specified() {
    let s = Scene::from_file(scenes_dir().join("bench-static.toml")).unwrap();
    assert_eq!(
        s.camera,
        Camera::Panorama {
            h_fov_deg: 220.0,
            v_fov_deg: 25.0,
            width: 440,
            height: 50
        }
    );
    assert_eq!(s.observer.forward, [0.0, 1.0, 0.0]);
    assert_eq!(s.observer.right(), [1.0, 0.0, 0.0]);
    assert_eq!(s.trace.max_past, 10.0);
    assert_eq!(s.objects[0].shape, Shape::Sphere { radius: 0.2 });
    let Motion::Rest { position } = s.objects[0].motion else {
        panic!()
    };
    assert_eq!((position.x, position.y, position.z), (1.0, 0.0, 0.0));
}

#[test]
fn floor_grid_has_a_coordinate_plane() {
    let s = Scene::from_file(scenes_dir().join("floor-grid.toml")).unwrap();
    assert_eq!(
        s.objects[0].shape,
        Shape::Plane {
            height: -0.5,
            extent: Some(3.0)
        }
    );
    assert_eq!(
        s.objects[0].texture,
        TextureSpec::Checker { rows: 12, cols: 12 }
    );
    assert_eq!(s.lights.len(), 1);
}

fn check_bad(path: &Path) -> SceneError {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(
        text.starts_with("# BAD: "),
        "{}: first line must say what is wrong",
        path.display()
    );
    let (field, line) = expectation(&text);
    let err = match Scene::from_file(path) {
        Ok(_) => panic!("{} was accepted", path.display()),
        Err(e) => e,
    };
    let shown = err.to_string();
    assert_eq!(err.file, path.display().to_string());
    assert_eq!(err.line(), Some(line), "{shown}");
    assert!(err.column().is_some_and(|c| c >= 1), "{shown}");
    if !field.is_empty() {
        assert_eq!(err.field, field, "{shown}");
        assert!(
            shown.contains(&format!(":{line}:")) && shown.contains(&field),
            "{shown}"
        );
    }
    err
}

#[test]
fn every_bad_scene_is_rejected_at_the_right_place() {
    let files = toml_files(&scenes_dir().join("bad"));
    assert!(files.len() >= 10);
    for f in files {
        let e = check_bad(&f);
        eprintln!("{e}");
    }
}

#[test]
fn error_display_matches_the_design() {
    let e = check_bad(&scenes_dir().join("bad/negative-radius.toml"));
    let file = scenes_dir()
        .join("bad/negative-radius.toml")
        .display()
        .to_string();
    assert_eq!(
        e.to_string(),
        format!("{file}:27:10: object[0].radius: must be positive, got -1")
    );
}

#[test]
fn unreadable_file_is_an_error_not_a_panic() {
    let e = Scene::from_file(scenes_dir().join("no-such-scene.toml")).unwrap_err();
    assert!(e.location.is_none());
    assert!(e.to_string().contains("no-such-scene.toml"));
}

#[test]
fn image_paths_resolve_against_the_scene_directory() {
    let dir = std::env::temp_dir().join(format!("scene-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("tex.png"),
        b"not really a png; only existence is checked",
    )
    .unwrap();
    let text = std::fs::read_to_string(scenes_dir().join("static-sphere.toml"))
        .unwrap()
        .replace(
            "{ kind = \"gradient\" }",
            "{ kind = \"image\", path = \"tex.png\" }",
        );
    let path = dir.join("s.toml");
    std::fs::write(&path, &text).unwrap();
    let s = Scene::from_file(&path).unwrap();
    assert_eq!(
        s.objects[0].texture,
        TextureSpec::Image(scene::ImageSource::File(dir.join("tex.png")))
    );
    // The same text read from elsewhere does not find the image.
    let e = Scene::from_str(&text, "elsewhere/s.toml").unwrap_err();
    assert_eq!(e.field, "object[0].texture.path");
    std::fs::remove_dir_all(&dir).ok();
}
