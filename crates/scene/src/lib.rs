//! Scene files for the Gödel ray tracer: parsing, validation with located errors, and the
//! runtime scene description (DESIGN.md, "Scene file (TOML)", "Cameras", "Errors").
//!
//! Main types:
//! - [`Scene`]: the validated scene — metric, [`Observer`], [`Camera`], [`TraceSettings`],
//!   [`Object`]s (shape, [`TextureSpec`], temperature, [`Motion`]) and [`Light`]s.
//!   Read with [`Scene::from_file`], [`Scene::from_str`] or [`Scene::builtin`].
//! - [`Camera`]: pixel → direction, exactly as DESIGN.md fixes it; [`Observer::pixel_direction`]
//!   gives the direction in the observer's local frame.
//! - [`SceneError`]: `file:line:column: field.path: message`.
//!
//! - [`input`]: the bounded reader every input file of `godel` goes through.
//!
//! Reading goes in three steps: the TOML text is parsed into a spanned tree (kept to locate
//! errors), deserialized into raw records (`raw.rs`, unknown fields rejected), then checked
//! and converted (`validate.rs`). No input makes it panic.

mod camera;
mod checker;
mod error;
pub mod input;
mod model;
mod objects;
mod raw;
mod validate;

pub use camera::{azimuth_elevation, direction_from, Camera};
pub use error::{line_column, one_line, Location, SceneError};
pub use model::{
    BuiltinImage, ImageSource, Light, Motion, Object, ObjectFrame, Observer, Scene, Shape,
    TextureSpec, TraceMethod, TraceSettings,
};
pub use validate::{MAX_LOCAL_RADIUS_PER_A, MAX_RAY_LOOPS};

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
    validate::camera_only(&loc, raw.camera)
}

fn parse(text: &str, file: &str, base_dir: &Path) -> Result<Scene, SceneError> {
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
    let parts = validate::build(raw, &loc, base_dir)?;
    Ok(Scene {
        name: parts.name,
        source_path: None,
        source_text: text.to_string(),
        metric: parts.metric,
        observer: parts.observer,
        camera: parts.camera,
        trace: parts.trace,
        objects: parts.objects,
        lights: parts.lights,
    })
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
