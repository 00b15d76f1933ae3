//! Writing output files atomically (temporary file + rename, via `render::atomic`), so a
//! failed run leaves no half-written file.

use anyhow::Context;
use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `path` through a temporary file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    render::atomic::write_atomically(path, |f| f.write_all(bytes))
        .with_context(|| format!("cannot write {}", path.display()))
}
