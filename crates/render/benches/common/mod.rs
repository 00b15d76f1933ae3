//! Shared by the render benches: an example scene at a given size and tracing method.
//!
//! Only the `[camera]` table's `width`, `height` and `samples` and the `[trace]` table's
//! `method` are replaced; every other line (an object's `height`, for instance, the height
//! of a plane) is kept as written, so that the bench renders the scene file's geometry.

use scene::Scene;
use std::path::Path;

/// The scene file `path` (relative to the repository) with its `width`, `height` and
/// `method` lines replaced, one sample per pixel.
pub fn scene(path: &str, width: u32, height: u32, method: &str) -> Scene {
    sampled_scene(path, width, height, method, 1)
}

/// The same with `samples` rays per pixel.
#[allow(dead_code)] // used by the render bench, not the speed bench
pub fn sampled_scene(path: &str, width: u32, height: u32, method: &str, samples: u32) -> Scene {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path);
    let text = std::fs::read_to_string(&p).expect("scene file");
    let mut table = "";
    let mut out = Vec::new();
    for l in text.lines() {
        let key = l.split('=').next().unwrap_or("").trim();
        if l.starts_with('[') {
            table = l.trim();
        }
        match (table, key) {
            ("[camera]", "width") => out.push(format!("width = {width}")),
            ("[camera]", "height") => {
                out.push(format!("height = {height}"));
                out.push(format!("samples = {samples}"));
            }
            ("[camera]", "samples") => {}
            ("[trace]", "method") => out.push(format!("method = \"{method}\"")),
            _ => out.push(l.to_string()),
        }
    }
    let scene = Scene::from_str(&out.join("\n"), path).expect("valid scene");
    assert_eq!(
        (scene.camera.width(), scene.camera.height()),
        (width, height),
        "{path}: the bench could not set the camera size"
    );
    scene
}
