//! Explore mode (`godel explore`, docs/guide/src/explore.md): the observer's event (t, x, y, z) changes
//! and the server re-traces the scene from there, progressively. The viewer does not trace: a
//! [`FrameSource`] (in `godel`, the exact tracer on the scene with its observer moved) makes
//! each frame; this module decides which frames are made and which are kept.
//!
//! - A change of event ([`Explorer::request`]) starts a new *generation*: first a coarse frame
//!   ([`Level::Coarse`], same camera, fewer pixels), then the full-resolution one
//!   ([`Level::Full`]). A flying page that finds the server faster than its own GPU asks for
//!   a [`View`] instead ([`Explorer::request_view`]): one frame of exactly that camera.
//! - Each frame says how long it took: the server's rays a millisecond, which the page weighs
//!   against its own kernel's to choose who traces ([`Explorer::rays_per_ms`]).
//! - The newest request wins: the work of an older generation is cancelled (its cancel flag is
//!   set; the source stops between tiles) and a frame of an older generation is never kept
//!   once a newer request has come, so it never replaces a newer one.
//! - One worker thread traces, one frame at a time (the source may use all cores for it);
//!   requests only leave the newest event for it, so any number of tabs or requests cost
//!   one pending slot.
//! - Two frames are served: the newest and the one it replaced, whose channels a page that
//!   has just seen it may still be fetching (while playing, the next event is sent as soon as
//!   a frame is seen); any older frame is gone (410). So at most three frames are in memory
//!   (those two and the one being traced), and a fourth while a viewer state prepared for an
//!   older one answers a request ([`crate::explore_routes`]): [`FRAMES_IN_MEMORY`].

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};

use datafile::{DataFile, PixelRecord};
use render::map::{LightRay, Map};
use serde::{Deserialize, Serialize};
use spacetime::message::short;

use crate::view::{Velocity, View};

/// An event of the observer: coordinate time and pseudo-Cartesian position (the scene file's
/// `observer.time` and `observer.position = { x, y, z }`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObserverEvent {
    pub t: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl From<spacetime::Event> for ObserverEvent {
    fn from(e: spacetime::Event) -> ObserverEvent {
        ObserverEvent {
            t: e.t,
            x: e.x,
            y: e.y,
            z: e.z,
        }
    }
}

impl ObserverEvent {
    /// The event itself.
    pub fn event(&self) -> spacetime::Event {
        spacetime::Event::new(self.t, self.x, self.y, self.z)
    }

    /// The first of t, x, y, z that is not a finite number within ±`bound`: its index and why
    /// (`1e7 is beyond ±1e6, …`).
    pub fn out_of_bounds(&self, bound: f64) -> Option<(usize, String)> {
        [self.t, self.x, self.y, self.z]
            .iter()
            .enumerate()
            .find_map(|(i, &v)| {
                if !v.is_finite() {
                    Some((i, format!("{v} is not a finite number")))
                } else if v.abs() > bound {
                    Some((
                        i,
                        format!(
                            "{} is beyond ±{bound:e}, the scene's bound on coordinates",
                            short(v)
                        ),
                    ))
                } else {
                    None
                }
            })
    }

    /// The first field that is not a finite number within ±`bound`, as `event.FIELD: why`
    /// (the fields of `/api/explore/event`), or `None`.
    pub fn refusal(&self, bound: f64) -> Option<String> {
        self.refusal_as(bound, "event", EVENT_FIELDS)
    }

    /// [`ObserverEvent::refusal`] naming the numbers as the request wrote them:
    /// `REQUEST.FIELD: why` (`view.position.x: …`).
    pub fn refusal_as(&self, bound: f64, request: &str, fields: [&str; 4]) -> Option<String> {
        self.out_of_bounds(bound)
            .map(|(i, why)| format!("{request}.{}: {why}", fields[i]))
    }
}

/// How a request names an event's t, x, y, z: as an event (`/api/explore/event`, the map's
/// query) …
pub const EVENT_FIELDS: [&str; 4] = ["t", "x", "y", "z"];
/// … or as a view's time and position ([`View`], `/api/explore/move`).
pub const VIEW_FIELDS: [&str; 4] = ["time", "position.x", "position.y", "position.z"];

impl ObserverEvent {
    /// The event of `view`'s observer.
    pub fn of_view(view: &View) -> ObserverEvent {
        let p = view.position;
        ObserverEvent {
            t: view.time,
            x: p.x,
            y: p.y,
            z: p.z,
        }
    }
}

/// The most frames of the scene's full size in memory at once (see the module documentation):
/// what a command sizes explore's memory by.
pub const FRAMES_IN_MEMORY: u64 = 4;

/// How finely a frame is traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    /// The same camera with fewer pixels (fast, first).
    Coarse,
    /// The scene's own size and samples: what `godel render` writes.
    Full,
}

/// What makes the frames: traces the scene seen from an event.
pub trait FrameSource: Send + Sync + 'static {
    /// The scene's own observer event (where exploring starts).
    fn start(&self) -> ObserverEvent;
    /// The largest |coordinate| an event may have.
    fn bound(&self) -> f64;
    /// The frame seen from `event` at `level`; `Ok(None)` when `cancel` was set before it was
    /// done (the source checks it between tiles); `Err` says why it cannot be traced.
    fn frame(
        &self,
        event: ObserverEvent,
        level: Level,
        cancel: &AtomicBool,
    ) -> Result<Option<DataFile>, String>;
    /// The frame of `view` (its observer and camera, size and samples as given); `Ok(None)`
    /// once `cancel` is set, as for [`FrameSource::frame`].
    fn view_frame(&self, view: &View, cancel: &AtomicBool) -> Result<Option<DataFile>, String>;
    /// Why `view`'s frame cannot be traced (naming the field: `view.camera: …`), checked
    /// before it is asked for: a view that makes no valid scene, or more rays than a frame of
    /// the scene's own camera (what explore's memory is sized by).
    fn view_refusal(&self, view: &View) -> Option<String>;
    /// What the explore map shows for an observer at `event`: its horizon, the balls at its
    /// time and their tracks ([`render::map`]); `Err` says why it cannot be made.
    fn map(&self, event: ObserverEvent) -> Result<Map, String>;
    /// The light ray of the pixel whose record is `record`, in a frame seen from `event`.
    fn light_ray(&self, event: ObserverEvent, record: &PixelRecord) -> LightRay;
    /// A sequence-script keyframe (TOML) at `frame` that puts the scene's observer (its
    /// velocity and axes, the camera's fields of view) at `event`.
    fn keyframe(&self, event: ObserverEvent, frame: u32) -> Result<String, String>;
    /// A sequence-script keyframe (TOML) at `frame` with the observer and camera fields of
    /// `view` (a flight's: its velocity and axes, not the scene's); `Err` says why, naming
    /// the field.
    fn view_keyframe(&self, view: &View, frame: u32) -> Result<String, String>;
    /// What the GPU kernel reads to trace the full frame seen from `event` (the page's own
    /// tracer, [`crate::kernel_routes`]); `Err` says why it cannot be made.
    fn kernel_input(&self, event: ObserverEvent) -> Result<gpu::KernelInput, String>;
    /// What the GPU kernel reads to trace `view` (the scene with the view's observer and
    /// camera fields); `Err` says why, naming the field.
    fn view_input(&self, view: &View) -> Result<gpu::KernelInput, String>;
    /// Holds the page's GPU records of `samples` (cells of `view`'s sample grid, traced by the
    /// page's `renderer`) to the CPU exact tracer, as `godel render --gpu` holds its own
    /// (`gpu::check`); `Err` says why the request is wrong, naming the field.
    fn check(
        &self,
        view: &View,
        samples: &[CheckedSample],
        renderer: &str,
    ) -> Result<Verdict, String>;
    /// Where an observer at `event` moving with `velocity` is after `tau` of its proper time
    /// when it falls freely, and its velocity there (`spacetime::worldline::fall`); `Err`
    /// says why not, naming the field (`velocity: …`, `tau: …`; the route adds its own name).
    fn fall(
        &self,
        event: ObserverEvent,
        velocity: Velocity,
        tau: f64,
    ) -> Result<(ObserverEvent, Velocity), String>;
}

/// A frame made for a request.
#[derive(Debug)]
pub struct Frame {
    pub generation: u64,
    pub level: Level,
    pub event: ObserverEvent,
    /// Shared with the viewer states that answer for this frame (never copied).
    pub data: Arc<DataFile>,
    /// The wall-clock time its trace took, in ms.
    pub trace_ms: f64,
}

/// What a request asks to be traced.
enum Sought {
    /// The scene's observer moved to `event`: its coarse frame, then (if `refine`) its full one.
    Event { event: ObserverEvent, refine: bool },
    /// One frame of this view ([`FrameSource::view_frame`]), kept as [`Level::Full`].
    View(Box<View>),
}

/// What the requests and the worker share.
#[derive(Default)]
struct Slots {
    /// The newest request's generation (0: none yet).
    generation: u64,
    /// The request the worker has not started yet, and its generation.
    pending: Option<(u64, Sought)>,
    /// The cancel flag of the work under way.
    cancel: Option<Arc<AtomicBool>>,
    /// The newest frame kept.
    latest: Option<Arc<Frame>>,
    /// The frame `latest` replaced (the coarse frame of the same generation, or the last frame
    /// of an older one): a page that saw it may still be fetching its channels.
    previous: Option<Arc<Frame>>,
    /// Why the newest generation could not be traced.
    error: Option<String>,
    /// Rays a millisecond of the last frame traced to its end (none before the first).
    rays_per_ms: Option<f64>,
    /// Set when the [`Explorer`] is dropped: the worker ends.
    closed: bool,
}

struct Shared {
    slots: Mutex<Slots>,
    /// Wakes the worker (a request, or the end).
    wake: Condvar,
    /// Wakes those waiting for a frame (a frame kept, or an error).
    kept: Condvar,
    source: Box<dyn FrameSource>,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Slots> {
        self.slots.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The explore mode's state: the frame source, the newest request, the newest frame.
pub struct Explorer {
    shared: Arc<Shared>,
}

impl Explorer {
    /// Starts the worker thread for `source` (nothing is traced before a request).
    pub fn new(source: impl FrameSource) -> std::io::Result<Explorer> {
        let shared = Arc::new(Shared {
            slots: Mutex::new(Slots::default()),
            wake: Condvar::new(),
            kept: Condvar::new(),
            source: Box::new(source),
        });
        let worker = shared.clone();
        std::thread::Builder::new()
            .name("explore".into())
            .spawn(move || work(&worker))?;
        Ok(Explorer { shared })
    }

    /// The scene's own observer event.
    pub fn start(&self) -> ObserverEvent {
        self.shared.source.start()
    }

    /// The largest |coordinate| of an event.
    pub fn bound(&self) -> f64 {
        self.shared.source.bound()
    }

    /// Asks for the frames seen from `event`: a new generation (returned), the older one's
    /// work cancelled. A bad event is refused (the message names the field) and changes
    /// nothing.
    pub fn request(&self, event: ObserverEvent) -> Result<u64, String> {
        self.request_levels(event, true)
    }

    /// [`Explorer::request`], with the full frame only if `refine` (a page that plays time
    /// asks for coarse frames only: the full one would be cancelled anyway, and tracing it
    /// would take the cores from the next coarse frame).
    pub fn request_levels(&self, event: ObserverEvent, refine: bool) -> Result<u64, String> {
        if let Some(why) = event.refusal(self.bound()) {
            return Err(why);
        }
        Ok(self.ask(Sought::Event { event, refine }))
    }

    /// Asks for one frame of `view` (a flying page's observer and camera, at the size and
    /// samples it gives): a new generation, as [`Explorer::request`]. A bad view is refused
    /// (the message names the field) and changes nothing.
    pub fn request_view(&self, view: View) -> Result<u64, String> {
        let event = ObserverEvent::of_view(&view);
        if let Some(why) = event
            .refusal_as(self.bound(), "view", VIEW_FIELDS)
            .or_else(|| view.refusal())
            .or_else(|| self.shared.source.view_refusal(&view))
        {
            return Err(why);
        }
        Ok(self.ask(Sought::View(Box::new(view))))
    }

    /// Makes `sought` the newest request: cancels the older one's work, wakes the worker.
    fn ask(&self, sought: Sought) -> u64 {
        let mut slots = self.shared.lock();
        slots.generation += 1;
        let generation = slots.generation;
        if let Some(cancel) = slots.cancel.take() {
            cancel.store(true, Ordering::SeqCst);
        }
        slots.pending = Some((generation, sought));
        slots.error = None;
        drop(slots);
        self.shared.wake.notify_all();
        generation
    }

    /// The CPU tracer's speed here: rays a millisecond of the last frame traced to its end.
    pub fn rays_per_ms(&self) -> Option<f64> {
        self.shared.lock().rays_per_ms
    }

    /// Waits until the newest generation has a frame (its coarse one first) and returns it,
    /// or says why it could not be traced. For the start, before the page asks: the server
    /// opens on the explorer's own first frame instead of tracing it twice.
    pub fn first_frame(&self) -> Result<Arc<Frame>, String> {
        let mut slots = self.shared.lock();
        loop {
            if let Some(why) = &slots.error {
                return Err(why.clone());
            }
            if let Some(frame) = slots
                .latest
                .as_ref()
                .filter(|f| f.generation == slots.generation)
            {
                return Ok(frame.clone());
            }
            if slots.generation == 0 {
                return Err("no event was asked for".into());
            }
            slots = self
                .shared
                .kept
                .wait(slots)
                .unwrap_or_else(|e| e.into_inner());
        }
    }

    /// The newest request's generation (0 before any).
    pub fn generation(&self) -> u64 {
        self.shared.lock().generation
    }

    /// The newest frame kept: of the newest generation, coarse or full, or of an older one
    /// until the newest has its first frame.
    pub fn latest(&self) -> Option<Arc<Frame>> {
        self.shared.lock().latest.clone()
    }

    /// The frame of `generation` at `level`, while it is the newest frame or the one the
    /// newest replaced.
    pub fn frame(&self, generation: u64, level: Level) -> Option<Arc<Frame>> {
        let slots = self.shared.lock();
        // Bound to a name so that the borrow of the guard ends before the guard is dropped.
        #[allow(clippy::let_and_return)]
        let found = [&slots.latest, &slots.previous]
            .into_iter()
            .flatten()
            .find(|f| f.generation == generation && f.level == level)
            .cloned();
        found
    }

    /// Why the newest generation could not be traced, if it could not.
    pub fn error(&self) -> Option<String> {
        self.shared.lock().error.clone()
    }

    /// The frame source (for the map, light rays and keyframes).
    pub fn source(&self) -> &dyn FrameSource {
        self.shared.source.as_ref()
    }
}

impl Drop for Explorer {
    fn drop(&mut self) {
        let mut slots = self.shared.lock();
        slots.closed = true;
        if let Some(cancel) = slots.cancel.take() {
            cancel.store(true, Ordering::SeqCst);
        }
        drop(slots);
        self.shared.wake.notify_all();
    }
}

/// The worker: takes the newest pending request and traces its frames (an event's coarse
/// then, if asked, its full frame; a view's one frame), keeping each only while its
/// generation is still the newest.
fn work(shared: &Shared) {
    loop {
        let (generation, sought, cancel) = {
            let mut slots = shared.lock();
            loop {
                if slots.closed {
                    return;
                }
                if let Some((generation, sought)) = slots.pending.take() {
                    let cancel = Arc::new(AtomicBool::new(false));
                    slots.cancel = Some(cancel.clone());
                    break (generation, sought, cancel);
                }
                slots = shared.wake.wait(slots).unwrap_or_else(|e| e.into_inner());
            }
        };
        let (event, levels): (ObserverEvent, &[Level]) = match &sought {
            Sought::Event {
                event,
                refine: true,
            } => (*event, &[Level::Coarse, Level::Full]),
            Sought::Event {
                event,
                refine: false,
            } => (*event, &[Level::Coarse]),
            Sought::View(view) => (ObserverEvent::of_view(view), &[Level::Full]),
        };
        for &level in levels {
            if cancel.load(Ordering::SeqCst) {
                break;
            }
            let started = std::time::Instant::now();
            let traced = match &sought {
                Sought::Event { .. } => shared.source.frame(event, level, &cancel),
                Sought::View(view) => shared.source.view_frame(view, &cancel),
            };
            let trace_ms = started.elapsed().as_secs_f64() * 1e3;
            match traced {
                Ok(Some(data)) => {
                    let mut slots = shared.lock();
                    // Measured whether or not the frame is kept: it was traced to its end.
                    slots.rays_per_ms = Some(data.records.len() as f64 / trace_ms.max(1e-3));
                    if slots.generation != generation || cancel.load(Ordering::SeqCst) {
                        break;
                    }
                    let frame = Arc::new(Frame {
                        generation,
                        level,
                        event,
                        data: Arc::new(data),
                        trace_ms,
                    });
                    slots.previous = slots.latest.replace(frame);
                    shared.kept.notify_all();
                }
                Ok(None) => break,
                Err(why) => {
                    let mut slots = shared.lock();
                    if slots.generation == generation {
                        slots.error = Some(why);
                        shared.kept.notify_all();
                    }
                    break;
                }
            }
        }
    }
}

/// What the CPU exact tracer says of the page's samples.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// They agree within `gpu::check`'s tolerance.
    Agree,
    /// They do not: why (how many differ, and the first).
    Disagree(String),
    /// The CPU tracer cannot trace them (this scene has no exact tracer): why.
    Unchecked(String),
}

/// One sample the page traced: its cell of the view's sample grid and the kernel's record
/// (status and object; the check compares nothing else).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckedSample {
    pub x: u32,
    pub y: u32,
    pub record: PixelRecord,
}
