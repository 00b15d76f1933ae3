//! `godel render [SCENE] [-o DIR | -o FILE.exr | -o FILE.png]`: traces a scene (or the built-in
//! reference scene) and writes `DIR/<name>.exr` (the per-pixel data file) and `DIR/<name>.png`
//! (the preview, shaded with the objects' own textures), or the pair named by `-o`
//! (`out_pair`). Before any tracing: the thread count, the scene,
//! its textures and the output folder are checked (`output::prepare`). Both files are
//! written to temporaries and then renamed together (`output::write_together`), so a failed
//! or interrupted run leaves no half-written output and never a new EXR beside an old PNG.
//!
//! With `--part i/N` it traces only part i of N (see `render::part`) and writes the part
//! file `DIR/<name>.part-i-of-N.exr`; `godel merge` joins the parts. Built with the `mpi`
//! feature and started by mpirun/srun with several ranks, it spreads the tiles over the
//! ranks (`cluster.rs`).

use crate::args::thread_pool;
use crate::inputs::Inputs;
use crate::out_pair::OutPair;
use crate::output::{prepare, write_data_and_preview};
use crate::progress::{progress_bar, Bar};
use clap::Args;
use datafile::DataFile;
use render::driver::{plan_pixels, render_plan};
use render::part::{fingerprint, write_part};
use render::plan::{Part, Plan};
use scene::overrides::{LoadError, Overrides, SceneSource};
use scene::Scene;
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
#[command(after_help = "\
Limits, checked before any tracing (exit code 2, naming the flag or file:line:field): \
--threads at most 8 per core; the scene a regular file of at most 16 MiB; its name at most \
100 bytes, no leading '.' or '-'; image sides at most 20000 and 5·10⁷ pixels; samples a \
square number at most 256, at most 5·10⁷ rays in all; \
[trace] tolerance in [1e-14, 1e-3], max_steps at most 10⁷; the output folder creatable and \
writable.

Output: -o names a FOLDER that receives NAME.exr and NAME.png (NAME the scene's name or \
--name), or one of the two files itself: -o x.exr or -o x.png writes x.exr and x.png (as \
merge; shade and look take file names too). With --part, -o is a folder. \
--width, --height, --max-past, --method and --name replace the scene's \
camera.width, camera.height, trace.max_past, trace.method and name, checked like the \
scene file (errors name the flag); the data file embeds the scene as rendered. --metric, \
--a, --m2 and --omega replace the scene's spacetime: a new --metric takes its constants \
from these flags alone (e.g. --metric godel-type --m2 0 --omega 0.7 --method numeric).

Writing: both files go to hidden temporaries `.NAME.godel-PID-HOST.XXXXXX.tmp` and are \
renamed together at the end. Ctrl-C or SIGTERM removes the temporaries (exit 130 or 143); \
temporaries that a killed run left are removed by the next run writing to that folder.")]
pub struct RenderArgs {
    /// Scene file (TOML); without it, the built-in reference scene.
    pub scene: Option<PathBuf>,
    /// Output FOLDER (created if missing) that receives NAME.exr and NAME.png, or the file
    /// x.exr or x.png: both are written, the other beside it.
    #[arg(short, long, default_value = "out", value_name = "FOLDER|FILE")]
    pub output: PathBuf,
    /// Image width in pixels (replaces [camera] width).
    #[arg(long, allow_negative_numbers = true)]
    pub width: Option<i64>,
    /// Image height in pixels (replaces [camera] height).
    #[arg(long, allow_negative_numbers = true)]
    pub height: Option<i64>,
    /// Follow rays this far into the past (replaces [trace] max_past).
    #[arg(long, allow_negative_numbers = true, value_name = "T")]
    pub max_past: Option<f64>,
    /// Tracing method, numeric or exact (replaces [trace] method).
    #[arg(long)]
    pub method: Option<String>,
    /// The output files' name NAME (replaces the scene's name).
    #[arg(long, allow_hyphen_values = true)]
    pub name: Option<String>,
    /// Orientation marks on the preview: azimuth/elevation grid with labelled ticks.
    #[arg(long)]
    pub grid: bool,
    /// Worker threads (default: all cores; at most 8 per core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// No progress bar.
    #[arg(long, short)]
    pub quiet: bool,
    /// Trace only part i of N (e.g. 2/8) and write DIR/<name>.part-i-of-N.exr, for
    /// array jobs; join the parts with `godel merge`.
    #[arg(long, value_name = "i/N")]
    pub part: Option<String>,
    /// Trace on the GPU: the exact tracer's kernel in an offscreen OpenGL ES 3 context
    /// through EGL (Mesa's llvmpipe renders it in software where there is no GPU); the
    /// same files as a CPU render. As `[trace] gpu = true`. One process: not with --part
    /// nor under MPI.
    #[arg(long)]
    pub gpu: bool,
    /// Rays per pixel, a square number (1, 4, 9, 16, … up to 256) traced on a grid in each
    /// pixel; overrides the scene's `[camera] samples`. Every sample's record is kept in
    /// the data file (see the guide, "The data file").
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    pub samples: Option<i64>,
    /// Spacetime metric, godel, godel-type or minkowski (replaces [spacetime] metric; the
    /// scene's a, m2 and omega are dropped: give the new metric's).
    #[arg(long)]
    pub metric: Option<String>,
    /// Gödel parameter a (replaces [spacetime] a).
    #[arg(long, allow_negative_numbers = true)]
    pub a: Option<f64>,
    /// m² of a Gödel-type member (replaces [spacetime] m2).
    #[arg(long, allow_negative_numbers = true, value_name = "M2")]
    pub m2: Option<f64>,
    /// Vorticity Ω of a Gödel-type member (replaces [spacetime] omega).
    #[arg(long, allow_negative_numbers = true, value_name = "OMEGA")]
    pub omega: Option<f64>,
}

impl RenderArgs {
    /// The scene fields the flags replace.
    pub fn overrides(&self) -> Overrides {
        Overrides {
            width: self.width,
            height: self.height,
            max_past: self.max_past,
            method: self.method.clone(),
            name: self.name.clone(),
            samples: self.samples,
            metric: self.metric.clone(),
            a: self.a,
            m2: self.m2,
            omega: self.omega,
        }
    }
}

/// What `-o` names (a folder, or the data file or preview), refused as a file with `--part`,
/// whose part files go into a folder.
fn output_target(args: &RenderArgs, part: bool) -> anyhow::Result<OutPair> {
    let target = OutPair::parse("--output", &args.output, args.name.is_some())?;
    if part && target != OutPair::Folder(args.output.clone()) {
        return Err(crate::args::usage(
            "--output",
            format!(
                "with --part, -o names the folder of the part files, got the file {}",
                args.output.display()
            ),
        ));
    }
    Ok(target)
}

/// The scene of the arguments with the flags' overrides; a refused override names its flag
/// (exit 2, as every scene error).
pub fn load_with_overrides(args: &RenderArgs) -> anyhow::Result<Scene> {
    let source = match &args.scene {
        Some(path) => SceneSource::File(path),
        None => SceneSource::Builtin,
    };
    scene::overrides::load(source, &args.overrides()).map_err(|e| match e {
        LoadError::Scene(e) => e.into(),
        LoadError::Override { settings, message } => {
            let flags: Vec<&str> = settings.iter().map(|s| s.flag()).collect();
            crate::args::usage(&flags.join("/"), message)
        }
    })
}

/// The scene path stored in part files: absolute, so `godel merge` finds the textures
/// from any folder; empty for the built-in scene.
pub fn scene_path_text(path: &Option<PathBuf>) -> String {
    path.as_ref()
        .map(|p| std::path::absolute(p).unwrap_or_else(|_| p.clone()))
        .map(|p| p.display().to_string())
        .unwrap_or_default()
}

/// Before tracing: the output folder creatable, the files `names` writable there, and none
/// of them an input of the run (the scene file, its image textures).
fn prepare_outputs(dir: &Path, scene: &scene::Scene, names: &[String]) -> anyhow::Result<()> {
    prepare("--output", dir, names)?;
    let paths: Vec<PathBuf> = names.iter().map(|n| dir.join(n)).collect();
    Inputs::new()
        .add_scene(scene)
        .refuse_outputs_over_inputs("--output", &paths)
}

pub fn run(args: RenderArgs) -> anyhow::Result<()> {
    let part = match &args.part {
        Some(text) => Some(
            text.parse::<Part>()
                .map_err(|e| crate::args::usage("--part", e))?,
        ),
        None => None,
    };
    if args.gpu && part.is_some() {
        return Err(crate::args::usage("--gpu", GPU_ONE_PROCESS));
    }
    #[cfg(feature = "mpi")]
    if part.is_none() && crate::cluster::launched_by_mpi() {
        return under_mpi::run(args);
    }
    let pool = thread_pool(args.threads)?;
    let target = output_target(&args, part.is_some())?;
    let scene = load_with_overrides(&args)?;
    // Textures load and the output folder is checked before tracing: bad input fails fast.
    shade::textures_for_scene(&scene)?;
    let pair = scene.stereo.filter(scene::Stereo::is_pair);
    if pair.is_some() && part.is_some() {
        return Err(crate::args::usage("--part", STEREO_ONE_PROCESS));
    }
    let outputs = match part {
        Some(part) => vec![part.file_name(&scene.name)],
        None if pair.is_some() => target.stereo_names(&scene.name),
        None => target.names(&scene.name),
    };
    if scene.trace.gpu && part.is_some() {
        return Err(crate::args::usage("--part", GPU_ONE_PROCESS));
    }
    if let (true, Some(why)) = (args.gpu, gpu::input::refusal(&scene)) {
        return Err(crate::args::usage(
            "--gpu",
            format!("{why}: trace this scene without --gpu"),
        ));
    }
    prepare_outputs(target.folder(), &scene, &outputs)?;
    let plan = part.map_or(Plan::All, Plan::Part);
    let file = args
        .scene
        .as_ref()
        .map_or("built-in scene".into(), |p| p.display().to_string());
    // A stereo pair holds both eyes' data files until they are written together.
    let files = if pair.is_some() { 2 } else { 1 };
    crate::memory::check_writing(
        &format!("{file}: camera"),
        "a data file of this width × height × samples",
        files * plan_pixels(&scene, &plan),
        scene.lights.len(),
    )?;
    if let Some(stereo) = pair {
        return render_stereo(&scene, stereo.layout, &args, &target, &pool);
    }
    if args.gpu || scene.trace.gpu {
        return render_on_gpu(&scene, &args, &target);
    }
    // The bar's length is set when tracing starts (`Progress::start`).
    let bar = progress_bar(&scene, 0, args.quiet);
    let traced = pool.install(|| render_plan(&scene, &plan, &Bar(bar.clone())));
    bar.finish_and_clear();
    let (data, stats) = traced?;
    match part {
        None => {
            let (exr, png) = target.files(&scene.name);
            pool.install(|| write_data_and_preview(&scene, &data, &exr, &png, args.grid))?
        }
        Some(part) => {
            let path = target.folder().join(part.file_name(&scene.name));
            let scene_path = scene_path_text(&args.scene);
            write_part(&path, &data, part, &fingerprint(&scene), &scene_path)?;
            eprintln!("wrote {} (part {part})", path.display());
        }
    }
    eprintln!("{}", stats.summary());
    Ok(())
}

/// What asked for the GPU when the command line did not (`--gpu`): the scene's
/// `[trace] gpu = true`, named with its file (`None`: the built-in scene), for messages.
pub fn gpu_in_scene(file: Option<&Path>) -> String {
    let file = file.map_or("the built-in scene".into(), |p| p.display().to_string());
    format!("{file}: [trace] gpu = true")
}

/// `gpu::render` of `scene`, asked for by `asked_by` (`--gpu` or the scene's field).
pub fn trace_on_gpu(
    scene: &scene::Scene,
    progress: &dyn render::driver::Progress,
    asked_by: String,
) -> anyhow::Result<gpu::GpuRender> {
    gpu::render(scene, progress).map_err(|e| gpu_failure(asked_by, e))
}

/// Why a GPU render failed, its causes kept; a trace the CPU check refused is not used, and
/// the message says how to trace without the GPU.
fn gpu_failure(asked_by: String, e: gpu::HostError) -> anyhow::Error {
    match e {
        gpu::HostError::Check(gpu::check::CheckError::Disagrees { .. }) => anyhow::anyhow!(
            "{asked_by}: {e}; its trace is not used: trace without --gpu (or [trace] gpu = false)"
        ),
        e => anyhow::Error::new(e).context(asked_by),
    }
}

/// Why a stereo scene goes with neither --part nor MPI.
const STEREO_ONE_PROCESS: &str =
    "a stereo scene renders its two eyes in one process: it cannot be split with --part or over MPI ranks";

/// A stereo scene: each eye's scene traced (on the GPU when asked), each eye's data file and
/// the preview of both in the scene's layout written together.
fn render_stereo(
    scene: &Scene,
    layout: scene::Layout,
    args: &RenderArgs,
    target: &OutPair,
    pool: &rayon::ThreadPool,
) -> anyhow::Result<()> {
    let ([left_exr, right_exr], png) = target.stereo_files(&scene.name);
    let mut eyes = Vec::with_capacity(2);
    for (eye, exr) in scene::Eye::BOTH.into_iter().zip([&left_exr, &right_exr]) {
        let seen = scene
            .eye(eye)
            .ok_or_else(|| anyhow::anyhow!("{}: not a stereo pair", scene.name))??;
        let (data, summary) = if args.gpu || scene.trace.gpu {
            // The scene's own field asks for the GPU in both eyes' scenes.
            gpu_trace(&seen, args)?
        } else {
            let bar = progress_bar(&seen, 0, args.quiet);
            let traced = pool.install(|| render_plan(&seen, &Plan::All, &Bar(bar.clone())));
            bar.finish_and_clear();
            let (data, stats) = traced?;
            (data, stats.summary())
        };
        eprintln!("{} eye: {summary}", eye.name());
        let bytes = data.to_bytes().map_err(|kind| datafile::DataFileError {
            path: exr.to_path_buf(),
            kind,
        })?;
        let picture = crate::output::preview(&seen, &data, args.grid)?;
        eyes.push((bytes, picture));
    }
    let both = shade::stereo::compose(layout, &eyes[0].1, &eyes[1].1);
    let png_bytes = shade::encode_png(&both, &png)?;
    crate::output::write_together(&[
        (left_exr.clone(), &eyes[0].0),
        (right_exr.clone(), &eyes[1].0),
        (png.clone(), &png_bytes),
    ])?;
    eprintln!(
        "wrote {} ({}), {} and {}",
        png.display(),
        layout.name(),
        left_exr.display(),
        right_exr.display()
    );
    Ok(())
}

/// Why --gpu goes with neither --part nor MPI.
const GPU_ONE_PROCESS: &str =
    "a GPU render runs in one process: it cannot be split with --part or over MPI ranks";

/// `godel render --gpu`: the whole image traced by the GPU kernel, the same files written.
fn render_on_gpu(scene: &scene::Scene, args: &RenderArgs, target: &OutPair) -> anyhow::Result<()> {
    let (data, summary) = gpu_trace(scene, args)?;
    let (exr, png) = target.files(&scene.name);
    write_data_and_preview(scene, &data, &exr, &png, args.grid)?;
    eprintln!("{summary}");
    Ok(())
}

/// The GPU kernel's trace of `scene` with its progress bar, and its summary line.
fn gpu_trace(scene: &scene::Scene, args: &RenderArgs) -> anyhow::Result<(DataFile, String)> {
    let camera = scene.sample_camera();
    let pixels = u64::from(camera.width()) * u64::from(camera.height());
    let bar = progress_bar(scene, pixels, args.quiet);
    let asked_by = match args.gpu {
        true => "--gpu".to_string(),
        false => gpu_in_scene(scene.source_path.as_deref()),
    };
    let done = trace_on_gpu(scene, &Bar(bar.clone()), asked_by)?;
    bar.finish_and_clear();
    let summary = format!("{} (on the GPU: {})", done.stats.summary(), done.renderer);
    Ok((done.data, summary))
}

/// `godel render` under MPI: batches of tiles as jobs of the generic queue
/// (`crate::cluster::run_jobs`); rank 0 assembles and writes the same files as a
/// single-process run.
#[cfg(feature = "mpi")]
mod under_mpi {
    use super::*;
    use crate::cluster::{abort, run_jobs, start};
    use mpi::topology::Communicator;
    use render::driver::{NoProgress, RenderStats, Renderer};
    use render::tiles::{Assembler, Sink, TileData};
    use std::time::Instant;

    /// Most tiles per job: enough to keep a rank's threads busy, few enough to balance.
    const TILES_PER_JOB: usize = 8;

    pub fn run(args: RenderArgs) -> anyhow::Result<()> {
        let universe = start()?;
        let world = universe.world();
        let rank0 = world.rank() == 0;
        let set_up = || -> anyhow::Result<_> {
            let pool = thread_pool(args.threads)?;
            let target = output_target(&args, false)?;
            let scene = load_with_overrides(&args)?;
            if args.gpu || scene.trace.gpu {
                return Err(crate::args::usage("--gpu", GPU_ONE_PROCESS));
            }
            if scene.stereo.is_some_and(|s| s.is_pair()) {
                return Err(anyhow::anyhow!(STEREO_ONE_PROCESS));
            }
            if rank0 {
                // Fail before tracing: textures, and the folder rank 0 writes to.
                shade::textures_for_scene(&scene)?;
                prepare_outputs(target.folder(), &scene, &target.names(&scene.name))?;
            }
            Ok((pool, scene, target))
        };
        let (pool, scene, target) = set_up().unwrap_or_else(|e| abort(&world, &e));
        let renderer =
            Renderer::new(&scene).unwrap_or_else(|e| abort(&world, &anyhow::Error::from(e)));
        let started = Instant::now();
        let tiles = renderer.tiles();
        // Small images still get a few jobs per rank.
        let per_job = (tiles.len() / (4 * world.size() as usize)).clamp(1, TILES_PER_JOB);
        let jobs: Vec<Vec<usize>> = (0..tiles.len())
            .collect::<Vec<_>>()
            .chunks(per_job)
            .map(<[usize]>::to_vec)
            .collect();
        let work = |job: usize| -> anyhow::Result<Vec<u8>> {
            let plan = Plan::Tiles(jobs[job].clone());
            let traced = pool.install(|| renderer.trace(&plan, &NoProgress));
            Ok(postcard::to_stdvec(&traced)?)
        };
        let camera = renderer.sample_camera();
        let pixels = camera.width() as u64 * camera.height() as u64;
        let bar = progress_bar(&scene, pixels, args.quiet || !rank0);
        let mut assembler = Assembler::new(renderer.blank(), tiles);
        let mut failure = None;
        let mut done =
            |job: usize, bytes: Vec<u8>| match postcard::from_bytes::<Vec<TileData>>(&bytes) {
                Ok(traced) if traced.iter().map(|t| t.index).eq(jobs[job].iter().copied()) => {
                    for t in traced {
                        bar.inc(t.records.len() as u64);
                        assembler.accept(t);
                    }
                }
                _ => failure = Some(job),
            };
        let per_rank = run_jobs(&world, jobs.len(), &fingerprint(&scene), &work, &mut done);
        bar.finish_and_clear();
        if !rank0 {
            return Ok(());
        }
        if let Some(job) = failure {
            let e = anyhow::anyhow!("the result of job {job} arrived damaged");
            abort(&world, &e);
        }
        let data = assembler.finish();
        let stats = RenderStats {
            wall: started.elapsed(),
            ..RenderStats::count(&data.records)
        };
        let (exr, png) = target.files(&scene.name);
        write_data_and_preview(&scene, &data, &exr, &png, args.grid)
            .unwrap_or_else(|e| abort(&world, &e));
        let shares: Vec<String> = per_rank.iter().map(usize::to_string).collect();
        eprintln!(
            "{} ({} ranks; jobs of {per_job} tiles per rank: {})",
            stats.summary(),
            world.size(),
            shares.join(", ")
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use gpu::check::CheckError;
    use gpu::HostError;

    #[test]
    fn a_refused_gpu_trace_says_how_to_trace_without_the_gpu() {
        let refused = HostError::Check(CheckError::Disagrees {
            renderer: "llvmpipe".into(),
            checked: 40,
            differ: 3,
            col: 1,
            row: 2,
            gpu: "hit object 0".into(),
            cpu: "escaped".into(),
        });
        let message = format!("{:#}", super::gpu_failure("--gpu".into(), refused));
        assert!(
            message.starts_with("--gpu: the GPU (llvmpipe) disagrees"),
            "{message}"
        );
        assert!(
            message.ends_with("trace without --gpu (or [trace] gpu = false)"),
            "{message}"
        );
        let failed = super::gpu_failure("--gpu".into(), HostError::Gl("out of memory".into()));
        assert_eq!(
            format!("{failed:#}"),
            "--gpu: the GPU failed: out of memory"
        );
    }
}
