//! Shared by the render benches: an example scene at a given size and tracing method.

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
    let text = text
        .lines()
        .map(|l| {
            if l.starts_with("width") {
                format!("width = {width}")
            } else if l.starts_with("height") {
                format!("height = {height}\nsamples = {samples}")
            } else if l.starts_with("samples") {
                String::new()
            } else if l.starts_with("method") {
                format!("method = \"{method}\"")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    Scene::from_str(&text, path).expect("valid scene")
}
