//! Encoding shaded pictures for the page: raw RGBA for the live image (no compression to
//! wait for: the page puts the bytes straight into a canvas), PNG for downloads and for the
//! overlay layer (RGBA with alpha, [`shade::layer`]).

use image::codecs::png::PngEncoder;
use image::{ImageEncoder, RgbImage, RgbaImage};

/// RGB8 bytes as RGBA bytes, alpha 255.
pub fn rgba_from_rgb(rgb: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(rgb.len() / 3 * 4);
    for px in rgb.chunks_exact(3) {
        out.extend_from_slice(&[px[0], px[1], px[2], 255]);
    }
    out
}

/// The picture as a PNG file.
pub fn png(img: &RgbImage) -> Result<Vec<u8>, image::ImageError> {
    let mut out = Vec::new();
    PngEncoder::new(&mut out).write_image(
        img.as_raw(),
        img.width(),
        img.height(),
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(out)
}

/// An RGBA image (the overlay layer) as a PNG file, alpha kept.
pub fn png_rgba(img: &RgbaImage) -> Result<Vec<u8>, image::ImageError> {
    let mut out = Vec::new();
    PngEncoder::new(&mut out).write_image(
        img.as_raw(),
        img.width(),
        img.height(),
        image::ExtendedColorType::Rgba8,
    )?;
    Ok(out)
}
