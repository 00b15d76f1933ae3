//! Moving observers and the fisheye camera, checked in flat spacetime where the answer is
//! known in closed form: relativistic aberration cos θ' = (cos θ + v)/(1 + v cos θ) for a
//! source at angle θ from the direction of motion, and the equidistant dome projection.

use crate::common::{render_scene, scene};
use datafile::record::RayStatus;

/// Mean angle from the camera's forward axis (radians) of the hit pixels of a sphere
/// camera image, and the mean pixel direction in the observer frame (forward, right, up).
fn mean_hit_direction(d: &datafile::DataFile, s: &scene::Scene) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for row in 0..d.height {
        for col in 0..d.width {
            if d.records[row * d.width + col].is_hit() {
                let n = s.camera.pixel_direction(col as u32, row as u32).unwrap();
                for i in 0..3 {
                    sum[i] += n[i];
                }
            }
        }
    }
    let n = (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt();
    [sum[0] / n, sum[1] / n, sum[2] / n]
}

fn flat_scene(speed: f64, camera: &str) -> scene::Scene {
    scene(&format!(
        r#"
name = "aberration"
[spacetime]
metric = "minkowski"
[observer]
velocity = {{ speed = {speed}, direction = [0, 1, 0] }}
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
{camera}
[trace]
max_past = 50.0
[[object]]
name = "ball"
radius = 0.1
motion = {{ kind = "rest", position = {{ x = 10.0, y = 0.0, z = 0.0 }} }}
"#
    ))
}

#[test]
fn a_moving_observer_sees_the_source_shifted_toward_its_motion_by_aberration() {
    for v in [0.0, 0.5, 0.8] {
        let s = flat_scene(v, "kind = \"sphere\"\nwidth = 720\nheight = 360");
        let (d, _) = render_scene(&s);
        let n = mean_hit_direction(&d, &s);
        // The source is at θ = 90° from the motion (+y) in the static frame; forward is +x,
        // right = forward × up = −y, so the motion direction is −right.
        let cos_from_motion = -n[1];
        assert!(
            (cos_from_motion - v).abs() < 0.01,
            "v = {v}: cos θ' = {cos_from_motion}, want {v}"
        );
        assert!(n[2].abs() < 0.01);
    }
}

#[test]
fn fisheye_dome_traces_only_the_inscribed_circle_and_is_equidistant() {
    let s = flat_scene(
        0.0,
        "kind = \"fisheye\"\nfov_deg = 180.0\nwidth = 201\nheight = 201",
    );
    let (d, stats) = render_scene(&s);
    let (w, h) = (d.width as f64, d.height as f64);
    let mut outside = 0;
    for row in 0..d.height {
        for col in 0..d.width {
            let (x, y) = (
                (col as f64 + 0.5) / w * 2.0 - 1.0,
                (row as f64 + 0.5) / h * 2.0 - 1.0,
            );
            let r = d.records[row * d.width + col];
            if x * x + y * y > 1.0 {
                outside += 1;
                assert_eq!(
                    r.status,
                    RayStatus::NotTraced,
                    "({col}, {row}) outside the dome circle"
                );
            } else {
                assert_ne!(r.status, RayStatus::NotTraced);
            }
        }
    }
    assert!(outside > 0 && stats.traced < stats.pixels);
    // The ball straight ahead sits at the dome's centre with angular radius asin(0.1/10):
    // equidistant, so its radius in pixels is that angle over (fov/2) times 100.5 pixels.
    let hits: Vec<(f64, f64)> = (0..d.height * d.width)
        .filter(|&i| d.records[i].is_hit())
        .map(|i| {
            (
                (i % d.width) as f64 + 0.5 - w / 2.0,
                (i / d.width) as f64 + 0.5 - h / 2.0,
            )
        })
        .collect();
    let r_max = hits.iter().map(|(x, y)| x.hypot(*y)).fold(0.0, f64::max);
    let want = (0.1f64 / 10.0).asin() / std::f64::consts::FRAC_PI_2 * (w / 2.0);
    assert!(
        (r_max - want).abs() <= 1.0,
        "image radius {r_max} px, want {want} px"
    );
}
