//! Semantics of valid scenes: defaults, conversions (cylindrical → pseudo-Cartesian,
//! normalization), the field combinations each kind accepts, and pixel directions in the
//! observer's frame.

use scene::*;

const MINIMAL: &str = "name = \"m\"\n[camera]\nkind = \"sphere\"\nwidth = 8\nheight = 4\n";

fn scene(extra: &str) -> Result<Scene, SceneError> {
    Scene::from_str(&format!("{MINIMAL}{extra}"), "test.toml")
}

fn err(extra: &str) -> SceneError {
    scene(extra).unwrap_err()
}

#[test]
fn defaults() {
    let s = scene("").unwrap();
    assert_eq!(s.metric.godel_a(), Some(1.0));
    assert_eq!(s.observer.event, spacetime::Event::default());
    assert_eq!(s.observer.velocity, spacetime::LocalVelocity::REST);
    assert_eq!(
        (s.observer.forward, s.observer.up),
        ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    );
    assert_eq!(
        s.trace,
        TraceSettings {
            method: TraceMethod::Numeric,
            max_past: 30.0,
            tolerance: 1e-11,
            max_steps: 100_000,
            gpu: false
        }
    );
    assert!(s.objects.is_empty() && s.lights.is_empty());
    assert_eq!(s.source_text, MINIMAL);
    assert!(s.source_path.is_none());
}

#[test]
fn object_defaults_and_cylindrical_positions() {
    let s = scene("[[object]]\nname = \"b\"\nradius = 0.5\nmotion = { kind = \"rest\", position = { r = 2.0, phi = 1.5707963267948966 } }\n").unwrap();
    let o = &s.objects[0];
    assert_eq!(o.frame, ObjectFrame::Local);
    assert_eq!(o.texture, TextureSpec::Checker { rows: 8, cols: 16 });
    assert_eq!(o.temperature, 5800.0);
    let Motion::Rest { position } = o.motion else {
        panic!()
    };
    assert!(position.x.abs() < 1e-15 && (position.y - 2.0).abs() < 1e-15 && position.z == 0.0);
}

#[test]
fn geodesic_motion_normalizes_direction() {
    let s = scene("[[object]]\nname = \"b\"\nradius = 0.1\nmotion = { kind = \"geodesic\", time = -2, position = { x = 1, y = 0, z = 0 }, speed = 0.5, direction = [0, 3, 4] }\n").unwrap();
    let Motion::Geodesic { start, velocity } = s.objects[0].motion else {
        panic!()
    };
    assert_eq!(start.t, -2.0);
    assert_eq!(velocity.speed, 0.5);
    assert!(
        (velocity.direction[1] - 0.6).abs() < 1e-15 && (velocity.direction[2] - 0.8).abs() < 1e-15
    );
}

#[test]
fn coordinate_objects() {
    let s = scene(
        "[[object]]\nname = \"s\"\nframe = \"coordinates\"\nshape = \"sphere\"\nradius = 1\ncenter = { x = 1, y = 2, z = 3 }\n\
         [[object]]\nname = \"p\"\nframe = \"coordinates\"\nshape = \"plane\"\nheight = -1\ntexture = { kind = \"gradient\" }\n",
    )
    .unwrap();
    assert_eq!(
        s.objects[0].shape,
        Shape::CoordinateSphere {
            center: [1.0, 2.0, 3.0],
            radius: 1.0
        }
    );
    assert_eq!(
        s.objects[1].shape,
        Shape::Plane {
            height: -1.0,
            extent: None
        }
    );
    assert_eq!(err("[[object]]\nname = \"p\"\nframe = \"coordinates\"\nshape = \"plane\"\nheight = 0\nmotion = { kind = \"rest\" }\n").field, "object[0].motion");
    assert_eq!(
        err("[[object]]\nname = \"p\"\nframe = \"coordinates\"\nradius = 1\n").field,
        "object[0].shape"
    );
    assert_eq!(
        err("[[object]]\nname = \"p\"\nshape = \"plane\"\nheight = 1\n").field,
        "object[0].shape"
    );
}

#[test]
fn minkowski_and_a() {
    let s = scene("[spacetime]\nmetric = \"minkowski\"\n").unwrap();
    assert_eq!(s.metric.name(), "minkowski");
    assert_eq!(
        err("[spacetime]\nmetric = \"minkowski\"\na = 2\n").field,
        "spacetime.a"
    );
    assert_eq!(err("[spacetime]\na = nan\n").field, "spacetime.a");
    assert_eq!(err("[spacetime]\na = -1\n").field, "spacetime.a");
}

#[test]
fn camera_kinds() {
    let fisheye = Scene::from_str(
        "name = \"f\"\n[camera]\nkind = \"fisheye\"\nwidth = 64\nheight = 64\n",
        "f",
    )
    .unwrap();
    assert_eq!(
        fisheye.camera,
        Camera::Fisheye {
            fov_deg: 180.0,
            size: 64
        }
    );
    let big = Scene::from_str(
        "name = \"f\"\n[camera]\nkind = \"sphere\"\nwidth = 20000\nheight = 20000\n",
        "f",
    )
    .unwrap_err();
    assert_eq!(big.field, "camera.height");
    let sphere_fov = Scene::from_str(
        "name = \"f\"\n[camera]\nkind = \"sphere\"\nfov_deg = 90\nwidth = 2\nheight = 2\n",
        "f",
    )
    .unwrap_err();
    assert_eq!(sphere_fov.field, "camera.fov_deg");
    let pano = Scene::from_str("name = \"f\"\n[camera]\nkind = \"panorama\"\nh_fov_deg = 360.5\nv_fov_deg = 10\nwidth = 2\nheight = 2\n", "f").unwrap_err();
    assert_eq!(pano.field, "camera.h_fov_deg");
    let missing = Scene::from_str("name = \"f\"\n", "f").unwrap_err();
    assert!(missing.message.contains("camera"), "{missing}");
}

#[test]
fn lights_and_trace() {
    let s = scene("[[light]]\nposition = { r = 1 }\n[trace]\nmethod = \"exact\"\nmax_steps = 5\n")
        .unwrap();
    assert_eq!(s.lights[0].color, [1.0; 3]);
    assert_eq!(s.lights[0].power, 1.0);
    assert_eq!(s.trace.method, TraceMethod::Exact);
    assert_eq!(s.trace.max_steps, 5);
    assert_eq!(
        err("[[light]]\nposition = { r = 1 }\npower = -1\n").field,
        "light[0].power"
    );
    assert_eq!(err("[trace]\nmax_past = 0\n").field, "trace.max_past");
    assert_eq!(err("[trace]\ntolerance = -1e-9\n").field, "trace.tolerance");
    assert_eq!(err("[trace]\nmax_steps = 0\n").field, "trace.max_steps");
}

#[test]
fn observer_checks() {
    assert_eq!(
        err("[observer]\nforward = [0, 0, 0]\n").field,
        "observer.forward"
    );
    assert_eq!(
        err("[observer]\nposition = { r = -1 }\n").field,
        "observer.position.r"
    );
    assert_eq!(
        err("[observer]\nvelocity = { speed = -0.1 }\n").field,
        "observer.velocity.speed"
    );
    assert_eq!(
        err("[observer]\nvelocity = { speed = 1 }\n").field,
        "observer.velocity.speed"
    );
    assert_eq!(
        err("[observer]\nup = [1, 0, inf]\n").field,
        "observer.up[2]"
    );
    assert_eq!(err("name2 = 1\n").field, "camera.name2");
    // Names become file names.
    assert_eq!(
        Scene::from_str(
            "name = \"a/b\"\n[camera]\nkind = \"sphere\"\nwidth = 2\nheight = 2\n",
            "f"
        )
        .unwrap_err()
        .field,
        "name"
    );
}

#[test]
fn observer_pixel_directions_use_forward_right_up() {
    let s = Scene::from_str(
        "name = \"o\"\n[observer]\nforward = [0, 2, 0]\nup = [0, 0, 1]\n[camera]\nkind = \"panorama\"\nh_fov_deg = 180\nv_fov_deg = 90\nwidth = 2\nheight = 2\n",
        "o",
    )
    .unwrap();
    let o = s.observer;
    assert_eq!(o.forward, [0.0, 1.0, 0.0]);
    assert_eq!(o.right(), [1.0, 0.0, 0.0]);
    // Column 1 of 2 looks 45° right of forward, row 0 looks 22.5° up.
    let d = o.pixel_direction(&s.camera, 1, 0).unwrap();
    let (c45, c225) = (45f64.to_radians().cos(), 22.5f64.to_radians().cos());
    assert!((d[0] - c225 * c45).abs() < 1e-12 && (d[1] - c225 * c45).abs() < 1e-12 && d[2] > 0.0);
    assert!(o.pixel_direction(&s.camera, 2, 0).is_none());
}

#[test]
fn image_textures() {
    let t = |tex: &str| {
        scene(&format!("[[object]]\nname = \"b\"\nradius = 0.2\ntexture = {tex}\nmotion = {{ kind = \"rest\", position = {{ r = 1 }} }}\n"))
    };
    assert_eq!(
        t("{ kind = \"image\", builtin = \"earth\" }")
            .unwrap()
            .objects[0]
            .texture,
        TextureSpec::Image(ImageSource::Builtin(BuiltinImage::Earth))
    );
    assert_eq!(
        t("{ kind = \"image\", builtin = \"mars\" }")
            .unwrap_err()
            .field,
        "object[0].texture.builtin"
    );
    assert_eq!(
        t("{ kind = \"image\" }").unwrap_err().field,
        "object[0].texture"
    );
    assert_eq!(
        t("{ kind = \"checker\", color = [1, 1, 1] }")
            .unwrap_err()
            .field,
        "object[0].texture.color"
    );
    assert_eq!(
        t("{ kind = \"uniform\" }").unwrap_err().field,
        "object[0].texture.color"
    );
}

/// Issue 10: `tolerance = 1e-300` or `1e10` was accepted, and then every pixel failed with
/// exit 0; a huge `max_steps` was accepted too. Both are refused at the field.
#[test]
fn tolerance_and_step_budget_are_bounded() {
    for bad in ["1e-300", "1e-15", "1e10", "0.01"] {
        let e = err(&format!("[trace]\ntolerance = {bad}\n"));
        assert_eq!(e.field, "trace.tolerance", "{bad}: {e}");
        assert_eq!(e.line(), Some(7), "{bad}: {e}");
        assert!(
            e.message.contains("1e-14") && e.message.contains("0.001"),
            "{e}"
        );
    }
    for good in ["1e-14", "1e-11", "1e-3"] {
        let s = scene(&format!("[trace]\ntolerance = {good}\n")).unwrap();
        assert_eq!(s.trace.tolerance, good.parse::<f64>().unwrap());
    }
    let e = err("[trace]\nmax_steps = 10000001\n");
    assert_eq!(e.field, "trace.max_steps", "{e}");
    assert!(e.message.contains("10000000"), "{e}");
    assert_eq!(
        scene("[trace]\nmax_steps = 10000000\n")
            .unwrap()
            .trace
            .max_steps,
        10_000_000
    );
}

/// Issue 10: `name = "."` wrote hidden files `..png` and `..exr`. Names that would make
/// hidden or odd output files are refused at the field.
#[test]
fn output_names_that_make_hidden_or_odd_files_are_refused() {
    let long = "n".repeat(101);
    for bad in [
        ".",
        "..",
        ".hidden",
        "-flag",
        " padded",
        "padded ",
        long.as_str(),
    ] {
        let text = MINIMAL.replacen("name = \"m\"", &format!("name = {bad:?}"), 1);
        let e = Scene::from_str(&text, "test.toml").unwrap_err();
        assert_eq!(e.field, "name", "{bad:?}: {e}");
        assert_eq!(e.line(), Some(1), "{bad:?}: {e}");
    }
    for good in [
        "a.b",
        "static-sphere",
        "n_1",
        "Gödel 1949",
        &"n".repeat(100),
    ] {
        let text = MINIMAL.replacen("name = \"m\"", &format!("name = {good:?}"), 1);
        assert_eq!(Scene::from_str(&text, "test.toml").unwrap().name, good);
    }
}

/// Issue 25: an object's light may be linearly polarized along a body axis
/// (`polarization = { axis = [x, y, z] }`, normalized), or unpolarized (no field); a bad axis
/// or an unknown field in it is refused with file, line and field.
#[test]
fn polarization_axis_is_a_direction_or_absent() {
    let ball = "[[object]]\nname = \"b\"\nradius = 0.5\nmotion = { kind = \"rest\", position = { x = 2.0, y = 0.0, z = 0.0 } }\n";
    assert_eq!(scene(ball).unwrap().objects[0].polarization, None);
    let s = scene(&format!("{ball}polarization = {{ axis = [0, 3, 4] }}\n")).unwrap();
    assert_eq!(s.objects[0].polarization, Some([0.0, 0.6, 0.8]));
    for (bad, field) in [
        ("{ axis = [0, 0, 0] }", "object[0].polarization.axis"),
        ("{ axis = [nan, 0, 1] }", "object[0].polarization.axis[0]"),
    ] {
        let e = err(&format!("{ball}polarization = {bad}\n"));
        assert_eq!(e.field, field, "{bad}: {e}");
        assert_eq!(e.line(), Some(10), "{bad}: {e}");
        assert!(e.to_string().contains("test.toml"), "{e}");
    }
    for bad in ["{ axis = [0, 1] }", "{ axes = [0, 0, 1] }", "\"linear\""] {
        let e = err(&format!("{ball}polarization = {bad}\n"));
        assert_eq!(e.line(), Some(10), "{bad}: {e}");
        assert!(e.to_string().contains("test.toml"), "{e}");
        assert!(e.to_string().contains("polarization"), "{bad}: {e}");
    }
}

/// A Gödel-type member (issue 34): m2 and omega with metric = "godel-type", each bad value or
/// misplaced constant refused at its field.
#[test]
fn godel_type_members_and_their_constants() {
    let member = |m2: &str, omega: &str| {
        format!("[spacetime]\nmetric = \"godel-type\"\nm2 = {m2}\nomega = {omega}\n")
    };
    for (m2, omega) in [("-1", "1"), ("0", "0.5"), ("2.25", "1.5"), ("6", "1")] {
        let s = scene(&member(m2, omega)).unwrap();
        let g = s.metric.godel_type().expect("a Gödel-type member");
        assert_eq!(
            (g.m2, g.omega),
            (m2.parse().unwrap(), omega.parse().unwrap())
        );
        assert_eq!(s.metric.name(), "godel-type");
        assert_eq!(s.metric.godel_a(), None);
    }
    let field = |extra: &str| err(extra).field;
    assert_eq!(field(&member("1", "0")), "spacetime.omega");
    assert_eq!(field(&member("1", "-1")), "spacetime.omega");
    assert_eq!(field(&member("1", "nan")), "spacetime.omega");
    assert_eq!(field(&member("1", "1e9")), "spacetime.omega");
    assert_eq!(field(&member("nan", "1")), "spacetime.m2");
    assert_eq!(field(&member("inf", "1")), "spacetime.m2");
    assert_eq!(field(&member("101", "1")), "spacetime.m2");
    assert_eq!(field(&member("-101", "1")), "spacetime.m2");
    assert_eq!(
        field("[spacetime]\nmetric = \"godel-type\"\nomega = 1\n"),
        "spacetime.m2"
    );
    assert_eq!(
        field("[spacetime]\nmetric = \"godel-type\"\nm2 = 1\n"),
        "spacetime.omega"
    );
    let with_a = format!("{}a = 1\n", member("1", "1"));
    assert_eq!(field(&with_a), "spacetime.a");
    assert_eq!(
        field("[spacetime]\nmetric = \"godel\"\nm2 = 1\n"),
        "spacetime.m2"
    );
    assert_eq!(
        field("[spacetime]\nmetric = \"minkowski\"\nomega = 1\n"),
        "spacetime.omega"
    );
    assert_eq!(field("[spacetime]\nm2 = 1\n"), "spacetime.m2");
    // The exact tracer, the lights and the GPU kernel have the family's closed forms.
    let exact = format!("{}[trace]\nmethod = \"exact\"\n", member("1", "1"));
    let s = scene(&exact).unwrap();
    assert_eq!(s.trace.method, TraceMethod::Exact);
    let light = format!("{}[[light]]\nposition = {{ r = 0.5 }}\n", member("1", "1"));
    assert_eq!(scene(&light).unwrap().lights.len(), 1);
    let gpu = format!("{}[trace]\ngpu = true\n", member("1", "1"));
    assert!(scene(&gpu).unwrap().trace.gpu);
    // max_past bounds the loops by the member's shortest loop time, π/(Ω + √(Ω² − m²/4)).
    let t_loop = std::f64::consts::PI / (1.0 + (1.0f64 - 0.25).sqrt());
    let loops = |n: f64| format!("{}[trace]\nmax_past = {}\n", member("1", "1"), n * t_loop);
    assert!(scene(&loops(99_000.0)).is_ok());
    let e = err(&loops(101_000.0));
    assert_eq!(e.field, "trace.max_past");
    assert!(e.message.contains("loops of a light ray"), "{}", e.message);
    // Flat spacetime still has no closed forms.
    let flat = "[spacetime]\nmetric = \"minkowski\"\n[trace]\nmethod = \"exact\"\n";
    assert_eq!(field(flat), "trace.method");
    let flat = "[spacetime]\nmetric = \"minkowski\"\n[[light]]\nposition = { r = 0.5 }\n";
    assert_eq!(field(flat), "light[0]");
}

/// Positions are bounded by the member's geometry: mρ ≤ 8 where m² > 0 (what the tracers
/// trace, `MAX_SCENE_M_RHO`); for m² = −μ² < 0
/// within π/μ − ρ_c of the axis (the coordinates end at the pole ρ = π/μ).
#[test]
fn godel_type_positions_stay_where_the_coordinates_hold() {
    let at = |m2: f64, r: f64| {
        scene(&format!(
            "[spacetime]\nmetric = \"godel-type\"\nm2 = {m2}\nomega = 1\n[observer]\nposition = {{ r = {r} }}\n"
        ))
    };
    // m² = 4: m = 2, the limit is ρ = 4.
    assert!(at(4.0, 3.9).is_ok());
    let e = at(4.0, 4.1).unwrap_err();
    assert_eq!(e.field, "observer.position");
    assert!(e.message.contains("mρ = 8"), "{}", e.message);
    // m² = −1: μ = 1, ρ_c = 2 atan(1/2), the limit is π − ρ_c ≈ 2.214.
    let limit = std::f64::consts::PI - 2.0 * 0.5f64.atan();
    assert!(at(-1.0, limit - 0.01).is_ok());
    let e = at(-1.0, limit + 0.01).unwrap_err();
    assert_eq!(e.field, "observer.position");
    assert!(e.message.contains("pole"), "{}", e.message);
    // m² = 0 (Som–Raychaudhuri) has only the general bound.
    assert!(at(0.0, 1e5).is_ok());
}
