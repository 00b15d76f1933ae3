//! What `-o` names for the commands that write a data file and its preview (`render`,
//! `merge`): a FOLDER that receives `NAME.exr` and `NAME.png` (NAME the scene's name or
//! `--name`), or one of the two files itself, `x.exr` or `x.png` (any case: the name given is
//! the name written), the other then written beside it with the other extension in the same
//! case — as `shade` and `look` take the file they write.

use crate::args::usage;
use shade::hdr::PictureFormat;
use std::path::{Path, PathBuf};

/// Where a data file and its preview go.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OutPair {
    /// `FOLDER/NAME.exr` and `FOLDER/NAME.png`.
    Folder(PathBuf),
    /// The two files named by `-o x.exr` or `-o x.png`.
    Files { exr: PathBuf, png: PathBuf },
}

impl OutPair {
    /// What `path` (given to `flag`) names: a file when it ends in `.exr` or `.png`, else a
    /// folder. `name_given` says whether `--name` was given: it chooses NAME in a folder and
    /// is refused beside a file name, which already says it.
    pub fn parse(flag: &str, path: &Path, name_given: bool) -> anyhow::Result<OutPair> {
        let Some(format) = PictureFormat::from_path(path) else {
            return Ok(OutPair::Folder(path.to_path_buf()));
        };
        if name_given {
            return Err(usage(
                "--name",
                format!(
                    "not used when {flag} names the files ({}); give {flag} a folder to choose NAME",
                    path.display()
                ),
            ));
        }
        // The file named is written under that very name (`pic.EXR`); its partner takes the
        // other extension in the same case (`pic.PNG`).
        let upper = path
            .extension()
            .is_some_and(|e| e.to_string_lossy().chars().all(|c| c.is_ascii_uppercase()));
        let partner = |ext: &str| match upper {
            true => path.with_extension(ext.to_ascii_uppercase()),
            false => path.with_extension(ext),
        };
        Ok(match format {
            PictureFormat::Exr => OutPair::Files {
                exr: path.to_path_buf(),
                png: partner("png"),
            },
            PictureFormat::Png => OutPair::Files {
                exr: partner("exr"),
                png: path.to_path_buf(),
            },
        })
    }

    /// The folder the files go to (`.` for a bare file name).
    pub fn folder(&self) -> &Path {
        match self {
            OutPair::Folder(dir) => dir,
            OutPair::Files { exr, .. } => exr
                .parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(Path::new(".")),
        }
    }

    /// The data file and the preview for a scene named `name`.
    pub fn files(&self, name: &str) -> (PathBuf, PathBuf) {
        match self {
            OutPair::Folder(dir) => (
                dir.join(format!("{name}.exr")),
                dir.join(format!("{name}.png")),
            ),
            OutPair::Files { exr, png } => (exr.clone(), png.clone()),
        }
    }

    /// The two files' names within [`OutPair::folder`], for checking them before any work.
    pub fn names(&self, name: &str) -> Vec<String> {
        let (exr, png) = self.files(name);
        file_names(&[exr, png])
    }

    /// A stereo scene's files: each eye's data file (`NAME.left.exr`, `NAME.right.exr`: the
    /// data file's name with the eye before its extension) and the preview of both eyes.
    pub fn stereo_files(&self, name: &str) -> ([PathBuf; 2], PathBuf) {
        let (exr, png) = self.files(name);
        let eye = |e: scene::Eye| {
            let stem = exr.file_stem().unwrap_or_default().to_string_lossy();
            let ext = exr.extension().unwrap_or_default().to_string_lossy();
            exr.with_file_name(format!("{stem}.{}.{ext}", e.name()))
        };
        ([eye(scene::Eye::Left), eye(scene::Eye::Right)], png)
    }

    /// [`OutPair::stereo_files`]' names within [`OutPair::folder`].
    pub fn stereo_names(&self, name: &str) -> Vec<String> {
        let ([left, right], png) = self.stereo_files(name);
        file_names(&[left, right, png])
    }
}

fn file_names(paths: &[PathBuf]) -> Vec<String> {
    paths
        .iter()
        .filter_map(|p| p.file_name())
        .map(|n| n.to_string_lossy().into_owned())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_and_file_pairs() {
        let folder = OutPair::parse("--output", Path::new("out"), true).unwrap();
        assert_eq!(folder.folder(), Path::new("out"));
        assert_eq!(
            folder.files("ref"),
            (PathBuf::from("out/ref.exr"), PathBuf::from("out/ref.png"))
        );
        for given in ["pics/x.png", "pics/x.exr"] {
            let pair = OutPair::parse("--output", Path::new(given), false).unwrap();
            assert_eq!(pair.folder(), Path::new("pics"));
            assert_eq!(pair.names("ignored"), ["x.exr", "x.png"]);
        }
        // Issue 36: `-o pic.EXR` wrote pic.exr, not the name given.
        for (given, names) in [
            ("pics/x.PNG", ["x.EXR", "x.PNG"]),
            ("pics/x.EXR", ["x.EXR", "x.PNG"]),
            ("pics/x.Exr", ["x.Exr", "x.png"]),
            ("pics/x.pNg", ["x.exr", "x.pNg"]),
        ] {
            let pair = OutPair::parse("--output", Path::new(given), false).unwrap();
            assert_eq!(pair.names("ignored"), names, "{given}");
            let (exr, png) = pair.files("ignored");
            assert!(
                exr == Path::new(given) || png == Path::new(given),
                "{given}"
            );
        }
        let bare = OutPair::parse("--output", Path::new("y.exr"), false).unwrap();
        assert_eq!(bare.folder(), Path::new("."));
        let e = OutPair::parse("--output", Path::new("y.png"), true).unwrap_err();
        assert!(e.to_string().contains("--name"), "{e}");
    }
}
