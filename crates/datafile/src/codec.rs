//! The per-pixel data file: one OpenEXR file per traced image
//! (docs/guide/src/data-file.md), read back by the post-render shaders without re-tracing.
//!
//! # Format (format version 2)
//!
//! A single-part, scan-line OpenEXR image, RLE compressed (lossless, so a
//! round trip is exact), one channel per field of [`PixelRecord`]:
//!
//! | channel | type | content |
//! | --- | --- | --- |
//! | `object` | f32 | object index as an exact integer; −1 where nothing was hit |
//! | `status` | u32 | [`RayStatus::code`] |
//! | `u`, `v`, `g`, `t_emit`, `x`, `y`, `z`, `lambda`, `cos_i` | f32 | the field of the same name |
//! | `dir_x`, `dir_y`, `dir_z` | f32 | `dir[0]`, `dir[1]`, `dir[2]` |
//! | `view_x`, `view_y`, `view_z` | f32 | `view[0]`, `view[1]`, `view[2]` |
//! | `pol_x`, `pol_y`, `pol_z` | f32 | `pol[0]`, `pol[1]`, `pol[2]` (where [`DataFile::polarization`]) |
//! | `light_0`, `light_1`, … | f32 | [`DataFile::lights`]`[k]` |
//!
//! *Polarization* came later within format version 2: files written before have no `pol_*`
//! channels and read with [`DataFile::polarization`] false (all three or none: a file with
//! one or two of them is refused as damaged). Readers that do not know the channels ignore
//! them, as any channel not listed here, so the version did not change: every reader of
//! version 2 reads files with and without them.
//!
//! *No value where there is none:* where a record's status is not "hit", the physical
//! channels (`u` … `cos_i`, `dir_*`, `pol_*`, `light_k`) hold NaN, and where a pixel was not traced
//! `view_*` holds NaN too, so that an analysis that forgets to mask by `status` sees NaN
//! rather than plausible zeros. Reading turns them back into the in-memory convention of
//! [`PixelRecord::miss`] (zeros).
//!
//! *Samples:* with `godel.supersample` = s > 1 the image is s×s samples per picture pixel
//! (see `samples.rs`): the stored image is (W·s)×(H·s) and picture pixel (col, row) is
//! the block of samples (s·col + i, s·row + j), 0 ≤ i, j < s.
//!
//! `object` is f32, not u32, so that −1 is representable; object indices are
//! therefore limited to [`MAX_OBJECT`] (2^24), below which f32 holds every
//! integer exactly. Channels not listed here are ignored on reading.
//!
//! Pixel order: the data window starts at (0, 0); row 0 is the top row of the
//! image and column 0 its left column; samples are stored row-major, so pixel
//! (col, row) is element `row * width + col` of every plane (see
//! [`DataFile::index`]).
//!
//! Header: text attributes `godel.format_version`, `godel.scene_name`,
//! `godel.scene` (the whole scene file), `godel.camera`, `godel.observer_time`,
//! `godel.metric`, `godel.a`, `godel.method`, `godel.objects` (object names
//! joined by `\n`), `godel.supersample` (samples per picture pixel along each
//! side). Text is UTF-8; numbers are Rust's shortest round-trip
//! decimal form (`{:?}`), so f64 values survive exactly.
//!
//! Part files of a split render (`render::part`) carry `godel.part` too; reading
//! one as a whole data file is refused.
//!
//! Output is deterministic: the exr crate keeps custom attributes in a
//! `HashMap` and writes them in random order, so after encoding the header's
//! attributes are sorted by name (same total length: no offset moves).

use std::io::Cursor;
use std::path::{Path, PathBuf};

use exr::prelude::{
    AnyChannel, AttributeValue, Compression, FlatSamples, LayerAttributes, ReadChannels,
    ReadLayers, SmallVec, Text,
};

use crate::atomic::write_atomically;
use crate::exr_write::exr_bytes;
use crate::planes::{
    light_channel_name, Plane, PHYSICAL_CHANNELS, POLARIZATION_CHANNELS, VIEW_CHANNELS,
};
use crate::record::{PixelRecord, RayStatus};
use exr_header::{check_layout, sort_header_attributes};

mod exr_header;

/// The format version this code writes and reads.
pub const FORMAT_VERSION: u32 = 2;

/// Largest object index that the f32 `object` channel stores exactly.
pub const MAX_OBJECT: i32 = 1 << 24;

/// Names of the header attributes.
pub mod attr {
    pub const FORMAT_VERSION: &str = "godel.format_version";
    pub const SCENE_NAME: &str = "godel.scene_name";
    pub const SCENE: &str = "godel.scene";
    pub const CAMERA: &str = "godel.camera";
    pub const OBSERVER_TIME: &str = "godel.observer_time";
    pub const METRIC: &str = "godel.metric";
    pub const A: &str = "godel.a";
    pub const METHOD: &str = "godel.method";
    /// The Gödel-type member's m² (only for `metric = "godel-type"`).
    pub const M2: &str = "godel.m2";
    /// The Gödel-type member's vorticity Ω (only for `metric = "godel-type"`).
    pub const OMEGA: &str = "godel.omega";
    pub const OBJECTS: &str = "godel.objects";
    /// Samples per picture pixel along each side (s; s² rays per pixel).
    pub const SUPERSAMPLE: &str = "godel.supersample";
    /// Part files of a split render: `"i/N"`.
    pub const PART: &str = "godel.part";
    /// Part files: the fingerprint of what was rendered.
    pub const FINGERPRINT: &str = "godel.fingerprint";
    /// Part files: the scene file's path (empty for the built-in scene), to find its
    /// textures.
    pub const SCENE_PATH: &str = "godel.scene_path";
}

/// A member of the Gödel-type family: its constants m² and Ω.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Member {
    pub m2: f64,
    pub omega: f64,
}

/// Self-description of a data file: the scene and camera it was traced from.
#[derive(Clone, Debug, PartialEq)]
pub struct DataHeader {
    /// Always [`FORMAT_VERSION`] for files this code writes.
    pub format_version: u32,
    /// The scene's `name`.
    pub scene_name: String,
    /// The full scene file text.
    pub scene_text: String,
    /// Camera description.
    pub camera: String,
    /// Coordinate time of the observer; `t_emit` is relative to it.
    pub observer_time: f64,
    /// `"godel"`, `"minkowski"` or `"godel-type"`.
    pub metric: String,
    /// The Gödel scale parameter `a` (0 for the other metrics).
    pub godel_a: f64,
    /// The member of the Gödel-type family, exactly for `metric = "godel-type"`.
    pub member: Option<Member>,
    /// Tracing method (`"numeric"` or `"exact"`).
    pub method: String,
    /// Object names in scene-file order; `object` ids index this list.
    /// Names must be non-empty and contain no newline.
    pub object_names: Vec<String>,
    /// Samples per picture pixel along each side, 1 to [`crate::MAX_SUPERSAMPLE`]: the
    /// image's width and height are multiples of it (see [`DataFile::picture_size`]).
    pub supersample: u32,
}

/// A traced image's per-pixel data.
#[derive(Clone, Debug, PartialEq)]
pub struct DataFile {
    pub header: DataHeader,
    pub width: usize,
    pub height: usize,
    /// One record per pixel, row-major, row 0 at the top.
    pub records: Vec<PixelRecord>,
    /// One plane per light source, `width * height` values each, same order as
    /// `records`; may be empty.
    pub lights: Vec<Vec<f32>>,
    /// Whether the records carry the polarization channels (`pol`): true for everything
    /// this program traces; false for files written before it traced polarization (their
    /// records' `pol` is zero).
    pub polarization: bool,
}

/// What went wrong with a data file, and which file.
#[derive(Debug, thiserror::Error)]
#[error("data file {}: {kind}", path.display())]
pub struct DataFileError {
    pub path: PathBuf,
    pub kind: DataFileErrorKind,
}

/// What went wrong, without the file name.
#[derive(Debug, thiserror::Error)]
pub enum DataFileErrorKind {
    /// The operating system's word, as it is ("No such file or directory (os error 2)",
    /// "not a regular file (a directory)"): a prefix such as "input/output error" made a
    /// folder given for a data file read like a disk fault.
    #[error("{0}")]
    Io(std::io::Error),
    #[error("not an OpenEXR file (wrong magic number)")]
    NotExr,
    #[error("damaged or truncated OpenEXR file: {0}")]
    Exr(String),
    #[error("unsupported image layout: {0}")]
    Layout(String),
    #[error("missing channel `{0}`")]
    MissingChannel(String),
    #[error("channel `{channel}` has sample type {found}, expected {expected}")]
    ChannelType {
        channel: String,
        expected: &'static str,
        found: &'static str,
    },
    #[error("missing header attribute `{0}`")]
    MissingAttribute(&'static str),
    #[error("header attribute `{name}`: {problem}")]
    BadAttribute { name: &'static str, problem: String },
    #[error("unsupported format version {0} (this program reads version {FORMAT_VERSION})")]
    UnsupportedVersion(u32),
    #[error("part {0} of a split render (`godel render --part`), not a whole image: join the parts with `godel merge` first")]
    PartFile(String),
    #[error("inconsistent sizes: {0}")]
    Inconsistent(String),
    #[error("channel `{channel}` at column {col}, row {row}: {problem}")]
    BadValue {
        channel: &'static str,
        col: usize,
        row: usize,
        problem: String,
    },
}

impl DataFile {
    /// Index of pixel (`col`, `row`) in `records` and in each light plane.
    pub fn index(&self, col: usize, row: usize) -> usize {
        row * self.width + col
    }

    /// The record of pixel (`col`, `row`); panics if out of range.
    pub fn record(&self, col: usize, row: usize) -> &PixelRecord {
        assert!(
            col < self.width && row < self.height,
            "pixel ({col}, {row}) out of range"
        );
        &self.records[self.index(col, row)]
    }

    /// Writes the data file to `path` atomically (temporary file, then
    /// rename): on error nothing is left at `path`.
    pub fn write(&self, path: &Path) -> Result<(), DataFileError> {
        let at = |kind| DataFileError {
            path: path.to_path_buf(),
            kind,
        };
        let bytes = self.to_bytes().map_err(at)?;
        write_atomically(path, |file| std::io::Write::write_all(file, &bytes))
            .map_err(|e| at(DataFileErrorKind::Io(e)))
    }

    /// Reads and checks a data file (a regular file of at most
    /// [`scene::input::MAX_DATA_BYTES`]).
    pub fn read(path: &Path) -> Result<DataFile, DataFileError> {
        let at = |kind| DataFileError {
            path: path.to_path_buf(),
            kind,
        };
        let bytes = scene::input::read_bounded(path, scene::input::MAX_DATA_BYTES)
            .map_err(|e| at(DataFileErrorKind::Io(e)))?;
        DataFile::from_bytes(&bytes).map_err(at)
    }

    /// Checks that sizes, ids and header fields can be stored and read back.
    pub fn validate(&self) -> Result<(), DataFileErrorKind> {
        let h = &self.header;
        if h.format_version != FORMAT_VERSION {
            return Err(DataFileErrorKind::UnsupportedVersion(h.format_version));
        }
        let pixels = self.width.saturating_mul(self.height);
        if self.width == 0 || self.height == 0 || self.width > i32::MAX as usize / 2 {
            return inconsistent(format!("image size {}×{}", self.width, self.height));
        }
        let s = h.supersample;
        if s == 0 || s > crate::MAX_SUPERSAMPLE {
            return Err(DataFileErrorKind::BadAttribute {
                name: attr::SUPERSAMPLE,
                problem: format!("{s} is not in 1..={}", crate::MAX_SUPERSAMPLE),
            });
        }
        if !self.width.is_multiple_of(s as usize) || !self.height.is_multiple_of(s as usize) {
            return inconsistent(format!(
                "image size {}×{} is not a multiple of the supersampling {s}",
                self.width, self.height
            ));
        }
        if self.records.len() != pixels {
            return inconsistent(format!(
                "{} records for {}×{} pixels",
                self.records.len(),
                self.width,
                self.height
            ));
        }
        for (k, plane) in self.lights.iter().enumerate() {
            if plane.len() != pixels {
                return inconsistent(format!("light plane {k} has {} values", plane.len()));
            }
        }
        for name in &h.object_names {
            if name.is_empty() || name.contains('\n') {
                return Err(DataFileErrorKind::BadAttribute {
                    name: attr::OBJECTS,
                    problem: format!("object name {name:?} is empty or contains a newline"),
                });
            }
        }
        check_finite(attr::OBSERVER_TIME, h.observer_time)?;
        check_finite(attr::A, h.godel_a)?;
        match (h.metric == "godel-type", h.member) {
            (true, Some(m)) => {
                check_finite(attr::M2, m.m2)?;
                check_finite(attr::OMEGA, m.omega)?;
            }
            (true, None) => return Err(DataFileErrorKind::MissingAttribute(attr::M2)),
            (false, Some(_)) => {
                return Err(DataFileErrorKind::BadAttribute {
                    name: attr::M2,
                    problem: format!("given for the metric {:?}", h.metric),
                })
            }
            (false, None) => {}
        }
        for (i, r) in self.records.iter().enumerate() {
            let (col, row) = (i % self.width, i / self.width);
            check_object(r.object, h.object_names.len(), col, row)?;
        }
        Ok(())
    }

    /// Encodes the data file as OpenEXR bytes (deterministic).
    pub fn to_bytes(&self) -> Result<Vec<u8>, DataFileErrorKind> {
        self.to_bytes_with(&[])
    }

    /// [`DataFile::to_bytes`] with extra text attributes in the header (the part
    /// files of a split render carry theirs this way, see `render::part`).
    pub fn to_bytes_with(&self, extra: &[(&str, String)]) -> Result<Vec<u8>, DataFileErrorKind> {
        self.validate()?;
        let h = &self.header;
        let channels: Vec<AnyChannel<FlatSamples>> = self
            .planes()
            .into_iter()
            .map(|(name, plane)| {
                let samples = match plane {
                    Plane::F32(values) => FlatSamples::F32(values),
                    Plane::U32(values) => FlatSamples::U32(values),
                };
                AnyChannel::new(Text::new_or_panic(name), samples) // ASCII names
            })
            .collect();

        let mut attributes = LayerAttributes::default();
        let member = h.member.into_iter().flat_map(|m| {
            [
                (attr::M2, format!("{:?}", m.m2)),
                (attr::OMEGA, format!("{:?}", m.omega)),
            ]
        });
        let texts = [
            (attr::FORMAT_VERSION, h.format_version.to_string()),
            (attr::SCENE_NAME, h.scene_name.clone()),
            (attr::SCENE, h.scene_text.clone()),
            (attr::CAMERA, h.camera.clone()),
            (attr::OBSERVER_TIME, format!("{:?}", h.observer_time)),
            (attr::METRIC, h.metric.clone()),
            (attr::A, format!("{:?}", h.godel_a)),
            (attr::METHOD, h.method.clone()),
            (attr::OBJECTS, h.object_names.join("\n")),
            (attr::SUPERSAMPLE, h.supersample.to_string()),
        ];
        let extra = extra.iter().map(|(n, v)| (*n, v.clone()));
        for (name, value) in texts.into_iter().chain(member).chain(extra) {
            // exr's Text is a byte string; store UTF-8 bytes unchanged.
            let text = Text::from_bytes_unchecked(SmallVec::from_vec(value.into_bytes()));
            attributes
                .other
                .insert(Text::new_or_panic(name), AttributeValue::Text(text));
        }

        // RLE, chosen by measurement (BENCHMARKS.md, "Speed issue"): encoding is several
        // times faster than ZIP (which was ~35 % of a static scene's exact render after the
        // speed-ups). Its runs are those of the missed pixels' NaN (`planes::NO_VALUE`, whose
        // bytes repeat in pairs): the peer scene's file is 3.4 times smaller than raw.
        let size = (self.width, self.height);
        let mut bytes = exr_bytes(size, attributes, Compression::RLE, channels)
            .map_err(DataFileErrorKind::Exr)?;
        sort_header_attributes(&mut bytes).map_err(DataFileErrorKind::Exr)?;
        Ok(bytes)
    }

    /// Decodes and checks OpenEXR bytes. Never panics. Refuses the part files of a split
    /// render (see `render::part`), which are not whole images.
    pub fn from_bytes(bytes: &[u8]) -> Result<DataFile, DataFileErrorKind> {
        Self::decode(bytes, false)
    }

    /// [`DataFile::from_bytes`], also reading part files when `allow_part`.
    pub fn decode(bytes: &[u8], allow_part: bool) -> Result<DataFile, DataFileErrorKind> {
        if bytes.len() < 4 || bytes[..4] != [0x76, 0x2f, 0x31, 0x01] {
            return Err(DataFileErrorKind::NotExr);
        }
        check_layout(bytes)?;
        let image = exr::prelude::read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .pedantic()
            .from_buffered(Cursor::new(bytes))
            .map_err(|e| DataFileErrorKind::Exr(e.to_string()))?;
        let layer = &image.layer_data;
        let part = Text::new_or_panic(attr::PART);
        if let (false, Some(value)) = (allow_part, layer.attributes.other.get(&part)) {
            let text = match value {
                AttributeValue::Text(t) => String::from_utf8_lossy(t.bytes()).into_owned(),
                _ => "?".into(),
            };
            return Err(DataFileErrorKind::PartFile(text));
        }
        let (width, height) = (layer.size.x(), layer.size.y());
        let pixels = width.saturating_mul(height); // bounded by check_layout

        let text = |name: &'static str| -> Result<String, DataFileErrorKind> {
            let value = layer
                .attributes
                .other
                .get(&Text::new_or_panic(name))
                .or_else(|| image.attributes.other.get(&Text::new_or_panic(name)))
                .ok_or(DataFileErrorKind::MissingAttribute(name))?;
            let bad = |problem: &str| DataFileErrorKind::BadAttribute {
                name,
                problem: problem.to_string(),
            };
            match value {
                AttributeValue::Text(t) => {
                    String::from_utf8(t.bytes().to_vec()).map_err(|_| bad("not valid UTF-8"))
                }
                _ => Err(bad("not a text attribute")),
            }
        };
        let number = |name: &'static str| -> Result<f64, DataFileErrorKind> {
            let value: f64 =
                text(name)?
                    .trim()
                    .parse()
                    .map_err(|_| DataFileErrorKind::BadAttribute {
                        name,
                        problem: "not a number".into(),
                    })?;
            check_finite(name, value)?;
            Ok(value)
        };

        let version_text = text(attr::FORMAT_VERSION)?;
        let format_version: u32 =
            version_text
                .trim()
                .parse()
                .map_err(|_| DataFileErrorKind::BadAttribute {
                    name: attr::FORMAT_VERSION,
                    problem: format!("{version_text:?} is not a version number"),
                })?;
        if format_version != FORMAT_VERSION {
            return Err(DataFileErrorKind::UnsupportedVersion(format_version));
        }
        let objects = text(attr::OBJECTS)?;
        let object_names = if objects.is_empty() {
            Vec::new()
        } else {
            objects.split('\n').map(str::to_string).collect()
        };
        let header = DataHeader {
            format_version,
            scene_name: text(attr::SCENE_NAME)?,
            scene_text: text(attr::SCENE)?,
            camera: text(attr::CAMERA)?,
            observer_time: number(attr::OBSERVER_TIME)?,
            metric: text(attr::METRIC)?,
            godel_a: number(attr::A)?,
            member: None,
            method: text(attr::METHOD)?,
            object_names,
            supersample: text(attr::SUPERSAMPLE)?
                .trim()
                .parse::<u32>()
                .ok()
                .filter(|s| (1..=crate::MAX_SUPERSAMPLE).contains(s))
                .ok_or_else(|| DataFileErrorKind::BadAttribute {
                    name: attr::SUPERSAMPLE,
                    problem: format!("not a whole number in 1..={}", crate::MAX_SUPERSAMPLE),
                })?,
        };
        let mut header = header;
        if header.metric == "godel-type" {
            header.member = Some(Member {
                m2: number(attr::M2)?,
                omega: number(attr::OMEGA)?,
            });
        }
        if width % header.supersample as usize != 0 || height % header.supersample as usize != 0 {
            return inconsistent(format!(
                "image size {width}×{height} is not a multiple of the supersampling {}",
                header.supersample
            ));
        }

        let channel = |name: &str| -> Result<&FlatSamples, DataFileErrorKind> {
            let found = layer.channel_data.list.iter().find(|c| c.name.eq(name));
            let samples = &found.ok_or_else(|| DataFileErrorKind::MissingChannel(name.into()))?;
            if samples.sample_data.len() != pixels {
                return inconsistent(format!(
                    "channel `{name}` has {} samples for {width}×{height} pixels (subsampled?)",
                    samples.sample_data.len()
                ));
            }
            Ok(&samples.sample_data)
        };
        let f32_channel = |name: &str| -> Result<&[f32], DataFileErrorKind> {
            match channel(name)? {
                FlatSamples::F32(values) => Ok(values),
                other => Err(wrong_type(name, "f32", other)),
            }
        };

        let mut records = vec![PixelRecord::MISS; pixels];
        let objects = f32_channel("object")?;
        let status = match channel("status")? {
            FlatSamples::U32(values) => values,
            other => return Err(wrong_type("status", "u32", other)),
        };
        for (i, record) in records.iter_mut().enumerate() {
            let (col, row) = (i % width, i / width);
            let object = objects[i];
            if object.fract() != 0.0 || !(-1.0..=MAX_OBJECT as f32).contains(&object) {
                return Err(DataFileErrorKind::BadValue {
                    channel: "object",
                    col,
                    row,
                    problem: format!("{object} is not an object index"),
                });
            }
            record.object = object as i32;
            check_object(record.object, header.object_names.len(), col, row)?;
            record.status =
                RayStatus::from_code(status[i]).ok_or_else(|| DataFileErrorKind::BadValue {
                    channel: "status",
                    col,
                    row,
                    problem: format!("unknown status code {}", status[i]),
                })?;
        }
        // Records without an emission (or not traced) keep the zeros of `PixelRecord::miss`
        // where the file has NaN.
        for (name, _, set) in PHYSICAL_CHANNELS {
            for (record, &value) in records.iter_mut().zip(f32_channel(name)?) {
                if record.has_emission() {
                    set(record, value);
                }
            }
        }
        for (name, _, set) in VIEW_CHANNELS {
            for (record, &value) in records.iter_mut().zip(f32_channel(name)?) {
                if record.status != RayStatus::NotTraced {
                    set(record, value);
                }
            }
        }
        // All three polarization channels or none (a file written before them).
        let present = POLARIZATION_CHANNELS.map(|(name, _, _)| f32_channel(name));
        let polarization = present
            .iter()
            .any(|c| !matches!(c, Err(DataFileErrorKind::MissingChannel(_))));
        if polarization {
            for ((_, _, set), values) in POLARIZATION_CHANNELS.into_iter().zip(present) {
                for (record, &value) in records.iter_mut().zip(values?) {
                    if record.has_emission() {
                        set(record, value);
                    }
                }
            }
        }

        let mut lights = Vec::new();
        while let Ok(values) = f32_channel(&light_channel_name(lights.len())) {
            let values = records.iter().zip(values);
            lights.push(
                values
                    .map(|(r, &v)| if r.has_emission() { v } else { 0.0 })
                    .collect(),
            );
        }
        // A light channel that is present but unreadable is an error, not the end.
        f32_channel(&light_channel_name(lights.len()))
            .map(|_| ())
            .or_else(|e| match e {
                DataFileErrorKind::MissingChannel(_) => Ok(()),
                e => Err(e),
            })?;

        Ok(DataFile {
            header,
            width,
            height,
            records,
            lights,
            polarization,
        })
    }
}

fn inconsistent<T>(problem: String) -> Result<T, DataFileErrorKind> {
    Err(DataFileErrorKind::Inconsistent(problem))
}

fn wrong_type(channel: &str, expected: &'static str, found: &FlatSamples) -> DataFileErrorKind {
    let found = match found {
        FlatSamples::F16(_) => "f16",
        FlatSamples::F32(_) => "f32",
        FlatSamples::U32(_) => "u32",
    };
    DataFileErrorKind::ChannelType {
        channel: channel.to_string(),
        expected,
        found,
    }
}

fn check_finite(name: &'static str, value: f64) -> Result<(), DataFileErrorKind> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(DataFileErrorKind::BadAttribute {
            name,
            problem: format!("{value} is not finite"),
        })
    }
}

/// An object id must be −1 or index one of the `count` named objects.
fn check_object(
    object: i32,
    count: usize,
    col: usize,
    row: usize,
) -> Result<(), DataFileErrorKind> {
    if object == PixelRecord::NO_OBJECT || (object >= 0 && (object as usize) < count) {
        return Ok(());
    }
    Err(DataFileErrorKind::BadValue {
        channel: "object",
        col,
        row,
        problem: format!("object {object} is not −1 or an index of the {count} objects"),
    })
}
