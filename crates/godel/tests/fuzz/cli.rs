//! The command line on a sample of the cases: `godel render`, `godel shade` and
//! `godel sequence` as subprocesses, killed if they run past their limit, with the
//! command line's promises checked (docs/guide/src/command-line.md; the project's rules):
//! exit 0, or exit 1 or 2 with one line `error: …` and no panic or signal; on success
//! exactly the promised files, on failure no file at all in the output folder (no
//! temporaries, nothing half-written); the same verdict as the library in process.

use crate::common::{files_in, run_within};
use std::path::Path;
use std::process::{Command, Output};
use std::time::Duration;

/// A subprocess is killed (and its case fails) past this.
const LIMIT: Duration = Duration::from_secs(15);

/// A fresh folder for one case's files.
pub fn scratch() -> tempfile::TempDir {
    tempfile::tempdir_in(crate::fixtures::scratch_root()).expect("create a case folder")
}

fn godel() -> Command {
    Command::new(env!("CARGO_BIN_EXE_godel"))
}

/// What the library said about the input, which the command must agree with.
pub enum Expect {
    /// Exit 0 and exactly these files in the output folder.
    Files(Vec<String>),
    /// Exit with this code (1 or 2).
    Code(i32),
    /// Exit 1 or 2.
    Failure,
}

/// Runs `cmd` and checks the promises; `out` is its output folder.
pub fn check(cmd: &mut Command, out: &Path, expect: Expect) -> Result<Output, String> {
    let o = run_within(cmd, LIMIT);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    let files = files_in(out);
    let code = o.status.code();
    let fail = |what: String| {
        Err(format!(
            "{what}\ncommand: {cmd:?}\nexit: {:?}\nstderr:\n{stderr}\nfiles: {files:?}",
            o.status
        ))
    };
    if stderr.contains("panicked") || stderr.contains("RUST_BACKTRACE") {
        return fail("the command panicked".into());
    }
    match code {
        Some(0) => {
            let Expect::Files(want) = &expect else {
                return fail("succeeded where the library refused".into());
            };
            if &files != want {
                return fail(format!("succeeded with files {files:?}, expected {want:?}"));
            }
        }
        Some(c @ (1 | 2)) => {
            let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
            let errors = lines.iter().filter(|l| l.starts_with("error")).count();
            if errors != 1 || !lines.last().is_some_and(|l| l.starts_with("error: ")) {
                return fail("the failure is not reported in one last line `error: …`".into());
            }
            if !files.is_empty() {
                return fail("a failed command left files in the output folder".into());
            }
            match expect {
                Expect::Files(_) => return fail("failed where the library succeeded".into()),
                Expect::Code(want) if want != c => {
                    return fail(format!("exit {c}, expected {want}"));
                }
                Expect::Code(_) | Expect::Failure => {}
            }
        }
        _ => return fail("exit status is neither 0, 1 nor 2".into()),
    }
    Ok(o)
}

/// `godel render scene.toml -o out`: a refused scene exits 2; a traced one writes exactly
/// NAME.exr and NAME.png, the EXR equal byte for byte to `exr` when given (the render in
/// process, with another thread count).
pub fn render(text: &str, expect: Expect, exr: Option<(&str, &[u8])>) -> Result<(), String> {
    let dir = scratch();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    let out = dir.path().join("out");
    check(
        godel()
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(&out)
            .args(["-q", "--threads", "1"]),
        &out,
        expect,
    )?;
    if let Some((name, bytes)) = exr {
        let written = std::fs::read(out.join(format!("{name}.exr"))).map_err(|e| e.to_string())?;
        if written != bytes {
            return Err("the CLI's data file differs from the render in process".into());
        }
    }
    Ok(())
}

/// `godel shade data.exr [--settings s.toml] -o out/pic.png`.
pub fn shade(data: &[u8], settings: Option<&str>, expect: Expect) -> Result<(), String> {
    let dir = scratch();
    let exr = dir.path().join("data.exr");
    std::fs::write(&exr, data).unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let mut cmd = godel();
    cmd.arg("shade")
        .arg(&exr)
        .arg("-o")
        .arg(out.join("pic.png"));
    if let Some(text) = settings {
        let path = dir.path().join("settings.toml");
        std::fs::write(&path, text).unwrap();
        cmd.arg("--settings").arg(path);
    }
    check(&mut cmd, &out, expect)?;
    Ok(())
}

/// `godel sequence script.toml` with the script's data file beside it as `data.exr`: a
/// success writes exactly the script's frames, a failure none.
pub fn sequence(script: &str, data: &[u8], frames: Option<u32>) -> Result<(), String> {
    let dir = scratch();
    std::fs::write(dir.path().join("data.exr"), data).unwrap();
    let path = dir.path().join("script.toml");
    std::fs::write(&path, script).unwrap();
    let out = dir.path().join("frames");
    let expect = match frames {
        Some(n) => Expect::Files(
            std::iter::once(crate::common::MANIFEST.to_string())
                .chain((0..n).map(|i| format!("frame_{i:04}.png")))
                .collect(),
        ),
        None => Expect::Code(2),
    };
    check(
        godel().arg("sequence").arg(&path).args(["-q", "--no-mp4"]),
        &out,
        expect,
    )?;
    Ok(())
}
