//! `[camera] stereo` (issue 37): read and checked with located errors, and each eye's scene
//! (`Scene::eye`) a mono scene whose text reads back to it exactly; in a Gödel-type member
//! (issue 34) the eyes placed by its isometries, and refused at the stereo table where they
//! cannot be placed or would lie beyond the scene's bound.

use scene::{Eye, Layout, Scene, Stereo};

fn text(metric: &str, stereo: &str) -> String {
    format!(
        "name = \"pair\"\n[spacetime]\n{metric}\n[observer]\ntime = 0.5\n\
         position = {{ r = 0.3, phi = 0.5, z = 0.0 }}\n\
         velocity = {{ speed = 0.3, direction = [0, 0, 1] }}\nforward = [1, 0, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"sphere\"\nwidth = 16\nheight = 8\n{stereo}\n\
         [[object]]\nname = \"ball\"\nradius = 0.1\n\
         motion = {{ kind = \"rest\", position = {{ x = 1.0, y = 0.0, z = 0.0 }} }}\n"
    )
}

const GODEL: &str = "metric = \"godel\"\na = 2.0";

#[test]
fn a_stereo_table_is_read_and_each_eye_reads_back_as_its_own_scene() {
    let s = Scene::from_str(&text(GODEL, "stereo = { separation = 0.1 }"), "p.toml").unwrap();
    assert_eq!(
        s.stereo,
        Some(Stereo {
            separation: 0.1,
            layout: Layout::SideBySide,
            convergence: None,
            eye: None
        })
    );
    let with = "stereo = { separation = 0.2, layout = \"anaglyph\", convergence = 3.0 }";
    let t = Scene::from_str(&text(GODEL, with), "p.toml").unwrap();
    assert_eq!(t.stereo.unwrap().layout, Layout::Anaglyph);
    assert_eq!(t.stereo.unwrap().convergence, Some(3.0));
    for scene in [&s, &t] {
        let [left, right] = Eye::BOTH.map(|e| scene.eye(e).unwrap().unwrap());
        assert_eq!(
            (left.name.as_str(), right.name.as_str()),
            ("pair.left", "pair.right")
        );
        for eye in [&left, &right] {
            let back = Scene::from_str(&eye.source_text, "eye.toml").unwrap();
            assert_eq!(back.observer, eye.observer, "the text says the eye exactly");
            assert_eq!(back.stereo, eye.stereo);
            assert!(
                back.stereo.is_some_and(|s| !s.is_pair()),
                "marked as one eye"
            );
            assert!(back.eye(Eye::Left).is_none(), "an eye has no eyes");
            assert_eq!(back.objects.len(), 1);
        }
        // The eyes are apart (at a = 2, half the separation times a on each side).
        assert_ne!(left.observer.event, right.observer.event);
        let marks = [&left, &right].map(|e| e.stereo.unwrap().eye);
        assert_eq!(marks, [Some(Eye::Left), Some(Eye::Right)]);
    }
}

#[test]
fn in_flat_space_the_eyes_sit_half_the_separation_either_side() {
    let flat = text("metric = \"minkowski\"", "stereo = { separation = 0.5 }")
        .replace(
            "position = { r = 0.3, phi = 0.5, z = 0.0 }",
            "position = { x = 0.0, y = 0.0, z = 0.0 }",
        )
        .replace(
            "velocity = { speed = 0.3, direction = [0, 0, 1] }",
            "velocity = { speed = 0.0, direction = [1, 0, 0] }",
        );
    let s = Scene::from_str(&flat, "f.toml").unwrap();
    // forward × up = (1, 0, 0) × (0, 0, 1) = (0, −1, 0): the left eye is at +y.
    let left = s.eye(Eye::Left).unwrap().unwrap().observer.event;
    let right = s.eye(Eye::Right).unwrap().unwrap().observer.event;
    assert_eq!((left.t, left.x, left.y, left.z), (0.5, 0.0, 0.25, 0.0));
    assert_eq!((right.t, right.x, right.y, right.z), (0.5, 0.0, -0.25, 0.0));
}

#[test]
fn bad_stereo_tables_are_refused_where_they_are_written() {
    for (stereo, field, needle) in [
        (
            "stereo = { separation = nan }",
            "camera.stereo.separation",
            "finite",
        ),
        (
            "stereo = { separation = -0.1 }",
            "camera.stereo.separation",
            "negative",
        ),
        (
            "stereo = { separation = 1.5 }",
            "camera.stereo.separation",
            "at most 1",
        ),
        (
            "stereo = { separation = 0.1, convergence = -2 }",
            "camera.stereo.convergence",
            "positive",
        ),
        (
            "stereo = { separation = 0.1, convergence = 1e9 }",
            "camera.stereo.convergence",
            "at most",
        ),
        (
            "stereo = { separation = 0.1, layout = \"top-bottom\" }",
            "camera.stereo.layout",
            "top-bottom",
        ),
        (
            "stereo = { layout = \"anaglyph\" }",
            "camera.stereo",
            "separation",
        ),
    ] {
        let e = Scene::from_str(&text(GODEL, stereo), "p.toml").unwrap_err();
        assert_eq!(e.file, "p.toml");
        assert!(e.field.starts_with(field), "{stereo}: {e}");
        assert_eq!(e.line(), Some(15), "{stereo}: {e}");
        assert!(e.to_string().contains(needle), "{stereo}: {e}");
    }
}

const MEMBER: &str = "metric = \"godel-type\"\nm2 = 1.0\nomega = 1.0";
const SPHERE: &str = "metric = \"godel-type\"\nm2 = -1.0\nomega = 1.0";

/// In a Gödel-type member (issue 34) a stereo pair is accepted and its eyes are placed by
/// the member's isometries: each eye is `Viewpoint::eye` at half the separation times the
/// member's length scale, and its scene reads back to it exactly.
#[test]
fn in_a_godel_type_member_the_eyes_are_placed_by_its_isometries() {
    let s = Scene::from_str(&text(MEMBER, "stereo = { separation = 0.4 }"), "m.toml").unwrap();
    let half = 0.5 * 0.4 * s.metric.length_scale();
    let o = &s.observer;
    let here = spacetime::Viewpoint {
        event: o.event,
        velocity: o.velocity,
        forward: o.forward,
        up: o.up,
    };
    for eye in Eye::BOTH {
        let scene = s.eye(eye).unwrap().unwrap();
        let side = if eye == Eye::Left { -1.0 } else { 1.0 };
        let want = here.eye(&s.metric, side * half).unwrap().event;
        let got = scene.observer.event;
        let off = [
            got.t - want.t,
            got.x - want.x,
            got.y - want.y,
            got.z - want.z,
        ];
        assert!(
            off.iter().all(|d| d.abs() < 1e-12),
            "{eye:?}: {got:?} vs {want:?}"
        );
        assert!((got.x - o.event.x).hypot(got.y - o.event.y) > 0.5 * half);
        let back = Scene::from_str(&scene.source_text, "eye.toml").unwrap();
        assert_eq!(back.observer, scene.observer);
        assert_eq!(back.metric, s.metric);
    }
}

/// On a member's sphere (m² = −Ω²) an eye that cannot be placed, or that would lie beyond
/// the scene's bound π/μ − ρ_c, is an error located at `[camera] stereo`; the other eye of
/// the same pair is placed.
#[test]
fn on_a_members_sphere_eyes_beyond_the_scenes_bound_are_refused_at_the_stereo_table() {
    // μ = 1, Ω = 1: ρ_c = 2 atan(1/2), the bound π − ρ_c ≈ 2.214. At φ = −π/2 the right axis
    // (forward × up = −y) points away from the axis.
    let limit = std::f64::consts::PI - 2.0 * 0.5f64.atan();
    let far = |r: f64, velocity: &str, separation: f64| {
        text(SPHERE, &format!("stereo = {{ separation = {separation} }}"))
            .replace(
                "position = { r = 0.3, phi = 0.5, z = 0.0 }",
                &format!("position = {{ r = {r}, phi = -1.5707963267948966, z = 0.0 }}"),
            )
            .replace(
                "velocity = { speed = 0.3, direction = [0, 0, 1] }",
                velocity,
            )
    };
    let at_rest = "velocity = { speed = 0.0, direction = [1, 0, 0] }";
    let fast_outwards = "velocity = { speed = 0.999, direction = [0, -1, 0] }";
    for (text, needle) in [
        (far(limit - 0.01, at_rest, 0.2), "beyond"),
        (far(limit - 0.5, fast_outwards, 0.2), "pole"),
    ] {
        let s = Scene::from_str(&text, "s.toml").unwrap_or_else(|e| panic!("{e}"));
        assert!(s.eye(Eye::Left).unwrap().is_ok());
        let e = s.eye(Eye::Right).unwrap().unwrap_err();
        assert_eq!(e.field, "camera.stereo", "{e}");
        assert_eq!(e.line(), Some(16), "{e}");
        // A scene read from text has no path: the eye's errors name it `<scene>`.
        assert!(
            e.to_string().starts_with("<scene>:16:10: camera.stereo: "),
            "{e}"
        );
        assert!(e.message.contains(needle), "{e}");
        assert!(e.message.contains("right eye"), "{e}");
    }
}
