//! A stereo pair's preview (`shade::stereo::compose`): each layout puts each eye's pixels
//! where it says, and an anaglyph's red is the left eye's brightness, its green and blue
//! the right eye's.

use image::{Rgb, RgbImage};
use scene::Layout;
use shade::stereo::compose;

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
        assert_eq!([p[1], p[2]], [right.get_pixel(x, y)[1], right.get_pixel(x, y)[2]]);
    }
}
