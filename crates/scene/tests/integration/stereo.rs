//! `[camera] stereo` (issue 37): read and checked with located errors, and each eye's scene
//! (`Scene::eye`) a mono scene whose text reads back to it exactly.

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
