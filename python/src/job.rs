//! `RenderJob`: one render of a scene on a thread of its own, so that the Python thread that
//! started it stays free to show progress and to notice Ctrl-C (or a notebook's interrupt).
//!
//! Everything the command line checks before tracing is checked here, before the thread
//! starts, with the same messages: the scene (a file, text or the built-in one) with its
//! overrides (`scene::overrides`), the thread count (`render::threads`), the textures and
//! the memory the data file will need (`datafile::memory`).
//! The trace itself is `render::driver::render` on the checked pool: the very code path of
//! `godel render`, so the records are the same, bit for bit. The render's progress consumer
//! counts the pixels done and reports a cancellation, which the driver honours between
//! tiles: a cancelled render stops within one tile per thread.
//!
//! A stereo scene (`[camera] stereo`) traces its two eyes one after the other, each eye's
//! scene made by `Scene::eye` as `godel render` makes it, so each eye's records are those of
//! that eye's data file (`NAME.left.exr`, `NAME.right.exr`).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use render::driver::{plan_pixels, render, Progress};
use render::plan::Plan;
use render::threads::{thread_pool, ThreadsError};
use scene::overrides::{load, LoadError, Overrides, SceneSource, Setting};

use crate::data::Data;
use crate::errors::{argument_error, file_argument, io_error, value_error};

/// What the render thread hands back: the traced image and its summary line (one per eye, left
/// first, for a stereo pair), or why not.
type Outcome = Result<Vec<(datafile::DataFile, String)>, String>;

/// Shared between the Python object and the render thread.
#[derive(Default)]
struct Shared {
    done: AtomicU64,
    cancel: AtomicBool,
    outcome: Mutex<Option<Outcome>>,
    finished: Condvar,
}

impl Shared {
    fn outcome(&self) -> MutexGuard<'_, Option<Outcome>> {
        self.outcome.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The driver's progress consumer: pixels done, and whether to stop.
struct Counter(Arc<Shared>);

impl Progress for Counter {
    fn advance(&self, pixels: u64) {
        self.0.done.fetch_add(pixels, Ordering::Relaxed);
    }
    fn cancelled(&self) -> bool {
        self.0.cancel.load(Ordering::Relaxed)
    }
}

/// A render under way (use `godel.render`, which drives it). Checks the scene and the
/// settings when made, then traces on a thread of its own.
#[pyclass(module = "godel._godel", frozen)]
pub struct RenderJob {
    shared: Arc<Shared>,
    name: String,
    total: u64,
    /// The scene as rendered, overrides included (TOML text).
    scene_text: String,
    /// A stereo pair's separation (units of a), layout name and convergence; `None` for one
    /// picture.
    stereo: Option<(f64, &'static str, Option<f64>)>,
}

/// A scene refused with its overrides, as `godel render` says it, the overrides named by
/// their keyword arguments (`width: camera.width: …`): a `ValueError`, or for a scene file
/// (`path`) that is missing or out of reach the `OSError` of its kind (`FileNotFoundError`).
fn load_error(e: LoadError, path: Option<&Path>) -> PyErr {
    let message = e.describe(Setting::keyword);
    // A file whose metadata cannot be read could not be read either: that was the failure.
    match path.map(std::fs::metadata) {
        Some(Err(missing)) if matches!(e, LoadError::Scene(_)) => io_error(&missing, message),
        _ => value_error(message),
    }
}

#[pymethods]
impl RenderJob {
    /// Checks everything and starts tracing. `scene_path` or `scene_text` (neither: the
    /// built-in reference scene); the other arguments as those of `godel.render`.
    #[new]
    #[pyo3(signature = (scene_path=None, scene_text=None, width=None, height=None, samples=None, method=None, max_past=None, threads=None, metric=None, a=None, m2=None, omega=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        scene_path: Option<PathBuf>,
        scene_text: Option<String>,
        width: Option<i64>,
        height: Option<i64>,
        samples: Option<i64>,
        method: Option<String>,
        max_past: Option<f64>,
        threads: Option<i64>,
        metric: Option<String>,
        a: Option<f64>,
        m2: Option<f64>,
        omega: Option<f64>,
    ) -> PyResult<RenderJob> {
        let pool = match threads {
            Some(n) if n < 1 => Err(ThreadsError::Count("must be at least 1".into())),
            _ => thread_pool(threads.map(|n| n as usize)),
        }
        .map_err(|e| match e {
            ThreadsError::Count(message) => argument_error("threads", message),
            e => PyRuntimeError::new_err(e.to_string()),
        })?;
        if let Some(path) = &scene_path {
            file_argument("scene", path, "a scene file")?;
        }
        let (source, file) = match (&scene_path, &scene_text) {
            (Some(path), _) => (SceneSource::File(path), path.display().to_string()),
            (None, Some(text)) => {
                let name = "<scene text>";
                (SceneSource::Text { text, name }, name.to_string())
            }
            (None, None) => (SceneSource::Builtin, "built-in scene".to_string()),
        };
        let overrides = Overrides {
            width,
            height,
            max_past,
            method,
            samples,
            name: None,
            metric,
            a,
            m2,
            omega,
        };
        let scene = load(source, &overrides).map_err(|e| load_error(e, scene_path.as_deref()))?;
        // Textures load before tracing, as on the command line: bad input fails fast.
        shade::textures_for_scene(&scene).map_err(value_error)?;
        // Sized against memory before any work, as on the command line; a bad
        // GODEL_MEMORY_BUDGET is named as such, not as the scene's camera.
        datafile::memory::budget().map_err(value_error)?;
        let pixels = plan_pixels(&scene, &Plan::All);
        let what = "a data file of this width × height × samples";
        datafile::memory::check_writing(what, pixels, scene.lights.len())
            .map_err(|e| value_error(format!("{file}: camera: {e}")))?;
        let pair = scene.stereo.filter(scene::Stereo::is_pair);
        let stereo = pair.map(|s| (s.separation, s.layout.name(), s.convergence));
        let (name, scene_text) = (scene.name.clone(), scene.source_text.clone());
        // One scene per picture: the scene itself, or each eye's (left first), as `godel
        // render` traces them.
        let pictures = match pair {
            None => vec![scene],
            Some(_) => scene::Eye::BOTH
                .into_iter()
                .map(|eye| match scene.eye(eye) {
                    Some(seen) => seen.map_err(value_error),
                    None => Err(PyRuntimeError::new_err("internal error: not a stereo pair")),
                })
                .collect::<PyResult<Vec<_>>>()?,
        };
        let total = pictures
            .iter()
            .map(|seen| plan_pixels(seen, &Plan::All))
            .sum();
        let shared = Arc::new(Shared::default());
        let worker = Arc::clone(&shared);
        std::thread::Builder::new()
            .name(format!("godel render {name}"))
            .spawn(move || {
                let counter = Counter(Arc::clone(&worker));
                let traced = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    pool.install(|| {
                        let mut done = Vec::with_capacity(pictures.len());
                        for seen in &pictures {
                            // A cancelled pair does not start its second eye.
                            if counter.cancelled() {
                                break;
                            }
                            let (data, stats) = render(seen, &counter)?;
                            done.push((data, stats.summary()));
                        }
                        Ok::<_, render::driver::RenderError>(done)
                    })
                }));
                let outcome = match traced {
                    Ok(Ok(done)) => Ok(done),
                    Ok(Err(e)) => Err(e.to_string()),
                    Err(_) => Err("internal error: the render stopped unexpectedly".into()),
                };
                *worker.outcome() = Some(outcome);
                worker.finished.notify_all();
            })
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start the render: {e}")))?;
        Ok(RenderJob {
            shared,
            name,
            total,
            scene_text,
            stereo,
        })
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// The scene as rendered, overrides included (TOML text): for a stereo pair, the pair's
    /// (each eye's image holds its eye's scene).
    #[getter]
    fn scene(&self) -> &str {
        &self.scene_text
    }

    /// `(separation, layout, convergence)` of a stereo pair (lengths in units of a,
    /// convergence None for parallel eyes); None for a scene of one picture.
    #[getter]
    fn stereo(&self) -> Option<(f64, &'static str, Option<f64>)> {
        self.stereo
    }

    /// Rays to trace in all (pixels × samples; both eyes' for a stereo pair).
    #[getter]
    fn total(&self) -> u64 {
        self.total
    }

    /// Rays traced so far.
    #[getter]
    fn done(&self) -> u64 {
        self.shared.done.load(Ordering::Relaxed)
    }

    /// Waits up to `timeout` seconds (None: until the end) without holding the GIL; True
    /// once the render has ended. Raises KeyboardInterrupt (or what a signal handler
    /// raises) when a signal arrived meanwhile.
    #[pyo3(signature = (timeout=None))]
    fn wait(&self, py: Python<'_>, timeout: Option<f64>) -> PyResult<bool> {
        let shared = Arc::clone(&self.shared);
        let ended = py.detach(move || {
            let guard = shared.outcome();
            match timeout {
                Some(t) => {
                    let t = Duration::from_secs_f64(t.clamp(0.0, 3600.0));
                    let (guard, _) = shared
                        .finished
                        .wait_timeout_while(guard, t, |o| o.is_none())
                        .unwrap_or_else(|e| e.into_inner());
                    guard.is_some()
                }
                None => shared
                    .finished
                    .wait_while(guard, |o| o.is_none())
                    .unwrap_or_else(|e| e.into_inner())
                    .is_some(),
            }
        });
        py.check_signals()?;
        Ok(ended)
    }

    /// Asks the render to stop: no further tile is started.
    fn cancel(&self) {
        self.shared.cancel.store(true, Ordering::Relaxed);
    }

    /// The traced images and their summary lines (one; two for a stereo pair, left eye
    /// first), once the render has ended (see `wait`); raises if it was cancelled or failed.
    fn result(&self) -> PyResult<Vec<(Data, String)>> {
        if self.shared.cancel.load(Ordering::Relaxed) {
            return Err(PyRuntimeError::new_err("the render was cancelled"));
        }
        match self.shared.outcome().take() {
            Some(Ok(done)) => Ok(done
                .into_iter()
                .map(|(data, summary)| (Data::new(data), summary))
                .collect()),
            Some(Err(message)) => Err(value_error(message)),
            None => Err(PyRuntimeError::new_err("the render has not ended yet")),
        }
    }
}

impl Drop for RenderJob {
    /// A job dropped before its end (an exception in the caller) stops tracing.
    fn drop(&mut self) {
        self.shared.cancel.store(true, Ordering::Relaxed);
    }
}
