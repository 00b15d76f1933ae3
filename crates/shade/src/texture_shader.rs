//! The texture shader: turns a traced image's per-pixel data into a picture of the objects'
//! textures. This is the preview PNG that `godel render` writes next to the data file.
//!
//! Per pixel, by [`RayStatus`] first, then by object:
//!
//! | pixel | colour (linear RGB) |
//! | --- | --- |
//! | hit object k | texture k at (u, v) × (0.25 + 0.75·max(cos_i, 0)) |
//! | nothing hit (escaped) | the `background` argument ([`BACKGROUND`] for the preview) |
//! | integration failed | [`FAILED`], magenta |
//! | step budget or work limit spent | [`STEP_BUDGET`], dark magenta |
//! | not traced (outside a fisheye circle) | [`NOT_TRACED`], black |
//! | object with no texture (data and textures disagree) | [`FAILED`] |
//!
//! The shading factor is a plain Lambert term with an ambient floor, not physics: `cos_i` is
//! the cosine between the surface normal and the emitted photon, so a sphere gets darker
//! toward its limb and looks round, while the floor of 0.25 keeps grazing parts visible.
//! A scene with `[[light]]` sources is previewed lit instead: texture × (0.06 + Σ_k colour_k ·
//! light_k), light_k the direct irradiance the renderer stores per light (see
//! `render::lighting`); [`direct_light`] is that sum for any shader.
//! An anti-aliased data file is coloured sample by sample, then box-filtered to the picture
//! size (never an averaged record: see `datafile`'s samples). Hit samples go through the
//! display tone curve ([`crate::colour::tone_map`]) before the filter; status colours are
//! display codes, shown as they are. Colours are encoded as 8-bit sRGB. Rows are shaded in
//! parallel; the result does not
//! depend on the thread count.

use std::path::Path;

use datafile::record::{PixelRecord, RayStatus};
use datafile::DataFile;
use image::RgbImage;
use rayon::prelude::*;
use scene::Scene;

use crate::colour::{rgb_to_srgb8, tone_map};
use crate::error::ShadeError;
use crate::texture::Texture;

/// Preview background where nothing was hit: blue-black.
pub const BACKGROUND: [f32; 3] = [0.004, 0.006, 0.02];
/// Integration failed: conspicuous magenta.
pub const FAILED: [f32; 3] = [1.0, 0.0, 1.0];
/// Step budget spent: dark magenta.
pub const STEP_BUDGET: [f32; 3] = [0.15, 0.0, 0.15];
/// Not traced: black.
pub const NOT_TRACED: [f32; 3] = [0.0, 0.0, 0.0];

/// Ambient floor of the shading factor.
const AMBIENT: f32 = 0.25;

/// Shades every pixel of `data` with the objects' textures (`textures[k]` for object k).
/// Never panics on inconsistent data: missing records and textures show as [`FAILED`].
pub fn shade_textures(data: &DataFile, textures: &[Texture], background: [f32; 3]) -> RgbImage {
    shade_pixels(data, |record| pixel_colour(record, textures, background))
}

/// Shades every pixel of `data` with `colour` (linear RGB of one record), rows in parallel;
/// the loop every shader shares. Records missing from an inconsistent file show as
/// [`FAILED`]; a zero or oversized image gives an empty one.
pub fn shade_pixels(data: &DataFile, colour: impl Fn(&PixelRecord) -> [f32; 3] + Sync) -> RgbImage {
    shade_pixels_at(data, |_, record| colour(record))
}

/// [`shade_pixels`] with the sample's index (into `records` and the light planes) as well.
/// An anti-aliased file is shaded sample by sample and box-filtered to its picture size
/// ([`DataFile::box_filter`]).
pub fn shade_pixels_at(
    data: &DataFile,
    colour: impl Fn(usize, &PixelRecord) -> [f32; 3] + Sync,
) -> RgbImage {
    let (w, h) = data.picture_size();
    let (Ok(width), Ok(height)) = (u32::try_from(w), u32::try_from(h)) else {
        return RgbImage::new(0, 0);
    };
    if width == 0 || height == 0 {
        return RgbImage::new(0, 0);
    }
    let row_bytes = w * 3;
    let mut bytes = vec![0u8; row_bytes * h];
    bytes
        .par_chunks_mut(row_bytes)
        .enumerate()
        .for_each(|(row, out)| {
            for (col, px) in out.chunks_exact_mut(3).enumerate() {
                let c = data.box_filter(col, row, |i| {
                    let Some(r) = data.records.get(i) else {
                        return FAILED;
                    };
                    displayed(colour(i, r), r, 1.0)
                });
                px.copy_from_slice(&rgb_to_srgb8(c));
            }
        });
    RgbImage::from_raw(width, height, bytes).expect("buffer has width × height × 3 bytes")
}

/// A sample's colour `c` (of record `r`) as displayed, in linear light before the 8-bit
/// encoding: a hit scaled by `gain` (2^ev) and put through the tone curve; status colours and
/// the failure colour are display codes, shown as they are. One rule for every shader.
pub fn displayed(c: [f32; 3], r: &PixelRecord, gain: f32) -> [f32; 3] {
    if status_colour(r, BACKGROUND).is_none() && c != FAILED {
        c.map(|x| tone_map(x * gain))
    } else {
        c
    }
}

/// What a record shows whatever the shader: the failure colours, and `background` where
/// no object was hit; `None` for a hit, which the shader colours.
pub fn status_colour(record: &PixelRecord, background: [f32; 3]) -> Option<[f32; 3]> {
    status_colour_of(record.status, record.object, background)
}

/// [`status_colour`] of a record's status and object index.
#[inline]
pub fn status_colour_of(status: RayStatus, object: i32, background: [f32; 3]) -> Option<[f32; 3]> {
    match status {
        RayStatus::Failed => Some(FAILED),
        RayStatus::StepBudget | RayStatus::WorkLimit => Some(STEP_BUDGET),
        RayStatus::NotTraced => Some(NOT_TRACED),
        RayStatus::Hit | RayStatus::Escaped => (object < 0).then_some(background),
    }
}

/// Linear RGB of one pixel (see the table in the module documentation).
pub fn pixel_colour(record: &PixelRecord, textures: &[Texture], background: [f32; 3]) -> [f32; 3] {
    if let Some(c) = status_colour(record, background) {
        return c;
    }
    let Some(texture) = textures.get(record.object as usize) else {
        return FAILED;
    };
    let colour = texture.sample(f64::from(record.u), f64::from(record.v));
    let factor = shading_factor(record.cos_i);
    colour.map(|c| c * factor)
}

/// 0.25 + 0.75·max(cos_i, 0); NaN counts as 0.
pub fn shading_factor(cos_i: f32) -> f32 {
    let c = if cos_i.is_nan() {
        0.0
    } else {
        cos_i.clamp(0.0, 1.0)
    };
    AMBIENT + (1.0 - AMBIENT) * c
}

/// Ambient floor of the preview of a scene with lights: what unlit surfaces keep.
pub const LIT_AMBIENT: f32 = 0.06;

/// Direct light at pixel `index`: Σ_k colour_k · light_k (the data file's `light_k`
/// irradiance times the light's linear-RGB colour); zero where a plane is missing or NaN.
pub fn direct_light(data: &DataFile, index: usize, colours: &[[f32; 3]]) -> [f32; 3] {
    let mut sum = [0.0f32; 3];
    for (plane, c) in data.lights.iter().zip(colours) {
        let l = plane.get(index).copied().unwrap_or(0.0);
        if l.is_finite() && l > 0.0 {
            for (s, c) in sum.iter_mut().zip(c) {
                *s += c * l;
            }
        }
    }
    sum
}

/// A lit preview: texture × ([`LIT_AMBIENT`] + [`direct_light`]) on hit pixels, the
/// status colours elsewhere.
pub fn shade_lit(
    data: &DataFile,
    textures: &[Texture],
    colours: &[[f32; 3]],
    background: [f32; 3],
) -> RgbImage {
    shade_pixels_at(data, |i, record| {
        if let Some(c) = status_colour(record, background) {
            return c;
        }
        let Some(texture) = textures.get(record.object as usize) else {
            return FAILED;
        };
        let light = direct_light(data, i, colours);
        let colour = texture.sample(f64::from(record.u), f64::from(record.v));
        [0, 1, 2].map(|k| colour[k] * (LIT_AMBIENT + light[k]))
    })
}

/// The runtime textures of a scene's objects, in scene-file order (the data file's object ids).
pub fn textures_for_scene(scene: &Scene) -> Result<Vec<Texture>, ShadeError> {
    scene
        .objects
        .iter()
        .map(|object| Texture::load(&object.texture))
        .collect()
}

/// The preview picture of a render: [`shade_textures`] with the scene's textures on the
/// [`BACKGROUND`]; for a scene with lights, [`shade_lit`] with their colours. Errs if the data file's objects are not the scene's.
pub fn preview(data: &DataFile, scene: &Scene) -> Result<RgbImage, ShadeError> {
    let scene_names: Vec<String> = scene.objects.iter().map(|o| o.name.clone()).collect();
    if data.header.object_names != scene_names {
        return Err(ShadeError::ObjectMismatch {
            data: data.header.object_names.clone(),
            scene: scene_names,
        });
    }
    let textures = textures_for_scene(scene)?;
    Ok(preview_with_textures(data, &textures, scene))
}

/// The preview with textures already loaded: [`shade_textures`] on the [`BACKGROUND`], or
/// [`shade_lit`] with the lights' colours when the scene has `[[light]]` sources.
pub fn preview_with_textures(data: &DataFile, textures: &[Texture], scene: &Scene) -> RgbImage {
    if scene.lights.is_empty() {
        return shade_textures(data, textures, BACKGROUND);
    }
    let colours: Vec<[f32; 3]> = scene
        .lights
        .iter()
        .map(|l| l.color.map(|c| c as f32))
        .collect();
    shade_lit(data, textures, &colours, BACKGROUND)
}

/// The PNG file of `img`, in memory (`path` only names it in errors).
pub fn encode_png(img: &RgbImage, path: &Path) -> Result<Vec<u8>, ShadeError> {
    let mut bytes = Vec::new();
    img.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    )
    .map_err(|source| ShadeError::Encode {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(bytes)
}

/// Writes `img` as a PNG file atomically: on error nothing is left at `path`.
pub fn write_png(img: &RgbImage, path: &Path) -> Result<(), ShadeError> {
    crate::hdr::write_bytes(path, &encode_png(img, path)?)
}
