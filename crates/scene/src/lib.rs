//! Scene files for the Gödel ray tracer: parsing, validation with located errors, and the
//! runtime scene description (docs/guide/src/scenes.md; docs/physics.md, "Pixels and cameras").
//!
//! Main types:
//! - [`Scene`]: the validated scene — metric, [`Observer`], [`Camera`], [`TraceSettings`],
//!   [`Object`]s (shape, [`TextureSpec`], temperature, [`Motion`]) and [`Light`]s.
//!   Read with [`Scene::from_file`], [`Scene::from_str`] or [`Scene::builtin`].
//! - [`Camera`]: pixel → direction, exactly as docs/physics.md ("Pixels and cameras") fixes
//!   it; [`Observer::pixel_direction`] gives the direction in the observer's local frame.
//! - [`SceneError`]: `file:line:column: field.path: message`.
//! - [`Scene::read_view`] and [`replace_view`]: read or replace only the observer's view
//!   (camera, velocity, camera axes) in scene text, as `godel look` does.
//!
//! - [`input`]: the bounded reader every input file of `godel` goes through.
//! - [`ranges`]: the ranges of `a` and of coordinates, for values given outside a scene.
//! - [`overrides`]: a scene (file, text or built-in) with some fields set for one run
//!   (`godel render --width …`, the Python module's `render(width=…)`), validated as a file.
//!
//! Reading goes in three steps: the TOML text is parsed into a spanned tree (kept to locate
//! errors), deserialized into raw records (`raw.rs`, unknown fields rejected), then checked
//! and converted (`validate.rs`). No input makes it panic.

mod camera;
mod checker;
mod edit;
mod error;
pub mod input;
mod model;
mod objects;
pub mod overrides;
pub mod ranges;
mod raw;
mod stereo;
mod validate;

pub use camera::{
    azimuth_elevation, direction_from, samples_per_side, Camera, MAX_RAYS, MAX_SAMPLES,
};
pub use edit::{replace_eye, replace_samples, replace_view};
pub use error::{line_column, line_of_path, one_line, Location, SceneError};
pub use model::{
    BuiltinImage, Eye, ImageSource, Layout, Light, Motion, Object, ObjectFrame, Observer, Scene,
    Shape, Stereo, TextureSpec, TraceMethod, TraceSettings, DEFAULT_TEMPERATURE,
};
pub use spacetime::message::short;
pub use stereo::MAX_SEPARATION_PER_A;

pub use validate::{A_RANGE, MAX_COORDINATE_PER_A, MAX_LOCAL_RADIUS_PER_A, MAX_RAY_LOOPS};

use error::Locator;
use serde::Deserialize;
use std::path::Path;

/// The built-in reference scene (scenes/reference.toml): the paper's reference picture.
pub const BUILTIN_SCENE_TEXT: &str = include_str!("../../../scenes/reference.toml");
/// The file name errors in the built-in scene would report.
pub const BUILTIN_SCENE_NAME: &str = "<builtin reference.toml>";

impl Scene {
    /// Reads and validates a scene file (a regular file of at most
    /// [`input::MAX_TEXT_BYTES`]). Relative image paths are resolved against the file's
    /// directory.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let file = path.display().to_string();
        let text = input::read_text(path, input::MAX_TEXT_BYTES).map_err(|e| SceneError {
            file: file.clone(),
            location: None,
            field: String::new(),
            message: format!("cannot read the scene file: {e}"),
        })?;
        let base = path.parent().unwrap_or(Path::new(""));
        let mut scene = parse(&text, &file, base)?;
        scene.source_path = Some(path.to_path_buf());
        Ok(scene)
    }

    /// Validates scene text. `name_for_errors` is the file name used in error messages and
    /// is treated as the would-be path of the text: relative image paths are resolved
    /// against its directory (the current directory for a bare name).
    #[allow(clippy::should_implement_trait)]
    pub fn from_str(text: &str, name_for_errors: &str) -> Result<Scene, SceneError> {
        let base = Path::new(name_for_errors).parent().unwrap_or(Path::new(""));
        parse(text, name_for_errors, base)
    }

    /// Reads only the observer and the camera of scene text (both validated as in a whole
    /// scene), leaving objects, textures and lights unchecked: data files embed their scene
    /// text, whose image paths may not resolve where the data file is read.
    pub fn read_view(text: &str, name_for_errors: &str) -> Result<(Observer, Camera), SceneError> {
        with_raw(text, name_for_errors, |raw, loc| {
            let c = checker::Checker { loc };
            Ok((
                validate::observer(&c, raw.observer)?,
                validate::camera(&c, raw.camera)?,
            ))
        })
    }

    /// Samples per pixel along each side: s for `samples` = s².
    pub fn supersample(&self) -> u32 {
        (f64::from(self.samples).sqrt().round() as u32).max(1)
    }

    /// The camera whose pixels are this scene's samples (see [`Camera::supersampled`]).
    pub fn sample_camera(&self) -> Camera {
        self.camera.supersampled(self.supersample())
    }

    /// Sets the rays per pixel (e.g. from `godel render --samples`), checked as
    /// `[camera] samples` is; the message names no flag (the caller does).
    pub fn set_samples(&mut self, samples: i64) -> Result<(), String> {
        samples_per_side(samples, self.camera.width(), self.camera.height())?;
        self.samples = samples as u32;
        Ok(())
    }

    /// The built-in reference scene ([`BUILTIN_SCENE_TEXT`]).
    pub fn builtin() -> Scene {
        // The embedded text is fixed at compile time and tested (`builtin_scene_is_valid`),
        // so this cannot fail at run time.
        parse(BUILTIN_SCENE_TEXT, BUILTIN_SCENE_NAME, Path::new(""))
            .expect("the built-in scene is valid")
    }
}

/// Only the `[camera]` of scene text, validated as in a scene file; the rest of the text
/// must be TOML but is not checked. For readers of a data file's embedded scene (marks, the
/// viewer's pixel directions), whose image textures need not be where the scene was.
pub fn camera_from_str(text: &str, name_for_errors: &str) -> Result<Camera, SceneError> {
    with_raw_camera(text, name_for_errors, validate::camera_only)
}

/// Only `[camera] stereo` of scene text, checked as in a scene file (`None` without one);
/// for readers of a data file's embedded scene, as [`camera_from_str`].
pub fn stereo_from_str(text: &str, name_for_errors: &str) -> Result<Option<Stereo>, SceneError> {
    with_raw_camera(text, name_for_errors, |loc, raw| {
        stereo::stereo(&checker::Checker { loc }, raw.stereo, MAX_COORDINATE_PER_A)
    })
}

/// The raw `[camera]` of scene text handed to `check` with its locator; the rest of the text
/// must be TOML but is not checked.
fn with_raw_camera<T>(
    text: &str,
    name_for_errors: &str,
    check: impl FnOnce(&Locator, raw::RawCamera) -> Result<T, SceneError>,
) -> Result<T, SceneError> {
    /// The document with everything but the camera ignored.
    #[derive(Deserialize)]
    struct CameraOnly {
        camera: raw::RawCamera,
    }
    let root = toml::de::DeTable::parse(text).map_err(|e| {
        Locator::new(name_for_errors, text, None).at_span(e.span(), e.message().to_string())
    })?;
    let loc = Locator::new(name_for_errors, text, Some(&root));
    let raw = CameraOnly::deserialize(toml::de::Deserializer::from(root.clone()))
        .map_err(|e| loc.at_span(e.span(), e.message().to_string()))?;
    check(&loc, raw.camera)
}

fn parse(text: &str, file: &str, base_dir: &Path) -> Result<Scene, SceneError> {
    with_raw(text, file, |raw, loc| {
        validate::build(raw, text, loc, base_dir)
    })
}

/// Parses scene text into the raw records (`raw.rs`) and hands them to `check`, with the
/// locator that places its errors in the text.
fn with_raw<T>(
    text: &str,
    file: &str,
    check: impl FnOnce(raw::RawScene, &Locator) -> Result<T, SceneError>,
) -> Result<T, SceneError> {
    let root = match toml::de::DeTable::parse(text) {
        Ok(root) => root,
        Err(e) => {
            // The best-effort tree of a broken document still names the field near the error.
            let (partial, _) = toml::de::DeTable::parse_recoverable(text);
            let loc = Locator::new(file, text, Some(&partial));
            let mut message = e.message().to_string();
            // toml does not say which key is duplicated; its span does.
            if let Some(key) = e
                .span()
                .and_then(|s| text.get(s))
                .filter(|k| !k.contains('\n'))
            {
                if message == "duplicate key" {
                    message = format!("duplicate key `{key}`");
                }
            }
            return Err(loc.at_span(e.span(), message));
        }
    };
    let loc = Locator::new(file, text, Some(&root));
    let raw = raw::RawScene::deserialize(toml::de::Deserializer::from(root.clone()))
        .map_err(|e| loc.at_span(e.span(), e.message().to_string()))?;
    check(raw, &loc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_scene_is_valid() {
        let s = Scene::builtin();
        assert_eq!(s.camera.width(), 880);
        assert_eq!(s.metric.godel_a(), Some(1.0));
    }

    #[test]
    fn the_camera_reads_without_the_rest_of_the_scene() {
        // An image texture that is not there: the scene is refused, its camera is not.
        let text = BUILTIN_SCENE_TEXT.replace(r#"builtin = "earth""#, r#"path = "gone.png""#);
        assert!(Scene::from_str(&text, "x.toml").is_err());
        let camera = camera_from_str(&text, "x.toml").unwrap();
        assert_eq!(camera, Scene::builtin().camera);
        // The camera itself is checked as in a scene file, with the place of the error.
        let bad = BUILTIN_SCENE_TEXT.replace("width = 880", "width = 0");
        let e = camera_from_str(&bad, "x.toml").unwrap_err();
        assert_eq!(e.field, "camera.width");
        assert!(e.line().is_some());
    }
}
