//! Atomic output (`datafile::atomic`): files that belong together appear together, an
//! unwritable target is found before any work, and temporaries of dead processes are swept
//! (issue 10: a kill between the EXR's rename and the PNG's left a new EXR beside an old
//! PNG; `.NAME.XXXXXX.tmp` files stayed forever).

use datafile::atomic::{
    check_all_writable, check_writable, commit_all, commit_all_with, live_temporaries, owner_of,
    stage, write_atomically, MAX_NAME_BYTES,
};
use std::io::Write;
use std::path::Path;

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn staged_files_appear_only_when_all_are_committed() {
    let dir = tempfile::tempdir().unwrap();
    let (exr, png) = (dir.path().join("a.exr"), dir.path().join("a.png"));
    std::fs::write(&exr, b"old exr").unwrap();
    std::fs::write(&png, b"old png").unwrap();
    let first = stage(&exr, |f| f.write_all(b"new exr")).unwrap();
    let second = stage(&png, |f| f.write_all(b"new png")).unwrap();
    // Both complete on disk as temporaries, neither target changed yet.
    assert_eq!(std::fs::read(&exr).unwrap(), b"old exr");
    assert_eq!(std::fs::read(&png).unwrap(), b"old png");
    assert_eq!(names(dir.path()).len(), 4, "{:?}", names(dir.path()));
    let live = live_temporaries();
    assert!(live.iter().any(|p| p.parent() == Some(dir.path())));
    commit_all(vec![first, second]).unwrap();
    assert_eq!(std::fs::read(&exr).unwrap(), b"new exr");
    assert_eq!(std::fs::read(&png).unwrap(), b"new png");
    assert_eq!(names(dir.path()), ["a.exr", "a.png"]);
    assert!(!live_temporaries()
        .iter()
        .any(|p| p.parent() == Some(dir.path())));

    // A failure while staging the second leaves both old files and no temporary.
    let first = stage(&exr, |f| f.write_all(b"newer exr")).unwrap();
    let failed = stage(&png, |f| {
        f.write_all(b"half")?;
        Err(std::io::Error::other("disk full"))
    });
    assert!(failed.is_err());
    drop(first);
    assert_eq!(std::fs::read(&exr).unwrap(), b"new exr");
    assert_eq!(names(dir.path()), ["a.exr", "a.png"]);
}

#[test]
fn unwritable_targets_are_found_up_front_and_leave_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // Missing folder, a directory in the target's place, a name too long for the file system.
    assert!(check_writable(&dir.path().join("absent/x.png")).is_err());
    std::fs::create_dir(dir.path().join("x.png")).unwrap();
    let e = check_writable(&dir.path().join("x.png")).unwrap_err();
    assert!(e.to_string().contains("is a directory"), "{e}");
    let long = dir
        .path()
        .join(format!("{}.png", "n".repeat(MAX_NAME_BYTES - 3)));
    let e = check_writable(&long).unwrap_err();
    assert!(e.to_string().contains("256 bytes long"), "{e}");
    assert!(check_writable(&dir.path().join("fine.png")).is_ok());
    assert_eq!(names(dir.path()), ["x.png"]);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let ro = dir.path().join("ro");
        std::fs::create_dir(&ro).unwrap();
        std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
        // Root ignores permissions: then there is nothing to refuse.
        if std::fs::write(ro.join("probe"), b"").is_err() {
            assert!(check_writable(&ro.join("x.png")).is_err());
        }
        std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
}

#[cfg(target_os = "linux")]
#[test]
fn temporaries_of_dead_processes_on_this_host_are_swept() {
    let dir = tempfile::tempdir().unwrap();
    // This process's own tag, read from a temporary it makes.
    let probe = stage(&dir.path().join("probe.png"), |_| Ok(())).unwrap();
    let own = live_temporaries()
        .into_iter()
        .find(|p| p.parent() == Some(dir.path()))
        .unwrap();
    let own_name = own.file_name().unwrap().to_str().unwrap().to_string();
    let (pid, host) = owner_of(&own_name).unwrap();
    assert_eq!(pid, std::process::id());
    let host = host.to_string();
    drop(probe);

    // A process that has ended: its id is free.
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let stale = format!(".old.png.godel-{dead}-{host}.AbCdEf.tmp");
    let alive = format!(".old.png.godel-{}-{host}.AbCdEf.tmp", std::process::id());
    let elsewhere = format!(".old.png.godel-{dead}-othernode.AbCdEf.tmp");
    let foreign = ".old.png.AbCdEf.tmp".to_string();
    // A fresh folder: the probe above already swept `dir`.
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).unwrap();
    for n in [&stale, &alive, &elsewhere, &foreign] {
        std::fs::write(sub.join(n), b"x").unwrap();
    }
    write_atomically(&sub.join("new.png"), |f| f.write_all(b"png")).unwrap();
    let mut expect = vec![alive, elsewhere, foreign, "new.png".to_string()];
    expect.sort();
    assert_eq!(names(&sub), expect);
}

/// Issue 24: a legal name of 250 bytes was refused because the hidden temporary's name
/// (the name and 60 more bytes) is longer than the file system takes.
#[test]
fn a_long_legal_name_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let name = format!("{}.png", "é".repeat(123)); // 250 bytes, a temporary cut mid-letter
    assert_eq!(name.len(), 250);
    let path = dir.path().join(&name);
    check_writable(&path).unwrap();
    write_atomically(&path, |f| f.write_all(b"png")).unwrap();
    assert_eq!(names(dir.path()), [name]);
}

/// Issue 24: a read-only file was silently replaced by a rename (permissions guard writes
/// into a file, not its replacement).
#[cfg(unix)]
#[test]
fn a_read_only_target_is_refused_and_kept() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let ro = dir.path().join("kept.png");
    std::fs::write(&ro, b"mine").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o444)).unwrap();
    let e = check_writable(&ro).unwrap_err();
    assert!(e.to_string().contains("read-only"), "{e}");
    let e = check_all_writable(&[dir.path().join("fine.exr"), ro.clone()]).unwrap_err();
    assert!(e.to_string().contains("read-only"), "{e}");
    // Found again at the commit (it may turn read-only after the check), with nothing renamed.
    let other = dir.path().join("other.exr");
    let staged = vec![
        stage(&other, |f| f.write_all(b"new")).unwrap(),
        stage(&ro, |f| f.write_all(b"new")).unwrap(),
    ];
    let e = commit_all(staged).unwrap_err();
    assert!(e.to_string().contains("read-only"), "{e}");
    assert_eq!(std::fs::read(&ro).unwrap(), b"mine");
    assert_eq!(names(dir.path()), ["kept.png"]);
}

/// Issue 24: when a later rename of a set fails, the files already renamed get their old
/// content back (a new file is removed): the set is replaced whole or not at all.
#[test]
fn a_failed_rename_rolls_the_set_back() {
    let dir = tempfile::tempdir().unwrap();
    let (exr, png, new) = (
        dir.path().join("a.exr"),
        dir.path().join("a.png"),
        dir.path().join("a.json"),
    );
    std::fs::write(&exr, b"old exr").unwrap();
    std::fs::write(&png, b"old png").unwrap();
    let staged = vec![
        stage(&exr, |f| f.write_all(b"new exr")).unwrap(),
        stage(&new, |f| f.write_all(b"new json")).unwrap(),
        stage(&png, |f| f.write_all(b"new png")).unwrap(),
    ];
    // After the first renames, the PNG's place becomes a folder that no rename replaces.
    let renamed = std::cell::Cell::new(0);
    let result = commit_all_with(staged, || {
        renamed.set(renamed.get() + 1);
        if renamed.get() == 2 {
            assert_eq!(std::fs::read(&exr).unwrap(), b"new exr");
            std::fs::remove_file(&png).unwrap();
            std::fs::create_dir_all(png.join("inside")).unwrap();
        }
    });
    assert!(result.is_err());
    assert_eq!(std::fs::read(&exr).unwrap(), b"old exr");
    assert!(!new.exists(), "a file new in the failed set stays");
    assert_eq!(names(dir.path()), ["a.exr", "a.png"]);
    assert!(!live_temporaries()
        .iter()
        .any(|p| p.parent() == Some(dir.path())));
}
