//! Writing output files (via `datafile::atomic`): each through a temporary file and a rename,
//! files that belong together (a render's EXR and PNG) all staged first and then renamed
//! together, and the output folder checked before any work ([`prepare`]), so that a failed
//! or interrupted run leaves no half-written file and no unwritable folder is found late.
//!
//! Testing hooks: with `GODEL_PAUSE_BEFORE_RENAME=SECONDS` in the environment,
//! [`write_together`] prints `staged: PATH …` on stderr once every file is a complete
//! temporary and waits that long before renaming, so that tests can interrupt a run exactly
//! there; with `GODEL_PAUSE_BETWEEN_RENAMES=SECONDS` it prints `renamed: PATH` after each
//! rename but the last and waits that long, so that tests can race another run or break
//! the next rename there (crates/godel/tests/integration/writes_cli.rs).

use anyhow::Context;
use datafile::atomic::{check_writable, commit_all_with, stage};
use datafile::DataFile;
use scene::Scene;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` through a temporary file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    write_together(&[(path.to_path_buf(), bytes)])
}

/// Writes every file to a temporary first, then renames them one right after the other:
/// either all appear (or are replaced) or, on an error or a signal, none does.
pub fn write_together(files: &[(PathBuf, &[u8])]) -> anyhow::Result<()> {
    let mut staged = Vec::with_capacity(files.len());
    for (path, bytes) in files {
        staged.push(
            stage(path, |f| f.write_all(bytes))
                .with_context(|| format!("cannot write {}", path.display()))?,
        );
    }
    let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    pause_for_tests("GODEL_PAUSE_BEFORE_RENAME", || {
        format!("staged: {}", names.join(" "))
    });
    let renamed = std::cell::Cell::new(0);
    let between = || {
        let name = &names[renamed.get()];
        renamed.set(renamed.get() + 1);
        pause_for_tests("GODEL_PAUSE_BETWEEN_RENAMES", || format!("renamed: {name}"));
    };
    commit_all_with(staged, between)
        .with_context(|| format!("cannot write {}", names.join(" and ")))
}

/// Creates the output folder `dir` (and missing parents: removed again if the run fails,
/// `datafile::folders`) and checks that every file in `names` can be written there, before
/// any work; failures are usage errors naming `flag`.
pub fn prepare(flag: &str, dir: &Path, names: &[String]) -> anyhow::Result<()> {
    datafile::folders::create_folder(dir).map_err(|e| {
        crate::args::usage(
            flag,
            format!("cannot create the output folder {}: {e}", dir.display()),
        )
    })?;
    for name in names {
        let path = dir.join(name);
        check_writable(&path).map_err(|e| {
            crate::args::usage(flag, format!("cannot write {}: {e}", path.display()))
        })?;
    }
    Ok(())
}

/// [`prepare`] for one file `path` (its folder `.` where it names none).
pub fn prepare_file(flag: &str, path: &Path) -> anyhow::Result<()> {
    let folder = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    prepare(flag, folder, &Vec::from_iter(name))
}

/// Writes the data file to `exr` and its preview (the scene's textures, lit where the scene
/// has lights) to `png`: both made in memory first ([`data_and_preview`]), then written
/// together ([`write_together`]). `godel render`, `godel merge` and `godel look` write this
/// pair.
pub fn write_data_and_preview(
    scene: &Scene,
    data: &DataFile,
    exr: &Path,
    png: &Path,
    grid: bool,
) -> anyhow::Result<()> {
    let (exr_bytes, png_bytes) = data_and_preview(scene, data, exr, png, grid)?;
    write_together(&[
        (exr.to_path_buf(), &exr_bytes),
        (png.to_path_buf(), &png_bytes),
    ])?;
    eprintln!("wrote {} and {}", png.display(), exr.display());
    Ok(())
}

/// The bytes of the data file and of its preview that [`write_data_and_preview`] writes to
/// `exr` and `png` (named in messages): explore's exact renders offer the same two files.
pub fn data_and_preview(
    scene: &Scene,
    data: &DataFile,
    exr: &Path,
    png: &Path,
    grid: bool,
) -> anyhow::Result<(Vec<u8>, Vec<u8>)> {
    // The two encodings are independent: side by side on the current pool (the command's
    // --threads), the preview (its texture, shading and PNG) beside the data file's.
    let (png_bytes, exr_bytes) = rayon::join(
        || -> anyhow::Result<Vec<u8>> { Ok(shade::encode_png(&preview(scene, data, grid)?, png)?) },
        || {
            data.to_bytes().map_err(|kind| datafile::DataFileError {
                path: exr.to_path_buf(),
                kind,
            })
        },
    );
    Ok((exr_bytes?, png_bytes?))
}

/// The preview of `scene`'s data file `data`: its textures, lit where the scene has lights,
/// with the orientation marks when `grid`.
pub fn preview(scene: &Scene, data: &DataFile, grid: bool) -> anyhow::Result<image::RgbImage> {
    let textures = shade::textures_for_scene(scene)?;
    let mut image = shade::texture_shader::preview_with_textures(data, &textures, scene);
    if grid {
        let marks = shade::layer::Overlays {
            marks: Some(scene.camera),
            ..Default::default()
        };
        if let Some(layer) = marks.draw(image.width(), image.height()) {
            shade::layer::composite(&mut image, &layer);
        }
    }
    Ok(image)
}

/// The testing hooks of the module doc: when the variable `var` holds a number of seconds,
/// prints `line()` on stderr and waits that long.
fn pause_for_tests(var: &str, line: impl FnOnce() -> String) {
    let Some(seconds) = std::env::var(var)
        .ok()
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0)
    else {
        return;
    };
    eprintln!("{}", line());
    std::thread::sleep(std::time::Duration::from_secs_f64(seconds.min(3600.0)));
}
