//! Limits checked before any work (issue 10), each refused with exit code 2 and a message
//! naming the flag or the file: thread counts beyond 8 per core (`--threads 100000` spawned
//! 16,500 threads), input files that are not regular files (`godel render /dev/zero` grew
//! by 1 GB/s, a FIFO blocked forever), and an output folder that cannot be written (found
//! only after 17.5 s of tracing). Every command runs under a time limit: it must never hang.

use std::path::Path;
use std::process::Command;
use std::time::Duration;

mod common;
use common::{files_in, run_within, stderr, write_scene};

const GODEL: &str = env!("CARGO_BIN_EXE_godel");
/// Far longer than any of these commands needs when it works (well under a second).
const NEVER_HANGS: Duration = Duration::from_secs(120);

fn godel(args: &[&str]) -> std::process::Output {
    run_within(Command::new(GODEL).args(args), NEVER_HANGS)
}

/// Exit code 2 with a one-line message that starts `error: {start}` and contains `needle`.
fn usage_error(args: &[&str], start: &str, needle: &str) {
    let o = godel(args);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
    assert!(e.starts_with(&format!("error: {start}")), "{args:?}: {e}");
    assert!(e.contains(needle), "{args:?}: expected {needle:?} in {e}");
    assert_eq!(e.lines().count(), 1, "{args:?}: {e}");
}

/// A scene whose trace takes tens of seconds: a check that waits for the tracing would
/// show up as a run that ends late or not with exit 2.
fn slow_scene(dir: &Path) -> String {
    let text = common::lit_scene_text("slow", 30.0)
        .replace("width = 90", "width = 1600")
        .replace("height = 37", "height = 800");
    write_scene(dir, "slow.toml", &text)
}

fn mkfifo(path: &Path) {
    let made = Command::new("mkfifo").arg(path).status().expect("mkfifo");
    assert!(made.success());
}

#[test]
fn thread_counts_beyond_8_per_core_are_refused_before_any_work() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = slow_scene(tmp.path());
    let out = tmp.path().join("out");
    let o = out.to_str().unwrap();
    for n in ["100000", "1000000000"] {
        usage_error(
            &["render", &scene, "-q", "-o", o, "--threads", n],
            "--threads: at most ",
            "per core",
        );
        usage_error(
            &[
                "render",
                &scene,
                "-q",
                "-o",
                o,
                "--threads",
                n,
                "--part",
                "1/2",
            ],
            "--threads: at most ",
            "per core",
        );
    }
    assert!(files_in(&out).is_empty());
}

#[test]
fn input_files_that_are_not_regular_files_are_refused_without_blocking() {
    let tmp = tempfile::tempdir().unwrap();
    let fifo = tmp.path().join("fifo.toml");
    mkfifo(&fifo);
    let f = fifo.to_str().unwrap();
    let out = tmp.path().join("out");
    let o = out.to_str().unwrap();
    // Scene files: exit 2 naming the file.
    for scene in ["/dev/zero", f, "/tmp"] {
        usage_error(
            &["render", scene, "-q", "-o", o],
            &format!("{scene}: cannot read the scene file: not a regular file"),
            "not a regular file",
        );
    }
    // Data files and part files: refused naming the file (exit 1: not a usage error).
    let png = tmp.path().join("x.png");
    let runs: [&[&str]; 4] = [
        &["shade", f, "-o", png.to_str().unwrap()],
        &["shade", "/dev/zero", "-o", png.to_str().unwrap()],
        &["merge", f, "-o", o],
        &["view", f, "--port", "0"],
    ];
    for args in runs {
        let out = godel(args);
        let e = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {e}");
        assert!(e.contains("not a regular file"), "{args:?}: {e}");
    }
    assert!(files_in(&out).is_empty());
    assert!(!png.exists());
}

#[test]
fn an_unwritable_output_is_found_before_tracing() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = slow_scene(tmp.path());
    // A file where the folder should be, a folder where the EXR should be.
    let file = tmp.path().join("a-file");
    std::fs::write(&file, b"x").unwrap();
    let taken = tmp.path().join("taken");
    std::fs::create_dir_all(taken.join("slow.exr")).unwrap();
    let cases: [(&Path, &[&str], &str); 4] = [
        (&file, &[], "cannot create the output folder"),
        (&file, &["--part", "2/3"], "cannot create the output folder"),
        (&taken, &[], "slow.exr: it is a directory"),
        (
            Path::new("/dev/null/out"),
            &[],
            "cannot create the output folder",
        ),
    ];
    for (dir, extra, needle) in cases {
        let mut args = vec!["render", &scene, "-q", "-o", dir.to_str().unwrap()];
        args.extend_from_slice(extra);
        usage_error(&args, "--output: ", needle);
    }
    assert_eq!(files_in(&taken), ["slow.exr"]);
    assert!(files_in(&taken.join("slow.exr")).is_empty());
}

#[test]
fn help_states_the_limits() {
    for (cmd, needles) in [
        (
            "render",
            &[
                "at most 8 per core",
                "16 MiB",
                "1e-14, 1e-3",
                "exit 130 or 143",
            ][..],
        ),
        (
            "sequence",
            &[
                "frames 1 to 100000",
                "fps at most 1000",
                "are removed first",
            ][..],
        ),
        ("shade", &["8 GiB", "16 MiB"][..]),
        ("geodesic", &["--samples at most 1000000", "λ = 10⁶"][..]),
    ] {
        let o = godel(&[cmd, "--help"]);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success());
        for n in needles {
            assert!(text.contains(n), "godel {cmd} --help lacks {n:?}: {text}");
        }
    }
}
