//! `godel sequence SCRIPT.toml`: image sequences with keyframed shader settings
//! ([`shade::script`]): numbered PNGs `frame_0000.png`, … in the script's output folder, and
//! `sequence.mp4` when `ffmpeg` is on PATH (a clear note, not an error, when it is not).
//! Traced frames follow the keyframed observer and camera ([`crate::flight`]); with
//! `[trace] keep_data = true` each frame's data file `frame_NNNN.exr` is written together
//! with its picture (both staged, then renamed one right after the other).
//!
//! Stereo: when the traced scene is a stereo pair (`[camera] stereo`), each frame traces the
//! two eyes of that frame's scene (the keyframes move the observer, the eyes follow it) and
//! its picture is the two eyes shaded with the frame's settings in the pair's layout
//! ([`shade::stereo::compose`]), as `godel render` writes a pair's preview; kept data files
//! are `frame_NNNN.left.exr` and `frame_NNNN.right.exr`. A sequence shading one eye's data
//! file (`NAME.left.exr`) shades both eyes, the other eye's file beside it, into the layout,
//! as `godel shade` does.
//!
//! Before the first frame: every output path of every frame is checked (writable, not an
//! input of the run), and what an earlier sequence wrote into the folder that this run does
//! not write again is removed — files named by the folder's manifest ([`crate::manifest`])
//! only, never another file; ffmpeg is told the exact frame count, so the MP4 never shows
//! another run's frames.
//!
//! [`Plan`] is built and checked completely before anything is written (the data file read,
//! every keyframe's settings validated), then each frame is an independent, pure job
//! [`Plan::frame`]`(i) -> image` (shade the data file, or trace the scene at that frame's
//! observer time and shade it); all writing happens in [`run`]'s loop, so frames can later be
//! spread over MPI ranks with one writer.

use std::path::{Path, PathBuf};
use std::process::{Child, Command};
use std::sync::{Mutex, MutexGuard};

use anyhow::Context;
use clap::Args;
use datafile::DataFile;
use image::RgbImage;
use indicatif::{ProgressBar, ProgressStyle};
use render::driver::{header, render, NoProgress};
use scene::{Eye, Layout, Scene};
use shade::{Channels, FrameSource, Needs, Script, ShadeSettings, Shading, Timeline};

use crate::cmd::shade::settings_error;
use crate::flight::Flight;
use crate::inputs::Inputs;
use crate::manifest::{self, Manifest, MANIFEST};
use crate::output::write_together;

#[derive(Args, Debug)]
#[command(after_help = "\
Limits, checked before the first frame (exit code 2, naming file:line:field): the script a \
regular file of at most 16 MiB; frames 1 to 100000; fps at most 1000; the output folder \
creatable and writable.

Every frame's output paths are checked before the first frame; an output that is an input of \
the run (its data file, scene or script) is refused. The files an earlier sequence wrote into the \
folder (named in its manifest .godel-sequence) and this run does not write again (frames \
beyond its count, data files, sequence.mp4) are removed first, a note lists them; no other \
file is ever removed. ffmpeg encodes exactly this run's frames.

Traced sequences may keyframe the observer ([keyframe.observer]: time, position {x, y, z}, \
velocity, forward, up) and the field of view ([keyframe.camera]); the position moves along a \
straight coordinate line. [trace] keep_data = true writes frame_NNNN.exr beside each frame.

A stereo scene ([camera] stereo) makes stereo frames: both eyes of each frame's observer in the \
pair's layout (side-by-side frames twice as wide, over-under twice as tall), keeping \
frame_NNNN.left.exr and frame_NNNN.right.exr with keep_data. A data file that is one eye of a \
pair (NAME.left.exr) is shaded with the other eye's file beside it into the layout.")]
pub struct SequenceArgs {
    /// The sequence script (TOML).
    pub script: PathBuf,
    /// No progress bar.
    #[arg(long, short)]
    pub quiet: bool,
    /// Do not encode an MP4 even when ffmpeg is available.
    #[arg(long)]
    pub no_mp4: bool,
}

/// Where each frame's data comes from, loaded.
enum Source {
    /// One data file for every frame, and its shading channels (copied once, every frame
    /// shaded from them); for one eye of a stereo pair, both eyes' (left first).
    Data {
        eyes: Vec<(DataFile, Channels)>,
        pair: Option<Layout>,
    },
    /// A scene traced per frame, each frame's scene from the flight (both eyes of it for a
    /// stereo pair, in `pair`'s layout); with `keep_data` the frame's data files are kept.
    Trace {
        flight: Box<Flight>,
        keep_data: bool,
        pair: Option<Layout>,
    },
}

/// One frame made: its picture, and its data files' bytes when the sequence keeps them (in
/// the order of [`Plan::data_paths`]: the left eye first for a stereo pair).
pub struct Frame {
    pub image: RgbImage,
    pub data: Vec<Vec<u8>>,
}

/// A checked sequence, ready to make frames.
pub struct Plan {
    script: Script,
    source: Source,
    timeline: Timeline,
    /// What the run reads: never replaced or removed.
    inputs: Inputs,
}

impl Plan {
    /// Reads the script and its source and checks every keyframe's settings.
    pub fn new(path: &Path) -> anyhow::Result<Plan> {
        let script = Script::from_file(path).map_err(|e| settings_error("sequence", e))?;
        let mut inputs = Inputs::new();
        inputs.add("the sequence script", path);
        let (source, probe) = match &script.source {
            FrameSource::Data(p) => {
                inputs.add("the data file", p);
                let data = DataFile::read(p)?;
                // One eye of a stereo pair is shaded with the other beside it, as godel shade does.
                let partner = shade::stereo::partner(p, &data).map_err(|e| match e {
                    shade::stereo::PartnerError::Read(e) => e.into(),
                    e => settings_error("sequence", script.error_at("data", e.to_string())),
                })?;
                let (pair, files) = match partner {
                    None => (None, vec![data.clone()]),
                    Some(other) => {
                        inputs.add("the other eye's data file", &other.path);
                        let (left, right) = other.left_right(data.clone(), other.data.clone());
                        (Some(other.layout), vec![left, right])
                    }
                };
                let eyes = files
                    .into_iter()
                    .map(|d| {
                        let channels = Channels::new(&d, Needs::ALL);
                        (d, channels)
                    })
                    .collect();
                (Source::Data { eyes, pair }, data)
            }
            FrameSource::Trace {
                scene, keep_data, ..
            } => {
                let s = Scene::from_file(scene)?;
                inputs.add_scene(&s);
                // A data file without pixels: the scene's objects and header, for defaults
                // and validation before anything is traced.
                let probe = DataFile {
                    header: header(&s),
                    width: 0,
                    height: 0,
                    records: Vec::new(),
                    lights: Vec::new(),
                    // Frames traced on the CPU carry the polarization channels; the GPU
                    // kernel does not write them yet.
                    polarization: !s.trace.gpu,
                };
                let flight = Flight::new(&s, &script).map_err(|e| settings_error("sequence", e))?;
                let pair = s.stereo.filter(scene::Stereo::is_pair).map(|st| st.layout);
                // A frame holds its traced records while it is shaded, and a stereo frame
                // keeping its data both eyes' files until they are written together. The
                // keyframes change neither the size nor the samples: frame 0 tells.
                let camera = s.sample_camera();
                let rays = u64::from(camera.width()) * u64::from(camera.height());
                let (files, what) = match pair.is_some() && *keep_data {
                    true => (
                        2,
                        "both eyes' data files of a frame of this width × height × samples",
                    ),
                    false => (1, "a frame's data file of this width × height × samples"),
                };
                crate::memory::check_writing(
                    &format!("{}: camera", scene.display()),
                    what,
                    rays.saturating_mul(files),
                    s.lights.len(),
                )?;
                if pair.is_some() {
                    // Each eye is the frame's scene moved by an isometry; what could refuse
                    // it (the scene's text) is the same in every frame: frame 0 tells.
                    let first = flight
                        .scene_at(0)
                        .map_err(|e| settings_error("sequence", e))?;
                    for eye in Eye::BOTH {
                        eye_scene(&first, eye)?;
                    }
                }
                let source = Source::Trace {
                    flight: Box::new(flight),
                    keep_data: *keep_data,
                    pair,
                };
                (source, probe)
            }
        };
        let timeline = script
            .timeline(&ShadeSettings::defaults_for(&probe))
            .map_err(|e| settings_error("sequence", e))?;
        // Every keyframe's settings must prepare (names, values, textures) before frame 0.
        let keyframe_frames: Vec<u32> = script.keyframes.iter().map(|k| k.frame).collect();
        for f in keyframe_frames.into_iter().chain([0]) {
            Shading::new(&probe, &timeline.settings_at(f))
                .map_err(|e| settings_error("sequence", e))
                .with_context(|| format!("{}: settings of frame {f}", script.file))?;
        }
        for k in &script.keyframes {
            inputs.add_settings(&timeline.settings_at(k.frame));
        }
        inputs.add_settings(&timeline.settings_at(0));
        Ok(Plan {
            script,
            source,
            timeline,
            inputs,
        })
    }

    /// Number of frames.
    pub fn frames(&self) -> u32 {
        self.script.frames
    }

    /// The picture of frame `i` (and its data file's bytes when kept): a pure function of
    /// the plan and `i`.
    pub fn frame(&self, i: u32) -> anyhow::Result<Frame> {
        let settings = self.timeline.settings_at(i);
        match &self.source {
            Source::Data { eyes, pair } => {
                let mut pictures = Vec::with_capacity(eyes.len());
                for (data, channels) in eyes {
                    pictures.push(Shading::new(data, &settings)?.image_with(channels));
                }
                Ok(Frame {
                    image: in_layout(*pair, pictures),
                    data: Vec::new(),
                })
            }
            Source::Trace {
                flight,
                keep_data,
                pair,
            } => {
                let scene = flight
                    .scene_at(i)
                    .map_err(|e| settings_error("sequence", e))?;
                // A stereo pair: the eyes of this frame's observer, left first.
                let (scenes, eyes) = match pair {
                    None => (vec![scene], vec![None]),
                    Some(_) => (
                        Eye::BOTH
                            .iter()
                            .map(|&e| eye_scene(&scene, e))
                            .collect::<anyhow::Result<_>>()?,
                        Eye::BOTH.map(Some).to_vec(),
                    ),
                };
                let mut pictures = Vec::with_capacity(scenes.len());
                let mut kept = Vec::new();
                for (seen, eye) in scenes.iter().zip(eyes) {
                    let data = self.trace(seen)?;
                    pictures.push(Shading::new(&data, &settings)?.image(&data));
                    if *keep_data {
                        kept.push(data.to_bytes().map_err(|kind| datafile::DataFileError {
                            path: self.data_path(i, eye),
                            kind,
                        })?);
                    }
                }
                Ok(Frame {
                    image: in_layout(*pair, pictures),
                    data: kept,
                })
            }
        }
    }

    /// The data file of one frame's `scene` (or of one eye of it), traced on the CPU, or
    /// with the GPU kernel where the scene says `[trace] gpu = true`.
    fn trace(&self, scene: &Scene) -> anyhow::Result<DataFile> {
        Ok(match scene.trace.gpu {
            true => {
                let file = match &self.script.source {
                    FrameSource::Trace { scene, .. } => Some(scene.as_path()),
                    FrameSource::Data(_) => None,
                };
                let asked_by = crate::cmd::render::gpu_in_scene(file);
                crate::cmd::render::trace_on_gpu(scene, &NoProgress, asked_by)?.data
            }
            false => render(scene, &NoProgress)?.0,
        })
    }

    /// The stereo pair's layout, when the frames are a pair's (traced or shaded).
    fn pair(&self) -> Option<Layout> {
        match &self.source {
            Source::Data { pair, .. } | Source::Trace { pair, .. } => *pair,
        }
    }

    /// Whether each frame's data file is written.
    pub fn keeps_data(&self) -> bool {
        matches!(
            self.source,
            Source::Trace {
                keep_data: true,
                ..
            }
        )
    }

    /// The folder the frames go to.
    pub fn output_dir(&self) -> &Path {
        &self.script.output
    }

    /// Where frame `i` is written.
    pub fn frame_path(&self, i: u32) -> PathBuf {
        self.script.output.join(format!("frame_{i:04}.png"))
    }

    /// Where frame `i`'s data file is written (with `keep_data`): `frame_NNNN.exr`, or for
    /// one eye of a stereo pair `frame_NNNN.left.exr` / `frame_NNNN.right.exr`.
    fn data_path(&self, i: u32, eye: Option<Eye>) -> PathBuf {
        let eye = eye.map_or(String::new(), |e| format!(".{}", e.name()));
        self.script.output.join(format!("frame_{i:04}{eye}.exr"))
    }

    /// The data files frame `i` writes: none without `keep_data`, else its one, or both
    /// eyes' of a stereo pair (left first).
    pub fn data_paths(&self, i: u32) -> Vec<PathBuf> {
        match (self.keeps_data(), self.pair()) {
            (false, _) => Vec::new(),
            (true, None) => vec![self.data_path(i, None)],
            (true, Some(_)) => Eye::BOTH.map(|e| self.data_path(i, Some(e))).to_vec(),
        }
    }

    /// Every file the run may write, frame by frame, then the MP4 and the manifest.
    fn outputs(&self) -> Vec<PathBuf> {
        let frames = (0..self.frames())
            .flat_map(|i| [self.frame_path(i)].into_iter().chain(self.data_paths(i)));
        let dir = self.output_dir();
        frames.chain([dir.join(MP4), dir.join(MANIFEST)]).collect()
    }

    /// Whether a run of this plan writes the file `name` of its folder again (the MP4 is
    /// removed first either way: made again at the end, or not at all).
    fn writes(&self, name: &str) -> bool {
        let frame = |ext: &str| {
            name.strip_prefix("frame_")
                .and_then(|n| n.strip_suffix(ext))
                .and_then(|n| n.parse::<u32>().ok())
                // Exactly the name this program gives that frame.
                .filter(|&i| name == format!("frame_{i:04}{ext}") && i < self.frames())
        };
        let data: &[&str] = match (self.keeps_data(), self.pair()) {
            (false, _) => &[],
            (true, None) => &[".exr"],
            (true, Some(_)) => &[".left.exr", ".right.exr"],
        };
        frame(".png").is_some() || data.iter().any(|ext| frame(ext).is_some())
    }

    /// Writes frame `i`: its picture, and its data files beside it when given (`data` in the
    /// order of [`Plan::data_paths`]), all complete before any is renamed into place; all
    /// recorded in the folder's manifest.
    pub fn write_frame(&self, i: u32, image: &RgbImage, data: &[Vec<u8>]) -> anyhow::Result<()> {
        let png = self.frame_path(i);
        if data.is_empty() {
            shade::write_png(image, &png)?;
            return manifest::record(self.output_dir(), &[&png]);
        }
        let png_bytes = shade::encode_png(image, &png)?;
        let mut files: Vec<(PathBuf, &[u8])> = self
            .data_paths(i)
            .into_iter()
            .zip(data.iter().map(Vec::as_slice))
            .collect();
        files.push((png, &png_bytes));
        write_together(&files)?;
        let paths: Vec<&Path> = files.iter().map(|(p, _)| p.as_path()).collect();
        manifest::record(self.output_dir(), &paths)
    }
}

/// The scene one eye of a frame's stereo pair sees (the frame's observer moved to the eye).
fn eye_scene(scene: &Scene, eye: Eye) -> anyhow::Result<Scene> {
    Ok(scene
        .eye(eye)
        .ok_or_else(|| anyhow::anyhow!("{}: not a stereo pair", scene.name))??)
}

/// A frame's picture from its eyes' pictures: the one picture, or both eyes (left first) in
/// the pair's layout.
fn in_layout(pair: Option<Layout>, mut pictures: Vec<RgbImage>) -> RgbImage {
    match pair {
        Some(layout) => shade::stereo::compose(layout, &pictures[0], &pictures[1]),
        None => pictures.swap_remove(0),
    }
}

/// Whether `ffmpeg` runs.
fn have_ffmpeg() -> bool {
    Command::new("ffmpeg")
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The MP4 of a sequence.
const MP4: &str = "sequence.mp4";

/// ffmpeg's arguments to encode frames 0..`frames` of `dir` at `fps` into `out`: exactly
/// that many frames, from frame 0, whatever else lies in the folder.
fn ffmpeg_args(dir: &Path, frames: u32, fps: f64, out: &Path) -> Vec<std::ffi::OsString> {
    let mut args: Vec<std::ffi::OsString> = [
        "-y",
        "-loglevel",
        "error",
        "-framerate",
        &fps.to_string(),
        "-start_number",
        "0",
        "-i",
    ]
    .iter()
    .map(Into::into)
    .collect();
    args.push(dir.join("frame_%04d.png").into());
    // H.264 in yuv420p needs even sizes; pad by one pixel where needed.
    for a in [
        "-frames:v",
        &frames.to_string(),
        "-vf",
        "pad=ceil(iw/2)*2:ceil(ih/2)*2",
        "-pix_fmt",
        "yuv420p",
        "-f",
        "mp4",
    ] {
        args.push(a.into());
    }
    args.push(out.into());
    args
}

/// The ffmpeg encoding now, if any: kept where a signal handler can stop it before its
/// temporary output is removed (otherwise ffmpeg could create that file again after).
static ENCODER: Mutex<Option<Child>> = Mutex::new(None);

fn encoder() -> MutexGuard<'static, Option<Child>> {
    ENCODER.lock().unwrap_or_else(|e| e.into_inner())
}

/// Stops (kills and reaps) a running ffmpeg, for the signal handler in `main.rs`, which
/// holds the returned lock until the process exits: the encoding waits on it meanwhile
/// instead of reporting a failure of its own.
pub fn stop_encoder() -> MutexGuard<'static, Option<Child>> {
    let mut running = encoder();
    if let Some(child) = running.as_mut() {
        let _ = child.kill();
        let _ = child.wait();
    }
    running
}

/// Encodes the frames into `DIR/sequence.mp4` (through a temporary file and a rename).
fn encode_mp4(dir: &Path, frames: u32, fps: f64) -> anyhow::Result<PathBuf> {
    let out = dir.join(MP4);
    datafile::atomic::write_atomically_via_path(&out, |tmp| {
        *encoder() = Some(
            Command::new("ffmpeg")
                .args(ffmpeg_args(dir, frames, fps, tmp))
                .spawn()?,
        );
        // Polled, so that the lock is free for [`stop_encoder`] in between.
        let status = loop {
            let done = match encoder().as_mut() {
                Some(child) => child.try_wait()?,
                None => return Err(std::io::Error::other("ffmpeg went missing")),
            };
            if let Some(status) = done {
                encoder().take();
                break status;
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        };
        if status.success() {
            Ok(())
        } else {
            Err(std::io::Error::other(format!("ffmpeg failed ({status})")))
        }
    })
    .with_context(|| format!("cannot encode {}", out.display()))?;
    Ok(out)
}

pub fn run(args: SequenceArgs) -> anyhow::Result<()> {
    // Under mpirun/srun the frames are spread over the ranks.
    #[cfg(feature = "mpi")]
    if crate::cluster::launched_by_mpi() {
        return under_mpi::run(args);
    }
    let plan = Plan::new(&args.script)?;
    let n = plan.frames();
    let bar = start(&plan, &args)?;
    // The one place that writes: frames in order, each atomically.
    for i in 0..n {
        let frame = plan.frame(i).with_context(|| format!("frame {i}"))?;
        plan.write_frame(i, &frame.image, &frame.data)?;
        bar.inc(1);
    }
    finish(&plan, &args, &bar)
}

/// Before the first frame: creates the output folder, checks every frame's output paths
/// (writable, not an input of the run; errors located at the script's `output`), removes
/// what an earlier sequence wrote there that this run does not write again; the progress
/// bar over the frames.
pub fn start(plan: &Plan, args: &SequenceArgs) -> anyhow::Result<ProgressBar> {
    let dir = plan.output_dir();
    let bad_output = |e: String| settings_error("sequence", plan.script.error_at("output", e));
    datafile::folders::create_folder(dir)
        .map_err(|e| bad_output(format!("cannot create the folder {}: {e}", dir.display())))?;
    let outputs = plan.outputs();
    datafile::atomic::check_all_writable(&outputs)
        .map_err(|e| bad_output(format!("cannot write {e}")))?;
    if let Some(why) = plan.inputs.clash(&outputs) {
        return Err(bad_output(why));
    }
    let earlier = Manifest::read(dir);
    let stale = earlier.stale(|name| plan.writes(name), &plan.inputs);
    for path in &stale.remove {
        std::fs::remove_file(path)
            .with_context(|| format!("cannot remove {} of an earlier run", path.display()))?;
    }
    earlier.rewrite()?;
    let names = |paths: &[PathBuf]| -> String {
        let names: Vec<String> = paths
            .iter()
            .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .collect();
        names.join(", ")
    };
    if !stale.remove.is_empty() {
        eprintln!(
            "removed {} file(s) of an earlier run from {}: {}",
            stale.remove.len(),
            dir.display(),
            names(&stale.remove)
        );
    }
    if !stale.changed.is_empty() {
        eprintln!(
            "note: left {} file(s) an earlier run wrote that changed since: {}",
            stale.changed.len(),
            names(&stale.changed)
        );
    }
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(u64::from(plan.frames()))
    };
    bar.set_style(
        ProgressStyle::with_template("{prefix} [{bar:40}] {pos}/{len} frames, ETA {eta}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix("sequence");
    Ok(bar)
}

/// After every frame is written: the summary line and the MP4.
pub fn finish(plan: &Plan, args: &SequenceArgs, bar: &ProgressBar) -> anyhow::Result<()> {
    let (n, dir) = (plan.frames(), plan.output_dir());
    bar.finish_and_clear();
    eprintln!(
        "wrote {n} frames {}/frame_0000.png … frame_{:04}.png",
        dir.display(),
        n - 1
    );
    if plan.script.mp4 && !args.no_mp4 {
        if have_ffmpeg() {
            let mp4 = encode_mp4(dir, n, plan.script.fps)?;
            manifest::record(dir, &[&mp4])?;
            eprintln!("wrote {}", mp4.display());
        } else {
            eprintln!(
                "note: ffmpeg is not on PATH, so no MP4 was made (the PNG frames are complete). \
                 Install it (Debian/Ubuntu: apt-get install ffmpeg; macOS: brew install ffmpeg) \
                 and run again, or: ffmpeg -framerate {} -i {}/frame_%04d.png -frames:v {n} -pix_fmt yuv420p sequence.mp4",
                plan.script.fps,
                dir.display()
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ffmpeg_encodes_exactly_this_runs_frames_from_zero() {
        let args = ffmpeg_args(Path::new("out"), 4, 24.0, Path::new("out/.tmp"));
        let args: Vec<String> = args
            .iter()
            .map(|a| a.to_string_lossy().into_owned())
            .collect();
        let after = |flag: &str| {
            let i = args.iter().position(|a| a == flag).expect(flag);
            args[i + 1].clone()
        };
        assert_eq!(after("-frames:v"), "4");
        assert_eq!(after("-start_number"), "0");
        assert_eq!(after("-framerate"), "24");
        assert_eq!(after("-i"), "out/frame_%04d.png");
        // Input options before the input, output options after it, the output last.
        let input = args.iter().position(|a| a == "-i").unwrap();
        assert!(args.iter().position(|a| a == "-start_number").unwrap() < input);
        assert!(args.iter().position(|a| a == "-frames:v").unwrap() > input);
        assert_eq!(args.last().unwrap(), "out/.tmp");
    }
}

/// `godel sequence` under MPI: frames as jobs of the generic queue
/// (`crate::cluster::run_jobs`), each traced and shaded whole on one rank and sent to rank
/// 0 as raw RGB followed by the data file's bytes (with `keep_data`), written by rank 0 as
/// they arrive, exactly as one process writes them; the MP4 at the end.
#[cfg(feature = "mpi")]
mod under_mpi {
    use super::*;
    use crate::cluster::{abort, run_jobs, start as start_mpi};
    use mpi::topology::Communicator;
    use render::part::fingerprint_of;

    pub fn run(args: SequenceArgs) -> anyhow::Result<()> {
        let universe = start_mpi()?;
        let world = universe.world();
        let rank0 = world.rank() == 0;
        let set_up = || -> anyhow::Result<_> {
            let text = scene::input::read_text(&args.script, scene::input::MAX_TEXT_BYTES)
                .with_context(|| format!("cannot read {}", args.script.display()))?;
            Ok((Plan::new(&args.script)?, fingerprint_of(&[&text])))
        };
        let (plan, key) = set_up().unwrap_or_else(|e| abort(&world, &e));
        let bar = if rank0 {
            start(&plan, &args).unwrap_or_else(|e| abort(&world, &e))
        } else {
            ProgressBar::hidden()
        };
        let work = |job: usize| -> anyhow::Result<Vec<u8>> {
            let frame = plan
                .frame(job as u32)
                .with_context(|| format!("frame {job}"))?;
            let mut bytes = frame.image.width().to_le_bytes().to_vec();
            bytes.extend_from_slice(&frame.image.height().to_le_bytes());
            bytes.extend_from_slice(frame.image.as_raw());
            for data in &frame.data {
                bytes.extend_from_slice(&(data.len() as u64).to_le_bytes());
                bytes.extend_from_slice(data);
            }
            Ok(bytes)
        };
        let mut failure = None;
        let mut done = |job: usize, bytes: Vec<u8>| {
            let written = match unpack(&bytes, plan.data_paths(job as u32).len()) {
                Some((image, data)) => plan.write_frame(job as u32, &image, &data),
                None => Err(anyhow::anyhow!("frame {job} arrived damaged")),
            };
            match written {
                Ok(()) => bar.inc(1),
                Err(e) => failure = Some(e),
            }
        };
        run_jobs(&world, plan.frames() as usize, &key, &work, &mut done);
        if let Some(e) = failure {
            abort(&world, &e);
        }
        if rank0 {
            finish(&plan, &args, &bar).unwrap_or_else(|e| abort(&world, &e));
        }
        Ok(())
    }

    /// A frame as `work` sends it: width and height (u32), the RGB bytes, then each of the
    /// `files` data files as its length (u64) and bytes; `None` unless exactly that.
    fn unpack(bytes: &[u8], files: usize) -> Option<(RgbImage, Vec<Vec<u8>>)> {
        let u32_at = |at: usize| Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?));
        let (w, h) = (u32_at(0)?, u32_at(4)?);
        let end = (w as usize)
            .checked_mul(h as usize)?
            .checked_mul(3)?
            .checked_add(8)?;
        let image = RgbImage::from_raw(w, h, bytes.get(8..end)?.to_vec())?;
        let mut at = end;
        let mut data = Vec::with_capacity(files);
        for _ in 0..files {
            let len = u64::from_le_bytes(bytes.get(at..at + 8)?.try_into().ok()?);
            let start = at + 8;
            let stop = start.checked_add(usize::try_from(len).ok()?)?;
            data.push(bytes.get(start..stop)?.to_vec());
            at = stop;
        }
        (at == bytes.len()).then_some((image, data))
    }
}
