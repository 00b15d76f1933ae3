//! `shade`: the post-render stage — shading per-pixel data files into pictures without
//! re-tracing (docs/guide/src/shading.md).
//!
//! Main types and functions:
//! - [`ShadeSettings`]: every shader parameter (serde; TOML files, keyframes, the viewer),
//!   with [`ShadeSettings::defaults_for`] a data file.
//! - [`Shading`]: settings checked against a data file with textures loaded;
//!   [`Shading::image`] / [`Shading::image_into`] shade it (texture, frequency, time and light
//!   layers, combined by multiplication; see [`shading`]).
//! - [`Channels`]: the channels shading reads, copied once per data file into flat planes;
//!   [`Shading::image_into_with`] / [`Shading::image_with`] shade from it (the same bytes as
//!   from the records; the viewer's and `godel sequence`'s path).
//! - [`Script`], [`Timeline`], [`Track`], [`keyframe_toml`]: sequence scripts with keyframed
//!   settings, observer and camera.
//! - [`Texture`]: a runtime texture (checker, gradient, uniform, equirectangular image such as
//!   the built-in earth) built from a scene's `TextureSpec` with [`Texture::load`], sampled at
//!   body coordinates (u, v) in linear RGB.
//! - [`TextureSource`]: where image textures may be read from — any file (the command line) or
//!   only regular files inside given folders (the viewer); reads are capped
//!   ([`MAX_IMAGE_FILE_BYTES`], [`MAX_IMAGE_SIDE`]).
//! - [`shade_textures`] / [`preview`]: the texture shader, a [`datafile::DataFile`] to
//!   an 8-bit sRGB image; [`write_png`] writes it atomically.
//! - [`blackbody`]: Planck's law, CIE 1931 XYZ, XYZ → linear sRGB, and the black-body
//!   colour table in temperature used by the frequency shader.
//! - [`shade_frequency`]: the frequency shader, objects as black bodies at g·T with
//!   [`Brightness`] normalized or physical, and reference squares of the unshifted colours.
//! - [`layer`]: the overlay layer (orientation marks, legend, labels) as one RGBA image,
//!   composited over the picture here and over the GPU's picture by the viewer; its text in
//!   the embedded typeface ([`text`]), laid out so that no two labels overlap ([`placement`]).
//! - [`polarization`]: the polarization layer's ticks along the observed polarization,
//!   coloured by its angle (legend in the overlay layer).
//! - [`colour`]: linear ↔ sRGB transfer functions and 8-bit conversion.
//! - [`stereo`]: a stereo pair's two pictures in one layout ([`stereo::compose`]), and the
//!   other eye's data file beside one eye's ([`stereo::partner`]).
//! - [`ShadeError`]: every error, naming the file or field concerned.

pub mod blackbody;
mod body;
pub mod channels;
mod checks;
pub mod colour;
mod error;
pub mod frequency_shader;
pub mod gt_table;
pub mod hdr;
pub mod layer;
pub mod legend;
pub mod marks;
pub mod placement;
pub mod polarization;
pub mod script;
pub mod settings;
pub mod shading;
pub mod stereo;
pub mod text;
pub mod texture;
pub mod texture_shader;
pub mod texture_source;
mod tree;

pub use channels::{Channels, Needs, Sample};
pub use error::ShadeError;
pub use frequency_shader::{shade_frequency, Brightness};
pub use script::{
    keyframe_toml, FrameSource, Interpolation, Keyframe, Script, Section, Timeline, Track,
    CAMERA_KEYS,
};
pub use settings::{
    BrightnessMode, Lamp, LightSettings, LightSource, ObjectSettings, ShadeSettings, ShaderKind,
    TextureChoice, TimeMode, TimeSettings, MAX_LAMPS, MAX_LIGHT_SOURCES,
};
pub use shading::Shading;
pub use texture::{ImageTexture, Texture, MAX_IMAGE_FILE_BYTES, MAX_IMAGE_SIDE};
pub use texture_shader::{
    encode_png, pixel_colour, preview, shade_textures, shading_factor, textures_for_scene,
    write_png, BACKGROUND,
};
pub use texture_source::TextureSource;
