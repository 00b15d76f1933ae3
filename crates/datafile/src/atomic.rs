//! Atomic file output: write to a temporary file next to the target, then
//! rename it over the target.
//!
//! Bad input or a failed write must leave no partial output behind. Every writer of
//! user-visible files (data files, PNGs, MP4s) goes through this module: on success the
//! target holds the complete new content; on any error the target is left as it was (absent
//! or with its old content) and the temporary file is removed.
//!
//! - [`write_atomically`], [`write_atomically_via_path`]: one file.
//! - [`stage`], [`stage_via_path`], then [`commit_all`]: several files that belong
//!   together (a render's EXR and PNG) are all written to temporaries first and
//!   renamed only when every one is complete, one rename right after the other.
//! - [`check_writable`], [`check_all_writable`]: every target a later write will
//!   replace, checked before any work: not a folder, not read-only, a name the file
//!   system takes, in a folder where the temporary can be created (made and removed).
//!
//! **One unit.** [`commit_all`] holds an exclusive lock on each target's folder
//! (`flock` on the folder itself, so no lock file is left behind) while it renames,
//! so two processes committing into the same names at once end with all the files of
//! one of them, never a mix. Under the lock every target is checked again, the old
//! content of each existing target is kept (a hard link under a temporary's name),
//! and if a rename fails the targets already renamed get their old content back (or
//! are removed where there was none): the set is replaced whole or not at all. A
//! read-only target is never replaced (a rename would do it silently).
//!
//! Temporary files are named `.NAME.godel-PID-HOST.XXXXXX.tmp` (hidden, beside
//! the target, so the rename never crosses a file system) and are kept in a
//! process-wide registry while they exist. [`remove_live_temporaries`] deletes
//! them all (the command line calls it on SIGINT/SIGTERM before exiting); it waits
//! for a commit in progress, so a signal never separates the renames of one
//! [`commit_all`]. Temporaries that a killed process left behind (SIGKILL, power
//! loss) are swept: the first time a process writes into a folder, it removes the
//! temporaries there whose name carries this host and a process id that no longer
//! runs (Linux, where `/proc` tells which processes run; elsewhere nothing is swept).
//! The registry is global state by necessity: a signal handler has no other way to
//! find the files.

use std::collections::{BTreeSet, HashSet};
use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use tempfile::NamedTempFile;

/// Most bytes of the target's name kept in its temporary's name: a legal name of up to
/// [`MAX_NAME_BYTES`] still gets a temporary name the file system takes (the rest of it,
/// `.` `.godel-PID-HOST.XXXXXX.tmp`, adds at most 62 bytes).
const NAME_BYTES_IN_TEMPORARY: usize = 100;

/// Longest file name, in bytes (NAME_MAX of Linux and most Unix file systems).
pub const MAX_NAME_BYTES: usize = 255;

/// Temporary files that exist now.
static LIVE: Mutex<BTreeSet<PathBuf>> = Mutex::new(BTreeSet::new());
/// Held while renames are under way (and by [`remove_live_temporaries`] for good).
static COMMIT: Mutex<()> = Mutex::new(());
/// Folders already swept for stale temporaries by this process.
static SWEPT: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);

/// A lock that a panicking holder does not poison for everyone else.
fn lock<T>(m: &'static Mutex<T>) -> MutexGuard<'static, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// A complete temporary file waiting to be renamed onto its target.
#[derive(Debug)]
pub struct Staged {
    /// `None` only once renamed.
    temp: Option<NamedTempFile>,
    target: PathBuf,
}

impl Staged {
    /// The file this will become.
    pub fn target(&self) -> &Path {
        &self.target
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        // Removed first, then unregistered: a signal in between finds it gone.
        if let Some(temp) = self.temp.take() {
            let path = temp.path().to_path_buf();
            drop(temp);
            lock(&LIVE).remove(&path);
        }
    }
}

/// Writes `path` atomically: `write` fills a fresh temporary file in the same
/// directory as `path`; the file is flushed, synced and renamed onto `path`.
///
/// If `write` (or the flush, sync or rename) fails, the temporary file is
/// deleted and `path` is untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut File) -> io::Result<()>,
) -> io::Result<()> {
    commit_all(vec![stage(path, write)?])
}

/// Like [`write_atomically`], for writers that want a file *path* rather than
/// an open file (for example a library or a program that opens the file itself).
///
/// `write` receives the path of an existing, empty temporary file in the same
/// directory as `path`; it may truncate and overwrite it. Afterwards the
/// temporary file is renamed onto `path`.
pub fn write_atomically_via_path(
    path: &Path,
    write: impl FnOnce(&Path) -> io::Result<()>,
) -> io::Result<()> {
    commit_all(vec![stage_via_path(path, write)?])
}

/// Writes the content of `path` to a temporary file (flushed and synced) and
/// hands it back for [`commit_all`]; dropping the result removes the temporary.
pub fn stage(path: &Path, write: impl FnOnce(&mut File) -> io::Result<()>) -> io::Result<Staged> {
    let mut staged = temp_file_for(path)?;
    let temp = staged.temp_mut()?;
    write(temp.as_file_mut())?;
    temp.as_file_mut().flush()?;
    temp.as_file().sync_all()?;
    Ok(staged)
}

/// [`stage`] for writers that want a path (see [`write_atomically_via_path`]).
pub fn stage_via_path(
    path: &Path,
    write: impl FnOnce(&Path) -> io::Result<()>,
) -> io::Result<Staged> {
    let mut staged = temp_file_for(path)?;
    let temp = staged.temp_mut()?.path().to_path_buf();
    write(&temp)?;
    File::open(&temp)?.sync_all()?;
    Ok(staged)
}

/// Renames every staged file onto its target, in order, with nothing in between
/// (and no signal cleanup: it waits until all are renamed), under the folders' locks:
/// all the targets are replaced or none is (see the module documentation). On an
/// error the temporaries are removed, the targets keep their old content, and the
/// error is returned.
pub fn commit_all(staged: Vec<Staged>) -> io::Result<()> {
    commit_all_with(staged, || {})
}

/// [`commit_all`], calling `between` after each rename but the last (a testing hook:
/// a pause there shows that no other process can slip its files in between).
pub fn commit_all_with(staged: Vec<Staged>, between: impl Fn()) -> io::Result<()> {
    // The folders first: waiting for another process must not hold up the signal
    // handler, which waits for `COMMIT` (and then removes these temporaries).
    let _folders = lock_folders(&staged);
    let _renaming = lock(&COMMIT);
    for s in &staged {
        check_replaceable(&s.target)?;
    }
    let mut kept = Vec::with_capacity(staged.len());
    for s in &staged {
        kept.push(keep_old(&s.target)?);
    }
    let last = staged.len().saturating_sub(1);
    for (k, mut s) in staged.into_iter().enumerate() {
        if let Some(temp) = s.temp.take() {
            let path = temp.path().to_path_buf();
            // On failure the temporary comes back in the error and is removed with it.
            let result = temp.persist(&s.target).map(|_| ()).map_err(|e| e.error);
            lock(&LIVE).remove(&path);
            if let Err(e) = result {
                roll_back(&mut kept[..k]);
                return Err(e);
            }
        }
        if k < last {
            between();
        }
    }
    Ok(())
}

/// The old content of a target, kept while its set is committed.
struct Kept {
    target: PathBuf,
    /// A hard link to (or copy of) the old file under a temporary's name; `None` where
    /// the target did not exist. Removed on drop.
    old: Option<NamedTempFile<()>>,
}

/// Keeps the old content of `target`, if it exists.
fn keep_old(target: &Path) -> io::Result<Kept> {
    if std::fs::symlink_metadata(target).is_err() {
        return Ok(Kept {
            target: target.to_path_buf(),
            old: None,
        });
    }
    let prefix = temp_prefix(target)?;
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    let old = builder.make_in(folder_of(target), |path| {
        // A hard link costs nothing; a copy where the file system has none.
        std::fs::hard_link(target, path).or_else(|_| std::fs::copy(target, path).map(|_| ()))
    });
    Ok(Kept {
        target: target.to_path_buf(),
        old: Some(old.map_err(without_temp_path)?),
    })
}

/// Gives the targets of `renamed` their old content back (removes those that had none).
/// Best effort: the rename that failed is the error reported.
fn roll_back(renamed: &mut [Kept]) {
    for kept in renamed.iter_mut().rev() {
        match kept.old.take() {
            Some(old) => {
                let _ = old.persist(&kept.target);
            }
            None => {
                let _ = std::fs::remove_file(&kept.target);
            }
        }
    }
}

/// Exclusive locks on the folders of `staged`'s targets, taken in a fixed order (no two
/// processes wait for each other), held until dropped. A folder that cannot be opened or
/// locked (a file system without `flock`) is written without: the lock only orders
/// godel's own processes.
fn lock_folders(staged: &[Staged]) -> Vec<File> {
    let folders: BTreeSet<PathBuf> = staged
        .iter()
        .map(|s| {
            let dir = folder_of(&s.target);
            std::fs::canonicalize(&dir).unwrap_or(dir)
        })
        .collect();
    folders
        .into_iter()
        .filter_map(|dir| File::open(dir).ok())
        .filter(|f| f.lock().is_ok())
        .collect()
}

/// Refuses a target that a rename must not replace: a folder, or a read-only file (a
/// rename replaces it silently, whatever its permissions say); a name longer than the
/// file system takes.
fn check_replaceable(path: &Path) -> io::Result<()> {
    let refuse = |why: String| Err(io::Error::new(io::ErrorKind::InvalidInput, why));
    let name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} does not name a file", path.display()),
        )
    })?;
    if name.len() > MAX_NAME_BYTES {
        return refuse(format!(
            "the file name is {} bytes long, more than the {MAX_NAME_BYTES} a file system takes",
            name.len()
        ));
    }
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return Ok(());
    };
    if meta.is_dir() {
        return refuse("it is a directory".into());
    }
    if meta.is_file() && meta.permissions().readonly() {
        return refuse(
            "it is read-only, and a read-only file is never replaced (make it writable, or \
             write elsewhere)"
                .into(),
        );
    }
    Ok(())
}

/// Checks that `path` can be written: it is not a directory or a read-only file, its name
/// is not too long, and the temporary file of a write can be created beside it (the folder
/// exists and is writable). The probe is removed again.
pub fn check_writable(path: &Path) -> io::Result<()> {
    check_replaceable(path)?;
    drop(temp_file_for(path)?);
    Ok(())
}

/// [`check_writable`] for many paths (every frame of a sequence), one probe per folder; the
/// error names the path (`PATH: why`).
pub fn check_all_writable<P: AsRef<Path>>(paths: &[P]) -> io::Result<()> {
    let mut probed = HashSet::new();
    for path in paths {
        let path = path.as_ref();
        let mut checked = check_replaceable(path);
        if checked.is_ok() && probed.insert(folder_of(path)) {
            checked = temp_file_for(path).map(drop);
        }
        checked.map_err(|e| io::Error::new(e.kind(), format!("{}: {e}", path.display())))?;
    }
    Ok(())
}

/// Deletes every temporary file this process has open and blocks any further
/// temporary file or rename for good: call it only right before the process
/// exits (the command line's signal handler does). Returns how many it removed.
pub fn remove_live_temporaries() -> usize {
    // Wait for renames under way; then keep both locks until the process ends.
    let commit = lock(&COMMIT);
    let live = lock(&LIVE);
    let removed = live
        .iter()
        .filter(|p| std::fs::remove_file(p).is_ok())
        .count();
    std::mem::forget(live);
    std::mem::forget(commit);
    removed
}

/// The temporary files this process has open now (for tests and messages).
pub fn live_temporaries() -> Vec<PathBuf> {
    lock(&LIVE).iter().cloned().collect()
}

impl Staged {
    fn temp_mut(&mut self) -> io::Result<&mut NamedTempFile> {
        self.temp
            .as_mut()
            .ok_or_else(|| io::Error::other("the temporary file was already renamed"))
    }
}

/// The folder of `path` (`.` for a bare name).
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The name prefix of `path`'s temporaries, `.NAME.godel-PID-HOST.` (then `XXXXXX.tmp`),
/// NAME cut to [`NAME_BYTES_IN_TEMPORARY`] bytes.
fn temp_prefix(path: &Path) -> io::Result<String> {
    let name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} does not name a file", path.display()),
        )
    })?;
    let name = name.to_string_lossy();
    let mut end = name.len().min(NAME_BYTES_IN_TEMPORARY);
    while !name.is_char_boundary(end) {
        end -= 1;
    }
    Ok(format!(".{}.{}.", &name[..end], owner_tag()))
}

/// A new, registered temporary file in the directory of `path`.
fn temp_file_for(path: &Path) -> io::Result<Staged> {
    let dir = folder_of(path);
    let prefix = temp_prefix(path)?;
    sweep_once(&dir);
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    // Temporary files are created private (0600); the output should get the
    // usual permissions of a new file (0666 less the umask).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    // Created and registered under the registry's lock, so that a signal handler
    // sees every temporary file that exists.
    let mut live = lock(&LIVE);
    // tempfile's errors append "at path <the temporary>": the user named the target, and
    // the caller names it, so only the cause is kept.
    let temp = builder.tempfile_in(&dir).map_err(without_temp_path)?;
    live.insert(temp.path().to_path_buf());
    Ok(Staged {
        temp: Some(temp),
        target: path.to_path_buf(),
    })
}

/// A tempfile error without its " at path <temporary>" suffix (tempfile keeps the operating
/// system's error private, so the suffix is cut from the text; the kind is kept).
fn without_temp_path(e: io::Error) -> io::Error {
    let text = e.to_string();
    match text.find(" at path ") {
        Some(i) => io::Error::new(e.kind(), text[..i].to_string()),
        None => e,
    }
}

/// `godel-PID-HOST`: who made a temporary file (HOST with anything but letters and
/// digits replaced by `_`, at most 32 characters).
fn owner_tag() -> String {
    format!("godel-{}-{}", std::process::id(), host())
}

fn host() -> String {
    let raw = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_default();
    let h: String = raw
        .trim()
        .chars()
        .take(32)
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if h.is_empty() {
        "unknown".into()
    } else {
        h
    }
}

/// The process id and host of a temporary file name of ours
/// (`.NAME.godel-PID-HOST.XXXXXX.tmp`), else `None`.
pub fn owner_of(file_name: &str) -> Option<(u32, &str)> {
    let rest = file_name.strip_prefix('.')?.strip_suffix(".tmp")?;
    let (rest, _random) = rest.rsplit_once('.')?;
    let (_name, tag) = rest.rsplit_once('.')?;
    let (pid, host) = tag.strip_prefix("godel-")?.split_once('-')?;
    Some((pid.parse().ok()?, host))
}

/// Removes, once per folder and process, the temporaries of this host whose
/// process no longer runs. Best effort: what cannot be read or removed stays.
fn sweep_once(dir: &Path) {
    // Only where /proc tells which processes run, and never for an unknown host (a
    // folder shared over the network holds other machines' temporaries).
    let proc = Path::new("/proc");
    let here = host();
    if !proc.join("self").exists() || here == "unknown" {
        return;
    }
    let key = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
    if !lock(&SWEPT).get_or_insert_with(HashSet::new).insert(key) {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some((pid, host)) = name.to_str().and_then(owner_of) else {
            continue;
        };
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && host == here && !proc.join(pid.to_string()).exists() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn owner_tags_read_back() {
        assert_eq!(
            owner_of(".a.b.png.godel-123-node_1.Ab3xYz.tmp"),
            Some((123, "node_1"))
        );
        assert_eq!(owner_of(".x.exr.Ab3xYz.tmp"), None);
        assert_eq!(owner_of("x.exr.godel-1-h.Ab3xYz.tmp"), None);
        assert_eq!(owner_of(".x.exr.godel-pid-h.Ab3xYz.tmp"), None);
        let tag = owner_tag();
        let name = format!(".out.png.{tag}.abcdef.tmp");
        assert_eq!(owner_of(&name), Some((std::process::id(), host().as_str())));
    }
}
