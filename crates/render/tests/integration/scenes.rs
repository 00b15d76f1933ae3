//! The example scenes in scenes/ show what the guide promises (docs/guide/src/scenes.md): a sphere at rest seen
//! exactly twice, one beyond the horizon never, the falling ball of the reference scene
//! several times, and 20+ times when followed ten times further into the past.

use crate::common::render_scene;
use datafile::DataFile;
use scene::Scene;
use std::path::Path;

fn load(name: &str) -> Scene {
    Scene::from_file(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenes")
            .join(name),
    )
    .expect("valid scene")
}

/// Images: 8-connected groups of hit pixels of one object whose emission times join
/// continuously (neighbours closer than 0.5 in t_emit); two images of one object are
/// emitted at clearly different times.
fn images(d: &DataFile) -> Vec<(usize, f32)> {
    let (w, h) = (d.width, d.height);
    let mut label = vec![false; w * h];
    let mut out = Vec::new();
    for start in 0..w * h {
        if label[start] || !d.records[start].is_hit() {
            continue;
        }
        label[start] = true;
        let (mut size, mut stack) = (0, vec![start]);
        while let Some(i) = stack.pop() {
            size += 1;
            let (c, r) = ((i % w) as i64, (i / w) as i64);
            for (dc, dr) in [
                (-1, -1),
                (0, -1),
                (1, -1),
                (-1, 0),
                (1, 0),
                (-1, 1),
                (0, 1),
                (1, 1),
            ] {
                let (cc, rr) = (c + dc, r + dr);
                if cc < 0 || rr < 0 || cc >= w as i64 || rr >= h as i64 {
                    continue;
                }
                let j = rr as usize * w + cc as usize;
                let (a, b) = (d.records[i], d.records[j]);
                if !label[j]
                    && b.is_hit()
                    && a.object == b.object
                    && (a.t_emit - b.t_emit).abs() < 0.5
                {
                    label[j] = true;
                    stack.push(j);
                }
            }
        }
        out.push((size, d.records[start].t_emit));
    }
    out
}

#[test]
fn static_sphere_is_seen_exactly_twice() {
    let (d, stats) = render_scene(&load("static-sphere.toml"));
    assert_eq!(images(&d).len(), 2, "{:?}", images(&d));
    assert_eq!(stats.failed + stats.step_budget, 0);
}

#[test]
fn sphere_beyond_the_horizon_is_never_seen() {
    let (_, stats) = render_scene(&load("beyond-horizon.toml"));
    assert_eq!(stats.hits, 0);
}

#[test]
fn reference_scene_shows_the_falling_ball_several_times() {
    // One ray per pixel: images are counted as groups of hit pixels.
    let mut s = load("reference.toml");
    s.set_samples(1).unwrap();
    let (d, _) = render_scene(&s);
    let imgs = images(&d);
    assert!(imgs.len() >= 4, "{imgs:?}");
}

#[test]
fn the_long_scene_shows_twenty_and_more_images_many_emitted_before_t_minus_30() {
    let (d, _) = render_scene(&load("moving-sphere-long.toml"));
    let imgs = images(&d);
    assert!(imgs.len() >= 20, "{} images: {imgs:?}", imgs.len());
    assert!(
        imgs.iter().filter(|(_, t)| *t < -30.0).count() >= 10,
        "{imgs:?}"
    );
}

/// The stereo dome master: each eye is its own observer (`Scene::eye`), and near a fold the
/// eyes do not see the same images: the image of the falling earth emitted around t = −1.3
/// covers over a thousand samples for the right eye and a few dozen for the left.
#[test]
fn the_stereo_fisheyes_right_eye_sees_an_image_the_left_hardly_sees() {
    let mut s = load("stereo-fisheye.toml");
    s.set_samples(1).unwrap();
    let image_near_t_minus_1_3 = |eye: scene::Eye| {
        let (d, stats) = render_scene(&s.eye(eye).unwrap().unwrap());
        assert_eq!(stats.failed + stats.step_budget, 0);
        let earth = |r: &&datafile::PixelRecord| r.is_hit() && r.object == 0;
        let near = |r: &&datafile::PixelRecord| (-1.6..-1.0).contains(&r.t_emit);
        d.records.iter().filter(earth).filter(near).count()
    };
    let left = image_near_t_minus_1_3(scene::Eye::Left);
    let right = image_near_t_minus_1_3(scene::Eye::Right);
    assert!(
        right > 1000 && right > 10 * left,
        "left {left}, right {right}"
    );
}
