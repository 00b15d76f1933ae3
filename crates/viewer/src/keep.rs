//! Keeping what one flies in explore mode (docs/guide/src/explore.md, *Render exactly* and *Record*):
//! the view on the page ([`View`], the scene file's observer and camera fields, as the page's
//! `viewer.explore.view()` gives it) rendered by the CPU exact tracer at a chosen size and
//! samples ([`Keeper::render`]: the PNG and data file `godel render` writes for the scene with
//! those fields), and a recorded flight ([`Recording`]: views with their wall-clock times)
//! turned into a sequence script with observer keyframes ([`Keeper::script`]) that
//! `godel sequence` renders offline.
//!
//! The viewer does not trace nor write scripts: a [`Keeper`] (in `godel`, over the scene's
//! text, as fly-through frames are made) does. This module holds the shapes of the requests,
//! their first checks (every number finite, the counts bounded) and the one exact render a
//! server runs at a time ([`ExactJob`]: its progress, its cancel flag, its files in memory).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;

use serde::{Deserialize, Serialize};
use spacetime::message::short;

use crate::view::View;

/// The most keyframes a recording holds (at the page's pace of at most four a second, ten
/// minutes of flight): the page stops recording there.
pub const MAX_KEYFRAMES: usize = 2400;

/// The longest recording, in seconds of wall-clock time.
pub const MAX_SECONDS: f64 = 3600.0;

/// The frame rate of a recorded flight's sequence: a keyframe taken `s` seconds after the
/// recording began is frame `round(s · RECORD_FPS)`.
pub const RECORD_FPS: f64 = 24.0;

/// One recorded view and when it was seen (seconds since the recording began).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordedView {
    pub seconds: f64,
    pub view: View,
}

/// A recorded flight: its views in the order seen.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Recording {
    pub keyframes: Vec<RecordedView>,
}

impl Recording {
    /// The frames of the keyframes at [`RECORD_FPS`], or why not
    /// (`recording.keyframes[i].FIELD: …`):
    /// at least one and at most [`MAX_KEYFRAMES`] keyframes, seconds from 0 to
    /// [`MAX_SECONDS`] on distinct, increasing frames, every view's numbers finite.
    pub fn frames(&self) -> Result<Vec<u32>, String> {
        let n = self.keyframes.len();
        if n == 0 || n > MAX_KEYFRAMES {
            return Err(format!(
                "recording.keyframes: a recording has 1 to {MAX_KEYFRAMES} keyframes, got {n}"
            ));
        }
        let mut frames: Vec<u32> = Vec::with_capacity(n);
        for (i, k) in self.keyframes.iter().enumerate() {
            if let Some(why) = k.view.refusal() {
                return Err(format!("recording.keyframes[{i}].{why}"));
            }
            if !(k.seconds.is_finite() && (0.0..=MAX_SECONDS).contains(&k.seconds)) {
                return Err(format!(
                    "recording.keyframes[{i}].seconds: must be from 0 to {MAX_SECONDS}, got {}",
                    short(k.seconds)
                ));
            }
            let frame = (k.seconds * RECORD_FPS).round() as u32;
            if let Some(&before) = frames.last() {
                if frame <= before {
                    return Err(format!(
                        "recording.keyframes[{i}].seconds: {} s is frame {frame}, not after \
                         keyframe {}'s frame {before} (at {RECORD_FPS} frames per second)",
                        short(k.seconds),
                        i - 1
                    ));
                }
            }
            frames.push(frame);
        }
        Ok(frames)
    }
}

/// A view rendered exactly: the two files `godel render` writes, in memory.
#[derive(Debug)]
pub struct Rendered {
    /// The scene's name: the files are `NAME.png` and `NAME.exr`.
    pub name: String,
    pub png: Vec<u8>,
    pub exr: Vec<u8>,
    /// The render's one-line summary (rays, hits, time), as `godel render` prints it.
    pub summary: String,
}

/// What makes the exact renders and the scripts: the scene, its exact tracer and the
/// sequence-script format.
pub trait Keeper: Send + Sync + 'static {
    /// The scene's name (the files are named after it).
    fn name(&self) -> String;
    /// The scene's own view (the observer and camera of the scene file).
    fn own_view(&self) -> View;
    /// Checks that `view` can be rendered exactly: the scene with its fields passes the usual
    /// checks and the render fits the memory budget. `Err` names the field (`view.FIELD`).
    fn check(&self, view: &View) -> Result<(), String>;
    /// Renders `view` with the exact tracer, telling `job` how far it got; `Ok(None)` once
    /// `job` is cancelled (checked between tiles).
    fn render(&self, view: &View, job: &ExactJob) -> Result<Option<Rendered>, String>;
    /// The sequence script (TOML) of `recording`, each keyframe at its frame of `frames`, read
    /// back by the sequence-script parser before it is given. `Err` names the field
    /// (`recording.keyframes[i].view.FIELD: …`, or `recording: …` for the whole).
    fn script(&self, recording: &Recording, frames: &[u32]) -> Result<String, String>;
}

/// Where an exact render stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum JobState {
    Rendering,
    Done,
    Failed,
    Cancelled,
}

/// One exact render: its number, progress, cancel flag, and in the end its files or why not.
#[derive(Debug)]
pub struct ExactJob {
    pub id: u64,
    pub view: View,
    /// Samples traced so far, and in all (0 until the tracer starts).
    pub done: AtomicU64,
    pub total: AtomicU64,
    pub cancel: AtomicBool,
    /// Set once the render has ended, whatever its outcome.
    pub finished: AtomicBool,
    pub outcome: Mutex<Option<Result<Rendered, String>>>,
    pub started: std::time::Instant,
    pub seconds: Mutex<Option<f64>>,
}

impl ExactJob {
    pub fn new(id: u64, view: View) -> ExactJob {
        ExactJob {
            id,
            view,
            done: AtomicU64::new(0),
            total: AtomicU64::new(0),
            cancel: AtomicBool::new(false),
            finished: AtomicBool::new(false),
            outcome: Mutex::new(None),
            started: std::time::Instant::now(),
            seconds: Mutex::new(None),
        }
    }

    /// Where the render stands: a finished job without an outcome was cancelled.
    pub fn state(&self) -> JobState {
        if !self.finished.load(Ordering::SeqCst) {
            return JobState::Rendering;
        }
        match &*self.outcome.lock().unwrap_or_else(|e| e.into_inner()) {
            Some(Ok(_)) => JobState::Done,
            Some(Err(_)) => JobState::Failed,
            None => JobState::Cancelled,
        }
    }

    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }

    /// Runs the render of this job's view by `keeper` and keeps the outcome.
    pub fn run(&self, keeper: &dyn Keeper) {
        let outcome = match keeper.render(&self.view, self) {
            Ok(Some(files)) => Some(Ok(files)),
            Ok(None) => None,
            Err(why) => Some(Err(why)),
        };
        *self.seconds.lock().unwrap_or_else(|e| e.into_inner()) =
            Some(self.started.elapsed().as_secs_f64());
        *self.outcome.lock().unwrap_or_else(|e| e.into_inner()) = outcome;
        self.finished.store(true, Ordering::SeqCst);
    }
}
