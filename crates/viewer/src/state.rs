//! What the server holds while it runs: the data file in memory, the textures of its
//! scene, and the operations the routes need (shade with settings, one pixel's record,
//! a keyframe). Immutable after loading, so every request shares it without locks.

use std::path::{Path, PathBuf};

use image::RgbImage;
use render::datafile::DataFile;
use render::record::RayStatus;
use serde::Serialize;
use shade::Texture;

use crate::settings::{Brightness, Shader, ViewSettings};

/// Why a data file cannot be viewed.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error(transparent)]
    Data(#[from] render::datafile::DataFileError),
    #[error("data file {}: the scene stored in its header: {source}", path.display())]
    Scene {
        path: PathBuf,
        #[source]
        source: scene::SceneError,
    },
    #[error("data file {}: {source}", path.display())]
    Textures {
        path: PathBuf,
        #[source]
        source: shade::ShadeError,
    },
    #[error("data file {}: its objects {data:?} are not its scene's objects {scene:?}", path.display())]
    Objects {
        path: PathBuf,
        data: Vec<String>,
        scene: Vec<String>,
    },
}

/// A loaded data file, ready to shade.
pub struct ViewerState {
    /// The file as named on the command line.
    pub path: PathBuf,
    pub data: DataFile,
    textures: Vec<Texture>,
    defaults: ViewSettings,
}

/// One pixel's record as the page shows it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PixelInfo {
    pub col: usize,
    pub row: usize,
    /// Object index, −1 for none.
    pub object: i32,
    /// Its name, or `null`.
    pub object_name: Option<String>,
    /// `hit`, `escaped`, `step budget`, `failed`, `not traced`.
    pub status: &'static str,
    pub u: f32,
    pub v: f32,
    pub g: f32,
    pub t_emit: f32,
    /// Light travel time −t_emit (coordinate time).
    pub travel_time: f32,
    /// Emission event, pseudo-Cartesian.
    pub x: f32,
    pub y: f32,
    pub z: f32,
    /// Direct light from each source, where the file has light channels.
    pub lights: Vec<f32>,
}

/// What the page needs to build its controls.
#[derive(Clone, Debug, Serialize)]
pub struct Info {
    pub file: String,
    pub scene_name: String,
    pub width: usize,
    pub height: usize,
    pub objects: Vec<String>,
    pub lights: usize,
    pub observer_time: f64,
    pub defaults: ViewSettings,
}

impl ViewerState {
    /// Reads `path` and prepares its scene's textures; errors name the file.
    pub fn load(path: &Path) -> Result<ViewerState, LoadError> {
        let data = DataFile::read(path)?;
        ViewerState::new(path, data)
    }

    /// Prepares an already-read data file (`path` names it in messages).
    pub fn new(path: &Path, data: DataFile) -> Result<ViewerState, LoadError> {
        let path = path.to_path_buf();
        let scene = scene::Scene::from_str(&data.header.scene_text, &path.display().to_string())
            .map_err(|source| LoadError::Scene {
                path: path.clone(),
                source,
            })?;
        let scene_names: Vec<String> = scene.objects.iter().map(|o| o.name.clone()).collect();
        if scene_names != data.header.object_names {
            return Err(LoadError::Objects {
                path,
                data: data.header.object_names.clone(),
                scene: scene_names,
            });
        }
        let textures = shade::textures_for_scene(&scene).map_err(|source| LoadError::Textures {
            path: path.clone(),
            source,
        })?;
        let temperatures: Vec<f64> = scene.objects.iter().map(|o| o.temperature).collect();
        Ok(ViewerState {
            path,
            data,
            textures,
            defaults: ViewSettings::defaults(&temperatures),
        })
    }

    pub fn info(&self) -> Info {
        let h = &self.data.header;
        Info {
            file: self.path.display().to_string(),
            scene_name: h.scene_name.clone(),
            width: self.data.width,
            height: self.data.height,
            objects: h.object_names.clone(),
            lights: self.data.lights.len(),
            observer_time: h.observer_time,
            defaults: self.defaults.clone(),
        }
    }

    /// Checks settings sent by the page against this file.
    pub fn check(&self, settings: &ViewSettings) -> Result<(), String> {
        settings.validate(self.data.header.object_names.len())
    }

    /// The picture for `settings` (checked with [`ViewerState::check`]); rows in parallel.
    pub fn shade(&self, settings: &ViewSettings) -> RgbImage {
        match settings.shader {
            Shader::Texture => shade::shade_textures(&self.data, &self.textures, shade::BACKGROUND),
            Shader::Frequency => {
                let temperatures: Vec<f64> =
                    settings.objects.iter().map(|o| o.temperature).collect();
                let brightness = match settings.brightness {
                    Brightness::Normalized => shade::Brightness::Normalized,
                    Brightness::Physical => shade::Brightness::Physical {
                        exposure: settings.exposure,
                    },
                };
                shade::shade_frequency(&self.data, &temperatures, brightness)
            }
        }
    }

    /// The record of pixel (`col`, `row`), or `None` outside the image.
    pub fn pixel(&self, col: usize, row: usize) -> Option<PixelInfo> {
        if col >= self.data.width || row >= self.data.height {
            return None;
        }
        let i = self.data.index(col, row);
        let r = self.data.records.get(i)?;
        let object_name = usize::try_from(r.object)
            .ok()
            .and_then(|k| self.data.header.object_names.get(k).cloned());
        Some(PixelInfo {
            col,
            row,
            object: r.object,
            object_name,
            status: status_name(r.status),
            u: r.u,
            v: r.v,
            g: r.g,
            t_emit: r.t_emit,
            travel_time: 0.0 - r.t_emit, // not -t_emit: a miss (t_emit 0) shows 0, not -0
            x: r.x,
            y: r.y,
            z: r.z,
            lights: self.data.lights.iter().map(|plane| plane[i]).collect(),
        })
    }

    /// A sequence-script keyframe (TOML) holding `settings`.
    pub fn keyframe(&self, settings: &ViewSettings) -> Result<String, String> {
        settings.keyframe_toml(0.0)
    }
}

/// The page's word for a ray's end.
pub fn status_name(status: RayStatus) -> &'static str {
    match status {
        RayStatus::Hit => "hit",
        RayStatus::Escaped => "escaped",
        RayStatus::StepBudget => "step budget",
        RayStatus::Failed => "failed",
        RayStatus::NotTraced => "not traced",
    }
}
