//! Clean writes (issue 10): a render interrupted by SIGTERM or SIGINT while its files are
//! being written leaves no temporary file and no half of its EXR/PNG pair (the EXR and the
//! PNG appear together or not at all), and temporaries that a killed process left are swept
//! by the next run. Never lose or mix a user's file (issue 24): concurrent runs into one name
//! leave one run's pair, a failed rename gives the first file back, read-only outputs and
//! outputs that are inputs are refused.
//!
//! The hooks of crates/godel/src/output.rs hold a run at the moments that matter:
//! `GODEL_PAUSE_BEFORE_RENAME` with both files complete as temporaries, neither renamed yet;
//! `GODEL_PAUSE_BETWEEN_RENAMES` with the EXR renamed, the PNG not yet.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use crate::common::{files_in, lit_scene_text, run_within, stderr, write_scene, GODEL};

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
    let mut child = spawn_render(scene, out, &[], &[("GODEL_PAUSE_BEFORE_RENAME", "600")]);
    let staged = wait_for_line(&mut child, "staged: ");
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
    (exit_code(child), seen)
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

/// Starts `godel render SCENE -q -o OUT` with `extra` arguments and the environment `env`.
fn spawn_render(scene: &str, out: &Path, extra: &[&str], env: &[(&str, &str)]) -> Child {
    let mut cmd = Command::new(GODEL);
    cmd.args(["render", scene, "-q", "-o", out.to_str().unwrap()])
        .args(extra)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.spawn().unwrap()
}

/// Waits (at most [`NEVER_HANGS`]) for a line of `child`'s stderr starting with `prefix`;
/// the rest of its stderr is drained in the background.
fn wait_for_line(child: &mut Child, prefix: &str) -> String {
    let (tx, rx) = mpsc::channel();
    let err = child.stderr.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    loop {
        match rx.recv_timeout(NEVER_HANGS) {
            Ok(line) if line.starts_with(prefix) => return line,
            Ok(_) => continue,
            Err(_) => {
                let _ = child.kill();
                panic!("no line {prefix:?} from the run");
            }
        }
    }
}

/// The exit code of `child` (waiting at most [`NEVER_HANGS`]).
fn exit_code(mut child: Child) -> Option<i32> {
    let started = std::time::Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status.code();
        }
        if started.elapsed() > NEVER_HANGS {
            let _ = child.kill();
            panic!("the run did not end");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The width of `out/pair.exr` and of `out/pair.png`: equal when the pair is one run's.
fn pair_widths(out: &Path) -> (usize, u32) {
    let data = datafile::DataFile::read(&out.join("pair.exr")).unwrap();
    let (png_width, _) = image::image_dimensions(out.join("pair.png")).unwrap();
    (data.picture_size().0, png_width)
}

/// Issue 24: two renders with the same name and different sizes at once left an EXR of one
/// beside the PNG of the other (4 times in 100). With a pause forced between the first run's
/// two renames, the second run's commit came in between every time; under the folder's lock
/// it waits, and the pair is the second run's, whole.
#[test]
fn concurrent_runs_into_one_name_leave_one_runs_pair() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, out) = ranks_scene_in(tmp.path());
    let named = |width: &'static str| ["--name", "pair", "--width", width, "--height", "8"];
    let mut first = spawn_render(
        &scene,
        &out,
        &named("30"),
        &[("GODEL_PAUSE_BETWEEN_RENAMES", "3")],
    );
    let renamed = wait_for_line(&mut first, "renamed: ");
    assert!(renamed.ends_with("pair.exr"), "{renamed}");
    let second = spawn_render(&scene, &out, &named("40"), &[]);
    assert_eq!(exit_code(second), Some(0));
    assert_eq!(exit_code(first), Some(0));
    assert_eq!(pair_widths(&out), (40, 40));
    assert_eq!(files_in(&out), ["pair.exr", "pair.png"]);

    // And without a pause, many times over.
    for _ in 0..10 {
        let runs: Vec<Child> = [named("30"), named("40")]
            .iter()
            .map(|args| spawn_render(&scene, &out, args, &[]))
            .collect();
        for run in runs {
            assert_eq!(exit_code(run), Some(0));
        }
        let (exr, png) = pair_widths(&out);
        assert_eq!(exr as u32, png, "a mixed pair");
    }
}

/// Issue 24: when the PNG's rename failed (it could not be replaced), the run exited 1 but
/// left its new EXR beside the old PNG. Now the EXR gets its old content back.
#[test]
fn a_failed_second_rename_gives_the_first_file_back() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, out) = ranks_scene_in(tmp.path());
    std::fs::write(out.join("ranks.exr"), b"earlier exr").unwrap();
    std::fs::write(out.join("ranks.png"), b"earlier png").unwrap();
    let mut run = spawn_render(&scene, &out, &[], &[("GODEL_PAUSE_BETWEEN_RENAMES", "1")]);
    wait_for_line(&mut run, "renamed: ");
    // The PNG's place becomes a folder with a file in it: no rename replaces that.
    std::fs::remove_file(out.join("ranks.png")).unwrap();
    std::fs::create_dir_all(out.join("ranks.png/inside")).unwrap();
    assert_eq!(exit_code(run), Some(1));
    assert_eq!(
        std::fs::read(out.join("ranks.exr")).unwrap(),
        b"earlier exr"
    );
    assert_eq!(files_in(&out), ["ranks.exr", "ranks.png"]);
}

/// Issue 24: a read-only output in a writable folder was silently replaced (a rename ignores
/// the file's permissions). It is refused before tracing, and kept.
#[cfg(unix)]
#[test]
fn a_read_only_output_is_refused_and_kept() {
    use std::os::unix::fs::PermissionsExt;
    let tmp = tempfile::tempdir().unwrap();
    let (scene, out) = ranks_scene_in(tmp.path());
    let png = out.join("ranks.png");
    std::fs::write(&png, b"mine").unwrap();
    std::fs::set_permissions(&png, std::fs::Permissions::from_mode(0o444)).unwrap();
    let o = run_within(
        Command::new(GODEL).args(["render", &scene, "-q", "-o", out.to_str().unwrap()]),
        NEVER_HANGS,
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("ranks.png: it is read-only"), "{e}");
    assert_eq!(std::fs::read(&png).unwrap(), b"mine");
    assert_eq!(files_in(&out), ["ranks.png"]);
}

/// Issue 24: `godel shade D.exr -o D.exr` replaced the data file with an RGB picture, and a
/// render could write over its own texture. An output that is an input of the same run (by
/// any path) is refused before any work, and the input kept.
#[test]
fn an_output_that_is_an_input_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, out) = ranks_scene_in(tmp.path());
    let o = run_within(
        Command::new(GODEL).args(["render", &scene, "-q", "-o", out.to_str().unwrap()]),
        NEVER_HANGS,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let exr = out.join("ranks.exr");
    let bytes = std::fs::read(&exr).unwrap();
    let spelled = format!("{}/../out/ranks.exr", out.display());
    for output in [exr.to_str().unwrap(), spelled.as_str()] {
        let o = run_within(
            Command::new(GODEL).args(["shade", exr.to_str().unwrap(), "-o", output]),
            NEVER_HANGS,
        );
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{e}");
        assert!(e.contains("--output") && e.contains("the data file"), "{e}");
    }
    let settings = tmp.path().join("s.exr");
    std::fs::write(&settings, "shaders = [\"texture\"]\n").unwrap();
    let o = run_within(
        Command::new(GODEL).args([
            "shade",
            exr.to_str().unwrap(),
            "--settings",
            settings.to_str().unwrap(),
            "-o",
            settings.to_str().unwrap(),
        ]),
        NEVER_HANGS,
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("the settings file"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&exr).unwrap(), bytes);

    // A scene whose texture is the picture the render would write.
    let textured = tmp.path().join("textured.toml");
    let text = std::fs::read_to_string(&scene).unwrap().replace(
        "texture = { kind = \"checker\", rows = 4, cols = 8 }",
        "texture = { kind = \"image\", path = \"out/ranks.png\" }",
    );
    assert!(text.contains("out/ranks.png"));
    std::fs::write(&textured, text).unwrap();
    let png = std::fs::read(out.join("ranks.png")).unwrap();
    let o = run_within(
        Command::new(GODEL).args([
            "render",
            textured.to_str().unwrap(),
            "-q",
            "-o",
            out.to_str().unwrap(),
        ]),
        NEVER_HANGS,
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("a texture of the scene"), "{e}");
    assert_eq!(std::fs::read(out.join("ranks.png")).unwrap(), png);
}
