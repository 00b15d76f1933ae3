//! What the server holds while it runs: the data file in memory, its default settings, where
//! image textures may come from, the bound on shading work, and the operations the routes
//! need (prepare and shade settings, one pixel's record, a keyframe), the shading all done by
//! the `shade` crate. Immutable after loading, so every request shares it without locks.
//!
//! Image textures (the embedded scene's and those a client names) are read only from the data
//! file's folder and the folders named with `--textures` ([`shade::TextureSource::within`]);
//! the embedded scene's are loaded once, here.
//!
//! One eye's data file of a stereo pair (`NAME.left.exr`) is loaded with the other eye's
//! beside it ([`shade::stereo::partner`]), as a state of its own ([`Stereo::partner`]), so
//! that both eyes shade with one set of settings; without that file the one eye is served
//! alone, and `/api/info` says so.

use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use datafile::record::RayStatus;
use datafile::DataFile;
use image::RgbImage;
use serde::Serialize;
use shade::{Channels, Needs, ShadeSettings, Shading, TextureSource};

use crate::limit::WorkLimit;

/// Why a data file cannot be viewed: it cannot be read, a texture folder cannot be used, the
/// embedded scene's textures cannot be loaded from the allowed folders, or its default
/// settings cannot be prepared.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error(transparent)]
    Data(#[from] datafile::DataFileError),
    #[error(transparent)]
    TextureFolder(shade::ShadeError),
    #[error(
        "data file {}: {source}; the viewer reads image textures only from the data file's \
         folder and the folders named with --textures DIR",
        path.display()
    )]
    SceneTextures {
        path: PathBuf,
        #[source]
        source: shade::ShadeError,
    },
    #[error("data file {}: {source}", path.display())]
    Shade {
        path: PathBuf,
        #[source]
        source: shade::ShadeError,
    },
    /// The other eye's file of a stereo pair is there but does not read or is not that eye.
    #[error(transparent)]
    Partner(shade::stereo::PartnerError),
}

/// How to serve a data file beyond the file itself.
#[derive(Debug)]
pub struct ViewerOptions {
    /// Folders image textures may come from besides the data file's own (`--textures`).
    pub texture_folders: Vec<PathBuf>,
    /// The bound on concurrent shading work.
    pub work: WorkLimit,
}

impl Default for ViewerOptions {
    /// No further texture folders; one shading job per core.
    fn default() -> ViewerOptions {
        ViewerOptions {
            texture_folders: Vec::new(),
            work: WorkLimit::for_this_machine(),
        }
    }
}

/// A loaded data file, ready to shade.
pub struct ViewerState {
    /// The file as named on the command line (never shown to clients: [`Info::file`] is its
    /// file name).
    pub path: PathBuf,
    /// Shared, not copied: explore mode serves its frames' data files as they were traced.
    pub data: Arc<DataFile>,
    defaults: ShadeSettings,
    textures: TextureSource,
    work: WorkLimit,
    /// The camera of the embedded scene, sized to the data file (for pixel directions).
    camera: Option<scene::Camera>,
    /// Every shading channel of `data`, copied once on the first picture shaded: what each
    /// picture is shaded from (a state that only answers hovers never makes it).
    channels: OnceLock<Channels>,
    /// Of one eye's data file of a stereo pair: which, and the other eye.
    stereo: Option<Stereo>,
}

/// One eye of a stereo pair being viewed, and the other when its file was beside it.
pub struct Stereo {
    /// Which eye the viewed file is.
    pub eye: scene::Eye,
    /// The pair's layout.
    pub layout: scene::Layout,
    /// The other eye's data file, loaded as the viewed one was (textures from the same
    /// folders); `None` when its file was missing.
    pub partner: Option<Box<ViewerState>>,
}

/// `stereo` of [`Info`]: the viewed file is this eye of a pair in this layout; `partner`
/// whether the other eye's file was found (both eyes can be shaded).
#[derive(Clone, Debug, Serialize)]
pub struct StereoInfo {
    pub eye: &'static str,
    pub layout: &'static str,
    pub partner: bool,
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
    /// Where the pixel looks, in degrees in the camera basis (azimuth from forward toward
    /// right, elevation above the forward–right plane; `shade::marks::pixel_angles`, from
    /// the camera in the data file's embedded scene); `null` where the camera does not look.
    pub azimuth_deg: Option<f64>,
    pub elevation_deg: Option<f64>,
}

/// What the page needs to build its controls.
#[derive(Clone, Debug, Serialize)]
pub struct Info {
    /// The data file's name, without its folder.
    pub file: String,
    pub scene_name: String,
    /// The picture's size (the data file's image divided by `supersample`).
    pub width: usize,
    pub height: usize,
    /// Samples per picture pixel along each side (1: one ray per pixel): the channels the
    /// GPU routes send are the sample grid, `width`·s × `height`·s.
    pub supersample: usize,
    pub objects: Vec<String>,
    pub lights: usize,
    /// Whether the file has the polarization channels (pol_x, pol_y, pol_z).
    pub polarization: bool,
    pub observer_time: f64,
    pub defaults: ShadeSettings,
    /// One eye of a stereo pair, `null` for a mono file.
    pub stereo: Option<StereoInfo>,
}

impl ViewerState {
    /// Reads `path` and checks that its default settings shade; errors name the file.
    pub fn load(path: &Path) -> Result<ViewerState, LoadError> {
        ViewerState::load_with(path, ViewerOptions::default())
    }

    /// [`ViewerState::load`] with `options`; one eye's file of a stereo pair with the other
    /// eye's beside it, when that is there (a file there that is not the other eye of the
    /// pair is an error).
    pub fn load_with(path: &Path, options: ViewerOptions) -> Result<ViewerState, LoadError> {
        let data = DataFile::read(path)?;
        let found = shade::stereo::partner(path, &data);
        let own = ViewerOptions {
            texture_folders: options.texture_folders.clone(),
            work: options.work.clone(),
        };
        let stereo = match found {
            Ok(None) => None,
            Ok(Some(p)) => Some(Stereo {
                eye: p.eye,
                layout: p.layout,
                partner: Some(Box::new(ViewerState::new_with(&p.path, p.data, own)?)),
            }),
            Err(e) if e.is_missing() => {
                // `partner` read the mark before it looked for the file.
                let mark = scene::stereo_from_str(&data.header.scene_text, "")
                    .ok()
                    .flatten();
                mark.and_then(|s| s.eye.map(|eye| (eye, s.layout)))
                    .map(|(eye, layout)| Stereo {
                        eye,
                        layout,
                        partner: None,
                    })
            }
            Err(e) => return Err(LoadError::Partner(e)),
        };
        let mut state = ViewerState::new_with(path, data, options)?;
        state.stereo = stereo;
        Ok(state)
    }

    /// Prepares an already-read data file (`path` names it in messages and gives its folder)
    /// with the default options.
    pub fn new(path: &Path, data: impl Into<Arc<DataFile>>) -> Result<ViewerState, LoadError> {
        ViewerState::new_with(path, data, ViewerOptions::default())
    }

    /// Prepares an already-read data file. The embedded scene's textures are loaded and the
    /// default settings shaded once here, so a file whose scene textures cannot be loaded is
    /// refused before anything is served.
    pub fn new_with(
        path: &Path,
        data: impl Into<Arc<DataFile>>,
        options: ViewerOptions,
    ) -> Result<ViewerState, LoadError> {
        let data = data.into();
        let mut folders = vec![path.parent().unwrap_or(Path::new("")).to_path_buf()];
        folders.extend(options.texture_folders);
        let textures = TextureSource::within(&folders)
            .map_err(LoadError::TextureFolder)?
            .with_scene_textures(&data)
            .map_err(|source| LoadError::SceneTextures {
                path: path.to_path_buf(),
                source,
            })?;
        let defaults = ShadeSettings::defaults_for(&data);
        Shading::with_textures(&data, &defaults, &textures).map_err(|source| LoadError::Shade {
            path: path.to_path_buf(),
            source,
        })?;
        let camera = shade::marks::data_camera(&data);
        Ok(ViewerState {
            path: path.to_path_buf(),
            data,
            defaults,
            textures,
            work: options.work,
            camera,
            channels: OnceLock::new(),
            stereo: None,
        })
    }

    /// Of one eye's data file of a stereo pair: which, and the other eye when loaded.
    pub fn stereo(&self) -> Option<&Stereo> {
        self.stereo.as_ref()
    }

    /// Every shading channel of the data file, copied on first use.
    fn channels(&self) -> &Channels {
        self.channels
            .get_or_init(|| Channels::new(&self.data, Needs::ALL))
    }

    /// The canonical folders image textures may come from (the data file's first).
    pub fn texture_folders(&self) -> &[PathBuf] {
        self.textures.folders().unwrap_or_default()
    }

    /// The embedded scene's textures in object order, image files from the allowed folders
    /// (loaded once, when the file was loaded).
    pub fn scene_textures(&self) -> Result<Vec<shade::Texture>, shade::ShadeError> {
        self.textures.scene_textures(&self.data)
    }

    /// The scene embedded in the data file, validated with its image paths resolved in the
    /// allowed folders (as its textures were when the file was loaded).
    pub fn embedded_scene(&self) -> Result<scene::Scene, shade::ShadeError> {
        self.textures.embedded_scene(&self.data.header.scene_text)
    }

    /// The bound on concurrent shading work.
    pub fn work(&self) -> &WorkLimit {
        &self.work
    }

    pub fn info(&self) -> Info {
        let h = &self.data.header;
        Info {
            file: self
                .path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            scene_name: h.scene_name.clone(),
            width: self.data.picture_size().0,
            height: self.data.picture_size().1,
            supersample: self.data.supersample(),
            objects: h.object_names.clone(),
            lights: self.data.lights.len(),
            polarization: self.data.polarization,
            observer_time: h.observer_time,
            defaults: self.defaults.clone(),
            stereo: self.stereo.as_ref().map(|s| StereoInfo {
                eye: s.eye.name(),
                layout: s.layout.name(),
                partner: s.partner.is_some(),
            }),
        }
    }

    /// Checks settings sent by the page against this file and prepares them (the `shade`
    /// crate checks the values and caps, loads the textures from the allowed folders and names
    /// the bad field).
    pub fn prepare(&self, settings: &ShadeSettings) -> Result<Shading, shade::ShadeError> {
        Shading::with_textures(&self.data, settings, &self.textures)
    }

    /// The picture for prepared settings as RGB8 bytes, row 0 first; rows in parallel, from
    /// the channels copied at load.
    pub fn shade_rgb(&self, shading: &Shading, bytes: &mut Vec<u8>) {
        shading.image_into_with(self.channels(), bytes);
    }

    /// The picture for prepared settings.
    pub fn shade(&self, shading: &Shading) -> RgbImage {
        shading.image_with(self.channels())
    }

    /// The record of picture pixel (`col`, `row`) ([`picture_sample`]), or `None` outside
    /// the picture.
    pub fn pixel(&self, col: usize, row: usize) -> Option<PixelInfo> {
        let i = picture_sample(&self.data, col, row)?;
        let r = self.data.records.get(i)?;
        let angles = self.camera.as_ref().and_then(|c| {
            shade::marks::pixel_angles(c, u32::try_from(col).ok()?, u32::try_from(row).ok()?)
        });
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
            azimuth_deg: angles.map(|a| a.0),
            elevation_deg: angles.map(|a| a.1),
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

/// The index of the record that stands for picture pixel (`col`, `row`) of `data`, or `None`
/// outside the picture: in an anti-aliased file (s×s samples per pixel) the sample at
/// (⌊s/2⌋, ⌊s/2⌋) of the pixel's block, the one nearest its centre.
pub fn picture_sample(data: &DataFile, col: usize, row: usize) -> Option<usize> {
    let (w, h) = data.picture_size();
    if col >= w || row >= h {
        return None;
    }
    let s = data.supersample();
    Some(data.index(s * col + s / 2, s * row + s / 2))
}
