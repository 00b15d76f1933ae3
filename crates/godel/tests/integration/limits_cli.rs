//! Limits checked before any work (issue 10), each refused with exit code 2 and a message
//! naming the flag or the file: thread counts beyond 8 per core (`--threads 100000` spawned
//! 16,500 threads), input files that are not regular files (`godel render /dev/zero` grew
//! by 1 GB/s, a FIFO blocked forever), and an output folder that cannot be written (found
//! only after 17.5 s of tracing). Every command runs under a time limit: it must never hang.

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use crate::common::{self, files_in, run_within, stderr, write_scene, GODEL};

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

/// Issue 24: memory was not bounded by the caps (`explore --sphere 8192` reached 8.6 GB after
/// two events, `godel look` at 20000×2500 took 9.8 GB). Every command sizes its work against
/// a memory budget before it starts (`GODEL_MEMORY_BUDGET` here stands for a small machine)
/// and refuses what would not fit, naming what sets the size and, for a sphere, what fits.
#[test]
fn work_beyond_the_memory_budget_is_refused_before_it_starts() {
    let tmp = tempfile::tempdir().unwrap();
    let text = common::lit_scene_text("small", 6.0);
    let scene = write_scene(tmp.path(), "small.toml", &text);
    let sphere_text = testkit::godel_scene(
        "sphere",
        "[camera]\nkind = \"sphere\"\nwidth = 32\nheight = 16\n",
        &format!(
            "{}{}",
            testkit::trace("exact", 6.0),
            testkit::ball_at_rest("ball", 0.2, 1.0, 0.0)
        ),
    );
    let sphere_scene = write_scene(tmp.path(), "sphere.toml", &sphere_text);
    let out = tmp.path().join("out");
    let o = godel(&["render", &sphere_scene, "-q", "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let sphere = out.join("sphere.exr");
    let refused = out.join("refused");
    let view = refused.join("v.exr");
    let small = |args: &[&str]| {
        run_within(
            Command::new(GODEL)
                .args(args)
                .env("GODEL_MEMORY_BUDGET", "2e4"),
            NEVER_HANGS,
        )
    };
    let cases: [(Vec<&str>, &str); 3] = [
        (
            vec!["render", &scene, "-q", "-o", refused.to_str().unwrap()],
            "small.toml: camera: a data file of this width × height × samples needs about",
        ),
        (
            vec![
                "look",
                sphere.to_str().unwrap(),
                "--camera",
                "sphere",
                "--width",
                "64",
                "-o",
                view.to_str().unwrap(),
            ],
            "--width: a view of this width × height × samples needs about",
        ),
        (
            vec!["explore", &sphere_scene, "--port", "0", "--sphere", "64"],
            "--sphere 64: exploring a sphere of that width needs about",
        ),
    ];
    for (args, start) in cases {
        let o = small(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
        assert!(
            e.starts_with("error: ") && e.contains(start),
            "{args:?}: {e}"
        );
        assert!(e.contains("GODEL_MEMORY_BUDGET"), "{e}");
        assert!(o.stdout.is_empty(), "nothing served or written: {args:?}");
    }
    assert!(files_in(&refused).is_empty());
    // The budget names the sphere that fits, and that one is explored.
    let o = small(&["explore", &sphere_scene, "--port", "0", "--sphere", "64"]);
    let e = stderr(&o);
    let fits = e
        .rsplit("--sphere ")
        .next()
        .unwrap()
        .trim_end_matches(" fits\n");
    let fits: u32 = fits.parse().unwrap_or_else(|_| panic!("{e}"));
    assert!((8..64).contains(&fits) && fits.is_multiple_of(2), "{e}");
}

/// Issue 36: a `GODEL_MEMORY_BUDGET` that is not a budget (`abc`, `-5`, 10²³) was ignored
/// silently, the work then sized by the machine's memory. It is refused before any work,
/// with a message naming the variable and no output (not even the folder `-o` named);
/// empty means unset.
#[test]
fn a_memory_budget_that_is_not_one_is_refused_naming_the_variable() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(
        tmp.path(),
        "small.toml",
        &common::lit_scene_text("small", 6.0),
    );
    let out = tmp.path().join("new/out");
    let render_with = |budget: &str| {
        run_within(
            Command::new(GODEL)
                .args(["render", &scene, "-q", "-o", out.to_str().unwrap()])
                .args(["--width", "8", "--height", "2"])
                .env("GODEL_MEMORY_BUDGET", budget),
            NEVER_HANGS,
        )
    };
    for bad in ["abc", "-5", "99999999999999999999999", "nan", "inf", "8 GB"] {
        let o = render_with(bad);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{bad}: {e}");
        assert!(
            e.starts_with("error: GODEL_MEMORY_BUDGET: must be a number of bytes")
                && e.contains(&format!("got {bad:?}")),
            "{bad}: {e}"
        );
        assert!(!tmp.path().join("new").exists(), "{bad}: a folder was left");
    }
    for good in ["", "8e9", " 1000000000 "] {
        let o = render_with(good);
        assert!(o.status.success(), "{good:?}: {}", stderr(&o));
        assert_eq!(files_in(&out), ["small.exr", "small.png"], "{good:?}");
        std::fs::remove_dir_all(tmp.path().join("new")).unwrap();
    }
}
