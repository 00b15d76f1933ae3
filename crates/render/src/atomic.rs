//! Atomic file output: write to a temporary file next to the target, then
//! rename it over the target.
//!
//! DESIGN.md, "Errors": bad input or a failed write must leave no partial
//! output behind. Every writer of user-visible files (data files, PNGs) goes
//! through [`write_atomically`] or [`write_atomically_via_path`]: on success the
//! target holds the complete new content; on any error the target is left as it
//! was (absent or with its old content) and the temporary file is removed.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

/// Writes `path` atomically: `write` fills a fresh temporary file in the same
/// directory as `path`; the file is flushed, synced and renamed onto `path`.
///
/// If `write` (or the flush, sync or rename) fails, the temporary file is
/// deleted and `path` is untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut File) -> io::Result<()>,
) -> io::Result<()> {
    let mut temp = temp_file_for(path)?;
    write(temp.as_file_mut())?;
    temp.as_file_mut().flush()?;
    temp.as_file().sync_all()?;
    persist(temp, path)
}

/// Like [`write_atomically`], for writers that want a file *path* rather than
/// an open file (for example a library that opens the file itself).
///
/// `write` receives the path of an existing, empty temporary file in the same
/// directory as `path`; it may truncate and overwrite it. Afterwards the
/// temporary file is renamed onto `path`.
pub fn write_atomically_via_path(
    path: &Path,
    write: impl FnOnce(&Path) -> io::Result<()>,
) -> io::Result<()> {
    let temp = temp_file_for(path)?;
    write(temp.path())?;
    File::open(temp.path())?.sync_all()?;
    persist(temp, path)
}

/// A new temporary file in the directory of `path`, named after it, so that
/// the final rename never crosses a file system.
fn temp_file_for(path: &Path) -> io::Result<NamedTempFile> {
    let dir = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} does not name a file", path.display()),
        )
    })?;
    let mut prefix = std::ffi::OsString::from(".");
    prefix.push(name);
    prefix.push(".");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    // Temporary files are created private (0600); the output should get the
    // usual permissions of a new file (0666 less the umask).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(dir)
}

/// Renames the temporary file onto `path`; on failure the temporary file is
/// deleted (dropping the `NamedTempFile` handed back in the error does that).
fn persist(temp: NamedTempFile, path: &Path) -> io::Result<()> {
    temp.persist(path).map(|_| ()).map_err(|e| e.error)
}
