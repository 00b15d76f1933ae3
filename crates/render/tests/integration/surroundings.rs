//! Surroundings (`scenes/surroundings.toml`): an observer on the axis inside a coordinate
//! sphere of radius R < 2a sees its inner surface in every direction. Every pixel is a hit,
//! and each inner-surface record is checked against an independent computation of the
//! ray's exit point: the closed-form light ray through the axis (docs/physics.md, "Closed
//! forms", written out here, not the renderer's) and a root of |X|² = R² found by scanning
//! and bisection (not the renderer's intersection search). A static emitter seen by a static
//! observer has g = 1 exactly (docs/physics.md, "Frequency shift").

use crate::common::{pixel_directions, render_scene, scene};
use std::f64::consts::{PI, SQRT_2};

const A: f64 = 1.0;

/// The surroundings scene at a small size and one sample per pixel.
fn surroundings() -> scene::Scene {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/surroundings.toml"
    );
    let text = std::fs::read_to_string(path).unwrap();
    let text = text
        .replace("width = 720", "width = 48")
        .replace("height = 320", "height = 22")
        .replace("samples = 4", "samples = 1");
    scene(&text)
}

/// The backward light ray from the origin along the unit direction n (static frame at the
/// origin = coordinate frame): past-directed, k = (−1, n), E = k^t = −1, so with
/// ω = √(1 + n_z²)/2a, r_max = |n_⊥|/ω, q = 1/(√2 a ω), θ = ωλ and
/// Φ(θ) = θ + atan2((q − 1) sin θ cos θ, cos²θ + q sin²θ):
/// x + iy = r_max sin θ · e^{i(χ − Φ)}, t = −2√2 a Φ + λ, z = n_z λ.
fn closed_form(n: [f64; 3], lambda: f64) -> [f64; 4] {
    let omega = (1.0 + n[2] * n[2]).sqrt() / (2.0 * A);
    let k_perp = n[0].hypot(n[1]);
    let r_max = k_perp / omega;
    let q = 1.0 / (SQRT_2 * A * omega);
    let chi = n[1].atan2(n[0]);
    let theta = omega * lambda;
    let (s, c) = theta.sin_cos();
    let phi = theta + ((q - 1.0) * s * c).atan2(c * c + q * s * s);
    let r = r_max * s;
    let angle = chi - phi;
    [
        -2.0 * SQRT_2 * A * phi + lambda,
        r * angle.cos(),
        r * angle.sin(),
        n[2] * lambda,
    ]
}

/// The first λ at which the ray leaves the ball |X| < radius: dense scan, then bisection.
fn exit(n: [f64; 3], radius: f64) -> [f64; 4] {
    let outside = |l: f64| {
        let p = closed_form(n, l);
        p[1] * p[1] + p[2] * p[2] + p[3] * p[3] > radius * radius
    };
    let step = 1e-3;
    let mut lo = 0.0;
    for i in 1..200_000 {
        let l = i as f64 * step;
        if outside(l) {
            let mut hi = l;
            for _ in 0..80 {
                let m = 0.5 * (lo + hi);
                if outside(m) {
                    hi = m;
                } else {
                    lo = m;
                }
            }
            return closed_form(n, 0.5 * (lo + hi));
        }
        lo = l;
    }
    panic!("the ray along {n:?} never leaves the sphere");
}

#[test]
fn every_pixel_sees_the_inner_surface_or_the_ball_inside_it() {
    let s = surroundings();
    let radius = 1.8;
    let (d, stats) = render_scene(&s);
    assert_eq!(stats.hits, stats.pixels, "{}", stats.summary());
    let mut checked = 0;
    let mut worst: f64 = 0.0;
    for (col, row, n) in pixel_directions(&s, &d) {
        let r = d.record(col, row);
        let e = exit(n, radius);
        if r.object == 1 {
            // The ball is inside the sphere: its light left after the ray's exit event.
            assert!(f64::from(r.t_emit) > e[0], "ball behind the surroundings");
            continue;
        }
        assert_eq!(r.object, 0, "pixel ({col}, {row})");
        let dev = [
            f64::from(r.t_emit) - e[0],
            f64::from(r.x) - e[1],
            f64::from(r.y) - e[2],
            f64::from(r.z) - e[3],
        ]
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(
            dev < 1e-5,
            "pixel ({col}, {row}): record (t {}, {}, {}, {}) vs closed form {e:?}",
            r.t_emit,
            r.x,
            r.y,
            r.z
        );
        worst = worst.max(dev);
        // Static emitter, static observer: g = 1 (E is conserved along the ray).
        assert!((r.g - 1.0).abs() < 1e-5, "g = {}", r.g);
        // Texture coordinates: longitude and latitude of the exit point on the sphere.
        let u = (e[2].atan2(e[1]) + PI) / (2.0 * PI);
        let v = 0.5 + (e[3] / radius).clamp(-1.0, 1.0).asin() / PI;
        let du = (f64::from(r.u) - u).abs();
        assert!(du.min(1.0 - du) < 1e-4, "u {} vs {u}", r.u);
        assert!((f64::from(r.v) - v).abs() < 1e-4, "v {} vs {v}", r.v);
        // The ray was followed backward: emitted in the past, within one loop.
        assert!(r.t_emit < 0.0 && f64::from(r.t_emit) > -2.0 * SQRT_2 * PI * A);
        checked += 1;
    }
    eprintln!("surroundings: {checked} inner-surface pixels, largest deviation {worst:.2e}");
    assert!(
        checked > d.records.len() * 9 / 10,
        "only {checked} surroundings pixels"
    );
}

#[test]
fn a_sphere_reaching_beyond_the_horizon_is_missed_by_the_rays_in_the_plane() {
    // The reason the surroundings sphere is smaller than 2a: in-plane rays from the axis
    // reach r = 2a at most, so a sphere of radius 2.2a is not hit along the horizon line.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/surroundings.toml"
    ))
    .unwrap()
    .replace("width = 720", "width = 16")
    .replace("height = 320", "height = 9")
    .replace("samples = 4", "samples = 1")
    .replace("radius = 1.8", "radius = 2.2")
    .replace("max_past = 20.0", "max_past = 8.0");
    let s = scene(&text);
    let (d, _) = render_scene(&s);
    // Row 4 of 9 looks along the plane z = 0 (elevation 0).
    for col in 0..d.width {
        let r = d.record(col, 4);
        assert_ne!(
            r.object, 0,
            "column {col} of the horizon line hit the sphere"
        );
    }
    // Rays steep enough to leave along z still hit it.
    assert_eq!(d.record(0, 0).object, 0);
}
