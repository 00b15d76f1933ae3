//! What `godel sequence` wrote into its output folder: the manifest `.godel-sequence` beside
//! the frames, one line `SIZE MTIME_NS NAME` per file written (a later line for a name
//! replaces an earlier one), appended as each file is renamed into place, so that a run that
//! fails halfway still names what it wrote.
//!
//! A later run removes an earlier run's files that it does not write again ([`Manifest::stale`]:
//! frames beyond its count, data files it does not keep, the MP4) — and only those: a file
//! the manifest does not name is never removed, nor one whose size or modification time
//! changed since it was written (someone else's now), nor an input of the run.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;

use crate::inputs::Inputs;

/// The manifest's file name in the output folder.
pub const MANIFEST: &str = ".godel-sequence";

/// A file as it was when written: its size and modification time (nanoseconds since the
/// Unix epoch).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Identity {
    len: u64,
    modified_ns: u128,
}

impl Identity {
    /// The identity of the file at `path` now, `None` if it is no regular file.
    pub fn of(path: &Path) -> Option<Identity> {
        let meta = std::fs::symlink_metadata(path).ok()?;
        let modified = meta.modified().ok()?;
        let since = modified.duration_since(std::time::UNIX_EPOCH).ok()?;
        meta.is_file().then_some(Identity {
            len: meta.len(),
            modified_ns: since.as_nanos(),
        })
    }
}

/// The files an earlier run wrote into a folder, by name.
#[derive(Debug, Default)]
pub struct Manifest {
    dir: PathBuf,
    files: BTreeMap<String, Identity>,
}

/// What [`Manifest::stale`] found: an earlier run's files to remove, and those it leaves
/// because they changed since.
#[derive(Debug, Default, PartialEq)]
pub struct Stale {
    pub remove: Vec<PathBuf>,
    pub changed: Vec<PathBuf>,
}

impl Manifest {
    /// The manifest of `dir` (empty where there is none; unreadable lines are skipped).
    pub fn read(dir: &Path) -> Manifest {
        let text = std::fs::read_to_string(dir.join(MANIFEST)).unwrap_or_default();
        let mut files = BTreeMap::new();
        for line in text.lines() {
            let mut parts = line.splitn(3, ' ');
            let (Some(len), Some(ns), Some(name)) = (parts.next(), parts.next(), parts.next())
            else {
                continue;
            };
            let (Ok(len), Ok(modified_ns)) = (len.parse(), ns.parse()) else {
                continue;
            };
            // Only plain names in this folder.
            if name.is_empty() || name.contains('/') || name == MANIFEST || name.starts_with('.') {
                continue;
            }
            files.insert(name.to_string(), Identity { len, modified_ns });
        }
        Manifest {
            dir: dir.to_path_buf(),
            files,
        }
    }

    /// The files of the earlier runs that a run writing the names `kept` says would not
    /// replace: to remove, unless changed since they were written or an input of the run.
    pub fn stale(&self, kept: impl Fn(&str) -> bool, inputs: &Inputs) -> Stale {
        let mut stale = Stale::default();
        for (name, identity) in &self.files {
            let path = self.dir.join(name);
            if kept(name) || inputs.role_of(&path).is_some() {
                continue;
            }
            match Identity::of(&path) {
                Some(now) if now == *identity => stale.remove.push(path),
                Some(_) => stale.changed.push(path),
                None => {}
            }
        }
        stale
    }

    /// Writes the manifest anew with the files it names that are still as written (after
    /// the stale ones were removed), so that it never grows without bound; where none is
    /// left, there is no manifest (until the run records its first file).
    pub fn rewrite(&self) -> anyhow::Result<()> {
        let lines: String = self
            .files
            .iter()
            .filter(|(name, identity)| Identity::of(&self.dir.join(name)) == Some(**identity))
            .map(|(name, identity)| line(name, *identity))
            .collect();
        let path = self.dir.join(MANIFEST);
        if lines.is_empty() {
            return match std::fs::remove_file(&path) {
                Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(anyhow::Error::new(e)
                    .context(format!("cannot remove the empty {}", path.display()))),
                _ => Ok(()),
            };
        }
        crate::output::write_atomic(&path, lines.as_bytes())
    }
}

fn line(name: &str, identity: Identity) -> String {
    format!("{} {} {name}\n", identity.len, identity.modified_ns)
}

/// Adds the files at `paths` (just written into `dir`) to `dir`'s manifest.
pub fn record(dir: &Path, paths: &[&Path]) -> anyhow::Result<()> {
    let manifest = dir.join(MANIFEST);
    let mut lines = String::new();
    for path in paths {
        let name = path.file_name().map(|n| n.to_string_lossy());
        if let (Some(name), Some(identity)) = (name, Identity::of(path)) {
            lines.push_str(&line(&name, identity));
        }
    }
    std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&manifest)
        .and_then(|mut f| f.write_all(lines.as_bytes()))
        .with_context(|| format!("cannot record the files written in {}", manifest.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_unchanged_files_of_earlier_runs_are_stale() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let write = |name: &str, bytes: &[u8]| {
            std::fs::write(d.join(name), bytes).unwrap();
            d.join(name)
        };
        let (a, b, c, input) = (
            write("frame_0000.png", b"a"),
            write("frame_0001.png", b"b"),
            write("frame_0002.png", b"c"),
            write("frame_0003.exr", b"d"),
        );
        write("notes.txt", b"mine");
        record(d, &[&a, &b, &c, &input]).unwrap();
        // Someone else's file now: written again with other content.
        std::fs::write(&b, b"changed by the user").unwrap();
        let mut inputs = Inputs::new();
        inputs.add("the data file", &input);
        let manifest = Manifest::read(d);
        // A run of one frame keeps frame 0; frame 1 changed; frame 3 is its input.
        let stale = manifest.stale(|n| n == "frame_0000.png", &inputs);
        assert_eq!(
            stale,
            Stale {
                remove: vec![c.clone()],
                changed: vec![b.clone()]
            }
        );
        std::fs::remove_file(&c).unwrap();
        manifest.rewrite().unwrap();
        let again = Manifest::read(d);
        let names: Vec<&String> = again.files.keys().collect();
        assert_eq!(names, ["frame_0000.png", "frame_0003.exr"]);
        // A damaged line and a line naming another folder are skipped.
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(d.join(MANIFEST))
            .unwrap();
        f.write_all(b"12 x frame_0009.png\n1 2 ../escape.png\n3 4")
            .unwrap();
        assert_eq!(Manifest::read(d).files.len(), 2);
    }
}
