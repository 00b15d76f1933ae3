//! A stereo pair's two pictures as one (`[camera] stereo` layouts, docs/guide/src/scenes.md):
//! side by side (left eye on the left), over-under (left eye on top), or an anaglyph for
//! red/cyan glasses; and, for one eye's data file, the other eye's ([`partner`]), as
//! `godel shade` and `godel view` find it.

use std::path::{Path, PathBuf};

use datafile::{DataFile, DataFileError};
use image::{Rgb, RgbImage};
use scene::{Eye, Layout, Stereo};

/// The other eye of a stereo pair, found beside one eye's data file and checked to be the
/// other eye of the same pair.
pub struct Partner {
    /// Which eye the given data file is (the partner is the other).
    pub eye: Eye,
    /// The pair's layout (`[camera] stereo`'s).
    pub layout: Layout,
    /// The other eye's data file's path: `NAME.right.exr` beside `NAME.left.exr`, and the
    /// other way round.
    pub path: PathBuf,
    /// The other eye's data file.
    pub data: DataFile,
}

impl Partner {
    /// The two eyes' things in order, left first: `mine` of the given file, `theirs` of the
    /// partner.
    pub fn left_right<T>(&self, mine: T, theirs: T) -> (T, T) {
        match self.eye {
            Eye::Left => (mine, theirs),
            Eye::Right => (theirs, mine),
        }
    }
}

/// Why the other eye of a stereo pair cannot be had; each names the file concerned.
#[derive(Debug, thiserror::Error)]
pub enum PartnerError {
    /// The file's name does not say which eye it is, so the other's cannot be named.
    #[error(
        "{} is the {} eye of a stereo pair, but its name does not say so (NAME.{}.exr): the \
         other eye's file cannot be found",
        path.display(), eye.name(), eye.name()
    )]
    Unnamed { path: PathBuf, eye: Eye },
    /// No file where the other eye's should be.
    #[error(
        "{} is the {} eye of a stereo pair; the {} eye's {} is missing",
        path.display(), eye.name(), other(*eye).name(), partner.display()
    )]
    Missing {
        path: PathBuf,
        eye: Eye,
        partner: PathBuf,
    },
    /// The other eye's file does not read.
    #[error(transparent)]
    Read(#[from] DataFileError),
    /// The file there is not the other eye of the same pair (another pair, the same eye, a
    /// mono file, other objects).
    #[error("{} is not the other eye of the same stereo pair", partner.display())]
    NotPartner { partner: PathBuf },
}

impl PartnerError {
    /// Whether the other eye's file is simply not there (or cannot be named): the given eye
    /// can still be shown alone.
    pub fn is_missing(&self) -> bool {
        matches!(
            self,
            PartnerError::Missing { .. } | PartnerError::Unnamed { .. }
        )
    }
}

fn other(eye: Eye) -> Eye {
    match eye {
        Eye::Left => Eye::Right,
        Eye::Right => Eye::Left,
    }
}

/// The other eye of the stereo pair whose eye `data` (read from `path`) is, read and checked:
/// its file is `path` with `.left.` and `.right.` swapped in its name, its embedded scene is
/// the other eye of the same pair (same separation, layout and convergence) and it sees the
/// same objects. `None` for a data file that is not one eye of a pair.
pub fn partner(path: &Path, data: &DataFile) -> Result<Option<Partner>, PartnerError> {
    // Only a data file whose embedded scene says it is one eye is one of a pair; one whose
    // scene's camera does not read (an older or a synthetic file) is shown as it is.
    let ours = scene::stereo_from_str(&data.header.scene_text, "").unwrap_or(None);
    let Some((ours, eye)) = ours.and_then(|s| s.eye.map(|e| (s, e))) else {
        return Ok(None);
    };
    let (mine, theirs) = (eye.name(), other(eye).name());
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let Some(at) = name.rfind(&format!(".{mine}.")) else {
        return Err(PartnerError::Unnamed {
            path: path.to_path_buf(),
            eye,
        });
    };
    let partner_name = format!("{}.{theirs}.{}", &name[..at], &name[at + mine.len() + 2..]);
    let partner = path.with_file_name(partner_name);
    if !partner.exists() {
        return Err(PartnerError::Missing {
            path: path.to_path_buf(),
            eye,
            partner,
        });
    }
    let other_data = DataFile::read(&partner)?;
    let their = scene::stereo_from_str(&other_data.header.scene_text, "").unwrap_or(None);
    let pair = |s: Stereo| Stereo { eye: None, ..s };
    let same_pair = their.is_some_and(|t| t.eye == Some(other(eye)) && pair(t) == pair(ours));
    if !same_pair || other_data.header.object_names != data.header.object_names {
        return Err(PartnerError::NotPartner { partner });
    }
    Ok(Some(Partner {
        eye,
        layout: ours.layout,
        path: partner,
        data: other_data,
    }))
}

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
