//! Measures `look` against direct renders: for several cameras and observer
//! velocities, the look of a full-sphere data file is compared with a trace of the same
//! view (the scene embedded in the sphere file, with the view written in). Prints, per view,
//! object mismatches on edge and non-edge pixels and the g and t_emit errors of nearest
//! neighbour and of bilinear interpolation, against the bound |∇f|·δ of docs/physics.md.
//! The views aim at the first image of a ball at rest at r = a seen from the axis (39.2°
//! left of +x): make SPHERE.exr with `godel render` of the scene `sphere_scene()` in
//! crates/look/tests/look.rs (the figures in docs/physics.md).
//! `cargo run -p look --example look_error -- SPHERE.exr [VIEW-NAME-PREFIX]`

#[path = "../tests/common/mod.rs"]
mod common;

use common::{FISHEYE, PANORAMA, PINHOLE};
use datafile::{DataFile, PixelRecord};
use look::{look, pixel_look, LookView, SphereSource};
use render::driver::{render, NoProgress};
use scene::{replace_view, Scene};
use spacetime::LocalVelocity;
use std::path::Path;

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    (c[0] * c[0] + c[1] * c[1] + c[2] * c[2])
        .sqrt()
        .atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
}

/// Static direction of source pixel centre (col, row).
fn centre(s: &SphereSource, col: i64, row: i64) -> [f64; 3] {
    let (w, h) = (s.width as f64, s.height as f64);
    let alpha = std::f64::consts::TAU * ((col as f64 + 0.5) / w - 0.5);
    let beta = std::f64::consts::PI * (0.5 - (row as f64 + 0.5) / h);
    let d = [
        beta.cos() * alpha.cos(),
        beta.cos() * alpha.sin(),
        beta.sin(),
    ];
    let r = [
        s.forward[1] * s.up[2] - s.forward[2] * s.up[1],
        s.forward[2] * s.up[0] - s.forward[0] * s.up[2],
        s.forward[0] * s.up[1] - s.forward[1] * s.up[0],
    ];
    [0, 1, 2].map(|i| d[0] * s.forward[i] + d[1] * r[i] + d[2] * s.up[i])
}

fn idx(s: &SphereSource, col: i64, row: i64) -> Option<usize> {
    if row < 0 || row >= s.height as i64 {
        return None;
    }
    Some(row as usize * s.width + col.rem_euclid(s.width as i64) as usize)
}

#[derive(Default)]
struct Stats {
    n: usize,
    worst: f64,
    worst_ratio: f64,
    sum: f64,
    errs: Vec<f64>,
}
impl Stats {
    fn add(&mut self, e: f64, bound: f64) {
        self.n += 1;
        self.worst = self.worst.max(e);
        self.sum += e;
        self.errs.push(e);
        if bound > 0.0 {
            self.worst_ratio = self.worst_ratio.max(e / bound);
        } else if e > 1e-6 {
            self.worst_ratio = f64::INFINITY;
        }
    }
    fn line(&mut self, name: &str) -> String {
        self.errs.sort_by(f64::total_cmp);
        let q = |p: f64| {
            self.errs
                .get(((self.n as f64 * p) as usize).min(self.n.saturating_sub(1)))
                .copied()
                .unwrap_or(0.0)
        };
        format!(
            "{name}: n {} max {:.2e} mean {:.2e} p50 {:.2e} p99 {:.2e} max err/bound {:.2}",
            self.n,
            self.worst,
            self.sum / self.n.max(1) as f64,
            q(0.5),
            q(0.99),
            self.worst_ratio
        )
    }
}

fn main() {
    let path = std::env::args().nth(1).expect("SPHERE.exr");
    let sphere = DataFile::read(Path::new(&path)).unwrap_or_else(|e| panic!("{e}"));
    let src = SphereSource::of(&sphere).unwrap_or_else(|e| panic!("{e}"));
    // Within one image of a ball, neighbouring pixels' emission times differ by much less
    // than twice its diameter; more is a boundary between two images of one object.
    let radius = Scene::from_str(&sphere.header.scene_text, "s")
        .unwrap()
        .objects
        .iter()
        .map(|o| match o.shape {
            scene::Shape::Sphere { radius } => radius,
            _ => 0.0,
        })
        .fold(0.0, f64::max);
    let jump = 4.0 * radius;
    let d39 = 39.2315f64.to_radians();
    let towards = [d39.cos(), d39.sin(), 0.0];
    let side = [-d39.sin(), d39.cos(), 0.0];
    let only = std::env::args().nth(2);
    let views = [
        ("pinhole 60° rest", PINHOLE, towards, 0.0, towards),
        ("pinhole 60° 0.5c towards", PINHOLE, towards, 0.5, towards),
        (
            "panorama 360x60 0.9c side",
            PANORAMA,
            [1.0, 0.0, 0.0],
            0.9,
            side,
        ),
        ("fisheye 180 0.9c side", FISHEYE, towards, 0.9, side),
    ];
    for (name, camera, forward, speed, dir) in views {
        if only.as_deref().is_some_and(|o| !name.starts_with(o)) {
            continue;
        }
        let velocity = LocalVelocity::new(speed, dir).unwrap();
        let view = LookView::new(camera, forward, [0.0, 0.0, 1.0], velocity).unwrap();
        let text = replace_view(
            &sphere.header.scene_text,
            "s",
            &camera,
            velocity,
            view.forward,
            view.up,
        )
        .unwrap();
        let scene = Scene::from_str(&text, "s").unwrap();
        let (direct, _) = render(&scene, &NoProgress).unwrap();
        let looked = look(&sphere, &view).unwrap();
        let (mut edge_mis, mut inner_mis, mut edge, mut inner, mut jumps) = (0, 0, 0, 0, 0);
        let mut st: [Stats; 4] = Default::default(); // g nearest, g bilinear, t nearest, t bilinear
        for row in 0..camera.height() {
            for col in 0..camera.width() {
                let Some(p) = pixel_look(&view, col, row) else {
                    continue;
                };
                let i = row as usize * camera.width() as usize + col as usize;
                let (a, b) = (&looked.records[i], &direct.records[i]);
                let pos = src.position(p.static_dir);
                let (c0, r0) = (pos[0].floor() as i64, pos[1].floor() as i64);
                let centre_rec = sphere.records[src.nearest(pos)];
                let (mut is_edge, mut is_jump) = (false, false);
                for dr in -1..=1 {
                    for dc in -1..=1 {
                        if let Some(j) = idx(&src, c0 + dc, r0 + dr) {
                            let rj = &sphere.records[j];
                            is_edge |=
                                rj.object != centre_rec.object || rj.status != centre_rec.status;
                            is_jump |= (rj.t_emit - centre_rec.t_emit).abs() as f64 > jump;
                        }
                    }
                }
                if is_edge {
                    edge += 1
                } else {
                    inner += 1
                }
                if a.object != b.object || a.status != b.status {
                    if is_edge {
                        edge_mis += 1
                    } else {
                        inner_mis += 1;
                        eprintln!(
                            "  inner mismatch at {col},{row}: look {} direct {}",
                            a.object, b.object
                        )
                    }
                    continue;
                }
                if !a.is_hit() || is_edge {
                    continue;
                }
                if is_jump {
                    jumps += 1;
                    continue;
                }
                // Gradient estimate from the 3x3 block around the nearest pixel.
                let c = centre(&src, c0, r0.clamp(0, src.height as i64 - 1));
                let r0c = r0.clamp(0, src.height as i64 - 1);
                let mut grad = [0.0f64; 2];
                for dr in -1..=1i64 {
                    for dc in -1..=1i64 {
                        if (dr, dc) == (0, 0) {
                            continue;
                        }
                        let Some(j) = idx(&src, c0 + dc, r0c + dr) else {
                            continue;
                        };
                        let ang = angle(c, centre(&src, c0 + dc, r0c + dr));
                        let rj: &PixelRecord = &sphere.records[j];
                        grad[0] = grad[0].max((rj.g - centre_rec.g).abs() as f64 / ang);
                        grad[1] = grad[1].max((rj.t_emit - centre_rec.t_emit).abs() as f64 / ang);
                    }
                }
                let delta = angle(p.static_dir, c);
                st[0].add((a.g - b.g).abs() as f64, p.doppler * grad[0] * delta);
                st[2].add((a.t_emit - b.t_emit).abs() as f64, grad[1] * delta);
                // Bilinear between the four surrounding pixel centres.
                let (x, y) = (pos[0] - 0.5, pos[1] - 0.5);
                let (cx, ry) = (x.floor() as i64, y.floor() as i64);
                let (fx, fy) = (x - cx as f64, y - ry as f64);
                let corners = [
                    (cx, ry, (1.0 - fx) * (1.0 - fy)),
                    (cx + 1, ry, fx * (1.0 - fy)),
                    (cx, ry + 1, (1.0 - fx) * fy),
                    (cx + 1, ry + 1, fx * fy),
                ];
                let mut ok = true;
                let (mut g, mut t, mut dmax) = (0.0, 0.0, 0.0f64);
                for (cc, rr, w) in corners {
                    let rr = rr.clamp(0, src.height as i64 - 1);
                    let j = idx(&src, cc, rr).unwrap();
                    let rj = &sphere.records[j];
                    ok &= rj.object == centre_rec.object && rj.is_hit();
                    g += w * rj.g as f64;
                    t += w * rj.t_emit as f64;
                    dmax = dmax.max(angle(p.static_dir, centre(&src, cc, rr)));
                }
                if ok {
                    st[1].add(
                        (g * p.doppler - b.g as f64).abs(),
                        p.doppler * grad[0] * dmax,
                    );
                    st[3].add((t - b.t_emit as f64).abs(), grad[1] * dmax);
                }
            }
        }
        println!("{name}: pixels inner {inner} edge {edge}; object/status mismatches inner {inner_mis} edge {edge_mis}; hits at image boundaries (t_emit jumps > {jump}) {jumps}");
        for (s, n) in st.iter_mut().zip([
            "g nearest",
            "g bilinear",
            "t_emit nearest",
            "t_emit bilinear",
        ]) {
            println!("  {}", s.line(n));
        }
    }
}
