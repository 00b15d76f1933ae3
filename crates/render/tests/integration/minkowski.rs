//! The renderer in flat spacetime (metric = "minkowski"), where everything is known in
//! closed form: a static sphere subtends asin(R/d); a fast sphere keeps a circular outline
//! (Penrose–Terrell), is seen where its *retarded* position is, and every pixel's frequency
//! shift is the special-relativistic Doppler factor g = 1/(γ(1 − β·d)).
//!
//! The expected hit mask is computed pixel by pixel from the definition of a local sphere
//! (the ray, in the sphere's rest frame, comes within R of its centre), with the pixel
//! directions taken from the pinhole formula of docs/physics.md ("Pixels and cameras"), not
//! from the scene crate.

use crate::common::*;
use datafile::DataFile;

const FOV_DEG: f64 = 30.0;
const N: usize = 81;

/// Pinhole pixel direction (docs/physics.md, "Pixels and cameras") in the observer's frame,
/// with forward = e_x, up = e_z, right = forward × up = −e_y.
fn pixel_dir(col: usize, row: usize) -> [f64; 3] {
    let t = (0.5 * FOV_DEG).to_radians().tan();
    let (w, h) = (N as f64, N as f64);
    let x = t * (2.0 * (col as f64 + 0.5) / w - 1.0);
    let y = t * (h / w) * (1.0 - 2.0 * (row as f64 + 0.5) / h);
    let n = (1.0 + x * x + y * y).sqrt();
    [1.0 / n, -x / n, y / n]
}

fn minkowski_scene(motion: &str, radius: f64) -> scene::Scene {
    scene(&format!(
        r#"
name = "flat"
[spacetime]
metric = "minkowski"
[observer]
position = {{ x = 0.0, y = 0.0, z = 0.0 }}
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "pinhole"
fov_deg = {FOV_DEG}
width = {N}
height = {N}
[trace]
max_past = 12.0
[[object]]
name = "ball"
radius = {radius}
motion = {motion}
"#
    ))
}

/// Smallest rest-frame distance² between the backward ray X(s) = (−s, s n), s ≥ 0, and the
/// worldline through event `p0` with four-velocity `u` (signature −+++): the spatial part
/// of X − P orthogonal to u, |Δ⊥|² = Δ·Δ + (Δ·u)², is quadratic in s.
fn min_rest_distance2(n: [f64; 3], p0: [f64; 4], u: [f64; 4]) -> f64 {
    let dot = |a: [f64; 4], b: [f64; 4]| -a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    let f = |s: f64| {
        let d = [
            -s - p0[0],
            s * n[0] - p0[1],
            s * n[1] - p0[2],
            s * n[2] - p0[3],
        ];
        dot(d, d) + dot(d, u).powi(2)
    };
    // f(s) = A s² + B s + C.
    let (f0, f1, f2) = (f(0.0), f(1.0), f(2.0));
    let a = 0.5 * (f2 - 2.0 * f1 + f0);
    let b = f1 - f0 - a;
    let s = if a > 0.0 {
        (-b / (2.0 * a)).max(0.0)
    } else {
        0.0
    };
    f(s)
}

/// Compares the rendered hit mask with the analytic one; pixels whose ray passes within
/// `margin` of the surface may go either way. Returns the number of such pixels.
fn assert_mask(d: &DataFile, p0: [f64; 4], u: [f64; 4], radius: f64, margin: f64) -> usize {
    let mut edge = 0;
    for row in 0..N {
        for col in 0..N {
            let dist = min_rest_distance2(pixel_dir(col, row), p0, u).sqrt();
            if (dist - radius).abs() < margin {
                edge += 1;
                continue;
            }
            assert_eq!(
                d.record(col, row).is_hit(),
                dist < radius,
                "pixel ({col}, {row}): rest-frame closest approach {dist}, radius {radius}"
            );
        }
    }
    edge
}

fn hits(d: &DataFile) -> Vec<(usize, usize)> {
    (0..N)
        .flat_map(|r| (0..N).map(move |c| (c, r)))
        .filter(|&(c, r)| d.record(c, r).is_hit())
        .collect()
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
        .clamp(-1.0, 1.0)
        .acos()
}

#[test]
fn static_sphere_subtends_asin_r_over_d() {
    let (dist, radius) = (3.0, 0.5);
    let s = minkowski_scene(
        &format!("{{ kind = \"rest\", position = {{ x = {dist}, y = 0.0, z = 0.0 }} }}"),
        radius,
    );
    let (d, stats) = render_scene(&s);
    assert_eq!(stats.failed + stats.step_budget, 0, "{}", stats.summary());
    let edge = assert_mask(
        &d,
        [0.0, dist, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0],
        radius,
        1e-4,
    );
    assert!(edge < 10, "{edge} pixels on the edge");
    // Angular radius from the pixel geometry: the largest angle between forward and a hit
    // pixel's centre is within one pixel's angle below asin(R/d).
    let expected = (radius / dist).asin();
    let max = hits(&d)
        .iter()
        .map(|&(c, r)| angle(pixel_dir(c, r), [1.0, 0.0, 0.0]))
        .fold(0.0, f64::max);
    let pixel = angle(pixel_dir(N / 2, N / 2), pixel_dir(N / 2 + 1, N / 2));
    assert!(
        max <= expected && max >= expected - pixel,
        "max angle {max}, asin(R/d) = {expected}, pixel {pixel}"
    );
    for &(c, r) in &hits(&d) {
        let rec = d.record(c, r);
        assert!((rec.g - 1.0).abs() <= 1e-6, "g = {}", rec.g);
        // Emitted on the near surface: t_emit = −(distance along the ray).
        assert!(rec.t_emit <= -(dist - radius) as f32 + 1e-4 && rec.t_emit >= -dist as f32);
    }
}

#[test]
fn fast_sphere_looks_round_at_its_retarded_position_with_doppler_shift() {
    // Centre worldline (t, D, v(t + D), 0): at the retarded time t = −D it is at (D, 0, 0),
    // straight ahead, whose light reaches the observer at t = 0 (|x_ret| = −t_ret).
    // At t = 0 (the instantaneous position) it is at (D, vD, 0), 42° to the left.
    let (dd, v, radius) = (5.0, 0.9, 0.5);
    let s = minkowski_scene(
        &format!(
            "{{ kind = \"geodesic\", time = {}, position = {{ x = {dd}, y = 0.0, z = 0.0 }}, speed = {v}, direction = [0, 1, 0] }}",
            -dd
        ),
        radius,
    );
    let (d, stats) = render_scene(&s);
    assert_eq!(stats.failed + stats.step_budget, 0, "{}", stats.summary());
    let gamma = 1.0 / (1.0f64 - v * v).sqrt();
    let u = [gamma, 0.0, gamma * v, 0.0];
    let edge = assert_mask(&d, [-dd, dd, 0.0, 0.0], u, radius, 1e-4);
    assert!(edge < 10, "{edge} pixels on the edge");

    let hit = hits(&d);
    assert!(hit.len() > 50, "{} hits", hit.len());
    // Circular outline: equal extents in the two image axes (the view is near the axis,
    // where the pinhole's distortion is below a pixel).
    let cols = hit.iter().map(|h| h.0).max().unwrap() - hit.iter().map(|h| h.0).min().unwrap() + 1;
    let rows = hit.iter().map(|h| h.1).max().unwrap() - hit.iter().map(|h| h.1).min().unwrap() + 1;
    assert!(
        cols.abs_diff(rows) <= 1,
        "extent {cols} columns × {rows} rows: not round"
    );
    // Seen at the retarded position (straight ahead: the image centre), not at the
    // instantaneous one.
    let n = hit.len() as f64;
    let cx = hit.iter().map(|h| h.0 as f64 + 0.5).sum::<f64>() / n;
    let cy = hit.iter().map(|h| h.1 as f64 + 0.5).sum::<f64>() / n;
    let centre = N as f64 / 2.0;
    assert!(
        (cx - centre).abs() <= 1.0 && (cy - centre).abs() <= 1.0,
        "centroid ({cx}, {cy}), retarded direction at ({centre}, {centre})"
    );
    let t = (0.5 * FOV_DEG).to_radians().tan();
    let inst_col = N as f64 * (1.0 + (-v * dd / dd) / t) / 2.0; // right = −e_y
    assert!((cx - inst_col).abs() > 20.0);
    // Doppler: the photon reaching pixel n travels along −n; the emitter moves with
    // β = v e_y: g = 1/(γ(1 − β·(−n))) exactly (f32 storage).
    for &(c, r) in &hit {
        let nd = pixel_dir(c, r);
        let expected = 1.0 / (gamma * (1.0 + v * nd[1]));
        let g = d.record(c, r).g as f64;
        assert!(
            (g / expected - 1.0).abs() < 1e-5,
            "pixel ({c}, {r}): g = {g}, expected {expected}"
        );
    }
    let centre_g = d.record(N / 2, N / 2).g as f64;
    assert!(
        (centre_g - 1.0 / gamma).abs() < 1e-5,
        "transverse Doppler: {centre_g}"
    );
}

/// Regression (fuzzing): a large ball falling at 0.5 c past the observer, in flat
/// spacetime, left some pixels "integration failed" (its rest-frame match diverged). Every
/// pixel now agrees with the closed form: the backward ray X(s) = (−s, s·n) meets the ball
/// where its rest-frame distance from the centre's worldline, |x′(s)|, first reaches R
/// (a quadratic in s), within max_past.
#[test]
fn regression_large_fast_ball_matches_the_closed_form() {
    let (t0, speed, radius, max_past): (f64, f64, f64, f64) = (-8.74, 0.5, 2.95, 5.0);
    let s = scene(&format!(
        "name = \"flat-fall\"\n[spacetime]\nmetric = \"minkowski\"\n[camera]\nkind = \"sphere\"\nwidth = 32\nheight = 16\n[trace]\nmax_past = {max_past:?}\n[[object]]\nname = \"ball\"\nradius = {radius}\nmotion = {{ kind = \"geodesic\", time = {t0}, position = {{ x = 0.0 }}, speed = {speed}, direction = [0, -1, 0] }}\n"
    ));
    let (d, stats) = render_scene(&s);
    assert_eq!(
        stats.failed + stats.step_budget + stats.work_limit,
        0,
        "{}",
        stats.summary()
    );
    let gamma = 1.0 / (1.0 - speed * speed).sqrt();
    let v = [0.0, -1.0, 0.0];
    let (mut hits, mut checked) = (0, 0);
    for (col, row, n) in pixel_directions(&s, &d) {
        // x′(s) = A·s + B: the boost along v of X(s) − (t0, 0).
        let boost = |dt: f64, dx: [f64; 3]| {
            let par: f64 = (0..3).map(|i| dx[i] * v[i]).sum();
            std::array::from_fn::<f64, 3, _>(|i| {
                dx[i] + ((gamma - 1.0) * par - gamma * speed * dt) * v[i]
            })
        };
        let (a, b) = (boost(-1.0, n), boost(-t0, [0.0; 3]));
        let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        let (qa, qb, qc) = (dot(a, a), 2.0 * dot(a, b), dot(b, b) - radius * radius);
        let disc = qb * qb - 4.0 * qa * qc;
        let first = (disc >= 0.0)
            .then(|| (-qb - disc.sqrt()) / (2.0 * qa))
            .filter(|&s| s > 0.0 && s <= max_past);
        let r = d.record(col, row);
        // Rays within 1e-6 of grazing or of max_past may go either way.
        let marginal =
            disc.abs() < 1e-6 * qb * qb || first.is_some_and(|s| (s - max_past).abs() < 1e-6);
        if marginal {
            continue;
        }
        checked += 1;
        match first {
            Some(s1) => {
                hits += 1;
                assert!(r.is_hit(), "pixel ({col}, {row}) should see the ball at s = {s1}");
                assert!((f64::from(r.t_emit) + s1).abs() < 1e-5, "{} vs {}", r.t_emit, -s1);
            }
            None => assert!(!r.is_hit(), "pixel ({col}, {row}) should miss (disc {disc}, qa {qa} qb {qb} qc {qc}, n {n:?}): {r:?}"),
        }
    }
    assert!(hits > 10 && checked > 400, "{hits} hits of {checked}");
}
