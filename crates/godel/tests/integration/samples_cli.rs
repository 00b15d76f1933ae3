//! Anti-aliasing (`[camera] samples`, `godel render --samples`): a render with 4×4 samples
//! per pixel traces exactly the rays of a render four times larger, keeps every sample's
//! record, and every picture made from it (the preview, `godel shade`, parts merged) is that
//! larger render shaded sample by sample and box-filtered, never a shaded average of records.

use datafile::DataFile;
use image::RgbImage;
use shade::colour::{rgb_to_srgb8, rgb_to_srgb8_fast, srgb8_to_linear};
use shade::{ShadeSettings, Shading};
use std::path::Path;

use crate::common::{self, assert_same_files, godel, godel_ok as ok, render, stderr, write_scene};

/// Runs `godel render SCENE -o OUT EXTRA…` and asserts that it succeeds.
fn ok_render(scene: &str, out: &Path, extra: &[&str]) {
    let o = render(Path::new(scene), out, extra);
    assert!(o.status.success(), "render {scene}: {}", stderr(&o));
}

/// A ball falling past at 0.7 c, seen several times with g from red to blue and a range of
/// emission times: a checkerboard whose edges and colours anti-aliasing must get right.
fn scene_text(name: &str, width: u32, height: u32, samples: u32) -> String {
    format!(
        "name = \"{name}\"\n{}samples = {samples}\n{}{}",
        testkit::panorama(300.0, 40.0, width as usize, height as usize),
        testkit::trace("numeric", 12.0),
        r#"[[object]]
name = "ball"
radius = 0.25
texture = { kind = "checker", rows = 4, cols = 8 }
motion = { kind = "geodesic", time = 0.0, position = { x = -1.0, y = 0.3, z = 0.0 }, speed = 0.7, direction = [1, 0, 0] }
"#
    )
}

const W: u32 = 48;
const H: u32 = 10;
const S: u32 = 4;

/// Renders the scene with 4×4 samples (into `dir/aa`) and the 4×-size scene with one
/// sample (into `dir/big`); returns both data files.
fn render_both(dir: &Path) -> (DataFile, DataFile) {
    let aa = write_scene(dir, "aa.toml", &scene_text("ball", W, H, S * S));
    let big = write_scene(dir, "big.toml", &scene_text("ball", W * S, H * S, 1));
    let (aa_dir, big_dir) = (dir.join("aa"), dir.join("big"));
    ok(&["render", &aa, "-o", aa_dir.to_str().unwrap(), "-q"]);
    ok(&["render", &big, "-o", big_dir.to_str().unwrap(), "-q"]);
    (
        DataFile::read(&aa_dir.join("ball.exr")).unwrap(),
        DataFile::read(&big_dir.join("ball.exr")).unwrap(),
    )
}

/// The box filter, written here: mean of the linear colours of each s×s block of `big`.
fn box_filter(big: &[[f32; 3]], width: usize, s: usize) -> Vec<[f32; 3]> {
    let (w, h) = (width / s, big.len() / width / s);
    let mut out = Vec::with_capacity(w * h);
    for row in 0..h {
        for col in 0..w {
            let mut sum = [0.0f64; 3];
            for j in 0..s {
                for i in 0..s {
                    let c = big[(row * s + j) * width + col * s + i];
                    for k in 0..3 {
                        sum[k] += f64::from(c[k]);
                    }
                }
            }
            out.push(sum.map(|v| (v / (s * s) as f64) as f32));
        }
    }
    out
}

fn linear_pixels(img: &RgbImage) -> Vec<[f32; 3]> {
    img.pixels().map(|p| p.0.map(srgb8_to_linear)).collect()
}

fn largest_difference(a: &RgbImage, b: &[[u8; 3]]) -> u8 {
    a.pixels()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |k| p.0[k].abs_diff(q[k])))
        .max()
        .unwrap_or(0)
}

#[test]
fn four_by_four_samples_equal_a_four_times_larger_render_box_filtered() {
    let tmp = tempfile::tempdir().unwrap();
    let (aa, big) = render_both(tmp.path());
    // The same rays: the sampled file is the larger render's records, with its factor.
    assert_eq!(aa.header.supersample, S);
    assert_eq!(big.header.supersample, 1);
    assert_eq!((aa.width, aa.height), (big.width, big.height));
    assert_eq!(aa.picture_size(), (W as usize, H as usize));
    assert_eq!(aa.records, big.records);
    assert!(aa.records.iter().any(|r| r.is_hit()));

    // The preview is W×H and equals the larger preview box-filtered in linear light (within
    // the larger PNG's 8-bit rounding).
    let preview = image::open(tmp.path().join("aa/ball.png"))
        .unwrap()
        .to_rgb8();
    let big_preview = image::open(tmp.path().join("big/ball.png"))
        .unwrap()
        .to_rgb8();
    assert_eq!(preview.dimensions(), (W, H));
    assert_eq!(big_preview.dimensions(), (W * S, H * S));
    let filtered: Vec<[u8; 3]> = box_filter(&linear_pixels(&big_preview), (W * S) as usize, 4)
        .into_iter()
        .map(rgb_to_srgb8)
        .collect();
    let diff = largest_difference(&preview, &filtered);
    assert!(
        diff <= 1,
        "preview differs by {diff} levels from the filtered large render"
    );

    // And the filter did something: edge pixels mix the ball and the background.
    let blocks_mixed = (0..(W * H) as usize)
        .filter(|&p| {
            let hits = aa
                .sample_indices(p % W as usize, p / W as usize)
                .filter(|&i| aa.records[i].is_hit())
                .count();
            hits > 0 && hits < (S * S) as usize
        })
        .count();
    assert!(blocks_mixed >= 10, "only {blocks_mixed} edge pixels");
}

#[test]
fn reshading_a_sampled_file_shades_each_sample_then_averages() {
    let tmp = tempfile::tempdir().unwrap();
    let (aa, big) = render_both(tmp.path());
    // Frequency and time layers read g and t_emit, which do not average.
    let settings = r#"
shaders = ["frequency", "time"]
reference_squares = false
[time]
mode = "window"
t0 = -4.0
dt = 2.0
"#;
    let look = tmp.path().join("look.toml");
    std::fs::write(&look, settings).unwrap();
    let out = tmp.path().join("f.png");
    let aa_exr = tmp.path().join("aa/ball.exr");
    ok(&[
        "shade",
        aa_exr.to_str().unwrap(),
        "--settings",
        look.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let shaded = image::open(&out).unwrap().to_rgb8();
    assert_eq!(shaded.dimensions(), (W, H));

    // Expected: every sample of the larger render shaded on its own, then averaged.
    let settings = ShadeSettings::defaults_for(&big)
        .overlay_toml(settings, "look.toml")
        .unwrap();
    let shading = Shading::new(&big, &settings).unwrap();
    let samples: Vec<[f32; 3]> = (0..big.records.len())
        .map(|i| shading.pixel(&big, i))
        .collect();
    let mean = box_filter(&samples, big.width, S as usize);
    let expected: Vec<[u8; 3]> = mean.iter().map(|&c| rgb_to_srgb8_fast(c)).collect();
    let diff = largest_difference(&shaded, &expected);
    assert!(
        diff <= 1,
        "shade differs by {diff} levels from shade-then-filter"
    );

    // Shading an averaged record instead would be visibly wrong somewhere: the mean g and
    // t_emit of a block whose samples all hit the ball.
    let mut worst = 0u8;
    for p in 0..(W * H) as usize {
        let (col, row) = (p % W as usize, p / W as usize);
        let at: Vec<usize> = aa.sample_indices(col, row).collect();
        if !at.iter().all(|&i| aa.records[i].is_hit()) {
            continue;
        }
        let mut averaged = aa.clone();
        let n = at.len() as f32;
        let mut r = aa.records[at[0]];
        r.g = at.iter().map(|&i| aa.records[i].g).sum::<f32>() / n;
        r.t_emit = at.iter().map(|&i| aa.records[i].t_emit).sum::<f32>() / n;
        averaged.records[at[0]] = r;
        let wrong = rgb_to_srgb8_fast(shading.pixel(&averaged, at[0]));
        let right = shaded.get_pixel(col as u32, row as u32).0;
        worst = worst.max((0..3).map(|k| wrong[k].abs_diff(right[k])).max().unwrap());
    }
    assert!(
        worst > 8,
        "averaged records would differ by only {worst} levels"
    );
}

#[test]
fn parts_of_a_sampled_render_merge_into_the_single_run() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(
        tmp.path(),
        "lit.toml",
        &common::lit_scene_text("lit", 6.0)
            .replace("width = 90\nheight = 37", "width = 30\nheight = 13"),
    );
    let single = tmp.path().join("single");
    ok_render(&scene, &single, &["--samples", "4", "-q"]);
    let parts = tmp.path().join("parts");
    for i in 1..=3 {
        let part = format!("{i}/3");
        ok_render(&scene, &parts, &["--samples", "4", "--part", &part, "-q"]);
    }
    // A part traced with other samples does not belong to the render.
    let other = tmp.path().join("other");
    ok_render(&scene, &other, &["--part", "3/3", "-q"]);
    let merged = tmp.path().join("merged");
    let part = |dir: &Path, i: u32| {
        dir.join(format!("lit.part-{i}-of-3.exr"))
            .display()
            .to_string()
    };
    let (p1, p2, p3) = (part(&parts, 1), part(&parts, 2), part(&parts, 3));
    let refused = godel(&[
        "merge",
        &p1,
        &p2,
        &part(&other, 3),
        "-o",
        merged.to_str().unwrap(),
    ]);
    assert_eq!(refused.status.code(), Some(1), "{}", stderr(&refused));
    assert!(!merged.join("lit.exr").exists());
    ok(&["merge", &p3, &p1, &p2, "-o", merged.to_str().unwrap()]);
    assert_same_files(
        &single,
        &merged,
        &["lit.exr", "lit.png"],
        "the single run and the merge",
    );
    let data = DataFile::read(&single.join("lit.exr")).unwrap();
    assert_eq!(
        (data.width, data.height, data.header.supersample),
        (60, 26, 2)
    );
    assert_eq!(data.lights.len(), 1);
    let png = image::open(single.join("lit.png")).unwrap();
    assert_eq!((png.width(), png.height()), (30, 13));
}

#[test]
fn bad_sample_counts_are_refused_before_tracing() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(tmp.path(), "s.toml", &scene_text("s", 40, 10, 1));
    let out = tmp.path().join("out");
    for (value, says) in [
        ("15", "square number"),
        ("0", "1..=256"),
        ("-4", "1..=256"),
        ("1024", "1..=256"),
        ("many", "--samples"),
    ] {
        let o = godel(&[
            "render",
            &scene,
            "--samples",
            value,
            "-o",
            out.to_str().unwrap(),
        ]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "--samples {value}: {e}");
        assert!(
            e.contains("--samples") && e.contains(says),
            "--samples {value}: {e}"
        );
        assert!(!out.join("s.exr").exists());
    }
    // Too many rays in all: refused by the bound on width × height × samples.
    let huge = write_scene(tmp.path(), "huge.toml", &scene_text("huge", 8000, 2000, 1));
    let o = godel(&[
        "render",
        &huge,
        "--samples",
        "16",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("rays"), "{}", stderr(&o));
    // In the scene file: located at the field.
    let text = scene_text("bad", 40, 10, 3);
    let line = 1 + text.lines().position(|l| l == "samples = 3").unwrap();
    let bad = write_scene(tmp.path(), "bad.toml", &text);
    let o = godel(&["render", &bad, "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let at = format!("bad.toml:{line}:");
    assert!(
        stderr(&o).contains(&at) && stderr(&o).contains("camera.samples"),
        "{}",
        stderr(&o)
    );
}
