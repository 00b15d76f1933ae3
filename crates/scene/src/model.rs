//! The validated, runtime scene description that the tracer and shaders read: every value
//! here has been checked (finite, in range, consistent), so users of these types need not
//! re-check. Built from the scene file by `validate.rs`.

use crate::camera::Camera;
use spacetime::{Event, LocalVelocity, Metric};
use std::path::PathBuf;

/// A complete scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Output base name (`<name>.png`, `<name>.exr`): 1 to 100 bytes, no path separators,
    /// no leading `.` or `-`, no surrounding blanks.
    pub name: String,
    /// The file the scene came from (`None` for [`Scene::from_str`] and the built-in scene).
    pub source_path: Option<PathBuf>,
    /// The scene text as read, so that data files can embed it.
    pub source_text: String,
    pub metric: Metric,
    pub observer: Observer,
    pub camera: Camera,
    /// Two eyes instead of one (`[camera] stereo`); each eye's scene is [`Scene::eye`].
    pub stereo: Option<Stereo>,
    /// Rays per pixel (`[camera] samples`): a square number s², traced on an s×s grid in each
    /// pixel ([`Camera::supersampled`]); width · height · samples ≤ `camera::MAX_RAYS`.
    pub samples: u32,
    pub trace: TraceSettings,
    /// In scene-file order; the data file's `object` channel indexes this list.
    pub objects: Vec<Object>,
    pub lights: Vec<Light>,
}

/// The camera's event, motion and orientation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observer {
    pub event: Event,
    /// Velocity relative to the static observer's frame at `event`.
    pub velocity: LocalVelocity,
    /// Unit vector in the observer's local spatial frame (e1, e2, e3).
    pub forward: [f64; 3],
    /// Unit vector orthogonal to `forward`.
    pub up: [f64; 3],
}

impl Observer {
    /// `forward` and `up` count as orthogonal when the cosine of their angle is at most this.
    pub const ORTHOGONALITY: f64 = 1e-6;

    /// Checks that the unit vectors `forward` and `up` are orthogonal (within
    /// [`Observer::ORTHOGONALITY`]); the error says by how much they are not.
    pub fn check_axes(forward: [f64; 3], up: [f64; 3]) -> Result<(), String> {
        let cos = forward[0] * up[0] + forward[1] * up[1] + forward[2] * up[2];
        if cos.abs() > Observer::ORTHOGONALITY {
            return Err(format!(
                "must be orthogonal to forward (cos of their angle is {cos:.3e})"
            ));
        }
        Ok(())
    }

    /// right = forward × up (unit, since forward ⟂ up).
    pub fn right(&self) -> [f64; 3] {
        cross(self.forward, self.up)
    }

    /// Local-frame components of a direction given in the camera basis
    /// (components along forward, right, up; see [`Camera::pixel_direction`]).
    pub fn camera_to_local(&self, d: [f64; 3]) -> [f64; 3] {
        let (f, r, u) = (self.forward, self.right(), self.up);
        [
            d[0] * f[0] + d[1] * r[0] + d[2] * u[0],
            d[0] * f[1] + d[1] * r[1] + d[2] * u[1],
            d[0] * f[2] + d[1] * r[2] + d[2] * u[2],
        ]
    }

    /// The unit direction (in the observer's local frame) that pixel (col, row) looks along;
    /// `None` for pixels the camera does not trace. The photon travels along the opposite.
    pub fn pixel_direction(&self, camera: &Camera, col: u32, row: u32) -> Option<[f64; 3]> {
        camera
            .pixel_direction(col, row)
            .map(|d| self.camera_to_local(d))
    }
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// How rays are traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TraceMethod {
    /// Adaptive numerical integration of the geodesic equations (any metric).
    Numeric,
    /// Gödel closed forms plus isometries.
    Exact,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceSettings {
    pub method: TraceMethod,
    /// Follow rays this far into the past in coordinate time (> 0; default 30).
    pub max_past: f64,
    /// Integrator tolerance, relative and absolute (in [1e-14, 1e-3]; default 1e-11).
    pub tolerance: f64,
    /// Step budget per ray (1 to 10⁷; default 100000).
    pub max_steps: u64,
    /// Trace on the GPU with the exact tracer's kernel (`godel render --gpu`; default false).
    pub gpu: bool,
}

impl Default for TraceSettings {
    fn default() -> Self {
        TraceSettings {
            method: TraceMethod::Numeric,
            max_past: 30.0,
            tolerance: 1e-11,
            max_steps: 100_000,
            gpu: false,
        }
    }
}

/// Whether an object lives in its own rest frame or is fixed in coordinates (docs/physics.md,
/// "Local objects").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ObjectFrame {
    Local,
    Coordinates,
}

/// An object's shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A local object: ball of this proper radius in its rest frame.
    Sphere { radius: f64 },
    /// A coordinate sphere: |X − center| ≤ radius in pseudo-Cartesian (x, y, z).
    CoordinateSphere { center: [f64; 3], radius: f64 },
    /// A coordinate plane z = height, bounded by |x|, |y| ≤ extent when given.
    Plane { height: f64, extent: Option<f64> },
}

/// Built-in images shipped with the binary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BuiltinImage {
    /// Public-domain earth map (assets/earth-natural-earth-720x360.png).
    Earth,
}

/// Where an image texture comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum ImageSource {
    /// A file, resolved relative to the scene file's directory and checked to exist.
    File(PathBuf),
    Builtin(BuiltinImage),
}

/// Texture on the object's own body coordinates (u, v).
#[derive(Clone, Debug, PartialEq)]
pub enum TextureSpec {
    /// Checkerboard with `rows` bands in v and `cols` in u (both ≥ 1).
    Checker {
        rows: u32,
        cols: u32,
    },
    Image(ImageSource),
    /// A colour ramp over (u, v) for orientation.
    Gradient,
    /// One linear RGB colour, components ≥ 0.
    Uniform {
        color: [f64; 3],
    },
}

impl Default for TextureSpec {
    /// The default texture: checker with 8 rows and 16 columns.
    fn default() -> Self {
        TextureSpec::Checker { rows: 8, cols: 16 }
    }
}

/// An object's worldline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Motion {
    /// At rest (constant x, y, z) at `position` (its `t` is 0 and meaningless).
    /// Coordinate objects are given this, at their centre (spheres) or (0, 0, height) (planes).
    Rest { position: Event },
    /// Free fall: the timelike geodesic through `start` with `velocity` in the static frame there.
    Geodesic {
        start: Event,
        velocity: LocalVelocity,
    },
}

/// An object's black-body temperature when the scene gives none, K (about the Sun's
/// surface). Shaders fall back to it for objects a settings file does not name.
pub const DEFAULT_TEMPERATURE: f64 = 5800.0;

#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Unique within the scene.
    pub name: String,
    pub frame: ObjectFrame,
    pub shape: Shape,
    pub texture: TextureSpec,
    /// Black-body temperature in kelvin (> 0; default [`DEFAULT_TEMPERATURE`]).
    pub temperature: f64,
    pub motion: Motion,
    /// The axis of the object's linear polarization, a unit vector in its body axes (those
    /// of the data file's `dir` and `pol`): the light leaves polarized along the axis
    /// projected orthogonal to its direction (degree 1). `None`: unpolarized.
    pub polarization: Option<[f64; 3]>,
}

/// A point light at rest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Its (constant) position; `t` is 0.
    pub position: Event,
    /// Linear RGB, components ≥ 0 (default [1, 1, 1]).
    pub color: [f64; 3],
    /// ≥ 0 (default 1).
    pub power: f64,
}

/// How the two eyes' pictures are put into one preview.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Left eye's picture on the left, right eye's on the right.
    SideBySide,
    /// Left eye's picture above the right eye's.
    OverUnder,
    /// One picture: red from the left eye, green and blue from the right (red/cyan glasses).
    Anaglyph,
}

impl Layout {
    /// The name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Layout::SideBySide => "side-by-side",
            Layout::OverUnder => "over-under",
            Layout::Anaglyph => "anaglyph",
        }
    }
}

/// `[camera] stereo`: two eyes `separation` apart (units of a), their pictures in `layout`,
/// turned to meet at `convergence` (units of a) or parallel. `eye` is set in the scene of one
/// eye ([`Scene::eye`]): its observer is that eye, and it traces as one picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stereo {
    pub separation: f64,
    pub layout: Layout,
    pub convergence: Option<f64>,
    pub eye: Option<Eye>,
}

impl Stereo {
    /// Whether this is a pair to trace (not one eye of one).
    pub fn is_pair(&self) -> bool {
        self.eye.is_none()
    }
}

/// One of the two eyes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Eye {
    Left,
    Right,
}

impl Eye {
    pub const BOTH: [Eye; 2] = [Eye::Left, Eye::Right];

    /// `left` or `right`: the eye's files are `NAME.left.exr`, `NAME.right.exr`.
    pub fn name(self) -> &'static str {
        match self {
            Eye::Left => "left",
            Eye::Right => "right",
        }
    }

    /// −1 for the left eye, +1 for the right (along the camera's right axis).
    pub(crate) fn side(self) -> f64 {
        match self {
            Eye::Left => -1.0,
            Eye::Right => 1.0,
        }
    }
}
