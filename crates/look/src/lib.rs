//! `look`: looking around without tracing. The data file of any camera, held by any observer at
//! the event of a full-sphere trace of the static observer, remapped from that trace
//! (docs/physics.md, "Observers at one event: aberration and Doppler").
//!
//! Every observer at one event receives the same photons, so the static observer's full
//! sphere of directions holds every view from that event. A pixel of a [`LookView`] looks
//! along n′ in the moving observer's own frame; the static observer sees the same photon
//! along the aberrated direction n ([`spacetime::aberrate`]), and the photon's frequency
//! is higher by the Doppler factor D = g′/g = γ(1 + n·v). The pixel's record is the
//! sphere's record at n with `g` and `lambda` multiplied by D (the tracer normalizes the
//! photon to unit energy in the observer's own frame), and `pol` turned about `dir` by the
//! angle between the two observers' screen-up directions for that photon
//! ([`spacetime::polarization::look_rotation`]; docs/physics.md, "Polarization"); every
//! other field as read there.
//!
//! The sphere is read bilinearly within one image of one object and by nearest neighbour at
//! the edges of objects and images ([`Filter::Smooth`], the default; [`Filter::Nearest`] for
//! every pixel), with s×s samples per output pixel where asked ([`Sampling`]; module
//! `sample`).
//!
//! Main items: [`look`] (the remapping, smooth, one sample per pixel) and [`look_with`] (any
//! [`Sampling`]); [`look_rows`] for a band of rows of [`samples_view`], so that a server can
//! shade a large view band by band in bounded memory; [`LookView`] (camera, axes, velocity),
//! [`SphereSource`] (the sphere's pixel geometry: [`SphereSource::position`] and
//! [`SphereSource::pixel_size`]), [`pixel_look`] (one output pixel: its direction in both
//! frames and D), [`resolution`] (how far the source's pixels limit the output).

mod sample;

pub use sample::{Filter, SAME_IMAGE_DT, SAME_IMAGE_DUV};

use datafile::{DataFile, DataFileErrorKind, PixelRecord, RayStatus};
use rayon::prelude::*;
use scene::{Camera, Observer, Scene, SceneError};
use spacetime::polarization::{look_rotation, turned};
use spacetime::{aberrate, LocalVelocity};
use std::f64::consts::{PI, TAU};

/// The name under which errors in a data file's embedded scene text are reported.
const EMBEDDED: &str = "<scene embedded in the data file>";

/// The first line of the scene text of a data file made by [`look`].
pub const LOOK_COMMENT: &str = "# View computed by `godel look` from a full-sphere trace of the static observer at\n# this event: camera, observer velocity and axes replaced, nothing traced again.\n";

/// What [`look`] makes: a camera held by an observer moving with `velocity` (relative to the
/// static observer at the sphere's event, in that observer's local frame), with `forward`
/// and `up` unit and orthogonal in the moving observer's own (boosted) frame. Build it with
/// [`LookView::new`], which normalizes and checks; [`look`] checks again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LookView {
    pub camera: Camera,
    pub forward: [f64; 3],
    pub up: [f64; 3],
    pub velocity: LocalVelocity,
}

/// The full-sphere source's pixel geometry: a 360°×180° equirectangular image whose
/// camera axes `forward` and `up` (right = forward × up) are given in the static
/// observer's local frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereSource {
    pub width: usize,
    pub height: usize,
    pub forward: [f64; 3],
    pub up: [f64; 3],
}

/// How [`look_with`] reads the sphere: the filter, and the samples per output pixel (a square
/// number s², read at the s×s grid of sub-pixel points where `godel render` traces its
/// `samples`; the data file keeps every sample, as a render's does).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sampling {
    pub filter: Filter,
    pub samples: u32,
}

impl Default for Sampling {
    fn default() -> Sampling {
        Sampling {
            filter: Filter::Smooth,
            samples: 1,
        }
    }
}

/// One output pixel of a [`LookView`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelLook {
    /// Unit direction the pixel looks along (towards the source), in the moving observer's
    /// own frame.
    pub own: [f64; 3],
    /// The same photon's direction for the static observer, in its local frame.
    pub static_dir: [f64; 3],
    /// D = g′/g = γ(1 + n·v) = λ′/λ: how much bluer the moving observer sees the photon.
    pub doppler: f64,
}

/// How far the source's resolution limits the output (angles in radians).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resolution {
    /// A source pixel's angular size at the equator: 360°/W (and 180°/H vertically).
    pub source_pixel: f64,
    /// The smallest and largest angular size of an output pixel, measured in the static
    /// observer's sky (the larger angle to the neighbouring pixels to the right and below):
    /// where this is below `source_pixel`, several output pixels share one source pixel.
    pub output_pixel_min: f64,
    pub output_pixel_max: f64,
}

/// What is wrong with a look: its source or its view. `View` names the scene-file field
/// (`camera.fov_deg`, `observer.up`, `observer.velocity.speed`, …).
#[derive(Debug, thiserror::Error)]
pub enum LookError {
    #[error("not a full-sphere data file: its camera is `{0}`; trace the sphere of directions with `[camera] kind = \"sphere\"` in the scene")]
    NotSphere(String),
    #[error("traced by an observer moving at {0} c: looking around needs the static observer's sphere (observer.velocity.speed = 0), the velocity is applied by the look itself")]
    MovingSource(f64),
    #[error("anti-aliased with {0}×{0} rays per pixel: looking around needs one ray per sphere pixel; trace the sphere without `samples` (at {0} times the width and height for the same rays)")]
    Supersampled(usize),
    #[error("the data file's header says its camera is `{header}`, its embedded scene `{scene}`")]
    Inconsistent { header: String, scene: String },
    #[error("{0}")]
    EmbeddedScene(SceneError),
    #[error("inconsistent data file: {0}")]
    Data(DataFileErrorKind),
    #[error("{field}: {message}")]
    View {
        field: &'static str,
        message: String,
    },
}

fn view_error(field: &'static str, message: impl Into<String>) -> LookError {
    LookError::View {
        field,
        message: message.into(),
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `v` normalized; an error naming `field` for a zero or non-finite vector. Components so
/// large or small that their squares overflow or vanish are scaled first
/// ([`spacetime::scaled_unit`]).
fn unit(field: &'static str, v: [f64; 3]) -> Result<[f64; 3], LookError> {
    spacetime::scaled_unit(v)
        .ok_or_else(|| view_error(field, format!("must be a non-zero direction, got {v:?}")))
}

impl LookView {
    /// A checked view; `forward` and `up` are normalized (and must be orthogonal, as in a
    /// scene file).
    pub fn new(
        camera: Camera,
        forward: [f64; 3],
        up: [f64; 3],
        velocity: LocalVelocity,
    ) -> Result<LookView, LookError> {
        let view = LookView {
            camera,
            forward: unit("observer.forward", forward)?,
            up: unit("observer.up", up)?,
            velocity,
        };
        view.check()?;
        Ok(view)
    }

    /// Checks the camera (sizes, angles), the axes (unit, orthogonal) and the velocity
    /// (speed in [0, 1), unit direction).
    pub fn check(&self) -> Result<(), LookError> {
        self.camera
            .check()
            .map_err(|(field, message)| view_error(field, message))?;
        for (field, v) in [("observer.forward", self.forward), ("observer.up", self.up)] {
            unit(field, v)?;
            if (dot(v, v) - 1.0).abs() > 1e-9 {
                return Err(view_error(
                    field,
                    format!("must be a unit vector, got {v:?}"),
                ));
            }
        }
        Observer::check_axes(self.forward, self.up).map_err(|m| view_error("observer.up", m))?;
        let v = self.velocity;
        if !(v.speed.is_finite() && (0.0..1.0).contains(&v.speed)) {
            return Err(view_error(
                "observer.velocity.speed",
                format!(
                    "must be in [0, 1) (a fraction of light speed), got {}",
                    v.speed
                ),
            ));
        }
        unit("observer.velocity.direction", v.direction)?;
        if (dot(v.direction, v.direction) - 1.0).abs() > 1e-9 {
            return Err(view_error(
                "observer.velocity.direction",
                format!("must be a unit vector, got {:?}", v.direction),
            ));
        }
        Ok(())
    }

    /// right = forward × up.
    pub fn right(&self) -> [f64; 3] {
        cross(self.forward, self.up)
    }
}

/// Output pixel (`col`, `row`) of `view`: where it looks in both frames, and its Doppler
/// factor; `None` for pixels the camera does not show (fisheye corners, outside the image).
pub fn pixel_look(view: &LookView, col: u32, row: u32) -> Option<PixelLook> {
    let d = view.camera.pixel_direction(col, row)?;
    let (f, r, u) = (view.forward, view.right(), view.up);
    let own = [0, 1, 2].map(|i| d[0] * f[i] + d[1] * r[i] + d[2] * u[i]);
    let (static_dir, doppler) = aberrate(view.velocity, own);
    Some(PixelLook {
        own,
        static_dir,
        doppler,
    })
}

impl SphereSource {
    /// The geometry of a full-sphere data file traced by the static observer. Refuses any
    /// other camera (a 360°×180° panorama counts as a sphere), a moving observer, an
    /// anti-aliased file (several rays per pixel, not one per direction), and a data file
    /// whose sizes or object ids do not hold together ([`DataFile::validate`]).
    pub fn of(data: &DataFile) -> Result<SphereSource, LookError> {
        data.validate().map_err(LookError::Data)?;
        let (observer, camera) = Scene::read_view(&data.header.scene_text, EMBEDDED)
            .map_err(LookError::EmbeddedScene)?;
        let full = match camera {
            Camera::Sphere { .. } => true,
            Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                ..
            } => h_fov_deg == 360.0 && v_fov_deg == 180.0,
            _ => false,
        };
        if !full {
            return Err(LookError::NotSphere(camera.describe()));
        }
        if data.supersample() > 1 {
            return Err(LookError::Supersampled(data.supersample()));
        }
        let size = (camera.width() as usize, camera.height() as usize);
        if camera.describe() != data.header.camera || size != (data.width, data.height) {
            return Err(LookError::Inconsistent {
                header: format!(
                    "{} ({}×{} pixels)",
                    data.header.camera, data.width, data.height
                ),
                scene: camera.describe(),
            });
        }
        if observer.velocity.speed != 0.0 {
            return Err(LookError::MovingSource(observer.velocity.speed));
        }
        Ok(SphereSource {
            width: data.width,
            height: data.height,
            forward: observer.forward,
            up: observer.up,
        })
    }

    /// Fractional image position (x, y) of the static-frame unit direction `n`:
    /// x ∈ [0, W], y ∈ [0, H]; pixel (c, r) covers [c, c + 1) × [r, r + 1) and has its
    /// centre at (c + ½, r + ½). Azimuth α = atan2(n·right, n·forward),
    /// elevation β = asin(n·up): x = W(α/2π + ½), y = H(½ − β/π).
    pub fn position(&self, n: [f64; 3]) -> [f64; 2] {
        let right = cross(self.forward, self.up);
        let alpha = dot(n, right).atan2(dot(n, self.forward));
        let beta = dot(n, self.up).clamp(-1.0, 1.0).asin();
        [
            self.width as f64 * (alpha / TAU + 0.5),
            self.height as f64 * (0.5 - beta / PI),
        ]
    }

    /// A source pixel's angular size in radians: [along the equator 2π/W (at elevation β
    /// it is cos β times that), vertically π/H].
    pub fn pixel_size(&self) -> [f64; 2] {
        [TAU / self.width as f64, PI / self.height as f64]
    }

    /// Index (row-major) of the pixel containing position `p` (from
    /// [`SphereSource::position`]): columns wrap around, rows are clamped at the poles.
    pub fn nearest(&self, p: [f64; 2]) -> usize {
        sample::nearest_index(self.width, self.height, p)
    }
}

/// The data file of `view` at the event of `sphere`, without tracing, read smoothly with one
/// sample per pixel ([`look_with`] with the default [`Sampling`]).
pub fn look(sphere: &DataFile, view: &LookView) -> Result<DataFile, LookError> {
    look_with(sphere, view, Sampling::default())
}

/// The data file of `view` at the event of `sphere`, without tracing: each pixel (each of its
/// s×s samples) takes the sphere's record at its static-frame direction as `sampling.filter`
/// reads it (module `sample`; docs/physics.md gives the error bounds), with `g` and `lambda`
/// multiplied by the pixel's Doppler factor. Light planes are carried the same way. Pixels
/// the camera does not show are `NotTraced`. `sampling.samples` is checked as `[camera]
/// samples` is (a square number up to 256, at most 5·10⁷ samples in all; errors name
/// `camera.samples`).
///
/// The header is the sphere's with the camera description replaced, and its scene text
/// the sphere's with `[camera]` (and its `samples`) and the observer's `velocity`, `forward`
/// and `up` replaced (so that shaders and viewers read the result as a normal data file),
/// headed by [`LOOK_COMMENT`].
pub fn look_with(
    sphere: &DataFile,
    view: &LookView,
    sampling: Sampling,
) -> Result<DataFile, LookError> {
    view.check()?;
    let source = SphereSource::of(sphere)?;
    let (samples_view, s) = samples_view(view, sampling.samples)?;
    let height = samples_view.camera.height();
    let (records, lights) = look_rows(sphere, &source, &samples_view, sampling.filter, 0..height);
    let width = samples_view.camera.width() as usize;
    let text = scene::replace_view(
        &sphere.header.scene_text,
        EMBEDDED,
        &view.camera,
        view.velocity,
        view.forward,
        view.up,
    )
    .and_then(|t| scene::replace_samples(&t, EMBEDDED, s * s))
    .map_err(LookError::EmbeddedScene)?;
    let text = if text.starts_with(LOOK_COMMENT) {
        text
    } else {
        format!("{LOOK_COMMENT}{text}")
    };
    let mut header = sphere.header.clone();
    header.scene_text = text;
    header.camera = view.camera.describe();
    header.supersample = s;
    Ok(DataFile {
        header,
        width,
        height: height as usize,
        records,
        lights,
        polarization: sphere.polarization,
    })
}

/// The view whose pixels are the samples of `view` at `samples` per pixel: the camera s times
/// wider and taller (s² = `samples`, checked as `[camera] samples` is: a square number up to
/// 256, at most 5·10⁷ samples in all; errors name `camera.samples`), and s.
pub fn samples_view(view: &LookView, samples: u32) -> Result<(LookView, u32), LookError> {
    let (w, h) = (view.camera.width(), view.camera.height());
    let s = scene::samples_per_side(i64::from(samples), w, h)
        .map_err(|m| view_error("camera.samples", m))?;
    let samples_view = LookView {
        camera: view.camera.supersampled(s),
        ..*view
    };
    Ok((samples_view, s))
}

/// Rows `rows` of the image [`look_with`] makes of `view` (a [`samples_view`] for several
/// samples per pixel) from `sphere` (whose geometry is `source`, [`SphereSource::of`]), read
/// with `filter`: the records, row-major, and each light plane of them. `view` must be
/// checked ([`LookView::new`]). Memory: one record per pixel, and the sphere pixels each
/// pixel reads only where the sphere has light planes.
pub fn look_rows(
    sphere: &DataFile,
    source: &SphereSource,
    view: &LookView,
    filter: Filter,
    rows: std::ops::Range<u32>,
) -> (Vec<PixelRecord>, Vec<Vec<f32>>) {
    let width = view.camera.width() as usize;
    let rows = rows.start..rows.end.min(view.camera.height());
    let pixels = width * rows.len();
    // The sphere pixels each pixel reads, and where it looks.
    let show = |col: usize, row: usize| {
        let p = pixel_look(view, col as u32, rows.start + row as u32)?;
        let at = source.position(p.static_dir);
        let taps = sample::taps(&sphere.records, source.width, source.height, at, filter);
        Some((taps, p))
    };
    let mut records = vec![PixelRecord::miss(RayStatus::NotTraced); pixels];
    records
        .par_chunks_mut(width.max(1))
        .enumerate()
        .for_each(|(row, out)| {
            for (col, slot) in out.iter_mut().enumerate() {
                if let Some((taps, p)) = show(col, row) {
                    let mut record = boosted(sample::record(&sphere.records, &taps), p.doppler);
                    if sphere.polarization && record.is_hit() {
                        record.pol = polarization(&record, source, view, &p);
                    }
                    // The direction this camera's pixel looks, in the moving observer's frame.
                    record.view = p.own.map(|c| c as f32);
                    *slot = record;
                }
            }
        });
    let lights = if sphere.lights.is_empty() {
        Vec::new()
    } else {
        let shown: Vec<Option<sample::Taps>> = (0..pixels)
            .into_par_iter()
            .map(|k| show(k % width, k / width).map(|(t, _)| t))
            .collect();
        sphere
            .lights
            .iter()
            .map(|plane| {
                shown
                    .iter()
                    .map(|t| t.as_ref().map_or(0.0, |t| sample::light(plane, t)))
                    .collect()
            })
            .collect()
    };
    (records, lights)
}

/// The record `r`'s polarization channels for the pixel `p` of `view`: the static observer's
/// screen basis at the photon's direction turned into this pixel's screen-up.
fn polarization(
    r: &PixelRecord,
    source: &SphereSource,
    view: &LookView,
    p: &PixelLook,
) -> [f32; 3] {
    let turn = look_rotation(
        view.velocity,
        p.own,
        view.up,
        view.forward,
        p.static_dir,
        source.up,
        source.forward,
    );
    let (pol, dir) = (r.pol.map(f64::from), r.dir.map(f64::from));
    turned(pol, dir, turn).map(|c| c as f32)
}

/// The static observer's record `r` as the moving observer of Doppler factor `doppler`
/// sees it: g and the affine parameter λ scale with the photon's energy in the observer's
/// frame; everything else belongs to the photon's path and its emission.
fn boosted(mut r: PixelRecord, doppler: f64) -> PixelRecord {
    if r.is_hit() {
        r.g = (r.g as f64 * doppler) as f32;
        r.lambda = (r.lambda as f64 * doppler) as f32;
    }
    r
}

/// How far the source's pixels limit `view`: the source pixel's angular size against the
/// output pixels' sizes in the static observer's sky. Samples at most about 256 × 256
/// output pixels.
pub fn resolution(source: &SphereSource, view: &LookView) -> Resolution {
    let (w, h) = (view.camera.width(), view.camera.height());
    let step = |n: u32| (n / 256).max(1);
    let angle = |a: [f64; 3], b: [f64; 3]| dot(cross(a, b), cross(a, b)).sqrt().atan2(dot(a, b));
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for row in (0..h).step_by(step(h) as usize) {
        for col in (0..w).step_by(step(w) as usize) {
            let Some(p) = pixel_look(view, col, row) else {
                continue;
            };
            // Neighbours to the right and below (left and above at the last column and row).
            let c2 = if col + 1 < w {
                col + 1
            } else {
                col.wrapping_sub(1)
            };
            let r2 = if row + 1 < h {
                row + 1
            } else {
                row.wrapping_sub(1)
            };
            let size = [(c2, row), (col, r2)]
                .iter()
                .filter_map(|&(c, r)| pixel_look(view, c, r))
                .map(|q| angle(p.static_dir, q.static_dir))
                .fold(0.0f64, f64::max);
            if size > 0.0 {
                lo = lo.min(size);
                hi = hi.max(size);
            }
        }
    }
    if hi == 0.0 {
        lo = 0.0; // a 1×1 image has no neighbours
    }
    Resolution {
        source_pixel: source.pixel_size()[0],
        output_pixel_min: lo,
        output_pixel_max: hi,
    }
}
