//! A stereo pair's preview (`shade::stereo::compose`): each layout puts each eye's pixels
//! where it says, and an anaglyph's red is the left eye's brightness, its green and blue
//! the right eye's. One eye's data file finds the other's beside it (`shade::stereo::partner`)
//! and refuses one that is missing or of another pair, naming it.

use std::path::{Path, PathBuf};

use datafile::{DataFile, PixelRecord};
use image::{Rgb, RgbImage};
use scene::{Eye, Layout};
use shade::stereo::{compose, partner, PartnerError};

/// One eye's data file of a 4×2 picture of one ball: `stereo` is the `[camera] stereo` line
/// (none: a mono file), `objects` what it sees.
fn eye_file(stereo: &str, objects: &[&str]) -> DataFile {
    let camera = format!("{}{stereo}", testkit::pinhole(60.0, 4, 2));
    let text = testkit::ball_ahead("s", &camera, "ball", &testkit::checker(2, 4));
    let mut records = vec![PixelRecord::MISS; 8];
    records[1] = testkit::hit(0, 0.5, 0.5, 1.0, -1.0, 1.0);
    DataFile {
        header: testkit::godel_header("s", &text, "pinhole", objects),
        width: 4,
        height: 2,
        records,
        lights: Vec::new(),
        polarization: false,
    }
}

/// `[camera] stereo` of the pair of separation 0.2 in over-under, marked as `eye`.
fn mark(eye: &str) -> String {
    format!("stereo = {{ separation = 0.2, layout = \"over-under\", eye = \"{eye}\" }}\n")
}

/// Writes `data` as `name` in `dir`.
fn write(dir: &Path, name: &str, data: &DataFile) -> PathBuf {
    let path = dir.join(name);
    data.write(&path).unwrap();
    path
}

fn pictures() -> (RgbImage, RgbImage) {
    let left = RgbImage::from_fn(5, 3, |x, y| Rgb([10 * x as u8, 20 * y as u8, 200]));
    let right = RgbImage::from_fn(5, 3, |x, y| Rgb([3, 30 * x as u8, 40 * y as u8 + 1]));
    (left, right)
}

#[test]
fn side_by_side_and_over_under_put_the_left_eye_first() {
    let (left, right) = pictures();
    let wide = compose(Layout::SideBySide, &left, &right);
    let tall = compose(Layout::OverUnder, &left, &right);
    assert_eq!((wide.dimensions(), tall.dimensions()), ((10, 3), (5, 6)));
    for (x, y, p) in left.enumerate_pixels() {
        assert_eq!((wide.get_pixel(x, y), tall.get_pixel(x, y)), (p, p));
    }
    for (x, y, p) in right.enumerate_pixels() {
        assert_eq!(wide.get_pixel(x + 5, y), p);
        assert_eq!(tall.get_pixel(x, y + 3), p);
    }
}

#[test]
fn an_anaglyph_takes_red_from_the_left_eye_and_cyan_from_the_right() {
    let (left, right) = pictures();
    let one = compose(Layout::Anaglyph, &left, &right);
    assert_eq!(one.dimensions(), (5, 3));
    for (x, y, p) in one.enumerate_pixels() {
        let [r, g, b] = left.get_pixel(x, y).0.map(f64::from);
        let luma = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        assert!((f64::from(p[0]) - luma).abs() <= 0.5, "{x},{y}");
        assert_eq!(
            [p[1], p[2]],
            [right.get_pixel(x, y)[1], right.get_pixel(x, y)[2]]
        );
    }
}

#[test]
fn each_eye_finds_the_other_beside_it() {
    let tmp = tempfile::tempdir().unwrap();
    let (left, right) = (
        eye_file(&mark("left"), &["ball"]),
        eye_file(&mark("right"), &["ball"]),
    );
    let l = write(tmp.path(), "s.left.exr", &left);
    let r = write(tmp.path(), "s.right.exr", &right);
    let found = partner(&l, &left).unwrap().unwrap();
    assert_eq!(
        (found.eye, found.layout, &found.path),
        (Eye::Left, Layout::OverUnder, &r)
    );
    assert_eq!(found.data.header.scene_text, right.header.scene_text);
    assert_eq!(found.left_right("mine", "theirs"), ("mine", "theirs"));
    let found = partner(&r, &right).unwrap().unwrap();
    assert_eq!((found.eye, &found.path), (Eye::Right, &l));
    assert_eq!(found.data.header.scene_text, left.header.scene_text);
    assert_eq!(found.left_right("mine", "theirs"), ("theirs", "mine"));
}

#[test]
fn a_mono_file_has_no_partner() {
    let tmp = tempfile::tempdir().unwrap();
    let mono = eye_file("", &["ball"]);
    assert!(partner(&write(tmp.path(), "s.left.exr", &mono), &mono)
        .unwrap()
        .is_none());
    // A pair's scene (not one eye's) is no eye either.
    let pair = eye_file("stereo = { separation = 0.2 }\n", &["ball"]);
    assert!(partner(&write(tmp.path(), "p.exr", &pair), &pair)
        .unwrap()
        .is_none());
}

#[test]
fn a_missing_or_unnamed_partner_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let left = eye_file(&mark("left"), &["ball"]);
    let l = write(tmp.path(), "s.left.exr", &left);
    let e = partner(&l, &left).err().unwrap();
    assert!(e.is_missing(), "{e}");
    let why = e.to_string();
    assert!(
        why.contains("left eye") && why.contains("s.right.exr") && why.contains("missing"),
        "{why}"
    );
    let odd = write(tmp.path(), "odd.exr", &left);
    let e = partner(&odd, &left).err().unwrap();
    assert!(
        matches!(e, PartnerError::Unnamed { .. }) && e.is_missing(),
        "{e}"
    );
    assert!(e.to_string().contains("NAME.left.exr"), "{e}");
}

#[test]
fn a_partner_of_another_pair_or_the_same_eye_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let left = eye_file(&mark("left"), &["ball"]);
    let l = write(tmp.path(), "s.left.exr", &left);
    let wider = mark("right").replace("0.2", "0.3");
    let anaglyph = mark("right").replace("over-under", "anaglyph");
    for wrong in [
        eye_file(&mark("left"), &["ball"]),
        eye_file(&wider, &["ball"]),
        eye_file(&anaglyph, &["ball"]),
        eye_file(&mark("right"), &["ball", "other"]),
        eye_file("", &["ball"]),
    ] {
        write(tmp.path(), "s.right.exr", &wrong);
        let e = partner(&l, &left).err().unwrap();
        assert!(!e.is_missing(), "{e}");
        let why = e.to_string();
        assert!(
            why.contains("s.right.exr") && why.contains("not the other eye"),
            "{why}"
        );
    }
    std::fs::write(tmp.path().join("s.right.exr"), b"not a data file").unwrap();
    let why = partner(&l, &left).err().unwrap().to_string();
    assert!(why.contains("s.right.exr"), "{why}");
}
