//! `godel sequence SCRIPT.toml`: image sequences with keyframed shader settings
//! ([`shade::script`]): numbered PNGs `frame_0000.png`, … in the script's output folder, and
//! `sequence.mp4` when `ffmpeg` is on PATH (a clear note, not an error, when it is not).
//!
//! [`Plan`] is built and checked completely before anything is written (the data file read,
//! every keyframe's settings validated), then each frame is an independent, pure job
//! [`Plan::frame`]`(i) -> image` (shade the data file, or trace the scene at that frame's
//! observer time and shade it); all writing happens in [`run`]'s loop, so frames can later be
//! spread over MPI ranks with one writer.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::Context;
use clap::Args;
use image::RgbImage;
use indicatif::{ProgressBar, ProgressStyle};
use render::datafile::DataFile;
use render::driver::{header, render, NoProgress};
use scene::Scene;
use shade::{FrameSource, Script, ShadeSettings, Shading, Timeline};

use crate::cmd_shade::settings_error;

#[derive(Args, Debug)]
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
    /// One data file for every frame.
    Data(DataFile),
    /// A scene traced per frame: its text, its path (for messages and image paths), and the
    /// observer-time range.
    Trace {
        text: String,
        path: PathBuf,
        observer_time: Option<[f64; 2]>,
    },
}

/// A checked sequence, ready to make frames.
pub struct Plan {
    script: Script,
    source: Source,
    timeline: Timeline,
}

impl Plan {
    /// Reads the script and its source and checks every keyframe's settings.
    pub fn new(path: &Path) -> anyhow::Result<Plan> {
        let script = Script::from_file(path).map_err(|e| settings_error("sequence", e))?;
        let (source, probe) = match &script.source {
            FrameSource::Data(p) => {
                let data = DataFile::read(p)?;
                (Source::Data(data.clone()), data)
            }
            FrameSource::Trace {
                scene,
                observer_time,
            } => {
                let s = Scene::from_file(scene)?;
                // A data file without pixels: the scene's objects and header, for defaults
                // and validation before anything is traced.
                let probe = DataFile {
                    header: header(&s),
                    width: 0,
                    height: 0,
                    records: Vec::new(),
                    lights: Vec::new(),
                };
                let source = Source::Trace {
                    text: s.source_text.clone(),
                    path: scene.clone(),
                    observer_time: *observer_time,
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
        Ok(Plan {
            script,
            source,
            timeline,
        })
    }

    /// Number of frames.
    pub fn frames(&self) -> u32 {
        self.script.frames
    }

    /// The picture of frame `i`: a pure function of the plan and `i`.
    pub fn frame(&self, i: u32) -> anyhow::Result<RgbImage> {
        let settings = self.timeline.settings_at(i);
        match &self.source {
            Source::Data(data) => Ok(Shading::new(data, &settings)?.image(data)),
            Source::Trace {
                text,
                path,
                observer_time,
            } => {
                let scene = scene_at(text, path, *observer_time, i, self.script.frames)?;
                let (data, _) = render(&scene, &NoProgress)?;
                Ok(Shading::new(&data, &settings)?.image(&data))
            }
        }
    }

    /// Where frame `i` is written.
    pub fn frame_path(&self, i: u32) -> PathBuf {
        self.script.output.join(format!("frame_{i:04}.png"))
    }
}

/// The scene with the observer's time of frame `i` of `n` (linear from the first value of
/// `range` to the second), or unchanged without a range.
fn scene_at(
    text: &str,
    path: &Path,
    range: Option<[f64; 2]>,
    i: u32,
    n: u32,
) -> anyhow::Result<Scene> {
    let name = path.display().to_string();
    let Some([t0, t1]) = range else {
        return Ok(Scene::from_str(text, &name)?);
    };
    let s = if n > 1 {
        f64::from(i) / f64::from(n - 1)
    } else {
        0.0
    };
    let mut table: toml::Table = text.parse().with_context(|| format!("{name}: not TOML"))?;
    let observer = table
        .entry("observer")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    if let toml::Value::Table(o) = observer {
        o.insert("time".into(), toml::Value::Float(t0 + s * (t1 - t0)));
    }
    Ok(Scene::from_str(&toml::to_string(&table)?, &name)?)
}

/// Whether `ffmpeg` runs.
fn have_ffmpeg() -> bool {
    Command::new("ffmpeg")
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Encodes the frames into `DIR/sequence.mp4` (through a temporary name and a rename).
fn encode_mp4(dir: &Path, fps: f64) -> anyhow::Result<PathBuf> {
    let out = dir.join("sequence.mp4");
    let tmp = dir.join(".sequence.partial.mp4");
    let status = Command::new("ffmpeg")
        .args([
            "-y",
            "-loglevel",
            "error",
            "-framerate",
            &fps.to_string(),
            "-i",
        ])
        .arg(dir.join("frame_%04d.png"))
        // H.264 in yuv420p needs even sizes; pad by one pixel where needed.
        .args([
            "-vf",
            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
            "-pix_fmt",
            "yuv420p",
            "-f",
            "mp4",
        ])
        .arg(&tmp)
        .status()
        .context("cannot run ffmpeg")?;
    if !status.success() {
        let _ = std::fs::remove_file(&tmp);
        anyhow::bail!("ffmpeg failed ({status}) encoding {}", out.display());
    }
    std::fs::rename(&tmp, &out).with_context(|| format!("cannot write {}", out.display()))?;
    Ok(out)
}

pub fn run(args: SequenceArgs) -> anyhow::Result<()> {
    let plan = Plan::new(&args.script)?;
    let n = plan.frames();
    let dir = plan.script.output.clone();
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(u64::from(n))
    };
    bar.set_style(
        ProgressStyle::with_template("{prefix} [{bar:40}] {pos}/{len} frames, ETA {eta}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix("sequence");
    // The one place that writes: frames in order, each atomically.
    for i in 0..n {
        let image = plan.frame(i).with_context(|| format!("frame {i}"))?;
        shade::write_png(&image, &plan.frame_path(i))?;
        bar.inc(1);
    }
    bar.finish_and_clear();
    eprintln!(
        "wrote {n} frames {}/frame_0000.png … frame_{:04}.png",
        dir.display(),
        n - 1
    );
    if plan.script.mp4 && !args.no_mp4 {
        if have_ffmpeg() {
            let mp4 = encode_mp4(&dir, plan.script.fps)?;
            eprintln!("wrote {}", mp4.display());
        } else {
            eprintln!(
                "note: ffmpeg is not on PATH, so no MP4 was made (the PNG frames are complete). \
                 Install it (Debian/Ubuntu: apt-get install ffmpeg; macOS: brew install ffmpeg) \
                 and run again, or: ffmpeg -framerate {} -i {}/frame_%04d.png -pix_fmt yuv420p sequence.mp4",
                plan.script.fps,
                dir.display()
            );
        }
    }
    Ok(())
}
