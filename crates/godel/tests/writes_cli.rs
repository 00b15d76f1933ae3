//! Clean writes (issue 10): a render interrupted by SIGTERM or SIGINT while its files are
//! being written leaves no temporary file and no half of its EXR/PNG pair (the EXR and the
//! PNG appear together or not at all), and temporaries that a killed process left are swept
//! by the next run.
//!
//! The hook `GODEL_PAUSE_BEFORE_RENAME` (crates/godel/src/output.rs) holds a run at the one
//! moment that matters: both files complete as temporaries, neither renamed yet.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

mod common;
use common::{files_in, lit_scene_text, run_within, stderr, write_scene};

const GODEL: &str = env!("CARGO_BIN_EXE_godel");
const NEVER_HANGS: Duration = Duration::from_secs(120);

/// Writes the lit test scene named "ranks" into `dir` and makes the output folder `dir/out`;
/// returns both paths.
fn ranks_scene_in(dir: &Path) -> (String, PathBuf) {
    let scene = write_scene(dir, "ranks.toml", &lit_scene_text("ranks", 6.0));
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    (scene, out)
}

/// Starts a render of the lit test scene into `out` that pauses once both files are
/// staged, sends `signal` there, and returns the exit code and the files seen in `out`
/// while paused.
fn interrupt_at_the_rename(scene: &str, out: &Path, signal: &str) -> (Option<i32>, Vec<String>) {
    let mut child = Command::new(GODEL)
        .args(["render", scene, "-q", "-o", out.to_str().unwrap()])
        .env("GODEL_PAUSE_BEFORE_RENAME", "600")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (tx, rx) = mpsc::channel();
    let err = child.stderr.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let staged = loop {
        match rx.recv_timeout(NEVER_HANGS) {
            Ok(line) if line.starts_with("staged: ") => break line,
            Ok(_) => continue,
            Err(_) => {
                let _ = child.kill();
                panic!("the render never reached its rename");
            }
        }
    };
    let seen = files_in(out);
    assert!(
        staged.contains("ranks.exr") && staged.contains("ranks.png"),
        "{staged}"
    );
    let sent = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let code = {
        let started = std::time::Instant::now();
        loop {
            if let Some(status) = child.try_wait().unwrap() {
                break status.code();
            }
            if started.elapsed() > NEVER_HANGS {
                let _ = child.kill();
                panic!("the render did not end after {signal}");
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    };
    (code, seen)
}

fn is_temporary(name: &str) -> bool {
    name.starts_with('.') && name.ends_with(".tmp")
}

#[test]
fn a_signal_during_the_write_leaves_neither_file_nor_temporary() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(tmp.path(), "ranks.toml", &lit_scene_text("ranks", 6.0));
    for (signal, code) in [("-TERM", 143), ("-INT", 130)] {
        let out = tmp.path().join(format!("out{code}"));
        let (exit, seen) = interrupt_at_the_rename(&scene, &out, signal);
        // While paused: two complete temporaries, no output yet.
        assert_eq!(seen.len(), 2, "{seen:?}");
        assert!(seen.iter().all(|n| is_temporary(n)), "{seen:?}");
        assert_eq!(exit, Some(code), "{signal}");
        assert!(files_in(&out).is_empty(), "{signal}: {:?}", files_in(&out));
    }
}

#[test]
fn an_interrupted_rerun_keeps_the_earlier_pair() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, out) = ranks_scene_in(tmp.path());
    std::fs::write(out.join("ranks.exr"), b"earlier exr").unwrap();
    std::fs::write(out.join("ranks.png"), b"earlier png").unwrap();
    let (exit, _) = interrupt_at_the_rename(&scene, &out, "-TERM");
    assert_eq!(exit, Some(143));
    assert_eq!(files_in(&out), ["ranks.exr", "ranks.png"]);
    assert_eq!(
        std::fs::read(out.join("ranks.exr")).unwrap(),
        b"earlier exr"
    );
    assert_eq!(
        std::fs::read(out.join("ranks.png")).unwrap(),
        b"earlier png"
    );
}

/// The host tag of temporary names, computed here from the same sources.
#[cfg(target_os = "linux")]
fn host_tag() -> String {
    let raw = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    raw.trim()
        .chars()
        .take(32)
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

#[cfg(target_os = "linux")]
#[test]
fn temporaries_left_by_a_killed_run_are_swept() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, out) = ranks_scene_in(tmp.path());
    // What a run killed with SIGKILL leaves: its process is gone.
    let mut gone = Command::new("true").spawn().unwrap();
    let pid = gone.id();
    gone.wait().unwrap();
    let host = host_tag();
    let stale = [
        format!(".ranks.exr.godel-{pid}-{host}.Xy12Ab.tmp"),
        format!(".ranks.png.godel-{pid}-{host}.Zz34Cd.tmp"),
    ];
    // Not ours to judge: another machine's (a shared folder), and an unknown name.
    let kept = [
        format!(".ranks.png.godel-{pid}-elsewhere.Qq56Ef.tmp"),
        ".ranks.png.Ab12Cd.tmp".to_string(),
    ];
    for name in stale.iter().chain(&kept) {
        std::fs::write(out.join(name), b"half").unwrap();
    }
    let o = run_within(
        Command::new(GODEL).args(["render", &scene, "-q", "-o", out.to_str().unwrap()]),
        NEVER_HANGS,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let mut expect: Vec<String> = kept.to_vec();
    expect.extend(["ranks.exr".to_string(), "ranks.png".to_string()]);
    expect.sort();
    assert_eq!(files_in(&out), expect);
}
