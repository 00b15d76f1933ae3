//! The data file's channels as named planes of values, exactly as the file stores them
//! (docs/guide/src/data-file.md): what the EXR encoder writes, and what other readers of a
//! traced image in memory (the Python module) hand out, so that both hold the same numbers.
//!
//! *No value where there is none:* the physical channels (`u` … `cos_i`, `dir_*`, `light_k`)
//! hold NaN where a record's status is not "hit", and `view_*` holds NaN where a pixel was not
//! traced; `object` (−1 for none) and `status` are always set. The table of channels
//! ([`PHYSICAL_CHANNELS`], [`VIEW_CHANNELS`], [`POLARIZATION_CHANNELS`]) also says how reading puts each back into a
//! [`PixelRecord`].

use crate::record::{PixelRecord, RayStatus};
use crate::DataFile;
use rayon::prelude::*;

/// Reading a record field as f32.
pub type Get = fn(&PixelRecord) -> f32;
/// Writing a record field from f32.
pub type Set = fn(&mut PixelRecord, f32);

/// The physical f32 channels (NaN in the file where the status is not "hit"), with their
/// record fields.
pub const PHYSICAL_CHANNELS: [(&str, Get, Set); 12] = [
    ("u", |r| r.u, |r, s| r.u = s),
    ("v", |r| r.v, |r, s| r.v = s),
    ("g", |r| r.g, |r, s| r.g = s),
    ("t_emit", |r| r.t_emit, |r, s| r.t_emit = s),
    ("x", |r| r.x, |r, s| r.x = s),
    ("y", |r| r.y, |r, s| r.y = s),
    ("z", |r| r.z, |r, s| r.z = s),
    ("lambda", |r| r.lambda, |r, s| r.lambda = s),
    ("dir_x", |r| r.dir[0], |r, s| r.dir[0] = s),
    ("dir_y", |r| r.dir[1], |r, s| r.dir[1] = s),
    ("dir_z", |r| r.dir[2], |r, s| r.dir[2] = s),
    ("cos_i", |r| r.cos_i, |r, s| r.cos_i = s),
];

/// The camera ray's direction (NaN in the file where the pixel was not traced).
pub const VIEW_CHANNELS: [(&str, Get, Set); 3] = [
    ("view_x", |r| r.view[0], |r, s| r.view[0] = s),
    ("view_y", |r| r.view[1], |r, s| r.view[1] = s),
    ("view_z", |r| r.view[2], |r, s| r.view[2] = s),
];

/// The polarization channels (NaN in the file where the status is not "hit"; present only in
/// files with [`DataFile::polarization`]).
pub const POLARIZATION_CHANNELS: [(&str, Get, Set); 3] = [
    ("pol_x", |r| r.pol[0], |r, s| r.pol[0] = s),
    ("pol_y", |r| r.pol[1], |r, s| r.pol[1] = s),
    ("pol_z", |r| r.pol[2], |r, s| r.pol[2] = s),
];

/// The NaN stored where there is no value: a quiet NaN whose bytes repeat in pairs
/// (c0 7f c0 7f), so that OpenEXR's RLE, which splits a block's bytes into the even and the
/// odd ones before looking for runs, finds runs in a stretch of them. (The usual NaN,
/// 00 00 c0 7f, gives alternating halves and no runs: the data files did not shrink at all.)
pub const NO_VALUE: f32 = f32::from_bits(0x7fc0_7fc0);

/// Name of the channel holding light plane `k`.
pub fn light_channel_name(k: usize) -> String {
    format!("light_{k}")
}

/// The values of one channel, one per record, row-major.
#[derive(Clone, Debug, PartialEq)]
pub enum Plane {
    F32(Vec<f32>),
    U32(Vec<u32>),
}

/// Records per block of [`DataFile::planes`]: a block's records (~84 bytes each) stay in the
/// cache while each channel takes its values from them.
const BLOCK: usize = 4096;

/// Where a channel's values come from.
#[derive(Clone, Copy)]
enum Column<'a> {
    /// The status codes (u32).
    Status,
    Float(Float<'a>),
}

/// Where an f32 channel's values come from.
#[derive(Clone, Copy)]
enum Float<'a> {
    Object,
    /// A physical or polarization channel: the field where the record has an emission.
    Physical(Get),
    /// A view channel: the field where the pixel was traced.
    View(Get),
    /// A light plane: its value where the record has an emission.
    Light(&'a [f32]),
}

impl DataFile {
    /// Every channel of the data file with its values as stored: `object` (f32, −1 for
    /// none), `status` (u32 codes), the physical channels, `view_*`, `pol_*` (where
    /// [`DataFile::polarization`]) and `light_k`, in that order.
    ///
    /// The channels in two halves side by side (on the current rayon pool), each block by
    /// block of records and each block channel by channel: one pass over all the records per
    /// channel read them from memory twenty times (43 ms of a 2200×250 render's files).
    pub fn planes(&self) -> Vec<(String, Plane)> {
        let pol: &[(&str, Get, Set)] = if self.polarization {
            &POLARIZATION_CHANNELS
        } else {
            &[]
        };
        let fields = |channels: &'static [(&str, Get, Set)], wrap: fn(Get) -> Float<'static>| {
            channels
                .iter()
                .map(move |&(name, get, _)| (name.to_string(), Column::Float(wrap(get))))
        };
        let mut columns = vec![
            ("object".to_string(), Column::Float(Float::Object)),
            ("status".to_string(), Column::Status),
        ];
        columns.extend(fields(&PHYSICAL_CHANNELS, Float::Physical));
        columns.extend(fields(&VIEW_CHANNELS, Float::View));
        columns.extend(fields(pol, Float::Physical));
        columns.extend(
            self.lights
                .iter()
                .enumerate()
                .map(|(k, values)| (light_channel_name(k), Column::Float(Float::Light(values)))),
        );
        let half = columns.len().div_ceil(2).max(1);
        let planes: Vec<Plane> = columns
            .par_chunks(half)
            .flat_map_iter(|group| self.planes_of(group.iter().map(|(_, c)| *c)))
            .collect();
        columns
            .into_iter()
            .map(|(name, _)| name)
            .zip(planes)
            .collect()
    }

    /// The planes of `columns`, block by block of records.
    fn planes_of<'a>(&self, columns: impl Iterator<Item = Column<'a>>) -> Vec<Plane> {
        /// A column and the values taken so far.
        enum Filling<'a> {
            Status(Vec<u32>),
            Float(Float<'a>, Vec<f32>),
        }
        let n = self.records.len();
        let mut out: Vec<Filling> = columns
            .map(|c| match c {
                Column::Status => Filling::Status(Vec::with_capacity(n)),
                Column::Float(f) => Filling::Float(f, Vec::with_capacity(n)),
            })
            .collect();
        let physical = |r: &PixelRecord, v: f32| if r.has_emission() { v } else { NO_VALUE };
        let traced = |r: &PixelRecord| r.status != RayStatus::NotTraced;
        for (b, block) in self.records.chunks(BLOCK).enumerate() {
            for filling in &mut out {
                match filling {
                    Filling::Status(p) => p.extend(block.iter().map(|r| r.status.code())),
                    Filling::Float(Float::Object, p) => {
                        p.extend(block.iter().map(|r| r.object as f32));
                    }
                    Filling::Float(Float::Physical(get), p) => {
                        p.extend(block.iter().map(|r| physical(r, get(r))));
                    }
                    Filling::Float(Float::View(get), p) => {
                        p.extend(
                            block
                                .iter()
                                .map(|r| if traced(r) { get(r) } else { NO_VALUE }),
                        );
                    }
                    Filling::Float(Float::Light(values), p) => {
                        let values = block.iter().zip(values.iter().skip(b * BLOCK));
                        p.extend(values.map(|(r, &v)| physical(r, v)));
                    }
                }
            }
        }
        out.into_iter()
            .map(|filling| match filling {
                Filling::Status(p) => Plane::U32(p),
                Filling::Float(_, p) => Plane::F32(p),
            })
            .collect()
    }
}
