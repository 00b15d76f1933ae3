//! `godel render [SCENE] [-o DIR]`: traces a scene (or the built-in reference scene) and
//! writes `DIR/<name>.exr` (the per-pixel data file) and `DIR/<name>.png` (the preview,
//! shaded with the objects' own textures). Textures are loaded before tracing, and both
//! files are produced in memory before either is written, each through a temporary file
//! and a rename, so a failed run leaves no half-written output.
//!
//! With `--part i/N` it traces only part i of N (see `render::part`) and writes the part
//! file `DIR/<name>.part-i-of-N.exr`; `godel merge` joins the parts. Built with the `mpi`
//! feature and started by mpirun/srun with several ranks, it spreads the tiles over the
//! ranks (`cluster.rs`).

use anyhow::Context;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use render::datafile::DataFile;
use render::driver::{render, Progress, RenderStats};
use render::part::{fingerprint, write_part, Part};
use render::tiles::{count, insert, TileRenderer};
use scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file (TOML); without it, the built-in reference scene.
    pub scene: Option<PathBuf>,
    /// Output folder (created if missing).
    #[arg(short, long, default_value = "out")]
    pub output: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// No progress bar.
    #[arg(long, short)]
    pub quiet: bool,
    /// Trace only part i of N (e.g. 2/8) and write DIR/<name>.part-i-of-N.exr, for
    /// array jobs; join the parts with `godel merge`.
    #[arg(long, value_name = "i/N")]
    pub part: Option<String>,
}

/// The progress bar, fed by the render driver.
pub struct Bar(pub ProgressBar);

impl Progress for Bar {
    fn advance(&self, pixels: u64) {
        self.0.inc(pixels);
    }
}

/// Loads the scene named on the command line, or the built-in one.
pub fn load_scene(path: &Option<PathBuf>) -> anyhow::Result<Scene> {
    Ok(match path {
        Some(p) => Scene::from_file(p)?,
        None => Scene::builtin(),
    })
}

/// A progress bar over `pixels` pixels (hidden when `quiet`).
pub fn progress_bar(scene: &Scene, pixels: u64, quiet: bool) -> ProgressBar {
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(pixels)
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{prefix} [{bar:40}] {percent:>3}% {pos}/{len} px, {per_sec}, ETA {eta}",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    bar.set_prefix(format!("tracing {}", scene.name));
    bar
}

/// The worker thread pool of `--threads`.
pub fn thread_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    if threads == Some(0) {
        return Err(crate::args::usage("--threads", "must be at least 1"));
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .context("cannot start worker threads")
}

/// Writes `DIR/<name>.exr` and `DIR/<name>.png` (the preview with the scene's textures,
/// lit where the scene has lights):
/// exactly the files of a single run, whoever traced the pixels.
pub fn write_outputs(scene: &Scene, data: &DataFile, dir: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let exr = dir.join(format!("{}.exr", scene.name));
    let png = dir.join(format!("{}.png", scene.name));
    write_data_and_preview(scene, data, &exr, &png)
}

/// Writes the data file to `exr` and its preview (the scene's textures, lit where the scene
/// has lights) to `png`, the preview shaded before either file is written.
pub fn write_data_and_preview(
    scene: &Scene,
    data: &DataFile,
    exr: &Path,
    png: &Path,
) -> anyhow::Result<()> {
    let textures = shade::textures_for_scene(scene)?;
    let image = shade::texture_shader::preview_with_textures(data, &textures, scene);
    data.write(exr)?;
    shade::write_png(&image, png)?;
    eprintln!("wrote {} and {}", png.display(), exr.display());
    Ok(())
}

/// The scene path stored in part files: absolute, so `godel merge` finds the textures
/// from any folder; empty for the built-in scene.
pub fn scene_path_text(path: &Option<PathBuf>) -> String {
    path.as_ref()
        .map(|p| std::path::absolute(p).unwrap_or_else(|_| p.clone()))
        .map(|p| p.display().to_string())
        .unwrap_or_default()
}

pub fn run(args: RenderArgs) -> anyhow::Result<()> {
    let part = match &args.part {
        Some(text) => Some(
            text.parse::<Part>()
                .map_err(|e| crate::args::usage("--part", e))?,
        ),
        None => None,
    };
    #[cfg(feature = "mpi")]
    if part.is_none() && crate::cluster::launched_by_mpi() {
        return crate::cluster::render(args);
    }
    let pool = thread_pool(args.threads)?;
    let scene = load_scene(&args.scene)?;
    // Textures load before tracing, so a bad texture fails fast.
    shade::textures_for_scene(&scene)?;
    if let Some(part) = part {
        return render_part(&args, &scene, part, &pool);
    }
    let pixels = scene.camera.width() as u64 * scene.camera.height() as u64;
    let bar = progress_bar(&scene, pixels, args.quiet);
    let (data, stats) = pool.install(|| render(&scene, &Bar(bar.clone())))?;
    bar.finish_and_clear();
    write_outputs(&scene, &data, &args.output)?;
    eprintln!("{}", stats.summary());
    Ok(())
}

/// `--part i/N`: traces the part's tiles and writes the part file.
fn render_part(
    args: &RenderArgs,
    scene: &Scene,
    part: Part,
    pool: &rayon::ThreadPool,
) -> anyhow::Result<()> {
    let started = Instant::now();
    let renderer = TileRenderer::new(scene)?;
    let mine = part.tiles(renderer.tiles().len());
    let pixels: u64 = mine
        .iter()
        .map(|&k| (renderer.tiles()[k].cols * renderer.tiles()[k].rows) as u64)
        .sum();
    let bar = progress_bar(scene, pixels, args.quiet);
    let traced = pool.install(|| renderer.trace(&mine, &Bar(bar.clone())));
    bar.finish_and_clear();
    let mut data = renderer.blank();
    for t in &traced {
        insert(&mut data, renderer.tiles()[t.index], t);
    }
    let stats = RenderStats {
        wall: started.elapsed(),
        ..count(
            &traced
                .iter()
                .flat_map(|t| t.records.iter().copied())
                .collect::<Vec<_>>(),
        )
    };
    std::fs::create_dir_all(&args.output)
        .with_context(|| format!("cannot create {}", args.output.display()))?;
    let path = args.output.join(part.file_name(&scene.name));
    write_part(
        &path,
        &data,
        part,
        &fingerprint(scene),
        &scene_path_text(&args.scene),
    )?;
    eprintln!("wrote {} (part {part})", path.display());
    eprintln!("{}", stats.summary());
    Ok(())
}
