//! Tests of the frequency shader on a synthetic data file: black-body colours at g·T, the
//! physical brightness ordering, statuses, and the reference squares.

use datafile::record::{PixelRecord, RayStatus};
use datafile::DataFile;
use shade::blackbody::{self, table};
use shade::colour::{display_srgb8, rgb_to_srgb8};
use shade::frequency_shader::{blackbody_colour, reference_square};
use shade::texture_shader::{BACKGROUND, FAILED, NOT_TRACED, STEP_BUDGET};
use shade::{shade_frequency, Brightness};

const T0: f64 = 5000.0;
const T1: f64 = 3000.0;
const ROW: usize = 20;

fn hit(object: i32, g: f32) -> PixelRecord {
    PixelRecord {
        object,
        status: RayStatus::Hit,
        g,
        cos_i: 0.3, // must not matter
        ..PixelRecord::MISS
    }
}

/// 40×24 pixels, all misses except row 20: object 0 at g = 1, 0.5, 2; a miss; the failed
/// statuses; object 1 at g = 1; object 2 (no temperature); object 0 with g = NaN.
fn synthetic() -> DataFile {
    let (width, height) = (40, 24);
    let mut records = vec![PixelRecord::MISS; width * height];
    let row = [
        hit(0, 1.0),
        hit(0, 0.5),
        hit(0, 2.0),
        PixelRecord::MISS,
        PixelRecord::miss(RayStatus::Failed),
        PixelRecord::miss(RayStatus::StepBudget),
        PixelRecord::miss(RayStatus::NotTraced),
        hit(1, 1.0),
        hit(2, 1.0),
        hit(0, f32::NAN),
    ];
    records[ROW * width..ROW * width + row.len()].copy_from_slice(&row);
    DataFile {
        header: testkit::godel_header("test", "", "test", &["a", "b", "c"]),
        width,
        height,
        records,
        lights: Vec::new(),
        polarization: false,
    }
}

/// A hit pixel's colour as displayed (through the tone curve).
fn srgb8(c: [f64; 3]) -> [u8; 3] {
    display_srgb8(c.map(|v| v as f32), 1.0)
}

fn px(img: &image::RgbImage, col: usize, row: usize) -> [u8; 3] {
    img.get_pixel(col as u32, row as u32).0
}

fn sum(c: [u8; 3]) -> u32 {
    c.iter().map(|&v| u32::from(v)).sum()
}

#[test]
fn normalized_pixels_show_the_colour_of_g_t() {
    let data = synthetic();
    let img = shade_frequency(&data, &[T0, T1], Brightness::Normalized);
    assert_eq!(img.dimensions(), (40, 24));
    assert_eq!(px(&img, 0, ROW), srgb8(blackbody::colour(T0)));
    assert_eq!(px(&img, 1, ROW), srgb8(blackbody::colour(0.5 * T0)));
    assert_eq!(px(&img, 2, ROW), srgb8(blackbody::colour(2.0 * T0)));
    assert_eq!(px(&img, 7, ROW), srgb8(blackbody::colour(T1)));
    // Red shift reddens, blue shift blues.
    let (red, blue) = (px(&img, 1, ROW), px(&img, 2, ROW));
    assert!(red[0] > red[2] && blue[2] > blue[0], "{red:?} {blue:?}");
}

#[test]
fn misses_and_failures_use_the_texture_shader_colours() {
    let data = synthetic();
    let img = shade_frequency(&data, &[T0, T1], Brightness::Normalized);
    assert_eq!(px(&img, 3, ROW), rgb_to_srgb8(BACKGROUND));
    assert_eq!(px(&img, 39, 23), rgb_to_srgb8(BACKGROUND));
    assert_eq!(px(&img, 4, ROW), rgb_to_srgb8(FAILED));
    assert_eq!(px(&img, 5, ROW), rgb_to_srgb8(STEP_BUDGET));
    assert_eq!(px(&img, 6, ROW), rgb_to_srgb8(NOT_TRACED));
    // Object without a temperature, and a NaN shift.
    assert_eq!(px(&img, 8, ROW), rgb_to_srgb8(FAILED));
    assert_eq!(px(&img, 9, ROW), rgb_to_srgb8(FAILED));
}

#[test]
fn physical_brightness_grows_with_the_shift() {
    let data = synthetic();
    let img = shade_frequency(&data, &[T0, T1], Brightness::Physical { exposure: 0.1 });
    let (g1, g_half, g2) = (px(&img, 0, ROW), px(&img, 1, ROW), px(&img, 2, ROW));
    assert!(
        sum(g2) > sum(g1) && sum(g1) > sum(g_half),
        "{g2:?} {g1:?} {g_half:?}"
    );
    // At g = 1 the luminance is the exposure: the unit colour times 0.1.
    let expected = table().unit_colour(T0).map(|c| c * 0.1);
    assert_eq!(g1, srgb8(expected));
    // The hue of a physical pixel is that of g·T.
    let c = blackbody_colour(0.5, T0, Brightness::Physical { exposure: 0.1 }).unwrap();
    let hue = blackbody::normalize_max(c.map(f64::from));
    let direct = blackbody::colour(0.5 * T0);
    for k in 0..3 {
        assert!((hue[k] - direct[k]).abs() < 1e-3, "{hue:?} vs {direct:?}");
    }
}

#[test]
fn physical_brightness_follows_the_luminance_ratio_and_clamps_the_tone() {
    let bright = blackbody_colour(2.0, T0, Brightness::Physical { exposure: 1.0 }).unwrap();
    // Y(10000 K)/Y(5000 K) ≫ 1: tone-clamped to a largest component of exactly 1, same hue.
    assert_eq!(bright.iter().cloned().fold(0.0f32, f32::max), 1.0);
    let ratio = table().luminance(0.5 * T0) / table().luminance(T0);
    let dim = blackbody_colour(0.5, T0, Brightness::Physical { exposure: 1.0 }).unwrap();
    let unit = table().unit_colour(0.5 * T0);
    for k in 0..3 {
        let want = unit[k] * ratio;
        assert!(
            (f64::from(dim[k]) - want).abs() < 1e-6 * want.max(1e-6),
            "{k}"
        );
    }
    assert!(blackbody_colour(1.0, T0, Brightness::Physical { exposure: f64::NAN }).is_none());
    assert!(blackbody_colour(0.0, T0, Brightness::Normalized).is_none());
    assert!(blackbody_colour(1.0, -1.0, Brightness::Normalized).is_none());
}

#[test]
fn reference_squares_show_the_unshifted_colours() {
    let data = synthetic();
    for brightness in [
        Brightness::Normalized,
        Brightness::Physical { exposure: 0.5 },
    ] {
        let img = shade_frequency(&data, &[T0, T1], brightness);
        for (k, t) in [T0, T1].into_iter().enumerate() {
            let (x0, y0, side) = reference_square(k, data.width, data.height).unwrap();
            assert!((8..=16).contains(&side));
            let want = display_srgb8(blackbody_colour(1.0, t, brightness).unwrap(), 1.0);
            for y in y0..y0 + side {
                for x in x0..x0 + side {
                    assert_eq!(px(&img, x, y), want, "square {k} at ({x}, {y})");
                }
            }
            // Just outside the square: the background of the data.
            assert_eq!(px(&img, x0 + side, y0), rgb_to_srgb8(BACKGROUND));
        }
    }
    // Only objects that exist get a square; none in a tiny image.
    let img = shade_frequency(&data, &[T0], Brightness::Normalized);
    let (x1, y1, _) = reference_square(1, 40, 24).unwrap();
    assert_eq!(px(&img, x1, y1), rgb_to_srgb8(BACKGROUND));
    assert_eq!(reference_square(0, 6, 6), None);
}

#[test]
fn shading_is_deterministic_across_thread_counts() {
    let data = synthetic();
    let shade_with = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| shade_frequency(&data, &[T0, T1], Brightness::Physical { exposure: 0.3 }))
    };
    assert_eq!(shade_with(1), shade_with(4));
}

#[test]
fn empty_and_inconsistent_data_do_not_panic() {
    let mut data = synthetic();
    data.records.truncate(10);
    let img = shade_frequency(&data, &[], Brightness::Normalized);
    assert_eq!(px(&img, 39, 23), rgb_to_srgb8(FAILED));
    data.width = 0;
    assert_eq!(
        shade_frequency(&data, &[T0], Brightness::Normalized).dimensions(),
        (0, 0)
    );
}
