//! Encoding shaded pictures for the page: raw RGBA for the live image (no compression to
//! wait for: the page puts the bytes straight into a canvas), PNG for downloads.

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ImageEncoder, RgbImage};

/// The picture as RGBA bytes, row 0 first, alpha 255.
pub fn rgba(img: &RgbImage) -> Vec<u8> {
    let mut out = Vec::with_capacity(img.as_raw().len() / 3 * 4);
    for px in img.as_raw().chunks_exact(3) {
        out.extend_from_slice(&[px[0], px[1], px[2], 255]);
    }
    out
}

/// The picture as a PNG file; `fast` trades size for speed.
pub fn png(img: &RgbImage, fast: bool) -> Result<Vec<u8>, image::ImageError> {
    let mut out = Vec::new();
    let encoder = if fast {
        PngEncoder::new_with_quality(&mut out, CompressionType::Fast, FilterType::Sub)
    } else {
        PngEncoder::new(&mut out)
    };
    encoder.write_image(
        img.as_raw(),
        img.width(),
        img.height(),
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(out)
}
