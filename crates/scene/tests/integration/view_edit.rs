//! `Scene::read_view`, `replace_view` and `replace_samples`: writing another view (or samples
//! per pixel) into scene text keeps the rest of the scene (objects, comments), reads back
//! exactly, and reading a view checks only the observer and the camera.

use scene::{replace_samples, replace_view, Camera, Scene};
use spacetime::LocalVelocity;

/// A scene with comments, an observer at t = 1.5 off the axis and a sphere camera.
fn text() -> String {
    format!(
        "# a comment that must survive\nname = \"v\"\n{}[camera]\n\
         kind = \"sphere\"   # the source\nwidth = 64\nheight = 32\n[[object]]\nname = \"ball\"\n\
         radius = 0.2\ntexture = {{ kind = \"image\", path = \"does-not-exist.png\" }}\n\
         motion = {{ kind = \"rest\", position = {{ r = 1.0, phi = 0.0, z = 0.0 }} }}\n",
        testkit::observer_at(1.5, 0.5, 0.25)
    )
}

fn cameras() -> Vec<Camera> {
    vec![
        Camera::Pinhole {
            fov_deg: 47.5,
            width: 33,
            height: 21,
        },
        Camera::Panorama {
            h_fov_deg: 220.0,
            v_fov_deg: 25.0,
            width: 880,
            height: 100,
        },
        Camera::Sphere {
            width: 64,
            height: 32,
        },
        Camera::Fisheye {
            fov_deg: 180.0,
            size: 99,
        },
    ]
}

#[test]
fn a_replaced_view_reads_back_exactly_and_keeps_the_rest() {
    // Texture files need not exist to read a view (a data file's embedded scene).
    let (observer, camera) = Scene::read_view(&text(), "t.toml").expect("view");
    assert_eq!(
        camera,
        Camera::Sphere {
            width: 64,
            height: 32
        }
    );
    assert_eq!(observer.event.t, 1.5);
    let third = 1.0 / 3f64.sqrt();
    for camera in cameras() {
        let velocity = LocalVelocity::new(0.123456789, [0.3, -0.4, 0.5]).unwrap();
        let (forward, up) = ([third, -third, third], [0.5f64.sqrt(), 0.5f64.sqrt(), 0.0]);
        let text = replace_view(&text(), "t.toml", &camera, velocity, forward, up).expect("edit");
        let (o, c) = Scene::read_view(&text, "t.toml").expect("valid");
        assert_eq!(c, camera);
        assert_eq!(o.velocity.speed, velocity.speed);
        assert_eq!(o.event, observer.event, "time and position kept");
        for (a, b) in [
            (o.forward, forward),
            (o.up, up),
            (o.velocity.direction, velocity.direction),
        ] {
            assert!((0..3).all(|i| (a[i] - b[i]).abs() < 1e-15), "{a:?} {b:?}");
        }
        assert!(text.starts_with("# a comment that must survive\nname = \"v\""));
        assert!(text.contains("path = \"does-not-exist.png\""));
        assert!(!text.contains("# the source"), "the old camera is gone");
    }
}

#[test]
fn samples_are_written_and_removed_keeping_the_rest() {
    // The ball's texture must exist for a full read: a checker instead.
    let base = text().replace(
        "{ kind = \"image\", path = \"does-not-exist.png\" }",
        "{ kind = \"checker\", rows = 4, cols = 8 }",
    );
    let sixteen = replace_samples(&base, "t.toml", 16).expect("edit");
    assert!(sixteen.starts_with("# a comment that must survive\n"));
    let scene = Scene::from_str(&sixteen, "t.toml").expect("valid");
    assert_eq!((scene.samples, scene.supersample()), (16, 4));
    assert_eq!(scene.camera.width(), 64);
    let one = replace_samples(&sixteen, "t.toml", 1).expect("edit");
    assert!(!one.contains("samples"), "{one}");
    assert_eq!(Scene::from_str(&one, "t.toml").expect("valid").samples, 1);
    let bad = replace_samples("[camera\n", "t.toml", 4).unwrap_err();
    assert_eq!(bad.file, "t.toml");
    assert!(bad.location.is_some());
}

#[test]
fn views_are_written_into_inline_and_missing_tables() {
    let camera = cameras()[0];
    let edit = |text: &str, file: &str| {
        let rest = LocalVelocity::REST;
        replace_view(text, file, &camera, rest, [0.0, 1.0, 0.0], [0.0, 0.0, 1.0])
    };
    let inline = "name = \"i\"\nobserver = { time = 2.0 }\ncamera = { kind = \"sphere\", width = 8, height = 4 }\n";
    let missing = "name = \"m\"\n[camera]\nkind = \"sphere\"\nwidth = 8\nheight = 4\n";
    for text in [inline, missing] {
        let out = edit(text, "t.toml").expect("edit");
        let (o, c) = Scene::read_view(&out, "t.toml").expect("valid");
        assert_eq!((c, o.forward), (camera, [0.0, 1.0, 0.0]), "{out}");
    }
    let e = edit("observer = 3\n", "t.toml").unwrap_err();
    assert_eq!(e.field, "observer");
    let e = edit("name = \n", "bad.toml").unwrap_err();
    assert!(e.to_string().starts_with("bad.toml:1:"), "{e}");
}

#[test]
fn reading_a_view_checks_observer_and_camera_with_located_errors() {
    let bad_fov = text().replace(
        "kind = \"sphere\"   # the source",
        "kind = \"pinhole\"\nfov_deg = 200",
    );
    let e = Scene::read_view(&bad_fov, "t.toml").unwrap_err();
    assert_eq!(
        (e.field.as_str(), e.line()),
        ("camera.fov_deg", Some(10)),
        "{e}"
    );
    let tilted = text().replace("up = [0, 0, 1]", "up = [0.1, 0, 1]");
    let e = Scene::read_view(&tilted, "t.toml").unwrap_err();
    assert_eq!(e.field, "observer.up");
    assert!(e.message.contains("orthogonal"), "{e}");
}

#[test]
fn a_cameras_json_form_is_its_scene_file_table() {
    for camera in cameras() {
        let text = replace_view(
            &text(),
            "t.toml",
            &camera,
            LocalVelocity::REST,
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
        )
        .expect("edit");
        let table: toml::Table = toml::from_str(&text).expect("toml");
        let from_file = serde_json::to_value(&table["camera"]).expect("json");
        let json = serde_json::to_value(camera).expect("json");
        assert_eq!(json, from_file, "{text}");
        assert_eq!(
            serde_json::from_value::<Camera>(json).expect("reads back"),
            camera
        );
    }
    let fisheye = |w: u32, h: u32| {
        serde_json::from_str::<Camera>(&format!(
            r#"{{"kind": "fisheye", "fov_deg": 180, "width": {w}, "height": {h}}}"#
        ))
    };
    assert_eq!(
        fisheye(64, 64).expect("square"),
        Camera::Fisheye {
            fov_deg: 180.0,
            size: 64
        }
    );
    let e = fisheye(64, 48).unwrap_err().to_string();
    assert!(e.contains("camera.height") && e.contains("square"), "{e}");
    let e =
        serde_json::from_str::<Camera>(r#"{"kind": "sphere", "width": 8, "height": 4, "size": 8}"#)
            .unwrap_err()
            .to_string();
    assert!(e.contains("size"), "an unknown field is refused: {e}");
}
