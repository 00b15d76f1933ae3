//! Output folders a run creates, and their removal when the run writes nothing.
//!
//! A command that writes into a folder that does not exist yet creates it (and any missing
//! parent) before any work, so that an unwritable place is found early. If the run then fails
//! or is interrupted, "writes nothing" includes those folders: [`create_folder`] remembers
//! each folder this process created, and [`remove_created_folders_left_empty`] removes them
//! again, deepest first, where they are still empty. A folder that holds anything (a file of
//! this run that landed, or anything another process put there) is never touched, nor is a
//! folder that existed before: `remove_dir` only ever removes an empty folder.
//!
//! The registry is process-wide, as `atomic`'s temporaries are: the signal handler that
//! cleans up on Ctrl-C has no other way to find the folders.

use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// Folders created by this process, in the order created (parents first).
static CREATED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn created() -> MutexGuard<'static, Vec<PathBuf>> {
    CREATED.lock().unwrap_or_else(|e| e.into_inner())
}

/// Creates `dir` and each missing parent, as `create_dir_all` does, remembering the ones
/// this call created (not those that existed, nor those another process made meanwhile).
pub fn create_folder(dir: &Path) -> io::Result<()> {
    // The missing ancestors, outermost last; bounded by the path's length.
    let mut missing = Vec::new();
    let mut next = Some(dir);
    while let Some(d) = next.filter(|d| !d.as_os_str().is_empty()) {
        if d.is_dir() {
            break;
        }
        missing.push(d.to_path_buf());
        next = d.parent();
    }
    for d in missing.into_iter().rev() {
        match std::fs::create_dir(&d) {
            Ok(()) => created().push(d),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && d.is_dir() => {}
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

/// Removes the folders [`create_folder`] created that are still empty, deepest first, and
/// forgets all of them. Returns how many it removed. Call it when a run ends without output
/// (an error, a signal).
pub fn remove_created_folders_left_empty() -> usize {
    let mut folders = created();
    let removed = folders
        .iter()
        .rev()
        .filter(|d| std::fs::remove_dir(d).is_ok())
        .count();
    folders.clear();
    removed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_folders_created_and_left_empty_are_removed() {
        let root = tempfile::tempdir().unwrap();
        let kept = root.path().join("was-there");
        std::fs::create_dir(&kept).unwrap();
        let deep = kept.join("a/b/c");
        create_folder(&deep).unwrap();
        assert!(deep.is_dir());
        // Something lands in a/b: a and a/b stay, c goes.
        std::fs::write(kept.join("a/b/file"), b"x").unwrap();
        assert_eq!(remove_created_folders_left_empty(), 1);
        assert!(!deep.exists());
        assert!(kept.join("a/b/file").is_file());
        assert!(kept.is_dir());
        // Forgotten after the first call: nothing more is removed, even once empty.
        std::fs::remove_file(kept.join("a/b/file")).unwrap();
        assert_eq!(remove_created_folders_left_empty(), 0);
        assert!(kept.join("a/b").is_dir());
        // A folder that existed before is never removed.
        create_folder(&kept).unwrap();
        assert_eq!(remove_created_folders_left_empty(), 0);
        assert!(kept.is_dir());
    }
}
