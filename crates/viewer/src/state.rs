//! What the server holds while it runs: the data file in memory, its default settings, and
//! the operations the routes need (prepare and shade settings, one pixel's record, a
//! keyframe), the shading all done by the `shade` crate. Immutable after loading, so every
//! request shares it without locks.

use std::path::{Path, PathBuf};

use image::RgbImage;
use render::datafile::DataFile;
use render::record::RayStatus;
use serde::Serialize;
use shade::{ShadeSettings, Shading};

/// Why a data file cannot be viewed: it cannot be read, or its default settings (the
/// scene's own textures) cannot be prepared.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error(transparent)]
    Data(#[from] render::datafile::DataFileError),
    #[error("data file {}: {source}", path.display())]
    Shade {
        path: PathBuf,
        #[source]
        source: shade::ShadeError,
    },
}

/// A loaded data file, ready to shade.
pub struct ViewerState {
    /// The file as named on the command line.
    pub path: PathBuf,
    pub data: DataFile,
    defaults: ShadeSettings,
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
    /// `hit`, `escaped`, `step budget`, `failed`, `not traced`, `work limit`.
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
    pub defaults: ShadeSettings,
}

impl ViewerState {
    /// Reads `path` and checks that its default settings shade; errors name the file.
    pub fn load(path: &Path) -> Result<ViewerState, LoadError> {
        let data = DataFile::read(path)?;
        ViewerState::new(path, data)
    }

    /// Prepares an already-read data file (`path` names it in messages). The default
    /// settings are shaded once here, so a file whose scene textures cannot be loaded is
    /// refused before anything is served.
    pub fn new(path: &Path, data: DataFile) -> Result<ViewerState, LoadError> {
        let defaults = ShadeSettings::defaults_for(&data);
        Shading::new(&data, &defaults).map_err(|source| LoadError::Shade {
            path: path.to_path_buf(),
            source,
        })?;
        Ok(ViewerState {
            path: path.to_path_buf(),
            data,
            defaults,
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

    /// Checks settings sent by the page against this file and prepares them (the `shade`
    /// crate loads the textures and names the bad field).
    pub fn prepare(&self, settings: &ShadeSettings) -> Result<Shading, shade::ShadeError> {
        Shading::new(&self.data, settings)
    }

    /// The picture for prepared settings as RGB8 bytes, row 0 first; rows in parallel.
    pub fn shade_rgb(&self, shading: &Shading, bytes: &mut Vec<u8>) {
        shading.image_into(&self.data, bytes);
    }

    /// The picture for prepared settings.
    pub fn shade(&self, shading: &Shading) -> RgbImage {
        shading.image(&self.data)
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

    /// A sequence-script keyframe (TOML) at `frame` holding `settings`.
    pub fn keyframe(&self, frame: u32, settings: &ShadeSettings) -> String {
        shade::keyframe_toml(frame, settings)
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
        RayStatus::WorkLimit => "work limit",
    }
}
