//! Coordinate objects (docs/physics.md, "Local objects": static spheres and planes given and
//! intersected in pseudo-Cartesian coordinates), checked in flat spacetime against the exact
//! geometry.

use crate::common::{pixel_directions, render_scene, scene};
use datafile::DataFile;

/// Renders `objects` in flat spacetime through a 90° pinhole of 81 × 81 pixels looking
/// along +x with +z up; returns the scene and its data file.
fn flat(objects: &str) -> (scene::Scene, DataFile) {
    let s = scene(&format!(
        "name = \"coords\"\n[spacetime]\nmetric = \"minkowski\"\n\
         [observer]\nforward = [1, 0, 0]\nup = [0, 0, 1]\n{}[trace]\nmax_past = 40.0\n{objects}\n",
        testkit::pinhole(90.0, 81, 81)
    ));
    let (d, _) = render_scene(&s);
    (s, d)
}

#[test]
fn a_floor_plane_is_hit_exactly_below_the_horizon_with_the_right_emission_point() {
    // Looking along +x with the floor z = −1: a pixel looking down at angle β hits it at
    // distance 1/sin β, at the point −t (n) (light from there took that long).
    let (s, d) = flat(
        "[[object]]\nname = \"floor\"\nframe = \"coordinates\"\nshape = \"plane\"\nheight = -1.0\ntexture = { kind = \"checker\", rows = 4, cols = 4 }",
    );
    for (col, row, n) in pixel_directions(&s, &d) {
        let r = d.records[row * d.width + col];
        // Nearly level rays meet the floor beyond max_past = 40: not seen.
        let dist = -1.0 / n[2];
        if n[2] < 0.0 && dist < 40.0 - 1e-6 {
            assert!(r.is_hit(), "({col},{row}) looks down but misses the floor");
            assert!(
                (r.t_emit as f64 + dist).abs() < 1e-4 * dist.max(1.0),
                "t_emit {} vs {}",
                r.t_emit,
                -dist
            );
            assert!((r.x as f64 - n[0] * dist).abs() < 1e-4 * dist.max(1.0));
            assert!((r.z as f64 + 1.0).abs() < 1e-5);
        } else {
            assert!(!r.is_hit(), "({col},{row}) looks up or too far but hits");
        }
    }
}

#[test]
fn a_coordinate_sphere_has_angular_radius_asin_r_over_d() {
    let (s, d) = flat(
        "[[object]]\nname = \"ball\"\nframe = \"coordinates\"\nshape = \"sphere\"\ncenter = { x = 4.0, y = 0.0, z = 0.0 }\nradius = 1.0",
    );
    let half = (1.0f64 / 4.0).asin();
    let pixel = 2.0 * (45f64.to_radians()).tan() / 81.0; // pixel size at the image centre
    for (col, row, n) in pixel_directions(&s, &d) {
        let angle = n[0].clamp(-1.0, 1.0).acos();
        let hit = d.records[row * d.width + col].is_hit();
        if angle < half - pixel {
            assert!(hit, "({col},{row}) at {angle} inside {half}");
        } else if angle > half + pixel {
            assert!(!hit, "({col},{row}) at {angle} outside {half}");
        }
    }
}
