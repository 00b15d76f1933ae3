//! Integration tests of the `shade` crate: sRGB encoding, textures, the texture shader and
//! PNG output.

use std::path::PathBuf;

use datafile::record::{PixelRecord, RayStatus};
use datafile::{DataFile, DataHeader};
use scene::{BuiltinImage, ImageSource, TextureSpec};
use shade::colour::{linear_to_srgb, linear_to_srgb8, rgb_to_srgb8, srgb_to_linear};
use shade::{shade_textures, shading_factor, write_png, ShadeError, Texture};

// ---- colour ----------------------------------------------------------------------------

#[test]
fn srgb_encodes_known_values() {
    assert_eq!(linear_to_srgb8(0.0), 0);
    assert_eq!(linear_to_srgb8(1.0), 255);
    assert_eq!(linear_to_srgb8(0.5), 188);
    assert_eq!(linear_to_srgb8(0.18), 118);
    // Out of range and NaN clamp.
    assert_eq!(linear_to_srgb8(-1.0), 0);
    assert_eq!(linear_to_srgb8(7.0), 255);
    assert_eq!(linear_to_srgb8(f32::NAN), 0);
}

#[test]
fn srgb_is_continuous_at_the_linear_segment_boundary() {
    let b = 0.003_130_8_f32;
    let below = linear_to_srgb(b * (1.0 - 1e-6));
    let above = linear_to_srgb(b * (1.0 + 1e-6));
    assert!((below - above).abs() < 1e-4, "{below} vs {above}");
    assert!((linear_to_srgb(b) - 0.040_45).abs() < 1e-4);
}

#[test]
fn srgb_decode_inverts_encode() {
    for i in 0..=100 {
        let x = i as f32 / 100.0;
        assert!((srgb_to_linear(linear_to_srgb(x)) - x).abs() < 1e-5, "{x}");
    }
}

// ---- textures --------------------------------------------------------------------------

fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

#[test]
fn checker_alternates_between_neighbouring_cells() {
    let (rows, cols) = (8u32, 16u32);
    let t = Texture::load(&TextureSpec::Checker { rows, cols }).unwrap();
    let centre = |i: u32, j: u32| {
        let u = (i as f64 + 0.5) / cols as f64;
        let v = (j as f64 + 0.5) / rows as f64;
        luminance(t.sample(u, v))
    };
    let mut light = 0;
    for j in 0..rows {
        for i in 0..cols {
            let l = centre(i, j);
            let is_light = l > 0.4;
            assert!(
                is_light || l < 0.2,
                "cell ({i}, {j}) is neither light nor dark: {l}"
            );
            assert_eq!(is_light, (i + j) % 2 == 0, "cell ({i}, {j})");
            light += usize::from(is_light);
        }
    }
    assert_eq!(light, (rows * cols / 2) as usize);
    // Across one cell boundary in u and in v the brightness flips.
    let du = 1.0 / cols as f64;
    let dv = 1.0 / rows as f64;
    let at = |u: f64, v: f64| luminance(t.sample(u, v)) > 0.4;
    assert_ne!(at(3.0 * du - 1e-6, 0.3), at(3.0 * du + 1e-6, 0.3));
    assert_ne!(at(0.3, 5.0 * dv - 1e-6), at(0.3, 5.0 * dv + 1e-6));
}

/// Fuzzing found `render` panicking ("attempt to add with overflow") on a checker with
/// rows = cols = 4294967295: the cell parity summed two cell indices near u32::MAX. The
/// largest checker still alternates between neighbouring cells.
#[test]
fn regression_fuzz_checker_with_u32_max_cells() {
    let n = u32::MAX;
    let t = Texture::load(&TextureSpec::Checker { rows: n, cols: n }).unwrap();
    let light = |u: f64, v: f64| luminance(t.sample(u, v)) > 0.4;
    // Near u = v = 1 the cell indices are n − 1 (even sum: light) and n − 2.
    let (last, before) = (1.0 - 0.5 / n as f64, 1.0 - 1.5 / n as f64);
    assert!(light(last, last));
    assert!(!light(before, last));
    assert!(!light(last, before));
    assert!(light(before, before));
}

#[test]
fn checker_shows_mirroring_and_the_marked_quadrant() {
    let t = Texture::load(&TextureSpec::Checker { rows: 2, cols: 4 }).unwrap();
    // A light cell and its mirror image in u differ in hue.
    let a = t.sample(0.125 + 0.01, 0.25);
    let b = t.sample(1.0 - 0.125 - 0.01, 0.25);
    assert_ne!(a, b, "checker is mirror-symmetric in u");
    // Dark cells: marked (dark red) in u < ½, v ≥ ½ only.
    let marked = t.sample(0.125, 0.75); // cell (0, 1): dark
    let plain = t.sample(0.625, 0.75); // cell (2, 1): dark
    assert!(marked[0] > 2.0 * marked[1], "{marked:?}");
    assert_eq!(plain[0], plain[1]);
}

#[test]
fn gradient_is_monotone_in_u_and_v() {
    let t = Texture::load(&TextureSpec::Gradient).unwrap();
    let mut last = -1.0;
    for i in 2..=98 {
        let c = t.sample(i as f64 / 100.0, 0.5);
        assert!(c[0] > last, "red at u = {}", i as f64 / 100.0);
        last = c[0];
    }
    assert!(t.sample(0.5, 0.8)[2] > t.sample(0.5, 0.2)[2]);
    // The seam marker differs from its surroundings.
    assert_eq!(t.sample(0.0, 0.5), [1.0, 1.0, 1.0]);
    assert_ne!(t.sample(0.05, 0.5), [1.0, 1.0, 1.0]);
}

#[test]
fn uniform_texture_and_odd_coordinates() {
    let t = Texture::load(&TextureSpec::Uniform {
        color: [0.25, 0.5, 1.0],
    })
    .unwrap();
    assert_eq!(t.sample(0.3, 0.7), [0.25, 0.5, 1.0]);
    for tex in [
        t,
        Texture::load(&TextureSpec::Gradient).unwrap(),
        Texture::load(&TextureSpec::default()).unwrap(),
        earth(),
    ] {
        for (u, v) in [
            (f64::NAN, 0.5),
            (2.5, -3.0),
            (-0.25, f64::INFINITY),
            (1.0, 1.0),
        ] {
            let c = tex.sample(u, v);
            assert!(c.iter().all(|x| x.is_finite()), "{u}, {v}: {c:?}");
        }
    }
}

fn earth() -> Texture {
    Texture::load(&TextureSpec::Image(ImageSource::Builtin(
        BuiltinImage::Earth,
    )))
    .unwrap()
}

/// (u, v) of a longitude and latitude in degrees.
fn lon_lat(lon: f64, lat: f64) -> (f64, f64) {
    ((lon + 180.0) / 360.0, (lat + 90.0) / 180.0)
}

#[test]
fn earth_texture_loads_and_is_oriented() {
    let t = earth();
    let Texture::Image(image) = &t else {
        panic!("earth is not an image texture");
    };
    assert_eq!((image.width(), image.height()), (720, 360));
    let (u, v) = lon_lat(-150.0, 0.0); // mid-Pacific
    let pacific = t.sample(u, v);
    assert!(
        pacific[2] > pacific[0] * 1.3 && pacific[2] > pacific[1],
        "Pacific is not blue: {pacific:?}"
    );
    let (u, v) = lon_lat(15.0, 23.0); // Sahara
    let sahara = t.sample(u, v);
    assert!(sahara[0] > sahara[2], "Sahara is blue: {sahara:?}");
}

#[test]
fn image_texture_wraps_in_u() {
    let t = earth();
    let (a, b) = (t.sample(0.0, 0.3), t.sample(1.0 - 1e-12, 0.3));
    for k in 0..3 {
        assert!((a[k] - b[k]).abs() < 1e-4, "{a:?} vs {b:?}");
    }
}

#[test]
fn unreadable_image_file_is_an_error_naming_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let junk = dir.path().join("not-an-image.png");
    std::fs::write(&junk, b"this is not a PNG").unwrap();
    let missing = dir.path().join("missing.png");
    for path in [junk, missing] {
        let err = Texture::load(&TextureSpec::Image(ImageSource::File(path.clone()))).unwrap_err();
        assert!(matches!(err, ShadeError::ImageRead { .. }), "{err:?}");
        assert!(
            err.to_string().contains(&path.display().to_string()),
            "{err}"
        );
    }
}

#[test]
fn image_file_texture_decodes_srgb() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("two.png");
    let img = image::RgbImage::from_fn(2, 1, |x, _| {
        if x == 0 {
            image::Rgb([188, 188, 188])
        } else {
            image::Rgb([0, 0, 255])
        }
    });
    img.save(&path).unwrap();
    let t = Texture::load(&TextureSpec::Image(ImageSource::File(path))).unwrap();
    // Pixel centres: u = 0.25 (left pixel), 0.75 (right pixel).
    let left = t.sample(0.25, 0.5);
    assert!((left[0] - 0.5).abs() < 0.003, "{left:?}");
    assert_eq!(t.sample(0.75, 0.5), [0.0, 0.0, 1.0]);
    // Half way between, bilinear.
    let mid = t.sample(0.5, 0.5);
    assert!((mid[2] - (left[2] + 1.0) / 2.0).abs() < 1e-6, "{mid:?}");
}

// ---- the texture shader ----------------------------------------------------------------

fn header(objects: &[&str]) -> DataHeader {
    testkit::godel_header("test", "", "test", objects)
}

fn hit(u: f32, v: f32, cos_i: f32) -> PixelRecord {
    PixelRecord {
        object: 0,
        status: RayStatus::Hit,
        u,
        v,
        cos_i,
        g: 1.0,
        ..PixelRecord::MISS
    }
}

/// A 3×2 image: row 0 hits at full and grazing light, and a miss; row 1 the other statuses.
fn synthetic() -> DataFile {
    let records = vec![
        hit(0.2, 0.7, 1.0),
        hit(0.9, 0.1, 0.0),
        PixelRecord::MISS,
        PixelRecord::miss(RayStatus::Failed),
        PixelRecord::miss(RayStatus::StepBudget),
        PixelRecord::miss(RayStatus::NotTraced),
    ];
    DataFile {
        header: header(&["ball"]),
        width: 3,
        height: 2,
        records,
        lights: Vec::new(),
        polarization: false,
    }
}

#[test]
fn texture_shader_gives_the_expected_colours() {
    let data = synthetic();
    let textures = [Texture::Uniform([1.0, 0.5, 0.0])];
    let img = shade_textures(&data, &textures, [0.0, 0.0, 1.0]);
    assert_eq!(img.dimensions(), (3, 2));
    let px = |c, r| img.get_pixel(c, r).0;
    // Shown through the tone curve: 1.0 (above the knee 0.8) becomes 0.8 + 0.2·½ = 0.9.
    assert_eq!(px(0, 0), rgb_to_srgb8([0.9, 0.5, 0.0]));
    // cos_i = 0: factor 0.25.
    assert_eq!(shading_factor(0.0), 0.25);
    assert_eq!(px(1, 0), rgb_to_srgb8([0.25, 0.125, 0.0]));
    assert_eq!(px(1, 0), [137, 99, 0]);
    assert_eq!(px(2, 0), [0, 0, 255]);
    assert_eq!(px(0, 1), [255, 0, 255]);
    assert_eq!(px(1, 1), rgb_to_srgb8(shade::texture_shader::STEP_BUDGET));
    assert_eq!(px(2, 1), [0, 0, 0]);
}

#[test]
fn texture_shader_survives_inconsistent_data() {
    let mut data = synthetic();
    data.records.truncate(4); // too few records
    let img = shade_textures(&data, &[], [0.0; 3]); // and no textures
    assert_eq!(img.get_pixel(0, 0).0, [255, 0, 255]);
    assert_eq!(img.get_pixel(2, 1).0, [255, 0, 255]);
    data.width = 0;
    assert_eq!(shade_textures(&data, &[], [0.0; 3]).dimensions(), (0, 0));
}

#[test]
fn preview_shades_a_scene_and_checks_its_objects() {
    let scene = scene::Scene::builtin();
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    let mut data = synthetic();
    data.header = header(&names);
    let img = shade::preview(&data, &scene).unwrap();
    assert_eq!(img.dimensions(), (3, 2));
    data.header = header(&["someone-else"]);
    let err = shade::preview(&data, &scene).unwrap_err();
    assert!(matches!(err, ShadeError::ObjectMismatch { .. }), "{err:?}");
}

// ---- PNG output ------------------------------------------------------------------------

#[test]
fn write_png_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.png");
    let img = shade_textures(
        &synthetic(),
        &[Texture::load(&TextureSpec::Gradient).unwrap()],
        [0.1, 0.2, 0.3],
    );
    write_png(&img, &path).unwrap();
    let back = image::open(&path).unwrap().to_rgb8();
    assert_eq!(back, img);
    // Only the output is left in the directory (no temporary file).
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn write_png_into_missing_directory_fails_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let missing: PathBuf = dir.path().join("no-such-dir");
    let path = missing.join("out.png");
    let img = image::RgbImage::new(4, 4);
    let err = write_png(&img, &path).unwrap_err();
    assert!(matches!(err, ShadeError::Write { .. }), "{err:?}");
    assert!(err.to_string().contains("out.png"), "{err}");
    assert!(!path.exists() && !missing.exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn fast_srgb_encoding_agrees_with_the_transfer_function() {
    use shade::colour::linear_to_srgb8_fast;
    // Dense sweep over [0, 1.2]: at most one step apart, and equal away from step edges.
    let mut differ = 0;
    for i in 0..=1_200_000 {
        let x = i as f32 / 1_000_000.0;
        let (a, b) = (linear_to_srgb8_fast(x), linear_to_srgb8(x));
        assert!(a.abs_diff(b) <= 1, "{x}: {a} vs {b}");
        differ += usize::from(a != b);
    }
    assert!(differ < 20, "{differ} values differ");
    assert_eq!(linear_to_srgb8_fast(f32::NAN), 0);
    assert_eq!(linear_to_srgb8_fast(-3.0), 0);
    assert_eq!(linear_to_srgb8_fast(1.0), 255);
    assert_eq!(linear_to_srgb8_fast(f32::INFINITY), 255);
    assert_eq!(linear_to_srgb8_fast(0.5), 188);
}
