//! [`ShadeError`]: everything that can go wrong while loading textures and writing shaded images.
//! Every variant names the file concerned, so that a message alone tells the user what to fix.

use std::path::PathBuf;

/// An error of the `shade` crate.
#[derive(Debug, thiserror::Error)]
pub enum ShadeError {
    /// An image texture file could not be read or decoded.
    #[error("image texture {}: {source}", one_line(path.display()))]
    ImageRead {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    /// An image texture path names something other than a regular file (a folder, a FIFO,
    /// a device).
    #[error("image texture {}: not a regular file", one_line(path.display()))]
    ImageNotFile { path: PathBuf },
    /// An image texture file or image is larger than the caps.
    #[error("image texture {}: {}", one_line(path.display()), one_line(what))]
    ImageTooLarge { path: PathBuf, what: String },
    /// An image texture path that the texture source does not allow: missing, outside its
    /// folders (symbolic links resolved), or not a regular file. The message says no more, so
    /// that it reveals nothing about files elsewhere.
    #[error("image texture {}: no image file of that name in the folders textures may come from", one_line(path.display()))]
    ImageRefused { path: PathBuf },
    /// A folder given as a place textures may come from cannot be used.
    #[error("texture folder {}: {}", one_line(path.display()), one_line(message))]
    TextureFolder { path: PathBuf, message: String },
    /// A built-in image failed to decode (a broken build, never user input).
    #[error("built-in image {name}: {source}")]
    Builtin {
        name: &'static str,
        #[source]
        source: image::ImageError,
    },
    /// An image texture has zero width or height.
    #[error("image texture {}: the image is empty ({width}×{height})", one_line(path.display()))]
    EmptyImage {
        path: PathBuf,
        width: u32,
        height: u32,
    },
    /// The data file was not traced from this scene: its object list differs.
    #[error("the data file's objects {data:?} do not match the scene's objects {scene:?}")]
    ObjectMismatch {
        data: Vec<String>,
        scene: Vec<String>,
    },
    /// Encoding an output image failed.
    #[error("encoding {}: {source}", one_line(path.display()))]
    Encode {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    /// Encoding an OpenEXR picture failed.
    #[error("encoding {}: {}", one_line(path.display()), one_line(message))]
    Exr { path: PathBuf, message: String },
    /// Writing an output file failed (nothing was left at `path`).
    #[error("writing {}: {source}", one_line(path.display()))]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A settings value is invalid (field path such as `objects.ball.temperature`).
    #[error("shade settings: {}: {}", one_line(field), one_line(message))]
    Invalid { field: String, message: String },
    /// A settings file is malformed or names unknown fields.
    #[error("{}{}{}: {}", one_line(file), line_suffix(*line), field_suffix(field), one_line(message))]
    Settings {
        file: String,
        /// 1-based; 0 when unknown.
        line: usize,
        field: String,
        message: String,
    },
    /// A sequence script is malformed, names unknown fields, or has keyframes out of order.
    #[error("{}{}{}: {}", one_line(file), line_suffix(*line), field_suffix(field), one_line(message))]
    Script {
        file: String,
        /// 1-based; 0 when unknown.
        line: usize,
        field: String,
        message: String,
    },
    /// The light shader was asked for, but the data file carries no `light_k` channels.
    #[error("the light shader needs light channels (light_0, light_1, …), and this data file has none: render a scene with [[light]] sources")]
    NoLightChannels,
    /// The scene embedded in the data file does not validate here (e.g. an image texture
    /// path that does not resolve from the current directory).
    #[error("the scene embedded in the data file: {0} (choose another texture for that object)")]
    EmbeddedScene(scene::SceneError),
}

fn line_suffix(line: usize) -> String {
    if line > 0 {
        format!(":{line}")
    } else {
        String::new()
    }
}

fn field_suffix(field: &str) -> String {
    if field.is_empty() {
        String::new()
    } else {
        format!(": {}", one_line(field))
    }
}

/// Text from the user (paths, names, values quoted in messages) kept on one line.
fn one_line(text: impl std::fmt::Display) -> String {
    scene::one_line(&text.to_string())
}
