//! The per-pixel record: what the tracer learned about one pixel's ray.
//!
//! One [`PixelRecord`] per pixel is everything the post-render shaders need
//! (docs/guide/src/data-file.md): which object the backward null geodesic hit, where
//! and when it was emitted, the frequency shift `g`, and the texture coordinates.
//! Direct light from each source (`light_k`) is not part of the record: it is
//! stored as separate planes in [`crate::DataFile::lights`] so that the
//! record stays small and `Copy`.

/// How a pixel's ray ended. The numeric codes are those stored in the data
/// file's `status` channel and never change.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[repr(u32)]
pub enum RayStatus {
    /// The ray hit an object (`object` ≥ 0).
    Hit = 0,
    /// Nothing was hit within `max_past` of coordinate time.
    Escaped = 1,
    /// The integrator's step budget was spent before anything was hit.
    StepBudget = 2,
    /// Integration failed (NaN, constraint drift).
    Failed = 3,
    /// The pixel was not traced (fisheye pixels outside the image circle).
    NotTraced = 4,
    /// A bounded search ran out of work before the ray was resolved: the intersection
    /// search's probe budget, or the limit on loop copies (every loop of the tracer has a
    /// limit fixed in advance, so a pixel is marked instead of hanging).
    WorkLimit = 5,
}

impl RayStatus {
    /// All statuses, in code order.
    pub const ALL: [RayStatus; 6] = [
        RayStatus::Hit,
        RayStatus::Escaped,
        RayStatus::StepBudget,
        RayStatus::Failed,
        RayStatus::NotTraced,
        RayStatus::WorkLimit,
    ];

    /// The code stored in the data file.
    pub const fn code(self) -> u32 {
        self as u32
    }

    /// The status with this code, or `None` for an unknown code.
    pub const fn from_code(code: u32) -> Option<RayStatus> {
        match code {
            0 => Some(RayStatus::Hit),
            1 => Some(RayStatus::Escaped),
            2 => Some(RayStatus::StepBudget),
            3 => Some(RayStatus::Failed),
            4 => Some(RayStatus::NotTraced),
            5 => Some(RayStatus::WorkLimit),
            _ => None,
        }
    }
}

/// What one pixel's ray found. All quantities are those of the first hit;
/// for a ray that hit nothing see [`PixelRecord::miss`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PixelRecord {
    /// Index of the object in scene-file order; [`PixelRecord::NO_OBJECT`]
    /// (−1) where nothing was hit.
    pub object: i32,
    /// How the ray ended.
    pub status: RayStatus,
    /// Texture coordinate on the object's own body.
    pub u: f32,
    /// Texture coordinate on the object's own body.
    pub v: f32,
    /// Frequency shift ν_obs / ν_emit.
    pub g: f32,
    /// Coordinate time of the emission event minus the observer's time (≤ 0).
    pub t_emit: f32,
    /// Emission event, pseudo-Cartesian x.
    pub x: f32,
    /// Emission event, pseudo-Cartesian y.
    pub y: f32,
    /// Emission event, pseudo-Cartesian z.
    pub z: f32,
    /// Affine parameter at the hit.
    pub lambda: f32,
    /// Photon direction at emission, in the object's rest frame.
    pub dir: [f32; 3],
    /// Cosine between the surface normal and the photon.
    pub cos_i: f32,
    /// The direction the pixel (or sample) looks along: the unit vector −(photon's spatial
    /// direction) in the observer's orthonormal frame (e1, e2, e3: the static frame at the
    /// observer's event boosted by its velocity; on the axis e1, e2, e3 = ∂x, ∂y, ∂z).
    /// Set for every traced ray, hit or not; zero for a pixel not traced.
    pub view: [f32; 3],
    /// The polarization channels: the observer's screen-up direction at this pixel (the
    /// camera's up projected orthogonal to `view`), parallel-transported back along the ray
    /// to the emission event and expressed in the emitter's rest frame (body axes, as
    /// `dir`): a unit vector orthogonal to `dir` (docs/physics.md, "Polarization"). Zero
    /// where the data file has no polarization channels ([`crate::DataFile::polarization`]).
    pub pol: [f32; 3],
}

impl PixelRecord {
    /// The `object` value of a pixel where nothing was hit.
    pub const NO_OBJECT: i32 = -1;

    /// A ray that escaped: nothing hit within `max_past`.
    pub const MISS: PixelRecord = PixelRecord::miss(RayStatus::Escaped);

    /// A record for a pixel where nothing was hit: object −1, the given
    /// status, and every other field zero in memory (the data file stores NaN in its
    /// physical channels instead, see `crate::DataFile`).
    pub const fn miss(status: RayStatus) -> PixelRecord {
        PixelRecord {
            object: PixelRecord::NO_OBJECT,
            status,
            u: 0.0,
            v: 0.0,
            g: 0.0,
            t_emit: 0.0,
            x: 0.0,
            y: 0.0,
            z: 0.0,
            lambda: 0.0,
            dir: [0.0; 3],
            cos_i: 0.0,
            view: [0.0; 3],
            pol: [0.0; 3],
        }
    }

    /// Whether the record holds an emission event (status hit): the fields u, v, g,
    /// t_emit, x, y, z, lambda, dir, cos_i and pol (and the light planes) mean something
    /// only then, and the data file stores NaN in them otherwise.
    pub const fn has_emission(&self) -> bool {
        matches!(self.status, RayStatus::Hit)
    }

    /// Whether the ray hit an object.
    pub const fn is_hit(&self) -> bool {
        self.object >= 0
    }
}

impl Default for PixelRecord {
    fn default() -> Self {
        PixelRecord::MISS
    }
}
