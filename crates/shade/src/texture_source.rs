//! [`TextureSource`]: where image textures may be read from when settings are prepared.
//!
//! - [`TextureSource::any`] (the command line: `godel shade`, `godel sequence`): any file the
//!   user names, relative paths from the current directory, and the embedded scene's own
//!   textures resolved from the current directory as well.
//! - [`TextureSource::within`] (the web viewer, whose settings come from any client): only
//!   regular files inside the given folders. A path is resolved against each folder in turn
//!   (an absolute path as it is), canonicalized (symbolic links resolved, `..` removed), and
//!   refused unless the result lies inside one of the folders. A refusal says the same
//!   whatever the reason (missing, outside, not a regular file), and names the path only as
//!   the client gave it, so that answers reveal nothing about other files.
//!
//! Every file read is bounded ([`crate::texture`]: regular files, size and side caps). Within
//! one preparation each file is decoded once, however many objects use it
//! ([`TextureSource::image_cached`]). [`TextureSource::with_scene_textures`] loads the embedded
//! scene's textures once, for a server that prepares settings on every request.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use datafile::DataFile;
use scene::{ImageSource, Scene, TextureSpec};

use crate::error::ShadeError;
use crate::texture::{ImageTexture, Texture};

/// The name the embedded scene goes by in messages.
const EMBEDDED: &str = "<scene embedded in the data file>";

/// Where image textures may come from, and the embedded scene's textures once loaded.
#[derive(Clone, Debug, Default)]
pub struct TextureSource {
    /// Canonical folders; `None`: any file.
    folders: Option<Vec<PathBuf>>,
    /// The embedded scene's textures, with the scene text they were loaded from.
    scene: Option<(String, Vec<Texture>)>,
}

impl TextureSource {
    /// Any file (the command line, where the user names the files).
    pub fn any() -> TextureSource {
        TextureSource::default()
    }

    /// Only regular files inside `folders` (each canonicalized here; one that is not a
    /// readable folder is an error naming it). With no folders, no image file at all.
    pub fn within<P: AsRef<Path>>(folders: &[P]) -> Result<TextureSource, ShadeError> {
        let mut canonical = Vec::with_capacity(folders.len());
        for folder in folders {
            let folder = folder.as_ref();
            let error = |message: String| ShadeError::TextureFolder {
                path: folder.to_path_buf(),
                message,
            };
            // `Path::new("")` (the parent of a bare file name) is the current directory.
            let named = if folder.as_os_str().is_empty() {
                Path::new(".")
            } else {
                folder
            };
            let c = std::fs::canonicalize(named).map_err(|e| error(e.to_string()))?;
            if !c.is_dir() {
                return Err(error("not a folder".into()));
            }
            canonical.push(c);
        }
        Ok(TextureSource {
            folders: Some(canonical),
            scene: None,
        })
    }

    /// The canonical folders textures may come from; `None` for any file.
    pub fn folders(&self) -> Option<&[PathBuf]> {
        self.folders.as_deref()
    }

    /// Where `path` may be read from: itself for [`TextureSource::any`]; otherwise the
    /// canonical path of a regular file inside one of the folders, or
    /// [`ShadeError::ImageRefused`].
    pub fn resolve(&self, path: &Path) -> Result<PathBuf, ShadeError> {
        let Some(folders) = &self.folders else {
            return Ok(path.to_path_buf());
        };
        let candidates: Vec<PathBuf> = if path.is_absolute() {
            vec![path.to_path_buf()]
        } else {
            folders.iter().map(|f| f.join(path)).collect()
        };
        candidates
            .into_iter()
            .filter_map(|c| std::fs::canonicalize(c).ok())
            .find(|c| folders.iter().any(|f| c.starts_with(f)) && c.is_file())
            .ok_or_else(|| ShadeError::ImageRefused {
                path: path.to_path_buf(),
            })
    }

    /// The image at `path` ([`TextureSource::resolve`], then read with the caps); errors name
    /// `path` as given.
    pub fn image(&self, path: &Path) -> Result<ImageTexture, ShadeError> {
        ImageTexture::read(&self.resolve(path)?, path)
    }

    /// [`TextureSource::image`], decoding each resolved file once per `cache`.
    pub fn image_cached(
        &self,
        path: &Path,
        cache: &mut HashMap<PathBuf, ImageTexture>,
    ) -> Result<ImageTexture, ShadeError> {
        let file = self.resolve(path)?;
        if let Some(t) = cache.get(&file) {
            return Ok(t.clone());
        }
        let t = ImageTexture::read(&file, path)?;
        cache.insert(file, t.clone());
        Ok(t)
    }

    /// The runtime texture of a scene's texture spec, image files through this source.
    pub fn load(&self, spec: &TextureSpec) -> Result<Texture, ShadeError> {
        match spec {
            TextureSpec::Image(ImageSource::File(path)) => {
                // Show a path found inside a folder relative to it: messages need not
                // reveal where the folders are.
                let shown = self
                    .folders()
                    .into_iter()
                    .flatten()
                    .find_map(|f| path.strip_prefix(f).ok())
                    .unwrap_or(path);
                Ok(Texture::Image(ImageTexture::read(
                    &self.resolve(path)?,
                    shown,
                )?))
            }
            other => Texture::load(other),
        }
    }

    /// The textures of the scene embedded in `data`, in object order: those loaded by
    /// [`TextureSource::with_scene_textures`] for that scene, else read now. Relative image
    /// paths in the scene resolve against the current directory ([`TextureSource::any`]) or
    /// against the first of the folders in which the whole scene validates.
    pub fn scene_textures(&self, data: &DataFile) -> Result<Vec<Texture>, ShadeError> {
        if let Some((text, textures)) = &self.scene {
            if *text == data.header.scene_text {
                return Ok(textures.clone());
            }
        }
        let scene = self.embedded_scene(&data.header.scene_text)?;
        scene
            .objects
            .iter()
            .map(|o| self.load(&o.texture))
            .collect()
    }

    /// This source with the textures of `data`'s embedded scene loaded once, for every later
    /// preparation of settings for that data file.
    pub fn with_scene_textures(mut self, data: &DataFile) -> Result<TextureSource, ShadeError> {
        let textures = self.scene_textures(data)?;
        self.scene = Some((data.header.scene_text.clone(), textures));
        Ok(self)
    }

    /// The embedded scene, validated with its relative image paths resolved as
    /// [`TextureSource::scene_textures`] says.
    pub fn embedded_scene(&self, text: &str) -> Result<Scene, ShadeError> {
        let Some((first, others)) = self.folders.as_deref().and_then(|f| f.split_first()) else {
            return Scene::from_str(text, EMBEDDED).map_err(ShadeError::EmbeddedScene);
        };
        // The scene crate resolves relative image paths against the directory of the name it
        // is given: try each folder, report the first folder's error.
        let parse = |folder: &Path| Scene::from_str(text, &folder.join(EMBEDDED).to_string_lossy());
        let first_try = parse(first);
        if first_try.is_err() {
            if let Some(scene) = others.iter().find_map(|f| parse(f).ok()) {
                return Ok(scene);
            }
        }
        first_try.map_err(ShadeError::EmbeddedScene)
    }
}
