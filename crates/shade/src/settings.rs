//! [`ShadeSettings`]: every parameter of the post-render shaders, as one serde value that the
//! CLI (`godel shade --settings`), the sequence scripts (keyframes) and the web viewer share.
//!
//! In TOML a complete settings file looks like this (every field is optional in a file read
//! with [`ShadeSettings::overlay_toml`]: missing fields keep the data file's defaults):
//!
//! ```toml
//! shaders = ["frequency", "time"]   # layers, multiplied: texture | frequency | time | light
//! brightness = "normalized"         # frequency shader: "normalized" | "physical"
//! exposure = 1.0                    # physical brightness: multiplier of Y(gT)/Y(T)
//! reference_squares = true          # frequency shader: unshifted colours top left
//! ev = 0.0                          # PNG: exposure compensation in stops before the tone curve
//! grid = false                      # PNG: azimuth/elevation marks (crate::marks)
//!
//! [time]
//! mode = "window"                   # "window" | "travel" (false colour by light travel time)
//! t0 = -8.0                         # window [t0, t0 + dt] of t_emit (emission time − observer time)
//! dt = 2.0
//! travel_min = 0.0                  # false-colour range of travel time −t_emit
//! travel_max = 30.0
//! legend = true                     # colour bar with its range, bottom left
//!
//! [light]
//! ambient = 0.2
//! sources = [{ on = true, intensity = 1.0, color = [1.0, 1.0, 1.0] }]   # one per light_k
//!
//! [objects.earth]                   # per object, by name
//! texture = { kind = "scene" }      # scene | checker (rows, cols) | gradient | uniform (color) | image (path) | earth
//! window_texture = { kind = "uniform", color = [1.0, 0.8, 0.1] }   # inside the time window
//! offset_u = 0.0                    # texture moved on the body
//! offset_v = 0.0
//! scale_u = 1.0
//! scale_v = 1.0
//! rotation_deg = 0.0                # the body turned about its axis (u is longitude)
//! temperature = 5800.0              # kelvin, frequency shader
//! lamps = [{ u = 0.5, v = 0.5, radius_deg = 20.0, period = 1.0, phase = 0.0, duty = 0.5, color = [1.0, 1.0, 0.0] }]
//! ```
//!
//! What each layer means and how layers combine is in [`crate::shading`].

use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;
use std::str::FromStr;

use datafile::DataFile;
use serde::{Deserialize, Serialize};

use crate::error::ShadeError;

/// One shader layer. A pixel's colour is the product of its layers (see [`crate::shading`]).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum ShaderKind {
    /// Each object's texture (moved, scaled, turned, with blinking lamps), Lambert-shaded.
    Texture,
    /// Each object a black body at T seen at g·T.
    Frequency,
    /// Time window (second texture inside) or false colour by light travel time.
    Time,
    /// Direct light from the data file's `light_k` channels.
    Light,
    /// Ticks along the observed polarization of polarized objects, over the other layers
    /// (over the texture layer when alone; [`crate::polarization`]).
    Polarization,
}

impl ShaderKind {
    /// Every kind, in the order used in messages.
    pub const ALL: [ShaderKind; 5] = [
        ShaderKind::Texture,
        ShaderKind::Frequency,
        ShaderKind::Time,
        ShaderKind::Light,
        ShaderKind::Polarization,
    ];

    /// The lowercase name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ShaderKind::Texture => "texture",
            ShaderKind::Frequency => "frequency",
            ShaderKind::Time => "time",
            ShaderKind::Light => "light",
            ShaderKind::Polarization => "polarization",
        }
    }
}

impl FromStr for ShaderKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        ShaderKind::ALL
            .into_iter()
            .find(|k| k.name() == s.trim())
            .ok_or_else(|| {
                format!("unknown shader '{s}' (expected texture, frequency, time, light or polarization)")
            })
    }
}

/// Brightness of the frequency shader.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum BrightnessMode {
    /// Colour only.
    Normalized,
    /// Luminance Y(gT)/Y(T) times the exposure.
    Physical,
}

/// What the time layer shows.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum TimeMode {
    /// The window texture inside [t0, t0 + dt] of t_emit, the object's texture outside.
    Window,
    /// False colour by light travel time −t_emit over [travel_min, travel_max].
    Travel,
}

/// A texture choice for one object.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum TextureChoice {
    /// The texture the scene gave the object.
    Scene,
    /// Checkerboard, `rows` bands in v and `cols` in u.
    Checker { rows: u32, cols: u32 },
    /// Orientation ramp over (u, v).
    Gradient,
    /// One linear RGB colour.
    Uniform { color: [f64; 3] },
    /// An equirectangular image file (relative paths: from the current directory).
    Image { path: PathBuf },
    /// The built-in earth map.
    Earth,
}

impl FromStr for TextureChoice {
    type Err = String;
    /// Parses the command-line form: `scene`, `checker:ROWSxCOLS`, `gradient`,
    /// `uniform:R,G,B`, `image:PATH`, `earth`.
    fn from_str(s: &str) -> Result<Self, String> {
        let (kind, arg) = match s.split_once(':') {
            Some((k, a)) => (k.trim(), Some(a.trim())),
            None => (s.trim(), None),
        };
        let bad = || {
            format!(
                "'{s}' is not a texture (expected scene, checker:ROWSxCOLS, gradient, \
                 uniform:R,G,B, image:PATH or earth)"
            )
        };
        Ok(match (kind, arg) {
            ("scene", None) => TextureChoice::Scene,
            ("gradient", None) => TextureChoice::Gradient,
            ("earth", None) => TextureChoice::Earth,
            ("checker", Some(a)) => {
                let (r, c) = a.split_once(['x', 'X']).ok_or_else(bad)?;
                let rows = r.trim().parse().map_err(|_| bad())?;
                let cols = c.trim().parse().map_err(|_| bad())?;
                TextureChoice::Checker { rows, cols }
            }
            ("uniform", Some(a)) => {
                let v: Vec<f64> = a
                    .split(',')
                    .map(|x| x.trim().parse::<f64>())
                    .collect::<Result<_, _>>()
                    .map_err(|_| bad())?;
                let color: [f64; 3] = v.try_into().map_err(|_| bad())?;
                TextureChoice::Uniform { color }
            }
            ("image", Some(a)) if !a.is_empty() => TextureChoice::Image {
                path: PathBuf::from(a),
            },
            _ => return Err(bad()),
        })
    }
}

impl fmt::Display for TextureChoice {
    /// The command-line form ([`TextureChoice::from_str`] reads it back).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TextureChoice::Scene => write!(f, "scene"),
            TextureChoice::Checker { rows, cols } => write!(f, "checker:{rows}x{cols}"),
            TextureChoice::Gradient => write!(f, "gradient"),
            TextureChoice::Uniform { color } => {
                write!(f, "uniform:{},{},{}", color[0], color[1], color[2])
            }
            TextureChoice::Image { path } => write!(f, "image:{}", path.display()),
            TextureChoice::Earth => write!(f, "earth"),
        }
    }
}

/// A lamp on an object's body that blinks with the emission time.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Lamp {
    /// Centre in texture coordinates (moves with the texture).
    pub u: f64,
    pub v: f64,
    /// Angular radius on the body, degrees (> 0).
    pub radius_deg: f64,
    /// Blink period in coordinate time (> 0).
    pub period: f64,
    /// The lamp switches on at coordinate time `phase` (mod `period`).
    pub phase: f64,
    /// Fraction of the period it is on, in [0, 1].
    pub duty: f64,
    /// Linear RGB when on (≥ 0); off it shows a tenth of it.
    pub color: [f64; 3],
}

/// Per-object settings.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ObjectSettings {
    /// The first texture (texture layer; time layer outside the window).
    pub texture: TextureChoice,
    /// The second texture, inside the time window.
    pub window_texture: TextureChoice,
    /// Texture coordinates: u_tex = scale_u·u + offset_u − rotation_deg/360, v_tex = scale_v·v + offset_v.
    pub offset_u: f64,
    pub offset_v: f64,
    /// Finite; 0 spreads one texel over the whole body (a keyframed flip passes through it).
    pub scale_u: f64,
    pub scale_v: f64,
    /// The body turned about its axis by this angle (u is the longitude).
    pub rotation_deg: f64,
    /// Black-body temperature, K (> 0).
    pub temperature: f64,
    /// Blinking lamps.
    #[serde(default)]
    pub lamps: Vec<Lamp>,
    /// The body axis the object's light is linearly polarized along (polarization layer);
    /// `None`: unpolarized. Defaults to the scene's `polarization = { axis = … }`.
    #[serde(default)]
    pub polarization: Option<[f64; 3]>,
}

/// The time layer.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TimeSettings {
    pub mode: TimeMode,
    /// Window start in t_emit (emission time minus observer time, ≤ 0 for what is seen).
    pub t0: f64,
    /// Window length (> 0): inside means t0 ≤ t_emit ≤ t0 + dt.
    pub dt: f64,
    /// False-colour range of the travel time −t_emit (travel_min < travel_max).
    pub travel_min: f64,
    pub travel_max: f64,
    /// Draw the false-colour legend.
    pub legend: bool,
}

/// One light source's controls (index k: data channel `light_k`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LightSource {
    pub on: bool,
    /// ≥ 0.
    pub intensity: f64,
    /// Linear RGB, ≥ 0.
    pub color: [f64; 3],
}

/// The light layer: colour = albedo × (ambient + Σ_k on_k·intensity_k·color_k·light_k).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LightSettings {
    /// ≥ 0.
    pub ambient: f64,
    #[serde(default)]
    pub sources: Vec<LightSource>,
}

/// Every shader parameter. Build with [`ShadeSettings::defaults_for`], change fields, then
/// prepare with [`crate::Shading::new`].
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ShadeSettings {
    /// The layers, multiplied (non-empty, no repeats).
    pub shaders: Vec<ShaderKind>,
    pub brightness: BrightnessMode,
    /// Physical brightness multiplier (≥ 0).
    pub exposure: f64,
    /// Frequency layer: reference squares of the unshifted colours (first two objects).
    pub reference_squares: bool,
    /// Exposure compensation of pictures for display, in stops: colours are scaled by 2^ev
    /// before the tone curve ([`crate::colour::tone_map`]); within ±20. Linear (EXR) output
    /// is not scaled.
    #[serde(default)]
    pub ev: f64,
    /// Orientation marks (azimuth/elevation grid, ticks and labels, [`crate::marks`]).
    #[serde(default)]
    pub grid: bool,
    pub time: TimeSettings,
    pub light: LightSettings,
    /// By object name; objects not listed keep their defaults.
    pub objects: BTreeMap<String, ObjectSettings>,
}

/// Most lamps on one object: each is tested at every pixel of the object, so the cost of a
/// picture grows with them (20,000 lamps took 21.7 s of two cores for one picture).
pub const MAX_LAMPS: usize = 64;
/// Most light sources a settings value may list beyond the data file's light channels (more
/// may be listed where the data file has more channels).
pub const MAX_LIGHT_SOURCES: usize = 64;

/// Default highlight inside the time window: warm yellow.
pub const WINDOW_COLOUR: [f64; 3] = [1.0, 0.75, 0.1];
pub use scene::DEFAULT_TEMPERATURE;
/// Default ambient light.
pub const DEFAULT_AMBIENT: f64 = 0.15;

impl ObjectSettings {
    /// The scene's texture, unmoved, with this temperature.
    pub fn new(temperature: f64) -> ObjectSettings {
        ObjectSettings {
            texture: TextureChoice::Scene,
            window_texture: TextureChoice::Uniform {
                color: WINDOW_COLOUR,
            },
            offset_u: 0.0,
            offset_v: 0.0,
            scale_u: 1.0,
            scale_v: 1.0,
            rotation_deg: 0.0,
            temperature,
            lamps: Vec::new(),
            polarization: None,
        }
    }
}

impl ShadeSettings {
    /// The defaults for a data file: the texture shader with the scene's own textures (the
    /// render's preview), each object's temperature and each light's colour from the embedded
    /// scene, a time window and travel-time range spanning the emission times seen.
    /// Never fails: values the embedded scene lacks take the scene format's defaults.
    pub fn defaults_for(data: &DataFile) -> ShadeSettings {
        let scene: toml::Table = data.header.scene_text.parse().unwrap_or_default();
        let array = |key: &str| match scene.get(key) {
            Some(toml::Value::Array(a)) => a.clone(),
            _ => Vec::new(),
        };
        let scene_objects = array("object");
        let number = |v: Option<&toml::Value>| match v {
            Some(toml::Value::Float(f)) => Some(*f),
            Some(toml::Value::Integer(i)) => Some(*i as f64),
            _ => None,
        };
        let objects = data
            .header
            .object_names
            .iter()
            .enumerate()
            .map(|(k, name)| {
                let o = scene_objects.get(k);
                let t = o
                    .and_then(|o| number(o.get("temperature")))
                    .unwrap_or(DEFAULT_TEMPERATURE);
                let axis = o
                    .and_then(|o| o.get("polarization"))
                    .and_then(|p| p.get("axis"))
                    .and_then(|c| c.as_array())
                    .and_then(|c| {
                        let v: Vec<f64> = c.iter().filter_map(|x| number(Some(x))).collect();
                        <[f64; 3]>::try_from(v).ok()
                    });
                let mut settings = ObjectSettings::new(t);
                settings.polarization = axis;
                (name.clone(), settings)
            })
            .collect();
        let scene_lights = array("light");
        let sources = (0..data.lights.len())
            .map(|k| {
                let color = scene_lights
                    .get(k)
                    .and_then(|l| l.get("color"))
                    .and_then(|c| c.as_array())
                    .and_then(|c| {
                        let v: Vec<f64> = c.iter().filter_map(|x| number(Some(x))).collect();
                        <[f64; 3]>::try_from(v).ok()
                    })
                    .unwrap_or([1.0; 3]);
                LightSource {
                    on: true,
                    intensity: 1.0,
                    color,
                }
            })
            .collect();
        let (tmin, tmax) = travel_range(data);
        let dt = ((tmax - tmin) / 4.0).max(0.1);
        ShadeSettings {
            shaders: vec![ShaderKind::Texture],
            brightness: BrightnessMode::Normalized,
            exposure: 1.0,
            reference_squares: true,
            ev: 0.0,
            grid: false,
            time: TimeSettings {
                mode: TimeMode::Window,
                t0: -(tmin + tmax) / 2.0 - dt / 2.0,
                dt,
                travel_min: tmin,
                travel_max: tmax,
                legend: true,
            },
            light: LightSettings {
                ambient: DEFAULT_AMBIENT,
                sources,
            },
            objects,
        }
    }

    /// The settings as a TOML document (the settings-file format; reads back equal).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("settings always serialize to TOML")
    }

    /// These settings with the fields given in a partial TOML document (`text`, read from
    /// `file`) replaced; integers are accepted where numbers are expected. Unknown fields
    /// and objects and wrong types are errors naming the file and field.
    pub fn overlay_toml(&self, text: &str, file: &str) -> Result<ShadeSettings, ShadeError> {
        let partial: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            let line = e
                .span()
                .map(|s| scene::line_column(text, s.start).line)
                .unwrap_or(0);
            ShadeError::Settings {
                file: file.to_string(),
                line,
                field: String::new(),
                message: e.message().to_string(),
            }
        })?;
        self.overlay(&partial).map_err(|(field, message)| {
            let line = scene::line_of_path(text, &field).unwrap_or(0);
            ShadeError::Settings {
                file: file.to_string(),
                line,
                field,
                message,
            }
        })
    }

    /// These settings with a partial table's fields replaced; on error, the field path and
    /// what is wrong.
    pub fn overlay(&self, partial: &toml::Table) -> Result<ShadeSettings, (String, String)> {
        let base = toml::Table::try_from(self).expect("settings serialize to a TOML table");
        let merged = crate::tree::merge(&base, partial, "")?;
        ShadeSettings::from_table(merged)
    }

    /// Complete settings from a TOML table; on error, the path of the field at fault (e.g.
    /// `objects.ball.texture` for a checker without `rows`) and what is wrong.
    pub(crate) fn from_table(table: toml::Table) -> Result<ShadeSettings, (String, String)> {
        serde_path_to_error::deserialize(table).map_err(|e| {
            let path = e.path().to_string();
            let path = if path == "." { String::new() } else { path };
            (path, e.inner().message().to_string())
        })
    }
}

/// The range of light travel time −t_emit over hit pixels, rounded out to whole units; (0, 1)
/// when nothing was hit.
pub fn travel_range(data: &DataFile) -> (f64, f64) {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for r in &data.records {
        if r.object >= 0 && r.t_emit.is_finite() {
            let t = -f64::from(r.t_emit);
            lo = lo.min(t);
            hi = hi.max(t);
        }
    }
    if lo > hi {
        return (0.0, 1.0);
    }
    let (lo, hi) = (lo.floor().max(0.0), hi.ceil());
    if hi > lo {
        (lo, hi)
    } else {
        (lo, lo + 1.0)
    }
}
