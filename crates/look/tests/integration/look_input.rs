//! `look` on input it must refuse (sources that are not a static observer's full
//! sphere, inconsistent files, views with bad values, each naming what is wrong) and the
//! header of what it writes (the new camera and view, the rest of the scene kept). Small
//! synthetic data files: nothing is traced.

use datafile::{DataFile, PixelRecord, RayStatus};
use look::{look, LookError, LookView, LOOK_COMMENT};
use scene::{Camera, Scene};
use spacetime::LocalVelocity;

/// A ball at rest at r = 1 seen from the axis over a small full sphere.
fn small_scene() -> String {
    testkit::sphere_scene(
        "small",
        8,
        4,
        &format!(
            "{}{}",
            testkit::trace("exact", 10.0),
            testkit::ball_at_rest("ball", 0.3, 1.0, 0.0)
        ),
    )
}

fn scene(text: &str) -> Scene {
    Scene::from_str(text, "t.toml").expect("scene")
}

/// A small synthetic sphere data file with the given scene text.
fn synthetic(text: &str, width: usize, height: usize) -> DataFile {
    let s = scene(text);
    let mut d = DataFile {
        header: render::driver::header(&s),
        width,
        height,
        records: vec![PixelRecord::MISS; width * height],
        lights: vec![],
        polarization: false,
    };
    for (i, r) in d.records.iter_mut().enumerate() {
        r.t_emit = -(i as f32);
    }
    d
}

fn with_camera(camera: &str, observer_extra: &str) -> String {
    small_scene()
        .replace("kind = \"sphere\"\nwidth = 8\nheight = 4", camera)
        .replace(
            "up = [0, 0, 1]",
            &format!("up = [0, 0, 1]\n{observer_extra}"),
        )
}

#[test]
fn sources_that_are_not_a_static_full_sphere_are_refused() {
    let pinhole_view = Camera::Pinhole {
        fov_deg: 60.0,
        width: 8,
        height: 8,
    };
    let v = LookView::new(
        pinhole_view,
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        LocalVelocity::REST,
    )
    .expect("view");
    let pinhole = with_camera(
        "kind = \"pinhole\"\nfov_deg = 60\nwidth = 8\nheight = 4",
        "",
    );
    let e = look(&synthetic(&pinhole, 8, 4), &v).unwrap_err();
    assert!(matches!(e, LookError::NotSphere(_)), "{e}");
    assert!(
        e.to_string().contains("pinhole 60°, 8×4") && e.to_string().contains("kind = \"sphere\""),
        "{e}"
    );
    let half = with_camera(
        "kind = \"panorama\"\nh_fov_deg = 360\nv_fov_deg = 90\nwidth = 8\nheight = 4",
        "",
    );
    assert!(matches!(
        look(&synthetic(&half, 8, 4), &v),
        Err(LookError::NotSphere(_))
    ));
    // A 360°×180° panorama is a full sphere.
    let full = with_camera(
        "kind = \"panorama\"\nh_fov_deg = 360\nv_fov_deg = 180\nwidth = 8\nheight = 4",
        "",
    );
    assert!(look(&synthetic(&full, 8, 4), &v).is_ok());
    let moving = with_camera(
        "kind = \"sphere\"\nwidth = 8\nheight = 4",
        "velocity = { speed = 0.3, direction = [0, 1, 0] }",
    );
    let e = look(&synthetic(&moving, 8, 4), &v).unwrap_err();
    assert!(matches!(e, LookError::MovingSource(s) if s == 0.3), "{e}");
    assert!(
        e.to_string().contains("0.3 c") && e.to_string().contains("static"),
        "{e}"
    );
    // Header and embedded scene must agree.
    let sphere = with_camera("kind = \"sphere\"\nwidth = 8\nheight = 4", "");
    let mut wrong = synthetic(&sphere, 8, 4);
    wrong.header.camera = "pinhole 60°, 8×4".into();
    assert!(matches!(
        look(&wrong, &v),
        Err(LookError::Inconsistent { .. })
    ));
    let wrong_size = synthetic(&sphere, 16, 4);
    assert!(matches!(
        look(&wrong_size, &v),
        Err(LookError::Inconsistent { .. })
    ));
    // An anti-aliased sphere (2×2 rays per pixel: 16×8 records) is refused, saying why.
    let mut sampled = synthetic(&sphere, 16, 8);
    sampled.header.supersample = 2;
    let e = look(&sampled, &v).unwrap_err();
    assert!(matches!(e, LookError::Supersampled(2)), "{e}");
    assert!(e.to_string().contains("2×2 rays per pixel"), "{e}");
    let mut short = synthetic(&sphere, 8, 4);
    short.records.pop();
    assert!(matches!(look(&short, &v), Err(LookError::Data(_))));
    let mut broken = synthetic(&sphere, 8, 4);
    broken.header.scene_text = "name = ".into();
    assert!(matches!(
        look(&broken, &v),
        Err(LookError::EmbeddedScene(_))
    ));
}

#[test]
fn views_with_bad_values_are_refused_naming_the_field() {
    let cam = Camera::Sphere {
        width: 8,
        height: 4,
    };
    let x = [1.0, 0.0, 0.0];
    let z = [0.0, 0.0, 1.0];
    let field = |r: Result<LookView, LookError>| match r {
        Err(LookError::View { field, .. }) => field,
        other => panic!("{other:?}"),
    };
    let rest = LocalVelocity::REST;
    assert_eq!(
        field(LookView::new(cam, [0.0; 3], z, rest)),
        "observer.forward"
    );
    assert_eq!(
        field(LookView::new(cam, x, [0.0, 0.0, f64::NAN], rest)),
        "observer.up"
    );
    // Not orthogonal: refused as in a scene file (no silent orthogonalization).
    assert_eq!(
        field(LookView::new(cam, x, [0.1, 0.0, 1.0], rest)),
        "observer.up"
    );
    let fast = LocalVelocity {
        speed: 1.0,
        direction: x,
    };
    assert_eq!(
        field(LookView::new(cam, x, z, fast)),
        "observer.velocity.speed"
    );
    let nan = LocalVelocity {
        speed: f64::NAN,
        direction: x,
    };
    assert_eq!(
        field(LookView::new(cam, x, z, nan)),
        "observer.velocity.speed"
    );
    let zero = LocalVelocity {
        speed: 0.5,
        direction: [0.0; 3],
    };
    assert_eq!(
        field(LookView::new(cam, x, z, zero)),
        "observer.velocity.direction"
    );
    let pinhole = |fov_deg| Camera::Pinhole {
        fov_deg,
        width: 8,
        height: 8,
    };
    assert_eq!(
        field(LookView::new(pinhole(180.0), x, z, rest)),
        "camera.fov_deg"
    );
    assert_eq!(
        field(LookView::new(pinhole(f64::NAN), x, z, rest)),
        "camera.fov_deg"
    );
    let wide = Camera::Pinhole {
        fov_deg: 60.0,
        width: 0,
        height: 8,
    };
    assert_eq!(field(LookView::new(wide, x, z, rest)), "camera.width");
    // A view changed after construction is checked again by `look`.
    let mut v = LookView::new(cam, x, z, rest).expect("view");
    v.up = [0.0, 0.0, 2.0];
    let text = with_camera("kind = \"sphere\"\nwidth = 8\nheight = 4", "");
    assert!(matches!(
        look(&synthetic(&text, 8, 4), &v),
        Err(LookError::View {
            field: "observer.up",
            ..
        })
    ));
}

#[test]
fn the_output_header_describes_the_new_view() {
    let text = with_camera("kind = \"sphere\"\nwidth = 8\nheight = 4", "");
    let data = synthetic(&text, 8, 4);
    let cam = Camera::Fisheye {
        fov_deg: 180.0,
        size: 6,
    };
    let velocity = LocalVelocity::new(0.9, [0.0, -1.0, 0.0]).expect("velocity");
    let v = LookView::new(cam, [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], velocity).expect("view");
    let out = look(&data, &v).expect("look");
    assert_eq!(out.header.camera, "fisheye 180°, 6×6");
    let (observer, camera) = Scene::read_view(&out.header.scene_text, "out").expect("valid");
    assert_eq!(camera, cam);
    assert_eq!(observer.velocity, velocity);
    assert_eq!((observer.forward, observer.up), (v.forward, v.up));
    // Everything else of the scene is kept: objects, trace settings.
    let s = Scene::from_str(&out.header.scene_text, "out").expect("a whole scene");
    assert_eq!(s.objects, scene(&small_scene()).objects);
    assert_eq!(s.trace, scene(&small_scene()).trace);
    assert!(out.header.scene_text.starts_with(LOOK_COMMENT));
    // The fisheye's corners are not shown.
    assert_eq!(out.records[0].status, RayStatus::NotTraced);
    // A fisheye, or a sphere seen by a moving observer, is not a source for another look.
    assert!(matches!(look(&out, &v), Err(LookError::NotSphere(_))));
    let cam = Camera::Sphere {
        width: 8,
        height: 4,
    };
    let moving = LookView::new(cam, [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], velocity).expect("view");
    let out = look(&data, &moving).expect("look");
    assert!(matches!(look(&out, &v), Err(LookError::MovingSource(s)) if s == 0.9));
}
