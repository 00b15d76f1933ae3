//! The shader settings the page sends (JSON) and the keyframe it saves (TOML).
//!
//! Interim: a thin stand-in over the shaders `shade` has today (texture, frequency),
//! until `shade::settings::ShadeSettings` takes its place; the page only ever sends this
//! JSON, and every pixel is shaded by the `shade` crate.

use serde::{Deserialize, Serialize};

/// Which shader colours the hit pixels.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Shader {
    Texture,
    Frequency,
}

/// Colour only, or physical luminance times an exposure.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Brightness {
    Normalized,
    Physical,
}

/// Settings of one object.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectSettings {
    /// Black-body temperature in kelvin.
    pub temperature: f64,
}

/// Everything the page can change.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViewSettings {
    pub shader: Shader,
    pub brightness: Brightness,
    pub exposure: f64,
    /// One per object of the data file, in its order.
    pub objects: Vec<ObjectSettings>,
}

impl ViewSettings {
    /// The scene's own temperatures, texture shader, normalized brightness.
    pub fn defaults(temperatures: &[f64]) -> ViewSettings {
        ViewSettings {
            shader: Shader::Texture,
            brightness: Brightness::Normalized,
            exposure: 1.0,
            objects: temperatures
                .iter()
                .map(|&temperature| ObjectSettings { temperature })
                .collect(),
        }
    }

    /// Checks the values against a data file with `objects` objects; the message names the field.
    pub fn validate(&self, objects: usize) -> Result<(), String> {
        if self.objects.len() != objects {
            return Err(format!(
                "objects: {} entries, the data file has {objects} objects",
                self.objects.len()
            ));
        }
        if !(self.exposure.is_finite() && self.exposure >= 0.0) {
            return Err(format!(
                "exposure: must be finite and ≥ 0, got {}",
                self.exposure
            ));
        }
        for (k, o) in self.objects.iter().enumerate() {
            if !(o.temperature.is_finite() && o.temperature > 0.0) {
                return Err(format!(
                    "objects[{k}].temperature: must be positive, got {}",
                    o.temperature
                ));
            }
        }
        Ok(())
    }

    /// One keyframe of a sequence script (TOML) holding these settings at `time`.
    pub fn keyframe_toml(&self, time: f64) -> Result<String, String> {
        #[derive(Serialize)]
        struct Keyframe<'a> {
            time: f64,
            #[serde(flatten)]
            settings: &'a ViewSettings,
        }
        #[derive(Serialize)]
        struct Script<'a> {
            keyframe: [Keyframe<'a>; 1],
        }
        toml::to_string(&Script {
            keyframe: [Keyframe {
                time,
                settings: self,
            }],
        })
        .map_err(|e| e.to_string())
    }
}
