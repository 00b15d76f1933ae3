//! What the page's WebGL2 shaders need from the server, encoded once per request in the
//! [`crate::wire`] format: the data file's channels (each fetched only when a layer needs
//! it), the objects' scene textures and the built-in earth image, and the black-body tables
//! of the `shade` crate, so that the GPU colours with the very numbers the CPU uses.
//!
//! Channels on the wire:
//!
//! | name | type | content |
//! | --- | --- | --- |
//! | `id` | u8, u16 or u32 (the smallest that holds them) | what the pixel shows: [`ID_BACKGROUND`], [`ID_FAILED`], [`ID_STEP_BUDGET`], [`ID_NOT_TRACED`], or [`ID_FIRST_OBJECT`] + k for object k (as `shade`'s `status_colour` decides) |
//! | `u`, `v`, `g`, `t_emit`, `light_K` | f32 | the data file's values, unchanged |
//! | `cos_i` | u16 | round(65535·clamp(cos_i, 0, 1)), NaN as 0: all the Lambert factor reads |
//! | `pol`, `dir` | f32, three components | (pol_x, pol_y, pol_z) and (dir_x, dir_y, dir_z): what the polarization layer reads (zeros in a file without the pol_* channels, whose info says so) |

use datafile::DataFile;
use datafile::{PixelRecord, RayStatus};
use serde::Serialize;
use shade::blackbody::{table, T_MAX, T_MIN};
use shade::gt_table::{gt_table, SHIFT};
use shade::Texture;

use crate::wire::{Array, SampleType};

/// Nothing hit: the background colour.
pub const ID_BACKGROUND: u32 = 0;
/// Integration failed (also an object index the file does not name).
pub const ID_FAILED: u32 = 1;
/// Step budget spent.
pub const ID_STEP_BUDGET: u32 = 2;
/// Outside a fisheye's circle.
pub const ID_NOT_TRACED: u32 = 3;
/// Object k is `ID_FIRST_OBJECT + k`.
pub const ID_FIRST_OBJECT: u32 = 4;

/// One channel the page can ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    Id,
    U,
    V,
    G,
    TEmit,
    CosI,
    Pol,
    Dir,
    Light(usize),
}

impl Channel {
    /// The channel of a name on the wire (`id`, `u`, `v`, `g`, `t_emit`, `cos_i`, `pol`,
    /// `dir`, `light_K`);
    /// `None` for any other name or a light the file does not have.
    pub fn parse(name: &str, lights: usize) -> Option<Channel> {
        Some(match name {
            "id" => Channel::Id,
            "u" => Channel::U,
            "v" => Channel::V,
            "g" => Channel::G,
            "t_emit" => Channel::TEmit,
            "cos_i" => Channel::CosI,
            "pol" => Channel::Pol,
            "dir" => Channel::Dir,
            _ => {
                let k: usize = name.strip_prefix("light_")?.parse().ok()?;
                if k >= lights || name != format!("light_{k}") {
                    return None;
                }
                Channel::Light(k)
            }
        })
    }

    /// The channel of `data` in the wire format.
    pub fn encode(self, data: &DataFile) -> Vec<u8> {
        let (w, h) = (data.width, data.height);
        let records = &data.records[..(w * h).min(data.records.len())];
        let floats = |get: fn(&PixelRecord) -> f32| {
            let mut a = Array::new(w, h, SampleType::F32, 1);
            records.iter().for_each(|r| a.push_f32(get(r)));
            a.finish()
        };
        match self {
            Channel::Id => {
                let objects = data.header.object_names.len();
                let kind = id_type(objects);
                let mut a = Array::new(w, h, kind, 1);
                for r in records {
                    let id = id_code(r, objects);
                    match kind {
                        SampleType::U8 => a.push_u8(id as u8),
                        SampleType::U16 => a.push_u16(id as u16),
                        _ => a.push_u32(id),
                    }
                }
                a.finish()
            }
            Channel::U => floats(|r| r.u),
            Channel::V => floats(|r| r.v),
            Channel::G => floats(|r| r.g),
            Channel::TEmit => floats(|r| r.t_emit),
            Channel::CosI => {
                let mut a = Array::new(w, h, SampleType::U16, 1);
                for r in records {
                    a.push_u16((shade::colour::clamp01(r.cos_i) * 65535.0).round() as u16);
                }
                a.finish()
            }
            Channel::Pol | Channel::Dir => {
                let mut a = Array::new(w, h, SampleType::F32, 3);
                for r in records {
                    let v = if self == Channel::Pol { r.pol } else { r.dir };
                    v.into_iter().for_each(|c| a.push_f32(c));
                }
                a.finish()
            }
            Channel::Light(k) => {
                let mut a = Array::new(w, h, SampleType::F32, 1);
                let plane = data.lights.get(k).map_or(&[][..], |p| &p[..]);
                for i in 0..records.len() {
                    a.push_f32(plane.get(i).copied().unwrap_or(0.0));
                }
                a.finish()
            }
        }
    }
}

/// The smallest sample type that holds every id of a file with `objects` objects.
pub fn id_type(objects: usize) -> SampleType {
    let largest = objects as u64 + u64::from(ID_FIRST_OBJECT) - 1;
    if largest <= u64::from(u8::MAX) {
        SampleType::U8
    } else if largest <= u64::from(u16::MAX) {
        SampleType::U16
    } else {
        SampleType::U32
    }
}

/// What pixel record `r` shows, as an id (the module's table); `objects` is the number of
/// objects the file names.
pub fn id_code(r: &PixelRecord, objects: usize) -> u32 {
    match r.status {
        RayStatus::Failed => ID_FAILED,
        RayStatus::StepBudget | RayStatus::WorkLimit => ID_STEP_BUDGET,
        RayStatus::NotTraced => ID_NOT_TRACED,
        RayStatus::Hit | RayStatus::Escaped => match usize::try_from(r.object) {
            Err(_) => ID_BACKGROUND,
            Ok(k) if k < objects => ID_FIRST_OBJECT + k as u32,
            Ok(_) => ID_FAILED,
        },
    }
}

/// A texture as the page's shader draws it: the procedural kinds with their parameters, or
/// an image the page fetches by name from `/api/gpu/image/NAME`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum GpuTexture {
    Checker {
        rows: u32,
        cols: u32,
    },
    Gradient,
    Uniform {
        color: [f32; 3],
    },
    Image {
        image: String,
        width: usize,
        height: usize,
    },
}

/// Name of the built-in earth image.
pub const EARTH: &str = "earth";

/// The name of object `k`'s scene image.
pub fn scene_image_name(k: usize) -> String {
    format!("scene-{k}")
}

/// The page's description of object `k`'s runtime texture.
pub fn describe_texture(k: usize, texture: &Texture) -> GpuTexture {
    match texture {
        Texture::Checker { rows, cols } => GpuTexture::Checker {
            rows: *rows,
            cols: *cols,
        },
        Texture::Gradient => GpuTexture::Gradient,
        Texture::Uniform(color) => GpuTexture::Uniform { color: *color },
        Texture::Image(image) => GpuTexture::Image {
            image: scene_image_name(k),
            width: image.width(),
            height: image.height(),
        },
    }
}

/// An image texture as 8-bit sRGB RGB samples, row 0 at the top (v = 1).
pub fn encode_image(image: &shade::ImageTexture) -> Vec<u8> {
    let mut a = Array::new(image.width(), image.height(), SampleType::U8, 3);
    for px in image.srgb8() {
        px.iter().for_each(|&c| a.push_u8(c));
    }
    a.finish()
}

/// The black-body tables of the `shade` crate, as the page reads them (`/api/gpu/blackbody`):
/// the 1-D table in g·T that the per-pixel colour comes from (its entries are the binary
/// array of [`encode_gt_table`]), and the log-spaced grid that colours the reference squares,
/// gives each object's unshifted luminance and colours g·T outside the table's range.
#[derive(Clone, Debug, Serialize)]
pub struct Blackbody {
    pub t_min: f64,
    pub t_max: f64,
    /// Bin of T: the f32 bit pattern of T shifted right by this.
    pub gt_shift: u32,
    /// Bin of the first entry.
    pub gt_first_bin: u32,
    pub gt_bins: usize,
    /// ln T of the grid's first node, and the step in ln T.
    pub ln_t_min: f64,
    pub step: f64,
    /// Linear sRGB at luminance 1 per node.
    pub unit: Vec<[f64; 3]>,
    /// ln Y per node.
    pub ln_y: Vec<f64>,
}

pub fn blackbody() -> Blackbody {
    let (ln_t_min, step) = table().grid();
    let (unit, ln_y) = table().nodes().unzip();
    Blackbody {
        t_min: T_MIN,
        t_max: T_MAX,
        gt_shift: SHIFT,
        gt_first_bin: gt_table().first_bin(),
        gt_bins: gt_table().entries().len(),
        ln_t_min,
        step,
        unit,
        ln_y,
    }
}

/// The table in g·T as a `bins` × 2 array of f32 RGBA: row 0 the colour at luminance 1 and the
/// luminance Y, row 1 the normalized colour (largest component 1) and 0.
pub fn encode_gt_table() -> Vec<u8> {
    let entries = gt_table().entries();
    let mut a = Array::new(entries.len(), 2, SampleType::F32, 4);
    for e in entries {
        e.unit.iter().for_each(|&c| a.push_f32(c));
        a.push_f32(e.luminance as f32);
    }
    for e in entries {
        e.normalized.iter().for_each(|&c| a.push_f32(c));
        a.push_f32(0.0);
    }
    a.finish()
}
