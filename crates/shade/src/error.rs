//! [`ShadeError`]: everything that can go wrong while loading textures and writing shaded images.
//! Every variant names the file concerned, so that a message alone tells the user what to fix.

use std::path::PathBuf;

/// An error of the `shade` crate.
#[derive(Debug, thiserror::Error)]
pub enum ShadeError {
    /// An image texture file could not be read or decoded.
    #[error("image texture {}: {source}", path.display())]
    ImageRead {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    /// A built-in image failed to decode (a broken build, never user input).
    #[error("built-in image {name}: {source}")]
    Builtin {
        name: &'static str,
        #[source]
        source: image::ImageError,
    },
    /// An image texture has zero width or height.
    #[error("image texture {}: the image is empty ({width}×{height})", path.display())]
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
    #[error("encoding {}: {source}", path.display())]
    Encode {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    /// Writing an output file failed (nothing was left at `path`).
    #[error("writing {}: {source}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}
