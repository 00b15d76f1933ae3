//! `godel render [SCENE] [-o DIR]`: traces a scene (or the built-in reference scene) and
//! writes `DIR/<name>.exr` (the per-pixel data file) and `DIR/<name>.png` (the preview,
//! shaded with the objects' own textures). Textures are loaded before tracing, and both
//! files are produced in memory before either is written, each through a temporary file
//! and a rename, so a failed run leaves no half-written output.

use anyhow::Context;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use render::driver::{render, Progress};
use scene::Scene;
use std::path::PathBuf;

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
}

/// The progress bar, fed by the render driver.
struct Bar(ProgressBar);

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

pub fn run(args: RenderArgs) -> anyhow::Result<()> {
    if args.threads == Some(0) {
        return Err(crate::args::usage("--threads", "must be at least 1"));
    }
    let scene = load_scene(&args.scene)?;
    let textures = shade::textures_for_scene(&scene)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("cannot start worker threads")?;
    let pixels = scene.camera.width() as u64 * scene.camera.height() as u64;
    let bar = if args.quiet {
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
    let (data, stats) = pool.install(|| render(&scene, &Bar(bar.clone())))?;
    bar.finish_and_clear();
    let image = shade::shade_textures(&data, &textures, shade::BACKGROUND);

    std::fs::create_dir_all(&args.output)
        .with_context(|| format!("cannot create {}", args.output.display()))?;
    let exr = args.output.join(format!("{}.exr", scene.name));
    let png = args.output.join(format!("{}.png", scene.name));
    data.write(&exr)?;
    shade::write_png(&image, &png)?;
    eprintln!("wrote {} and {}", png.display(), exr.display());
    eprintln!("{}", stats.summary());
    Ok(())
}
