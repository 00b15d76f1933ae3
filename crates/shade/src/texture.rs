//! Runtime textures: [`Texture`] built from a scene's [`TextureSpec`], sampled at an object's
//! body coordinates (u, v) ∈ [0, 1]², returning *linear* RGB.
//!
//! The procedural textures are designed so that a picture shows the object's orientation,
//! and a mirrored picture is recognisable as mirrored:
//!
//! - checker: `rows` bands in v, `cols` in u; light cells 0.9 grey tinted by a hue that
//!   runs once around the colour wheel as u goes from 0 to 1 (red → yellow → green → blue →
//!   magenta), dark cells 0.15 grey, except in the quadrant u < ½, v ≥ ½ where the dark
//!   cells are dark red;
//! - gradient: red grows with u, blue with v (green fixed at 0.2), with a thin white line
//!   along the seam u = 0 (= u = 1);
//! - uniform: one colour;
//! - image: an equirectangular map, u = longitude from −180° (u = 0, the image's left
//!   edge) to +180° (u = 1), v = latitude from −90° (v = 0, bottom row) to +90° (v = 1,
//!   top row); sRGB pixels decoded to linear, sampled bilinearly, wrapping in u and
//!   clamping in v.
//!
//! Out-of-range u wraps and v clamps for every texture; NaN counts as 0.
//!
//! Image files are read with bounded work: regular files only (never a FIFO or a device), at
//! most [`MAX_IMAGE_FILE_BYTES`], decoded with at most [`MAX_IMAGE_SIDE`] pixels on a side.
//! Which files may be read at all is [`crate::texture_source`]'s business.

use std::io::Read;
use std::path::Path;
use std::sync::{Arc, OnceLock};

use scene::{BuiltinImage, ImageSource, TextureSpec};

use crate::colour::srgb8_to_linear;
use crate::error::ShadeError;

/// The built-in earth map (Natural Earth, public domain; see assets/NOTICE.md).
const EARTH_PNG: &[u8] = include_bytes!("../../../assets/earth-natural-earth-720x360.png");

/// Largest image texture file read, in bytes (256 MiB).
pub const MAX_IMAGE_FILE_BYTES: u64 = 256 << 20;
/// Largest image texture side, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16_384;
/// Most memory the decoder may allocate for one image (an RGBA image 16384 × 8192 fits).
const MAX_DECODE_BYTES: u64 = 512 << 20;

/// Light checker cells: 0.9 grey, mixed this much with the hue of u.
const CHECKER_LIGHT: f32 = 0.9;
const CHECKER_TINT: f32 = 0.5;
/// Dark checker cells.
const CHECKER_DARK: [f32; 3] = [0.15, 0.15, 0.15];
/// Dark cells in the marked quadrant u < ½, v ≥ ½.
const CHECKER_MARK: [f32; 3] = [0.35, 0.03, 0.03];
/// Half-width (in u) of the gradient's seam marker line.
const GRADIENT_MARKER: f64 = 0.01;

/// A texture ready to sample.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// Checkerboard: `rows` bands in v, `cols` in u (both ≥ 1).
    Checker { rows: u32, cols: u32 },
    /// Orientation ramp over (u, v).
    Gradient,
    /// One linear RGB colour.
    Uniform([f32; 3]),
    /// An equirectangular image.
    Image(ImageTexture),
}

/// A decoded image in linear RGB, row 0 at the top (v = 1).
#[derive(Clone, Debug, PartialEq)]
pub struct ImageTexture {
    width: usize,
    height: usize,
    /// Row-major 8-bit sRGB, decoded to linear through [`linear_lut`] when sampled: a quarter
    /// of the cache footprint of linear f32 texels, the same values. Shared: clones (one per
    /// object and per prepared shading) do not copy the pixels.
    pixels: Arc<[[u8; 3]]>,
}

impl Texture {
    /// Builds the runtime texture for a scene's texture spec; image files are read and
    /// decoded here. Errors name the image file.
    pub fn load(spec: &TextureSpec) -> Result<Texture, ShadeError> {
        Ok(match spec {
            TextureSpec::Checker { rows, cols } => Texture::Checker {
                rows: (*rows).max(1),
                cols: (*cols).max(1),
            },
            TextureSpec::Gradient => Texture::Gradient,
            TextureSpec::Uniform { color } => {
                Texture::Uniform([color[0] as f32, color[1] as f32, color[2] as f32])
            }
            TextureSpec::Image(ImageSource::File(path)) => {
                Texture::Image(ImageTexture::from_file(path)?)
            }
            TextureSpec::Image(ImageSource::Builtin(BuiltinImage::Earth)) => {
                Texture::Image(ImageTexture::earth()?)
            }
        })
    }

    /// Linear RGB at body coordinates (u, v).
    pub fn sample(&self, u: f64, v: f64) -> [f32; 3] {
        let (u, v) = (wrap01(u), clamp01(v));
        match self {
            Texture::Checker { rows, cols } => checker(*rows, *cols, u, v),
            Texture::Gradient => gradient(u, v),
            Texture::Uniform(c) => *c,
            Texture::Image(image) => image.sample(u, v),
        }
    }
}

impl ImageTexture {
    /// Reads and decodes an image file (any format the `image` crate was built with: PNG):
    /// a regular file of at most [`MAX_IMAGE_FILE_BYTES`], at most [`MAX_IMAGE_SIDE`] pixels
    /// on a side. Errors name `path`.
    pub fn from_file(path: &Path) -> Result<ImageTexture, ShadeError> {
        ImageTexture::read(path, path)
    }

    /// [`ImageTexture::from_file`] of `file`, with errors naming `shown` instead (the path as
    /// the user gave it, where `file` is where it was found).
    pub fn read(file: &Path, shown: &Path) -> Result<ImageTexture, ShadeError> {
        let io_error = |e: std::io::Error| ShadeError::ImageRead {
            path: shown.to_path_buf(),
            source: image::ImageError::IoError(e),
        };
        let too_large = |what: String| ShadeError::ImageTooLarge {
            path: shown.to_path_buf(),
            what,
        };
        // Checked before opening: opening a FIFO would wait for a writer.
        if !std::fs::metadata(file).map_err(io_error)?.is_file() {
            return Err(ShadeError::ImageNotFile {
                path: shown.to_path_buf(),
            });
        }
        let opened = std::fs::File::open(file).map_err(io_error)?;
        // Checked again on what was opened, in case the name was replaced meanwhile.
        let meta = opened.metadata().map_err(io_error)?;
        if !meta.is_file() {
            return Err(ShadeError::ImageNotFile {
                path: shown.to_path_buf(),
            });
        }
        let cap = format!("{} MiB", MAX_IMAGE_FILE_BYTES >> 20);
        if meta.len() > MAX_IMAGE_FILE_BYTES {
            return Err(too_large(format!("the file is larger than {cap}")));
        }
        let mut bytes = Vec::new();
        opened
            .take(MAX_IMAGE_FILE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(io_error)?;
        if bytes.len() as u64 > MAX_IMAGE_FILE_BYTES {
            return Err(too_large(format!("the file grew larger than {cap}")));
        }
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(io_error)?;
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_IMAGE_SIDE);
        limits.max_image_height = Some(MAX_IMAGE_SIDE);
        limits.max_alloc = Some(MAX_DECODE_BYTES);
        reader.limits(limits);
        let decoded = reader.decode().map_err(|e| match e {
            image::ImageError::Limits(_) => too_large(format!(
                "more than {MAX_IMAGE_SIDE} pixels on a side or {} MiB decoded",
                MAX_DECODE_BYTES >> 20
            )),
            source => ShadeError::ImageRead {
                path: shown.to_path_buf(),
                source,
            },
        })?;
        let rgb = decoded.into_rgb8();
        if rgb.width() == 0 || rgb.height() == 0 {
            return Err(ShadeError::EmptyImage {
                path: shown.to_path_buf(),
                width: rgb.width(),
                height: rgb.height(),
            });
        }
        Ok(ImageTexture::from_rgb8(&rgb))
    }

    /// The built-in earth map, 720×360, decoded on first use and shared afterwards (the
    /// viewer prepares settings on every slider step; decoding takes ~10 ms).
    pub fn earth() -> Result<ImageTexture, ShadeError> {
        static EARTH: OnceLock<ImageTexture> = OnceLock::new();
        if let Some(t) = EARTH.get() {
            return Ok(t.clone());
        }
        let t = ImageTexture::decode_earth()?;
        Ok(EARTH.get_or_init(|| t).clone())
    }

    fn decode_earth() -> Result<ImageTexture, ShadeError> {
        let decoded = image::load_from_memory_with_format(EARTH_PNG, image::ImageFormat::Png)
            .map_err(|source| ShadeError::Builtin {
                name: "earth",
                source,
            })?;
        Ok(ImageTexture::from_rgb8(&decoded.to_rgb8()))
    }

    /// Decodes 8-bit sRGB pixels to linear.
    pub fn from_rgb8(rgb: &image::RgbImage) -> ImageTexture {
        let pixels = rgb.pixels().map(|p| p.0).collect();
        ImageTexture {
            width: rgb.width() as usize,
            height: rgb.height() as usize,
            pixels,
        }
    }

    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    /// The 8-bit sRGB pixels, row-major, row 0 at the top (the viewer uploads them to the
    /// GPU, which decodes and filters them as [`Texture::sample`] does).
    pub fn srgb8(&self) -> &[[u8; 3]] {
        &self.pixels
    }

    /// Linear RGB of pixel (col, row), row 0 at the top.
    pub fn pixel(&self, col: usize, row: usize) -> [f32; 3] {
        let lut = linear_lut();
        self.pixels[row * self.width + col].map(|c| lut[c as usize])
    }

    /// Bilinear sample at (u, v) (u already in [0, 1), v in [0, 1]); wraps in u, clamps in v.
    fn sample(&self, u: f64, v: f64) -> [f32; 3] {
        if self.pixels.is_empty() {
            return [0.0; 3];
        }
        // Continuous pixel coordinates with pixel centres at integers.
        let x = u * self.width as f64 - 0.5;
        let y = (1.0 - v) * self.height as f64 - 0.5;
        let (x0, y0) = (floor(x), floor(y));
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let w = self.width as i64;
        let h = self.height as i64;
        // x0 ∈ [−1, w − 1] since u ∈ [0, 1): one comparison instead of a division.
        let col = |i: i64| {
            if i < 0 {
                (i + w) as usize
            } else if i >= w {
                (i - w) as usize
            } else {
                i as usize
            }
        };
        let row = |j: i64| j.clamp(0, h - 1) as usize;
        let (c0, c1) = (col(x0 as i64), col(x0 as i64 + 1));
        let (r0, r1) = (row(y0 as i64), row(y0 as i64 + 1));
        let lut = linear_lut();
        let texel = |c: usize, r: usize| self.pixels[r * self.width + c].map(|b| lut[b as usize]);
        let top = lerp3(texel(c0, r0), texel(c1, r0), fx);
        let bottom = lerp3(texel(c0, r1), texel(c1, r1), fx);
        lerp3(top, bottom, fy)
    }
}

/// 8-bit sRGB → linear, all 256 values.
fn linear_lut() -> &'static [f32; 256] {
    static LUT: OnceLock<[f32; 256]> = OnceLock::new();
    LUT.get_or_init(|| std::array::from_fn(|k| srgb8_to_linear(k as u8)))
}

fn checker(rows: u32, cols: u32, u: f64, v: f64) -> [f32; 3] {
    let i = ((u * cols as f64) as u32).min(cols - 1);
    let j = ((v * rows as f64) as u32).min(rows - 1);
    // The parity of i + j, without the sum (rows and cols go up to u32::MAX).
    if (i ^ j) & 1 == 0 {
        let tint = hue(u as f32);
        let grey = [CHECKER_LIGHT; 3];
        lerp3(grey, tint.map(|c| c * CHECKER_LIGHT), CHECKER_TINT)
    } else if u < 0.5 && v >= 0.5 {
        CHECKER_MARK
    } else {
        CHECKER_DARK
    }
}

fn gradient(u: f64, v: f64) -> [f32; 3] {
    if !(GRADIENT_MARKER..=1.0 - GRADIENT_MARKER).contains(&u) {
        return [1.0, 1.0, 1.0];
    }
    [u as f32, 0.2, v as f32]
}

/// Fully saturated colour of hue `h` ∈ [0, 1] (0 red, ⅓ green, ⅔ blue).
fn hue(h: f32) -> [f32; 3] {
    let channel = |n: f32| {
        // n + 6h ∈ [0, 12) for h ∈ [0, 1): one exact subtraction instead of fmod.
        let k = n + h * 6.0;
        let k = if k >= 6.0 { k - 6.0 } else { k };
        1.0 - k.min(4.0 - k).clamp(0.0, 1.0)
    };
    [channel(5.0), channel(3.0), channel(1.0)]
}

fn lerp3(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

/// u wrapped into [0, 1); NaN and infinities → 0.
fn wrap01(u: f64) -> f64 {
    if !u.is_finite() {
        return 0.0;
    }
    // u − ⌊u⌋ rather than rem_euclid: no fmod call per sample.
    let w = u - floor(u);
    if w >= 1.0 {
        0.0
    } else {
        w
    }
}

/// v clamped into [0, 1]; NaN → 0.
fn clamp01(v: f64) -> f64 {
    if v.is_nan() {
        0.0
    } else {
        v.clamp(0.0, 1.0)
    }
}

/// ⌊x⌋, bit-identical to `f64::floor`, without the libm call that `floor` compiles to on the
/// baseline x86-64 target (no SSE4.1 rounding instruction): truncation through i64 where that
/// is exact (|x| < 2^52, where every float with a fraction lies), `f64::floor` elsewhere.
#[inline]
fn floor(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 {
        let t = x as i64 as f64;
        // −0.0 and negative fractions: floor(−0.0) = −0.0, floor(−0.5) = −1.
        if t > x {
            t - 1.0
        } else if t == 0.0 {
            // Keep the sign of zero as f64::floor does (x ∈ (−1, 1) truncates to +0).
            if x.is_sign_negative() && x == 0.0 {
                -0.0
            } else {
                0.0
            }
        } else {
            t
        }
    } else {
        x.floor()
    }
}

#[cfg(test)]
mod floor_tests {
    #[test]
    fn fast_floor_matches_f64_floor() {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            0.999_999_999,
            -0.999_999_999,
            719.5,
            -1e-300,
            1e-300,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            1e20,
            -1e20,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for k in 0..10_000 {
            let x = (f64::from(k) - 5000.0) * 0.123_456_7;
            xs.push(x);
            if x != 0.0 {
                // The floats on either side (away from and towards zero).
                xs.push(f64::from_bits(x.to_bits() + 1));
                xs.push(f64::from_bits(x.to_bits() - 1));
            }
        }
        for x in xs {
            assert_eq!(super::floor(x).to_bits(), x.floor().to_bits(), "{x}");
        }
        assert!(super::floor(f64::NAN).is_nan());
    }
}
