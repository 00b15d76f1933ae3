//! Never lose a user's file (issue 24), fuzzed through the `godel` binary: sequence scripts
//! that re-shade a data file lying in their own output folder, named like a frame, among
//! other files (traced frames, the user's pictures, notes), run twice (the second run with
//! fewer frames); and outputs that are inputs (`sequence` reading `frame_0000.png`, `shade
//! D.exr -o D.exr`, `--settings S -o S`).
//!
//! Promises checked: the input is never changed or removed; a file that was there before
//! and that the run does not write as one of its frames is never changed or removed; a
//! rerun removes exactly the earlier run's frames it does not write again; an output that
//! is an input is refused with exit 2; no command panics.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use crate::cli::scratch;
use crate::common::{files_in, run_within, MANIFEST};
use crate::gen::Gen;

/// A command is killed (and its case fails) past this.
const LIMIT: std::time::Duration = std::time::Duration::from_secs(15);

/// Scripts of more frames are not run (a case stays small).
const MOST_FRAMES: u64 = 12;

/// The files of `dir` and their bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    files_in(dir)
        .into_iter()
        .map(|name| {
            let bytes = std::fs::read(dir.join(&name)).unwrap_or_default();
            (name, bytes)
        })
        .collect()
}

fn frame(i: u64) -> String {
    format!("frame_{i:04}.png")
}

/// Runs `godel sequence script -q --no-mp4`: its exit code and stderr; a panic, a signal or
/// an exit other than 0, 1, 2 is an error.
fn sequence(script: &Path) -> Result<(i32, String), String> {
    let o = run_within(
        Command::new(env!("CARGO_BIN_EXE_godel"))
            .arg("sequence")
            .arg(script)
            .args(["-q", "--no-mp4"]),
        LIMIT,
    );
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    match o.status.code() {
        _ if stderr.contains("panicked") => Err(format!("the sequence panicked:\n{stderr}")),
        Some(c @ 0..=2) => Ok((c, stderr)),
        other => Err(format!("exit {other:?}:\n{stderr}")),
    }
}

/// The frame count of `text` when it is a script `godel sequence` accepts (as the library
/// reads it).
fn frames_of(text: &str, path: &Path) -> Option<u64> {
    shade::Script::parse(text, path)
        .ok()
        .map(|s| u64::from(s.frames))
}

/// Checks the folder after a run: `before` is what was there, `written` the frames the run
/// wrote (empty when it failed), `removed` the earlier run's frames it had to remove.
fn check_folder(
    dir: &Path,
    before: &BTreeMap<String, Vec<u8>>,
    written: &[String],
    removed: &[String],
    what: &str,
) -> Result<(), String> {
    let after = snapshot(dir);
    for (name, bytes) in before {
        if written.contains(name) || removed.contains(name) || name == MANIFEST {
            continue;
        }
        if after.get(name) != Some(bytes) {
            return Err(format!(
                "{what}: {name} was there before and is changed or gone; now {:?}",
                after.keys().collect::<Vec<_>>()
            ));
        }
    }
    for name in removed {
        if after.contains_key(name) {
            return Err(format!("{what}: the earlier run's {name} was not removed"));
        }
    }
    for name in after.keys() {
        let known = before.contains_key(name) && !removed.contains(name);
        if !(known || written.contains(name) || (name == MANIFEST && !written.is_empty())) {
            return Err(format!(
                "{what}: a file {name} that the run did not promise"
            ));
        }
    }
    Ok(())
}

/// One case: `script` (a generated sequence script for `data.exr`, possibly mutated) made to
/// read `frames/frame_0002.exr` and to write into `frames/`, among the files `g` picks; run,
/// then run again with fewer frames. `data` is a valid data file's bytes.
pub fn reshade(g: &mut Gen, script: &str, data: &[u8]) -> Result<String, String> {
    let dir = scratch();
    let frames_dir = dir.path().join("frames");
    std::fs::create_dir(&frames_dir).unwrap();
    let input = "frame_0002.exr";
    std::fs::write(frames_dir.join(input), data).unwrap();
    let extras: [(&str, &[u8]); 5] = [
        ("frame_0000.exr", data),
        ("frame_0001.png", b"the user's picture"),
        ("frame_0007.png", b"another picture"),
        ("sequence.mp4", b"the user's film"),
        ("notes.txt", b"notes"),
    ];
    for (name, bytes) in extras {
        if g.chance(0.5) {
            std::fs::write(frames_dir.join(name), bytes).unwrap();
        }
    }
    let text = script.replace("data = \"data.exr\"", "data = \"frames/frame_0002.exr\"");
    let path = dir.path().join("script.toml");
    std::fs::write(&path, &text).unwrap();
    let n = frames_of(&text, &path);
    if n.is_some_and(|n| n > MOST_FRAMES) {
        return Ok("not run: many frames".into());
    }
    let before = snapshot(&frames_dir);
    let (code, stderr) = sequence(&path)?;
    let written: Vec<String> = match (code, n) {
        (0, Some(n)) => (0..n).map(frame).collect(),
        (0, None) => return Err(format!("ran a script the library refuses:\n{stderr}")),
        _ => Vec::new(),
    };
    check_folder(&frames_dir, &before, &written, &[], "first run")?;
    if code != 0 {
        return Ok(format!("refused ({code})"));
    }
    // Fewer frames: the first run's frames beyond go, nothing else.
    let n = written.len() as u64;
    let m = g.int(1, n.max(1));
    let fewer = text.replacen(&format!("frames = {n}\n"), &format!("frames = {m}\n"), 1);
    if frames_of(&fewer, &path) != Some(m) {
        return Ok("ran once".into());
    }
    std::fs::write(&path, &fewer).unwrap();
    let between = snapshot(&frames_dir);
    let (code, stderr) = sequence(&path)?;
    if code != 0 {
        return Err(format!("the same script with {m} frames failed:\n{stderr}"));
    }
    let again: Vec<String> = (0..m).map(frame).collect();
    let removed: Vec<String> = (m..n).map(frame).collect();
    check_folder(&frames_dir, &between, &again, &removed, "second run")?;
    Ok("ran twice".into())
}

/// Outputs that are inputs, each refused with exit 2 and the input unchanged: a sequence
/// reading `frames/frame_0000.png` and writing frames there, `shade D.exr -o D.exr`, and
/// `shade D.exr --settings S.png -o S.png`.
pub fn outputs_over_inputs(script: &str, data: &[u8]) -> Result<String, String> {
    let dir = scratch();
    let frames_dir = dir.path().join("frames");
    std::fs::create_dir(&frames_dir).unwrap();
    let input = frames_dir.join("frame_0000.png");
    std::fs::write(&input, data).unwrap();
    let text = script.replace("data = \"data.exr\"", "data = \"frames/frame_0000.png\"");
    let path = dir.path().join("script.toml");
    std::fs::write(&path, &text).unwrap();
    let (code, stderr) = sequence(&path)?;
    if code == 0 || std::fs::read(&input).ok().as_deref() != Some(data) {
        return Err(format!(
            "the sequence wrote over its input (exit {code}):\n{stderr}"
        ));
    }
    let exr = dir.path().join("d.exr");
    std::fs::write(&exr, data).unwrap();
    let settings = dir.path().join("s.png");
    std::fs::write(&settings, "shaders = [\"texture\"]\n").unwrap();
    let shade = |extra: &[&Path], output: &Path| {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_godel"));
        cmd.arg("shade").arg(&exr);
        for p in extra {
            cmd.arg("--settings").arg(p);
        }
        cmd.arg("-o").arg(output);
        run_within(&mut cmd, LIMIT)
    };
    for (extra, output) in [(&[][..], &exr), (&[settings.as_path()][..], &settings)] {
        let o = shade(extra, output);
        let stderr = String::from_utf8_lossy(&o.stderr);
        if o.status.code() != Some(2) || !stderr.contains("--output") {
            return Err(format!(
                "shade -o {} (an input): exit {:?}\n{stderr}",
                output.display(),
                o.status.code()
            ));
        }
    }
    if std::fs::read(&exr).ok().as_deref() != Some(data) {
        return Err("shade wrote over its data file".into());
    }
    Ok(format!("refused ({code})"))
}
