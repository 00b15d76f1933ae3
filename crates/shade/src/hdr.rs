//! Picture files by extension: `.png` (8-bit sRGB through exposure and the display tone curve,
//! overlays drawn) or `.exr` (linear, scene-referred RGB as 32-bit float channels R, G, B:
//! the shaded colours before exposure compensation and tone curve, without overlays; pixels
//! that hit nothing or failed hold their status colours). Both are written atomically
//! (`datafile::atomic`), so a failed write leaves nothing at the path.

use std::path::Path;

use exr::prelude::{AnyChannel, Compression, FlatSamples, LayerAttributes};

use crate::error::ShadeError;

/// The picture formats `godel shade` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PictureFormat {
    Png,
    Exr,
}

impl PictureFormat {
    /// The format a path's extension names (case-insensitive), or `None` for any other.
    pub fn from_path(path: &Path) -> Option<PictureFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(PictureFormat::Png),
            "exr" => Some(PictureFormat::Exr),
            _ => None,
        }
    }
}

/// The OpenEXR file (in memory) of a `width` × `height` linear RGB picture, row-major with
/// row 0 at the top; `path` only names it in errors.
pub fn encode_exr(
    rgb: &[[f32; 3]],
    width: usize,
    height: usize,
    path: &Path,
) -> Result<Vec<u8>, ShadeError> {
    let fail = |message: String| ShadeError::Exr {
        path: path.to_path_buf(),
        message,
    };
    if rgb.len() != width * height || rgb.is_empty() {
        return Err(fail(format!(
            "{} pixels for a {width}×{height} picture",
            rgb.len()
        )));
    }
    let plane = |k: usize| FlatSamples::F32(rgb.iter().map(|c| c[k]).collect());
    let channels = vec![
        AnyChannel::new("R", plane(0)),
        AnyChannel::new("G", plane(1)),
        AnyChannel::new("B", plane(2)),
    ];
    let attributes = LayerAttributes::default();
    datafile::exr_bytes((width, height), attributes, Compression::ZIP16, channels).map_err(fail)
}

/// Writes bytes to `path` atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), ShadeError> {
    datafile::atomic::write_atomically(path, |file| std::io::Write::write_all(file, bytes)).map_err(
        |source| ShadeError::Write {
            path: path.to_path_buf(),
            source,
        },
    )
}
