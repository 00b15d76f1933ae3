//! [`Channels`]: a compact, channel-major copy of the data-file channels that shading reads
//! (status, object, u, v, g, t_emit, cos_i, the light planes, pol and dir), made once per data file so
//! that re-shading it streams a few flat planes instead of whole pixel records; and
//! [`Sample`], the values of one sample that the colour rule of [`crate::shading`] reads,
//! taken from a record or from the planes (so both paths colour with the same rule).
//!
//! The copy holds only the channels [`Needs`] asks for (the others are left empty); statuses
//! are kept as their one-byte codes.

use datafile::record::{PixelRecord, RayStatus};
use datafile::DataFile;

/// Which channels a shader set reads, besides status and object (always kept).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Needs {
    /// u, v and t_emit (textures, lamps, the time layer).
    pub texture_coordinates: bool,
    /// The frequency shift g.
    pub shift: bool,
    /// cos_i (the Lambert factor of painted pixels without the light layer).
    pub incidence: bool,
    /// The light planes.
    pub lights: bool,
    /// pol and dir (the polarization layer).
    pub polarization: bool,
}

impl Needs {
    /// Every channel any shader set reads.
    pub const ALL: Needs = Needs {
        texture_coordinates: true,
        shift: true,
        incidence: true,
        lights: true,
        polarization: true,
    };
}

/// The shading channels of one data file, one plane per channel, in record order.
#[derive(Clone, Debug, Default)]
pub struct Channels {
    /// The stored image's size (records), and the supersampling of the file.
    pub width: usize,
    pub height: usize,
    pub supersample: usize,
    /// [`RayStatus`] codes.
    pub status: Vec<u8>,
    pub object: Vec<i32>,
    pub u: Vec<f32>,
    pub v: Vec<f32>,
    pub g: Vec<f32>,
    pub t_emit: Vec<f32>,
    pub cos_i: Vec<f32>,
    /// One plane per light channel of the file (empty without [`Needs::lights`]).
    pub lights: Vec<Vec<f32>>,
    /// The polarization channels and the emission direction (empty without
    /// [`Needs::polarization`]).
    pub pol: Vec<[f32; 3]>,
    pub dir: Vec<[f32; 3]>,
}

/// One sample's values as the colour rule reads them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub status: RayStatus,
    pub object: i32,
    pub u: f32,
    pub v: f32,
    pub g: f32,
    pub t_emit: f32,
    pub cos_i: f32,
}

impl Sample {
    /// The values of `record`.
    pub fn of(record: &PixelRecord) -> Sample {
        Sample {
            status: record.status,
            object: record.object,
            u: record.u,
            v: record.v,
            g: record.g,
            t_emit: record.t_emit,
            cos_i: record.cos_i,
        }
    }
}

impl Channels {
    /// Copies the channels `needs` names (status and object always) of `data`'s records;
    /// the others stay empty. Records beyond width × height are left out.
    pub fn new(data: &DataFile, needs: Needs) -> Channels {
        let n = (data.width * data.height).min(data.records.len());
        let records = &data.records[..n];
        let plane = |on: bool, f: fn(&PixelRecord) -> f32| -> Vec<f32> {
            if on {
                records.iter().map(f).collect()
            } else {
                Vec::new()
            }
        };
        let uvt = needs.texture_coordinates;
        Channels {
            width: data.width,
            height: data.height,
            supersample: data.supersample(),
            status: records.iter().map(|r| r.status as u8).collect(),
            object: records.iter().map(|r| r.object).collect(),
            u: plane(uvt, |r| r.u),
            v: plane(uvt, |r| r.v),
            g: plane(needs.shift, |r| r.g),
            t_emit: plane(uvt, |r| r.t_emit),
            cos_i: plane(needs.incidence, |r| r.cos_i),
            lights: if needs.lights {
                data.lights
                    .iter()
                    .map(|p| (0..n).map(|i| p.get(i).copied().unwrap_or(0.0)).collect())
                    .collect()
            } else {
                Vec::new()
            },
            pol: if needs.polarization {
                records.iter().map(|r| r.pol).collect()
            } else {
                Vec::new()
            },
            dir: if needs.polarization {
                records.iter().map(|r| r.dir).collect()
            } else {
                Vec::new()
            },
        }
    }

    /// Number of samples held (width × height of a consistent file).
    pub fn len(&self) -> usize {
        self.status.len()
    }

    /// Whether no sample is held.
    pub fn is_empty(&self) -> bool {
        self.status.is_empty()
    }

    /// Whether every channel `needs` names is held (with `lights` light planes).
    pub fn serves(&self, needs: Needs, lights: usize) -> bool {
        let n = self.len();
        let full = |p: &Vec<f32>, on: bool| !on || p.len() == n;
        n == self.width * self.height
            && self.object.len() == n
            && full(&self.u, needs.texture_coordinates)
            && full(&self.v, needs.texture_coordinates)
            && full(&self.t_emit, needs.texture_coordinates)
            && full(&self.g, needs.shift)
            && full(&self.cos_i, needs.incidence)
            && (!needs.lights
                || (self.lights.len() >= lights && self.lights.iter().all(|p| p.len() == n)))
            && (!needs.polarization || (self.pol.len() == n && self.dir.len() == n))
    }

    /// The size of the picture (W, H): the stored image divided by the supersampling.
    pub fn picture_size(&self) -> (usize, usize) {
        let s = self.supersample.max(1);
        (self.width / s, self.height / s)
    }

    /// Sample `i` (row-major index); channels not held read as 0.
    #[inline]
    pub fn sample(&self, i: usize) -> Sample {
        let at = |p: &[f32]| p.get(i).copied().unwrap_or(0.0);
        let status = self
            .status
            .get(i)
            .and_then(|&c| RayStatus::ALL.get(usize::from(c)))
            .copied()
            .unwrap_or(RayStatus::Failed);
        Sample {
            status,
            object: self.object.get(i).copied().unwrap_or(-1),
            u: at(&self.u),
            v: at(&self.v),
            g: at(&self.g),
            t_emit: at(&self.t_emit),
            cos_i: at(&self.cos_i),
        }
    }

    /// What the polarization layer reads of sample `i` (zeros where not held).
    pub fn polarization(&self, i: usize) -> crate::polarization::PolSample {
        crate::polarization::PolSample {
            object: self.object.get(i).copied().unwrap_or(-1),
            pol: self.pol.get(i).copied().unwrap_or_default(),
            dir: self.dir.get(i).copied().unwrap_or_default(),
        }
    }

    /// Light plane `k` at sample `i`; 0 where the plane is not held.
    #[inline]
    pub fn light(&self, k: usize, i: usize) -> f32 {
        self.lights
            .get(k)
            .and_then(|p| p.get(i))
            .copied()
            .unwrap_or(0.0)
    }
}
