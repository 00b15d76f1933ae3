//! Reading scene files (and every other input file, through `scene::input`): regular files
//! only, with a size cap, read through a bounded reader. Issue 10: `godel render /dev/zero`
//! grew by 1 GB/s, and a FIFO blocked forever.

use scene::input::{read_bounded, read_text, MAX_TEXT_BYTES};
use scene::Scene;
use std::io::Write;

#[test]
fn non_regular_files_are_refused_without_reading() {
    // A character device that never ends, and a directory.
    for path in ["/dev/zero", "/tmp"] {
        let e = Scene::from_file(path).unwrap_err();
        assert_eq!(e.file, path);
        assert!(e.message.contains("not a regular file"), "{e}");
        let e = read_bounded(std::path::Path::new(path), 10).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
    }
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("scene.toml");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo");
    assert!(made.success());
    // Nobody ever writes to the FIFO: opening it for reading would block forever.
    let e = Scene::from_file(&fifo).unwrap_err();
    assert!(e.message.contains("not a regular file"), "{e}");
    assert!(e.message.contains("FIFO"), "{e}");
}

#[test]
fn files_above_the_cap_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.toml");
    let mut f = std::fs::File::create(&path).unwrap();
    // A sparse file one byte over the cap: its size alone refuses it.
    f.set_len(MAX_TEXT_BYTES + 1).unwrap();
    f.flush().unwrap();
    let e = Scene::from_file(&path).unwrap_err();
    assert!(e.message.contains("larger than"), "{e}");
    assert!(e.message.contains("16 MiB"), "{e}");

    let small = dir.path().join("small.txt");
    std::fs::write(&small, "0123456789").unwrap();
    assert_eq!(read_bounded(&small, 10).unwrap(), b"0123456789");
    let e = read_bounded(&small, 9).unwrap_err();
    assert!(e.to_string().contains("larger than"), "{e}");
    assert_eq!(read_text(&small, 10).unwrap(), "0123456789");
    std::fs::write(&small, [0xff, 0xfe]).unwrap();
    assert!(read_text(&small, 10).is_err());
}
