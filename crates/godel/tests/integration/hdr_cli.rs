//! Highlights do not clip (issue 12): `scenes/lit-shadow.toml` has lit pixels brighter than
//! white in linear light (the linear EXR from `godel shade -o x.exr` shows them), yet neither
//! the render's preview nor the default `godel shade` PNG has a clipped pixel.
//!
//! "Clipped" is defined as: a hit pixel with any 8-bit channel at 255. Before the tone
//! curve, every lit pixel with a linear channel above 0.9955 (sRGB 254.5/255) showed as 255
//! and lost its gradation; the test checks that such pixels exist in the linear image and
//! that none is at 255 in either PNG. Orientation marks are drawn only when asked for.

use std::path::{Path, PathBuf};

use crate::common::{read_rgb, render, shade, shade_lit_pair, stderr};

/// Renders the example scene `scenes/STEM.toml` at `width` × `height` into `dir`; returns
/// the data file.
fn render_example(dir: &Path, stem: &str, width: &str, height: &str) -> PathBuf {
    let scene = testkit::scenes_dir().join(format!("{stem}.toml"));
    let o = render(&scene, dir, &["-q", "--width", width, "--height", height]);
    assert!(o.status.success(), "{}", stderr(&o));
    dir.join(format!("{stem}.exr"))
}

#[test]
fn lit_shadow_highlights_do_not_clip() {
    let dir = tempfile::tempdir().unwrap();
    // Half the scene's size, as the render tests trace it: the same rays, fewer of them.
    let data_path = render_example(dir.path(), "lit-shadow", "360", "40");
    let data = datafile::DataFile::read(&data_path).unwrap();
    let hit: Vec<bool> = data
        .records
        .iter()
        .map(|r| r.status == datafile::RayStatus::Hit && r.object >= 0)
        .collect();

    // The default shading (the scene's textures, lit), linear and for display.
    let (exr, png) = shade_lit_pair(&data_path, dir.path(), "lit");
    let linear = read_rgb(&exr);
    let white = 0.9955; // linear value that 8-bit sRGB rounds to 255
    let bright = (0..linear.len())
        .filter(|&i| hit[i] && linear[i].iter().any(|&c| c > white))
        .count();
    assert!(
        bright >= 20,
        "the scene should have highlights above white, found {bright}"
    );

    let preview = image::open(dir.path().join("lit-shadow.png"))
        .unwrap()
        .to_rgb8();
    let shaded = image::open(&png).unwrap().to_rgb8();
    for (name, img) in [("preview", &preview), ("shade PNG", &shaded)] {
        let clipped = img
            .pixels()
            .enumerate()
            .filter(|(i, p)| hit[*i] && p.0.contains(&255))
            .count();
        assert_eq!(
            clipped, 0,
            "{name}: {clipped} clipped of {bright} bright pixels"
        );
    }
    // Brighter stays brighter: the brightest linear pixel is among the brightest shown.
    let luma = |c: [f32; 3]| c[0] + c[1] + c[2];
    let top = (0..linear.len())
        .filter(|&i| hit[i])
        .max_by(|&a, &b| luma(linear[a]).total_cmp(&luma(linear[b])))
        .unwrap();
    let shown = |i: usize| {
        shaded.as_raw()[3 * i..3 * i + 3]
            .iter()
            .map(|&v| u32::from(v))
            .sum::<u32>()
    };
    let brighter = (0..linear.len())
        .filter(|&i| hit[i] && shown(i) > shown(top))
        .count();
    assert_eq!(brighter, 0, "the brightest pixel is shown brightest");
}

#[test]
fn exposure_compensation_scales_the_png_by_two_to_the_ev() {
    let dir = tempfile::tempdir().unwrap();
    let data_path = render_example(dir.path(), "static-sphere", "120", "20");
    let exr = dir.path().join("linear.exr");
    let o = shade(&data_path, &exr, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let linear = read_rgb(&exr);
    let data = datafile::DataFile::read(&data_path).unwrap();
    let mut hits = 0;
    for (ev, gain) in [("0", 1.0f32), ("1", 2.0), ("-1.5", 0.353_553_4)] {
        let png = dir.path().join(format!("ev{ev}.png"));
        let o = shade(&data_path, &png, &["--ev", ev]);
        assert!(o.status.success(), "{}", stderr(&o));
        let img = image::open(&png).unwrap().to_rgb8();
        hits = 0;
        for (i, rec) in data.records.iter().enumerate() {
            if rec.status != datafile::RayStatus::Hit || rec.object < 0 {
                continue;
            }
            hits += 1;
            // 2^ev times the linear colour, then the display transform.
            let want = shade::colour::display_srgb8(linear[i].map(|c| c * gain), 1.0);
            let got = &img.as_raw()[3 * i..3 * i + 3];
            for k in 0..3 {
                assert!(
                    want[k].abs_diff(got[k]) <= 1,
                    "ev {ev}, pixel {i}: {want:?} vs {got:?}"
                );
            }
        }
    }
    assert!(hits > 20, "the sphere is seen");
}

/// An anti-aliased data file (2×2 rays per pixel) shades to an EXR of its picture's size,
/// each pixel the box filter of its samples' linear colours (the sample grid's size was
/// once used, and the command failed).
#[test]
fn an_anti_aliased_file_shades_to_an_exr_of_its_picture_size() {
    let dir = tempfile::tempdir().unwrap();
    let scene = testkit::scenes_dir().join("lit-shadow.toml");
    let o = render(
        &scene,
        dir.path(),
        &["-q", "--width", "120", "--height", "14", "--samples", "4"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let data_path = dir.path().join("lit-shadow.exr");
    let data = datafile::DataFile::read(&data_path).unwrap();
    assert_eq!((data.width, data.height), (240, 28));
    assert_eq!(data.picture_size(), (120, 14));
    let (exr, _) = shade_lit_pair(&data_path, dir.path(), "aa");
    let linear = read_rgb(&exr);
    let mut settings = shade::ShadeSettings::defaults_for(&data);
    settings.shaders = vec![shade::ShaderKind::Texture, shade::ShaderKind::Light];
    let want = shade::Shading::new(&data, &settings).unwrap().linear(&data);
    assert_eq!(linear.len(), 120 * 14);
    assert_eq!(linear, want);
}
