//! Measures `look` against direct renders: for several cameras and observer velocities, the
//! look of a full-sphere data file is compared with a trace of the same view (the scene
//! embedded in the sphere file, with the view written in). Prints, per view:
//!
//! - object mismatches on edge and non-edge pixels;
//! - the g and t_emit errors inside objects (hit pixels whose 3×3 source neighbourhood is one
//!   object and one image) of the nearest-neighbour look and of the smooth look, against the
//!   bound |∇f|·δ of docs/physics.md for nearest neighbour;
//! - the pictures' error: the mean and 99th percentile of the 8-bit difference (largest of R,
//!   G, B) between the preview of each look (nearest, smooth, smooth with 4 and 16 samples) and
//!   the preview of a direct render with 16 rays per pixel, over all pixels and over the
//!   pixels at objects' edges; direct renders with 1 and 4 rays per pixel for comparison.
//!
//! The views aim at the first image of a ball at rest at r = a seen from the axis (39.2°
//! left of +x): make SPHERE.exr with `godel render` of the scene `sphere_scene()` in
//! crates/look/tests/integration/look.rs (the figures in docs/physics.md).
//! `cargo run --release -p look --example look_error -- SPHERE.exr [VIEW-NAME-PREFIX]`

#[path = "../tests/integration/common.rs"]
mod common;

use common::{FISHEYE, PANORAMA, PINHOLE};
use datafile::{DataFile, PixelRecord};
use look::{look_with, pixel_look, Filter, LookView, Sampling, SphereSource};
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
    worst_ratio: f64,
    errs: Vec<f64>,
}

impl Stats {
    fn add(&mut self, e: f64, bound: f64) {
        self.errs.push(e);
        if bound > 0.0 {
            self.worst_ratio = self.worst_ratio.max(e / bound);
        } else if e > 1e-6 {
            self.worst_ratio = f64::INFINITY;
        }
    }

    fn quantile(&mut self, p: f64) -> f64 {
        self.errs.sort_by(f64::total_cmp);
        let n = self.errs.len();
        self.errs
            .get(((n as f64 * p) as usize).min(n.saturating_sub(1)))
            .copied()
            .unwrap_or(0.0)
    }

    fn line(&mut self, name: &str, bound: bool) -> String {
        let n = self.errs.len();
        let mean = self.errs.iter().sum::<f64>() / n.max(1) as f64;
        let ratio = if bound {
            format!(" max err/bound {:.2}", self.worst_ratio)
        } else {
            String::new()
        };
        format!(
            "{name}: n {n} median {:.2e} mean {:.2e} p99 {:.2e} max {:.2e}{ratio}",
            self.quantile(0.5),
            mean,
            self.quantile(0.99),
            self.quantile(1.0),
        )
    }
}

/// The preview picture of a data file made from `scene`.
fn picture(data: &DataFile, scene: &Scene) -> image::RgbImage {
    shade::preview(data, scene).expect("preview")
}

/// Largest 8-bit channel difference per pixel between two pictures.
fn differences(a: &image::RgbImage, b: &image::RgbImage) -> Vec<f64> {
    a.pixels()
        .zip(b.pixels())
        .map(|(p, q)| (0..3).map(|k| p.0[k].abs_diff(q.0[k])).max().unwrap_or(0) as f64)
        .collect()
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
    let nearest = Sampling {
        filter: Filter::Nearest,
        samples: 1,
    };
    let smooth = |samples| Sampling {
        filter: Filter::Smooth,
        samples,
    };
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
        let traced = |samples: u32| {
            let text = scene::replace_samples(&text, "s", samples).unwrap();
            let scene = Scene::from_str(&text, "s").unwrap();
            let data = render(&scene, &NoProgress).unwrap().0;
            (picture(&data, &scene), data)
        };
        let scene = Scene::from_str(&text, "s").unwrap();
        let (direct_picture, direct) = traced(1);
        let looked_nearest = look_with(&sphere, &view, nearest).unwrap();
        let looked_smooth = look_with(&sphere, &view, smooth(1)).unwrap();
        let (mut edge_mis, mut inner_mis, mut edge, mut inner, mut jumps) = (0, 0, 0, 0, 0);
        // g nearest, g smooth, t_emit nearest, t_emit smooth.
        let mut st: [Stats; 4] = Default::default();
        let mut edge_pixels = vec![false; direct.records.len()];
        for row in 0..camera.height() {
            for col in 0..camera.width() {
                let Some(p) = pixel_look(&view, col, row) else {
                    continue;
                };
                let i = row as usize * camera.width() as usize + col as usize;
                let (a, s, b) = (
                    &looked_nearest.records[i],
                    &looked_smooth.records[i],
                    &direct.records[i],
                );
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
                edge_pixels[i] = is_edge;
                if is_edge {
                    edge += 1
                } else {
                    inner += 1
                }
                if a.object != b.object || a.status != b.status || s.object != b.object {
                    if is_edge {
                        edge_mis += 1
                    } else {
                        inner_mis += 1;
                        eprintln!(
                            "  inner mismatch at {col},{row}: look {} / {} direct {}",
                            a.object, s.object, b.object
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
                let r0c = r0.clamp(0, src.height as i64 - 1);
                let c = centre(&src, c0, r0c);
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
                let (bound_g, bound_t) = (p.doppler * grad[0] * delta, grad[1] * delta);
                st[0].add((a.g - b.g).abs() as f64, bound_g);
                st[1].add((s.g - b.g).abs() as f64, bound_g);
                st[2].add((a.t_emit - b.t_emit).abs() as f64, bound_t);
                st[3].add((s.t_emit - b.t_emit).abs() as f64, bound_t);
            }
        }
        println!("{name}: pixels inner {inner} edge {edge}; object/status mismatches inner {inner_mis} edge {edge_mis}; hits at image boundaries (t_emit jumps > {jump}) {jumps}");
        for (s, n) in
            st.iter_mut()
                .zip(["g nearest", "g smooth", "t_emit nearest", "t_emit smooth"])
        {
            println!("  inside objects, {}", s.line(n, true));
        }
        // The pictures against a direct render with 16 rays per pixel.
        let (truth, _) = traced(16);
        let report = |what: &str, img: &image::RgbImage| {
            let d = differences(img, &truth);
            let mut all = Stats::default();
            let mut edges = Stats::default();
            for (k, e) in d.into_iter().enumerate() {
                all.add(e, 0.0);
                if edge_pixels[k] {
                    edges.add(e, 0.0);
                }
            }
            println!(
                "  picture vs direct 16 rays/px, {what}: all pixels mean {:.2} p99 {:.0}; edge pixels mean {:.2} p99 {:.0}",
                all.errs.iter().sum::<f64>() / all.errs.len().max(1) as f64,
                all.quantile(0.99),
                edges.errs.iter().sum::<f64>() / edges.errs.len().max(1) as f64,
                edges.quantile(0.99),
            );
        };
        report("direct 1 ray/px", &direct_picture);
        report("direct 4 rays/px", &traced(4).0);
        report("look nearest", &picture(&looked_nearest, &scene));
        report("look smooth", &picture(&looked_smooth, &scene));
        for samples in [4, 16] {
            let looked = look_with(&sphere, &view, smooth(samples)).unwrap();
            let scene = Scene::from_str(&looked.header.scene_text, "s").unwrap();
            report(
                &format!("look smooth {samples} samples"),
                &picture(&looked, &scene),
            );
        }
    }
}
