//! Split renders for array jobs: the part file of part `i/N` of an image (`crate::plan::Part`) (a full-size data file whose other pixels are "not traced",
//! with header attributes naming the part and a fingerprint of what was rendered), and
//! the merge that checks the parts belong together and joins them.
//!
//! Tiles are dealt round-robin (tile k goes to part k mod N + 1), not in stripes, so
//! that the costly rays near the horizon spread over all parts.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use exr::prelude::{AttributeValue, Text};
use sha2::{Digest, Sha256};

use crate::plan::{tiles, Part};
use crate::tiles::{extract, insert, pixel_indices};
use datafile::atomic::write_atomically;
use datafile::{attr, DataFile, DataFileError, DataFileErrorKind, RayStatus, FORMAT_VERSION};
use scene::Scene;

/// Hex SHA-256 of everything that decides a render's pixels: the scene text (camera and
/// trace settings included), the camera as understood, the samples per pixel (which
/// `--samples` may set), the program and format versions.
pub fn fingerprint(scene: &Scene) -> String {
    let samples = format!("samples {}", scene.samples);
    fingerprint_of(&[&scene.source_text, &scene.camera.describe(), &samples])
}

/// Hex SHA-256 of `fields` (each length-prefixed) and the program and format versions.
pub fn fingerprint_of(fields: &[&str]) -> String {
    let mut hash = Sha256::new();
    let versions = [
        env!("CARGO_PKG_VERSION").to_string(),
        FORMAT_VERSION.to_string(),
    ];
    for field in fields
        .iter()
        .copied()
        .chain(versions.iter().map(String::as_str))
    {
        hash.update((field.len() as u64).to_le_bytes());
        hash.update(field.as_bytes());
    }
    hash.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// A part file as read back.
#[derive(Debug)]
pub struct PartFile {
    pub path: PathBuf,
    pub part: Part,
    pub fingerprint: String,
    pub scene_path: String,
    pub data: DataFile,
}

/// Writes part `part` of a render atomically.
pub fn write_part(
    path: &Path,
    data: &DataFile,
    part: Part,
    fingerprint: &str,
    scene_path: &str,
) -> Result<(), DataFileError> {
    let at = |kind| DataFileError {
        path: path.to_path_buf(),
        kind,
    };
    let bytes = data
        .to_bytes_with(&[
            (attr::PART, part.to_string()),
            (attr::FINGERPRINT, fingerprint.to_string()),
            (attr::SCENE_PATH, scene_path.to_string()),
        ])
        .map_err(at)?;
    write_atomically(path, |f| std::io::Write::write_all(f, &bytes))
        .map_err(|e| at(DataFileErrorKind::Io(e)))
}

/// Why parts cannot be merged. Every message names the file(s).
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    #[error(transparent)]
    Read(#[from] DataFileError),
    #[error("{}: not a part file (no `{}` attribute): write parts with `godel render --part i/N`", .0.display(), attr::PART)]
    NotAPart(PathBuf),
    #[error("{}: header attribute `{name}`: {problem}", path.display())]
    BadAttribute {
        path: PathBuf,
        name: &'static str,
        problem: String,
    },
    #[error("no part files given")]
    Empty,
    #[error("{} and {} are not parts of the same render ({what} differ)", a.display(), b.display())]
    Mismatch {
        a: PathBuf,
        b: PathBuf,
        what: &'static str,
    },
    #[error("part {part} given twice: {} and {}", a.display(), b.display())]
    Duplicate { part: Part, a: PathBuf, b: PathBuf },
    #[error("part(s) {} of {count} missing (have {have} of {count})", missing.join(", "))]
    Missing {
        missing: Vec<String>,
        have: usize,
        count: u32,
    },
    #[error("{}: pixel (col {col}, row {row}) is traced but belongs to another part than {part}", path.display())]
    Overlap {
        path: PathBuf,
        part: Part,
        col: usize,
        row: usize,
    },
}

/// Reads a part file and its part attributes.
pub fn read_part(path: &Path) -> Result<PartFile, MergeError> {
    let bytes = scene::input::read_bounded(path, scene::input::MAX_DATA_BYTES).map_err(|e| {
        DataFileError {
            path: path.to_path_buf(),
            kind: DataFileErrorKind::Io(e),
        }
    })?;
    let data = DataFile::decode(&bytes, true).map_err(|kind| DataFileError {
        path: path.to_path_buf(),
        kind,
    })?;
    // Decoding succeeded, so the header is readable.
    let meta =
        exr::meta::MetaData::read_from_buffered(Cursor::new(&bytes), false).map_err(|e| {
            DataFileError {
                path: path.to_path_buf(),
                kind: DataFileErrorKind::Exr(e.to_string()),
            }
        })?;
    let header = &meta.headers[0];
    let text = |name: &'static str| -> Option<Result<String, MergeError>> {
        let key = Text::new_or_panic(name);
        let value = header
            .own_attributes
            .other
            .get(&key)
            .or_else(|| header.shared_attributes.other.get(&key))?;
        let bad = |problem: &str| MergeError::BadAttribute {
            path: path.to_path_buf(),
            name,
            problem: problem.into(),
        };
        Some(match value {
            AttributeValue::Text(t) => {
                String::from_utf8(t.bytes().to_vec()).map_err(|_| bad("not valid UTF-8"))
            }
            _ => Err(bad("not a text attribute")),
        })
    };
    let part_text = text(attr::PART).ok_or_else(|| MergeError::NotAPart(path.into()))??;
    let part = part_text
        .parse::<Part>()
        .map_err(|problem| MergeError::BadAttribute {
            path: path.into(),
            name: attr::PART,
            problem,
        })?;
    let missing = |name: &'static str| MergeError::BadAttribute {
        path: path.into(),
        name,
        problem: "missing".into(),
    };
    Ok(PartFile {
        path: path.into(),
        part,
        fingerprint: text(attr::FINGERPRINT).ok_or_else(|| missing(attr::FINGERPRINT))??,
        scene_path: text(attr::SCENE_PATH).ok_or_else(|| missing(attr::SCENE_PATH))??,
        data,
    })
}

/// Joins parts 1..N of one render into the data file a single run writes. Refuses parts
/// of different renders, a missing or repeated part, and a part with pixels of another.
pub fn merge(parts: &[PartFile]) -> Result<DataFile, MergeError> {
    let first = parts.first().ok_or(MergeError::Empty)?;
    for p in &parts[1..] {
        let mismatch = |what| MergeError::Mismatch {
            a: first.path.clone(),
            b: p.path.clone(),
            what,
        };
        if p.fingerprint != first.fingerprint {
            return Err(mismatch("scene, camera, settings or program version"));
        }
        if p.data.header != first.data.header
            || (p.data.width, p.data.height) != (first.data.width, first.data.height)
        {
            return Err(mismatch("data file headers"));
        }
        if p.part.count != first.part.count {
            return Err(mismatch("part counts"));
        }
    }
    let count = first.part.count;
    let mut by_index: Vec<Option<&PartFile>> = vec![None; count as usize];
    for p in parts {
        let slot = &mut by_index[(p.part.index - 1) as usize];
        if let Some(a) = slot {
            return Err(MergeError::Duplicate {
                part: p.part,
                a: a.path.clone(),
                b: p.path.clone(),
            });
        }
        *slot = Some(p);
    }
    let missing: Vec<String> = (1..=count)
        .filter(|&i| by_index[(i - 1) as usize].is_none())
        .map(|i| i.to_string())
        .collect();
    if !missing.is_empty() {
        return Err(MergeError::Missing {
            missing,
            have: parts.len(),
            count,
        });
    }

    let (w, h) = (first.data.width, first.data.height);
    let all = tiles(w as u32, h as u32);
    let mut merged = first.data.clone();
    merged.lights.clear();
    for (k, &tile) in all.iter().enumerate() {
        for p in parts {
            if p.part.has_tile(k) {
                insert(&mut merged, tile, &extract(&p.data, tile, k));
            } else if let Some(i) =
                pixel_indices(tile, w).find(|&i| p.data.records[i].status != RayStatus::NotTraced)
            {
                return Err(MergeError::Overlap {
                    path: p.path.clone(),
                    part: p.part,
                    col: i % w,
                    row: i / w,
                });
            }
        }
    }
    Ok(merged)
}
