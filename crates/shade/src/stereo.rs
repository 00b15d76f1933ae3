//! A stereo pair's two pictures as one (`[camera] stereo` layouts, docs/guide/src/scenes.md):
//! side by side (left eye on the left), over-under (left eye on top), or an anaglyph for
//! red/cyan glasses.

use image::{Rgb, RgbImage};
use scene::Layout;

/// The pictures of the left and the right eye (of one size) in `layout`.
pub fn compose(layout: Layout, left: &RgbImage, right: &RgbImage) -> RgbImage {
    let (w, h) = left.dimensions();
    assert_eq!(
        (w, h),
        right.dimensions(),
        "both eyes' pictures have one size"
    );
    match layout {
        Layout::SideBySide => {
            let mut out = RgbImage::new(2 * w, h);
            image::imageops::replace(&mut out, left, 0, 0);
            image::imageops::replace(&mut out, right, i64::from(w), 0);
            out
        }
        Layout::OverUnder => {
            let mut out = RgbImage::new(w, 2 * h);
            image::imageops::replace(&mut out, left, 0, 0);
            image::imageops::replace(&mut out, right, 0, i64::from(h));
            out
        }
        Layout::Anaglyph => RgbImage::from_fn(w, h, |x, y| {
            anaglyph(*left.get_pixel(x, y), *right.get_pixel(x, y))
        }),
    }
}

/// A half-colour anaglyph pixel: red is the left eye's brightness (Rec. 709 luma of its
/// encoded values), green and blue are the right eye's own. Pure colours of the left eye
/// would reach only one eye through the glasses; its brightness reaches the red filter.
fn anaglyph(left: Rgb<u8>, right: Rgb<u8>) -> Rgb<u8> {
    let [r, g, b] = left.0;
    let luma = 0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b);
    Rgb([luma.round() as u8, right[1], right[2]])
}
