//! The files a run reads, so that no output of the run replaces one of them (`godel shade
//! D.exr -o D.exr` would replace the data file with a picture, `godel look S.exr -o S.exr`
//! the sphere with a small view). Every output path is compared with every input before any
//! work, as files (`same_file`: device and inode on Unix, so another spelling, a symbolic
//! link or a hard link to an input is that input); such an output is refused as a usage
//! error naming the flag and the input's role.

use std::path::{Path, PathBuf};

use same_file::Handle;
use scene::{ImageSource, Scene, TextureSpec};
use shade::{ShadeSettings, TextureChoice};

use crate::args::usage;

/// The files a run reads, each with its role (`the data file`, `a texture of the scene`, …).
#[derive(Debug, Default)]
pub struct Inputs {
    files: Vec<(&'static str, PathBuf)>,
}

impl Inputs {
    /// No inputs yet.
    pub fn new() -> Inputs {
        Inputs::default()
    }

    /// Adds `path`, read as `role`.
    pub fn add(&mut self, role: &'static str, path: impl Into<PathBuf>) -> &mut Inputs {
        self.files.push((role, path.into()));
        self
    }

    /// Adds a scene's file (the built-in scene has none) and its image textures.
    pub fn add_scene(&mut self, scene: &Scene) -> &mut Inputs {
        if let Some(path) = &scene.source_path {
            self.add("the scene file", path);
        }
        for object in &scene.objects {
            if let TextureSpec::Image(ImageSource::File(path)) = &object.texture {
                self.add("a texture of the scene", path);
            }
        }
        self
    }

    /// Adds the image files that shade settings name.
    pub fn add_settings(&mut self, settings: &ShadeSettings) -> &mut Inputs {
        for object in settings.objects.values() {
            for choice in [&object.texture, &object.window_texture] {
                if let TextureChoice::Image { path } = choice {
                    self.add("a texture", path);
                }
            }
        }
        self
    }

    /// The role of the input that `output` is, if it is one.
    pub fn role_of(&self, output: &Path) -> Option<&'static str> {
        self.files
            .iter()
            .find(|(_, input)| match (handle(input), handle(output)) {
                (Some(a), Some(b)) => a == b,
                _ => false,
            })
            .map(|(role, _)| *role)
    }

    /// Refuses, as a usage error naming `flag`, the first of `outputs` that is an input.
    pub fn refuse_outputs_over_inputs<P: AsRef<Path>>(
        &self,
        flag: &str,
        outputs: &[P],
    ) -> anyhow::Result<()> {
        match self.clash(outputs) {
            Some(why) => Err(usage(flag, why)),
            None => Ok(()),
        }
    }

    /// Why the first of `outputs` that is an input must not be written, if one is (each
    /// input opened once, each output that exists once: fine for every frame of a sequence).
    pub fn clash<P: AsRef<Path>>(&self, outputs: &[P]) -> Option<String> {
        let inputs: Vec<(&str, Handle)> = self
            .files
            .iter()
            .filter_map(|(role, path)| Some((*role, handle(path)?)))
            .collect();
        if inputs.is_empty() {
            return None;
        }
        outputs.iter().find_map(|output| {
            let output = output.as_ref();
            // No file there: nothing is read from it.
            let handle = handle(output)?;
            let (role, _) = inputs.iter().find(|(_, input)| *input == handle)?;
            Some(format!(
                "{} is {role} this run reads; it is never overwritten: write elsewhere",
                output.display()
            ))
        })
    }
}

/// The identity of the regular file at `path` (through links), `None` for anything else: a
/// FIFO or device is never opened (opening a FIFO waits for a writer), and no output
/// replaces one.
fn handle(path: &Path) -> Option<Handle> {
    let regular = std::fs::metadata(path).is_ok_and(|m| m.is_file());
    regular.then(|| Handle::from_path(path).ok()).flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_that_is_an_input_by_any_path_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let data = dir.path().join("d.exr");
        std::fs::write(&data, b"data").unwrap();
        let mut inputs = Inputs::new();
        inputs.add("the data file", &data);
        // The same file by another spelling, and through a hard link.
        let spelled = dir.path().join(".").join("d.exr");
        let linked = dir.path().join("link.exr");
        std::fs::hard_link(&data, &linked).unwrap();
        for output in [&data, &spelled, &linked] {
            let e = inputs
                .refuse_outputs_over_inputs("--output", &[output])
                .unwrap_err();
            assert!(e.to_string().starts_with("--output: "), "{e}");
            assert!(e.to_string().contains("the data file"), "{e}");
        }
        // Another file, existing or not, is no input.
        let other = dir.path().join("other.exr");
        inputs
            .refuse_outputs_over_inputs("--output", &[&other])
            .unwrap();
        std::fs::write(&other, b"x").unwrap();
        inputs
            .refuse_outputs_over_inputs("--output", &[&other])
            .unwrap();
    }
}
