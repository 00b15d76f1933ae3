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

impl DataFile {
    /// Every channel of the data file with its values as stored: `object` (f32, −1 for
    /// none), `status` (u32 codes), the physical channels, `view_*`, `pol_*` (where
    /// [`DataFile::polarization`]) and `light_k`, in that order.
    ///
    /// Block by block of records, each block channel by channel: one pass over all the records
    /// per channel read them from memory twenty times (24 ms of a 2200×250 render's files).
    pub fn planes(&self) -> Vec<(String, Plane)> {
        let n = self.records.len();
        let physical = |r: &PixelRecord, v: f32| if r.has_emission() { v } else { NO_VALUE };
        let traced = |r: &PixelRecord| r.status != RayStatus::NotTraced;
        let pol: &[(&str, Get, Set)] = if self.polarization {
            &POLARIZATION_CHANNELS
        } else {
            &[]
        };
        let empty = || Vec::<f32>::with_capacity(n);
        let mut object = empty();
        let mut status = Vec::<u32>::with_capacity(n);
        let mut phys: Vec<Vec<f32>> = PHYSICAL_CHANNELS.iter().map(|_| empty()).collect();
        let mut view: Vec<Vec<f32>> = VIEW_CHANNELS.iter().map(|_| empty()).collect();
        let mut pols: Vec<Vec<f32>> = pol.iter().map(|_| empty()).collect();
        let mut lights: Vec<Vec<f32>> = self.lights.iter().map(|_| empty()).collect();
        for (b, block) in self.records.chunks(BLOCK).enumerate() {
            object.extend(block.iter().map(|r| r.object as f32));
            status.extend(block.iter().map(|r| r.status.code()));
            for ((_, get, _), plane) in PHYSICAL_CHANNELS.iter().zip(&mut phys) {
                plane.extend(block.iter().map(|r| physical(r, get(r))));
            }
            for ((_, get, _), plane) in VIEW_CHANNELS.iter().zip(&mut view) {
                plane.extend(
                    block
                        .iter()
                        .map(|r| if traced(r) { get(r) } else { NO_VALUE }),
                );
            }
            for ((_, get, _), plane) in pol.iter().zip(&mut pols) {
                plane.extend(block.iter().map(|r| physical(r, get(r))));
            }
            for (values, plane) in self.lights.iter().zip(&mut lights) {
                let values = block.iter().zip(values.iter().skip(b * BLOCK));
                plane.extend(values.map(|(r, &v)| physical(r, v)));
            }
        }
        let named = |channels: &[(&str, Get, Set)], planes: Vec<Vec<f32>>| {
            let names = channels.iter().map(|(name, _, _)| name.to_string());
            names
                .zip(planes.into_iter().map(Plane::F32))
                .collect::<Vec<_>>()
        };
        let mut out = vec![
            ("object".to_string(), Plane::F32(object)),
            ("status".to_string(), Plane::U32(status)),
        ];
        out.extend(named(&PHYSICAL_CHANNELS, phys));
        out.extend(named(&VIEW_CHANNELS, view));
        out.extend(named(pol, pols));
        out.extend(
            lights
                .into_iter()
                .enumerate()
                .map(|(k, values)| (light_channel_name(k), Plane::F32(values))),
        );
        out
    }
}
