//! The scene file exactly as written (docs/guide/src/scenes.md): serde structs with unknown
//! fields rejected everywhere. Nothing is checked here beyond TOML types; the meaning (which
//! fields go with which `kind`, ranges, units) is checked in `validate.rs`, which turns these
//! records into the runtime types with located errors.
//!
//! Tables with a `kind` are flat structs with optional fields rather than serde-tagged
//! enums: serde buffers tagged enums, which loses the byte spans that locate errors.

use serde::Deserialize;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub name: String,
    pub spacetime: Option<RawSpacetime>,
    pub observer: Option<RawObserver>,
    pub camera: RawCamera,
    pub trace: Option<RawTrace>,
    #[serde(default)]
    pub object: Vec<RawObject>,
    #[serde(default)]
    pub light: Vec<RawLight>,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum MetricName {
    Godel,
    Minkowski,
    #[serde(rename = "godel-type")]
    GodelType,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSpacetime {
    pub metric: Option<MetricName>,
    pub a: Option<f64>,
    pub m2: Option<f64>,
    pub omega: Option<f64>,
}

/// `{ r, phi, z }` (cylindrical) or `{ x, y, z }` (pseudo-Cartesian); missing components
/// are 0. Which form is meant is decided in validation, with a clear message when mixed.
#[derive(Debug, Deserialize, Default, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawPosition {
    pub r: Option<f64>,
    pub phi: Option<f64>,
    pub x: Option<f64>,
    pub y: Option<f64>,
    pub z: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawVelocity {
    pub speed: f64,
    pub direction: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObserver {
    pub time: Option<f64>,
    pub position: Option<RawPosition>,
    pub velocity: Option<RawVelocity>,
    pub forward: Option<[f64; 3]>,
    pub up: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum CameraKind {
    Pinhole,
    Panorama,
    Sphere,
    Fisheye,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCamera {
    pub kind: CameraKind,
    pub fov_deg: Option<f64>,
    pub h_fov_deg: Option<f64>,
    pub v_fov_deg: Option<f64>,
    pub width: u32,
    pub height: u32,
    /// Rays per pixel (a square number); default 1.
    pub samples: Option<i64>,
    /// Two eyes instead of one (`crate::stereo`).
    pub stereo: Option<RawStereo>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStereo {
    pub separation: f64,
    pub layout: Option<LayoutName>,
    pub convergence: Option<f64>,
    /// Written by `Scene::eye` into each eye's scene: which eye it is.
    pub eye: Option<EyeName>,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum EyeName {
    Left,
    Right,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "kebab-case")]
pub enum LayoutName {
    SideBySide,
    OverUnder,
    Anaglyph,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum MethodName {
    Numeric,
    Exact,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTrace {
    pub method: Option<MethodName>,
    pub max_past: Option<f64>,
    pub tolerance: Option<f64>,
    pub max_steps: Option<u64>,
    pub gpu: Option<bool>,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum FrameName {
    Local,
    Coordinates,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum ShapeName {
    Sphere,
    Plane,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObject {
    pub name: String,
    pub frame: Option<FrameName>,
    pub shape: Option<ShapeName>,
    pub radius: Option<f64>,
    /// Coordinate spheres only.
    pub center: Option<RawPosition>,
    /// Coordinate planes only: the plane z = height.
    pub height: Option<f64>,
    /// Coordinate planes only: half-size of the square |x|, |y| ≤ extent.
    pub extent: Option<f64>,
    pub texture: Option<RawTexture>,
    pub temperature: Option<f64>,
    /// Local objects only.
    pub motion: Option<RawMotion>,
    pub polarization: Option<RawPolarization>,
}

/// How an object's light is polarized: linearly, along a body axis.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPolarization {
    pub axis: [f64; 3],
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum TextureKind {
    Checker,
    Image,
    Gradient,
    Uniform,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTexture {
    pub kind: TextureKind,
    pub rows: Option<u32>,
    pub cols: Option<u32>,
    pub path: Option<String>,
    pub builtin: Option<String>,
    pub color: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum MotionKind {
    Rest,
    Geodesic,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMotion {
    pub kind: MotionKind,
    pub position: Option<RawPosition>,
    /// Geodesic only.
    pub time: Option<f64>,
    pub speed: Option<f64>,
    pub direction: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLight {
    pub position: RawPosition,
    pub color: Option<[f64; 3]>,
    pub power: Option<f64>,
}
