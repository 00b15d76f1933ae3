//! Reading input files with a bound: every file `godel` reads (scene files, shade settings,
//! sequence scripts, data files) goes through [`read_bounded`], so that no input can make a
//! read block or grow without limit (docs/guide/src/command-line.md, **Limits**).
//!
//! Only regular files are read: a FIFO would block on open, a device such as `/dev/zero`
//! never ends, a directory is a mistake. The type is checked on the path before it is
//! opened and again on the open file; the size is checked before reading and enforced while
//! reading (at most `max_bytes + 1` bytes are ever read), so a file that grows in between
//! is refused as well.

use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::Path;

/// The cap on text inputs: scene files, shade settings files, sequence scripts.
pub const MAX_TEXT_BYTES: u64 = 16 << 20;

/// The cap on data files (`.exr`): a render at the largest image a scene allows
/// (5·10⁷ pixels) with 17 channels and a dozen light channels, uncompressed, stays below it.
pub const MAX_DATA_BYTES: u64 = 8 << 30;

/// The contents of the regular file `path`, refused when larger than `max_bytes`.
pub fn read_bounded(path: &Path, max_bytes: u64) -> io::Result<Vec<u8>> {
    check(&std::fs::metadata(path)?, max_bytes)?;
    let file = File::open(path)?;
    let meta = file.metadata()?;
    check(&meta, max_bytes)?;
    let mut bytes = Vec::with_capacity(meta.len().min(max_bytes) as usize);
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(max_bytes));
    }
    Ok(bytes)
}

/// [`read_bounded`] for UTF-8 text.
pub fn read_text(path: &Path, max_bytes: u64) -> io::Result<String> {
    String::from_utf8(read_bounded(path, max_bytes)?).map_err(|_| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            "the file is not UTF-8 text".to_string(),
        )
    })
}

/// `16 MiB`, `8 GiB`, `1000 bytes`: a cap as people write it.
pub fn size_text(bytes: u64) -> String {
    for (unit, name) in [(1u64 << 30, "GiB"), (1 << 20, "MiB"), (1 << 10, "KiB")] {
        if bytes >= unit && bytes.is_multiple_of(unit) {
            return format!("{} {name}", bytes / unit);
        }
    }
    format!("{bytes} bytes")
}

fn check(meta: &Metadata, max_bytes: u64) -> io::Result<()> {
    if !meta.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("not a regular file ({})", kind(meta)),
        ));
    }
    if meta.len() > max_bytes {
        return Err(too_large(max_bytes));
    }
    Ok(())
}

fn too_large(max_bytes: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!(
            "the file is larger than the limit of {}",
            size_text(max_bytes)
        ),
    )
}

/// What kind of non-regular file this is, for the message.
fn kind(meta: &Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "not a plain file"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_people_write_them() {
        assert_eq!(size_text(MAX_TEXT_BYTES), "16 MiB");
        assert_eq!(size_text(8 << 30), "8 GiB");
        assert_eq!(size_text(1000), "1000 bytes");
        assert_eq!(size_text(3 << 10), "3 KiB");
    }
}
