//! `godel explore SCENE.toml [--port P] [--host H] [--textures DIR]… [--threads N]`: the live
//! viewer in explore mode (docs/guide/src/explore.md). The page changes the observer's event
//! (t, x, y, z); the server re-traces the scene from there with the exact tracer of
//! `godel render` (the `render` crate's driver, on all cores), a coarse frame first (the same
//! camera with a quarter of the width and height, one ray per pixel), then the full one, which
//! holds the records `godel render` writes for the scene with that observer. A flying page
//! that finds this CPU faster than its GPU sends its view instead: one frame of that observer
//! and camera, the records `godel render` writes for the scene with the view's fields. The
//! newest request wins: older work stops between tiles
//! ([`render::driver::Progress::cancelled`]). Which frames are kept is decided in the `viewer`
//! crate (`viewer::explore`); this file only traces.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use anyhow::Context;
use clap::Args;
use datafile::record::RayStatus;
use datafile::DataFile;
use datafile::PixelRecord;
use gpu::check::CheckError;
use render::driver::{Progress, Renderer};
use render::map::{light_ray, map, LightRay, Map};
use render::plan::Plan;
use render::tiles::Assembler;
use scene::Scene;
use spacetime::message::short;
use toml::Table;
use viewer::explore::{Explorer, FrameSource, Level, ObserverEvent, FRAMES_IN_MEMORY};
use viewer::kernel_routes::KernelInput;
use viewer::page_check::{CheckedSample, Verdict};
use viewer::view::{Velocity, View};

use crate::args::{thread_pool, usage};
use crate::keep::file_of;
use crate::memory;
use crate::scene_edit::section;
use crate::serve::{load_error, ServeArgs};

/// The coarse frame's width and height are the scene's divided by this (at least 1 pixel).
const COARSE_DIVISOR: u32 = 4;

#[derive(Args, Debug)]
pub struct ExploreArgs {
    /// Scene file (TOML): the observer starts at its event.
    pub scene: PathBuf,
    #[command(flatten)]
    pub serve: ServeArgs,
    /// Worker threads for tracing (default: all cores; at most 8 per core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Trace the full sphere around the observer, WIDTH × WIDTH/2 pixels of one ray each,
    /// instead of the scene's camera: the page can then look around, zoom and change the
    /// velocity instantly between traces (as `godel view` of a sphere file). WIDTH is even,
    /// 8 to 8192.
    #[arg(long, value_name = "WIDTH")]
    pub sphere: Option<u32>,
    /// Give the page this GLSL source of the GPU kernel instead of godel's own (to try a
    /// change or a driver: the page checks its frames against the CPU exact tracer, and
    /// traces on the server where they disagree).
    #[arg(long, value_name = "FILE")]
    pub kernel: Option<PathBuf>,
}

/// The largest `--sphere` width.
const MAX_SPHERE_WIDTH: u32 = 8192;

/// The scene with its camera replaced by the full sphere `width` × `width`/2, one ray per
/// pixel.
fn with_sphere(scene: &Scene, width: u32) -> anyhow::Result<Scene> {
    if !width.is_multiple_of(2) || !(8..=MAX_SPHERE_WIDTH).contains(&width) {
        return Err(usage(
            &format!("--sphere {width}"),
            format!("the width must be even, from 8 to {MAX_SPHERE_WIDTH}"),
        ));
    }
    edited(scene, |table| {
        let mut camera = Table::new();
        camera.insert("kind".into(), "sphere".into());
        camera.insert("width".into(), i64::from(width).into());
        camera.insert("height".into(), i64::from(width / 2).into());
        table.insert("camera".into(), camera.into());
    })
}

/// The scene with its observer moved to `event` and traced by the exact tracer (Gödel's
/// universe; Minkowski space has only the numeric one); for [`Level::Coarse`] with the
/// camera's width and height divided by [`COARSE_DIVISOR`] and one ray per pixel.
pub fn scene_at(scene: &Scene, event: ObserverEvent, level: Level) -> anyhow::Result<Scene> {
    let godel = scene.metric.godel_a().is_some();
    let (w, h) = (scene.camera.width(), scene.camera.height());
    edited(scene, |table| {
        let observer = section(table, "observer");
        observer.insert("time".into(), event.t.into());
        let mut position = Table::new();
        for (k, v) in [("x", event.x), ("y", event.y), ("z", event.z)] {
            position.insert(k.into(), v.into());
        }
        observer.insert("position".into(), position.into());
        if godel {
            section(table, "trace").insert("method".into(), "exact".into());
        }
        if level == Level::Coarse {
            let camera = section(table, "camera");
            let smaller = |side: u32| i64::from((side / COARSE_DIVISOR).max(1));
            camera.insert("width".into(), smaller(w).into());
            camera.insert("height".into(), smaller(h).into());
            camera.insert("samples".into(), 1.into());
        }
    })
}

/// The scene with its observer and camera those of `view` (the flying page's), as
/// *Render exactly* makes it ([`crate::keep::scene_of_view`]).
pub fn scene_of_view(scene: &Scene, view: &View) -> anyhow::Result<Scene> {
    crate::keep::scene_of_view(scene, &file_of(scene), view).map_err(anyhow::Error::msg)
}

/// The scene read again from its text after `edit`, with the usual checks: the data files
/// embed the scene they were traced from (observer, camera size, method). Relative paths
/// (image textures) stay relative to the scene file.
fn edited(scene: &Scene, edit: impl FnOnce(&mut Table)) -> anyhow::Result<Scene> {
    Ok(crate::scene_edit::edited(
        &scene.source_text,
        &file_of(scene),
        edit,
    )?)
}

/// The exact tracer on a scene, as the frame source of explore mode.
pub struct SceneFrames {
    scene: Scene,
    pool: rayon::ThreadPool,
}

/// Tells the driver to stop when the explorer cancels the work.
struct Cancel<'a>(&'a AtomicBool);

impl Progress for Cancel<'_> {
    fn advance(&self, _pixels: u64) {}
    fn cancelled(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}

impl SceneFrames {
    pub fn new(scene: Scene, pool: rayon::ThreadPool) -> SceneFrames {
        SceneFrames { scene, pool }
    }

    /// The frame of `scene_at(event, level)`, or `None` once `cancel` is set.
    pub fn trace(
        &self,
        event: ObserverEvent,
        level: Level,
        cancel: &AtomicBool,
    ) -> anyhow::Result<Option<DataFile>> {
        self.trace_scene(&scene_at(&self.scene, event, level)?, cancel)
    }

    /// The frame of `scene`, traced on this pool, or `None` once `cancel` is set.
    fn trace_scene(&self, scene: &Scene, cancel: &AtomicBool) -> anyhow::Result<Option<DataFile>> {
        let renderer = Renderer::new(scene)?;
        let mut assembler = Assembler::new(renderer.blank(), renderer.tiles());
        let stop = Cancel(cancel);
        self.pool
            .install(|| renderer.run(&Plan::All, &mut assembler, &stop));
        if cancel.load(Ordering::SeqCst) {
            return Ok(None);
        }
        Ok(Some(assembler.finish()))
    }

    /// `scene` when its sample grid is no larger than the scene's own (`what` names the
    /// request's camera in the refusal): explore's memory holds frames of that size.
    fn within_own(&self, scene: Scene, what: &str) -> Result<Scene, String> {
        let (grid, own) = (scene.sample_camera(), self.scene.sample_camera());
        let cells = |c: &scene::Camera| u64::from(c.width()) * u64::from(c.height());
        if cells(&grid) > cells(&own) {
            return Err(format!(
                "{what}: {}×{} samples, more than the scene's {}×{}",
                grid.width(),
                grid.height(),
                own.width(),
                own.height()
            ));
        }
        Ok(scene)
    }

    /// The scene of a view sent to be traced here, within the scene's own frame size.
    fn view_scene(&self, view: &View) -> Result<Scene, String> {
        let scene = scene_of_view(&self.scene, view).map_err(|e| format!("{e:#}"))?;
        self.within_own(scene, "view.camera")
    }
}

impl FrameSource for SceneFrames {
    fn start(&self) -> ObserverEvent {
        self.scene.observer.event.into()
    }

    fn bound(&self) -> f64 {
        scene::MAX_COORDINATE_PER_A * self.scene.metric.length_scale()
    }

    fn frame(
        &self,
        event: ObserverEvent,
        level: Level,
        cancel: &AtomicBool,
    ) -> Result<Option<DataFile>, String> {
        self.trace(event, level, cancel)
            .map_err(|e| format!("{e:#}"))
    }

    fn view_frame(&self, view: &View, cancel: &AtomicBool) -> Result<Option<DataFile>, String> {
        let scene = self.view_scene(view)?;
        self.trace_scene(&scene, cancel)
            .map_err(|e| format!("{e:#}"))
    }

    fn view_refusal(&self, view: &View) -> Option<String> {
        self.view_scene(view).err()
    }

    fn map(&self, event: ObserverEvent) -> Result<Map, String> {
        map(&self.scene, event.event()).map_err(|(name, e)| format!("object {name:?}: {e}"))
    }

    fn light_ray(&self, event: ObserverEvent, record: &PixelRecord) -> LightRay {
        light_ray(&self.scene, event.event(), record)
    }

    fn keyframe(&self, event: ObserverEvent, frame: u32) -> Result<String, String> {
        let mut moved = self.scene.clone();
        moved.observer.event = event.event();
        crate::flight::keyframe_text(&moved, frame).map_err(|e| e.to_string())
    }

    fn view_keyframe(&self, view: &View, frame: u32) -> Result<String, String> {
        let scene = scene_of_view(&self.scene, view).map_err(|e| format!("{e:#}"))?;
        crate::flight::keyframe_text(&scene, frame).map_err(|e| e.to_string())
    }

    fn check(
        &self,
        view: &View,
        samples: &[CheckedSample],
        renderer: &str,
    ) -> Result<Verdict, String> {
        let scene = scene_of_view(&self.scene, view).map_err(|e| format!("{e:#}"))?;
        // A grid no larger than the scene's own frames (which explore holds anyway).
        let scene = self.within_own(scene, "check.view.camera")?;
        let grid = scene.sample_camera();
        let (w, h) = (grid.width(), grid.height());
        let cells = u64::from(w) * u64::from(h);
        let mut records = vec![PixelRecord::miss(RayStatus::NotTraced); cells as usize];
        for (k, s) in samples.iter().enumerate() {
            if s.x >= w || s.y >= h {
                return Err(format!(
                    "check.samples[{k}]: ({}, {}) is outside the {w}×{h} samples",
                    s.x, s.y
                ));
            }
            records[s.y as usize * w as usize + s.x as usize] = s.record;
        }
        // The records the page did not send are `not traced`: gpu::check passes them over.
        Ok(match gpu::check::against_cpu(&scene, &records, renderer) {
            Ok(()) => Verdict::Agree,
            Err(e @ CheckError::Disagrees { .. }) => Verdict::Disagree(e.to_string()),
            Err(e @ CheckError::Setup(_)) => Verdict::Unchecked(e.to_string()),
        })
    }

    fn kernel_input(&self, event: ObserverEvent) -> Result<KernelInput, String> {
        let scene = scene_at(&self.scene, event, Level::Full).map_err(|e| format!("{e:#}"))?;
        kernel_refusal(&scene)?;
        Ok(KernelInput::new(&scene))
    }

    fn view_input(&self, view: &View) -> Result<KernelInput, String> {
        let scene = scene_of_view(&self.scene, view).map_err(|e| format!("{e:#}"))?;
        kernel_refusal(&scene)?;
        Ok(KernelInput::new(&scene))
    }

    fn fall(
        &self,
        event: ObserverEvent,
        velocity: Velocity,
        tau: f64,
    ) -> Result<(ObserverEvent, Velocity), String> {
        let v = if velocity.speed == 0.0 {
            Some(spacetime::LocalVelocity::REST)
        } else {
            spacetime::LocalVelocity::new(velocity.speed, velocity.direction)
        }
        .ok_or_else(|| {
            format!(
                "velocity: speed {} must be in [0, 1) with a non-zero finite direction {:?}",
                short(velocity.speed),
                velocity.direction
            )
        })?;
        let (to, w) = spacetime::worldline::fall(&self.scene.metric, event.event(), v, tau)
            .ok_or_else(|| {
                format!(
                    "tau: the observer's free fall over tau = {} is not finite",
                    short(tau)
                )
            })?;
        Ok((
            to.into(),
            Velocity {
                speed: w.speed,
                direction: w.direction,
            },
        ))
    }
}

/// Bytes explore holds per ray of a full frame, at most: the record in each of the
/// [`FRAMES_IN_MEMORY`] frames it may have in memory, and the shading channels (about half a
/// record) of one of them, made when a picture of it is saved.
fn bytes_per_ray(scene: &Scene) -> u64 {
    let record = memory::record_bytes(scene.lights.len());
    FRAMES_IN_MEMORY * record + record / 2
}

/// Refuses, before anything is traced, frames whose memory explore cannot hold (the
/// frame's size named: `--sphere W`, or the scene's camera and samples).
fn check_memory(scene: &Scene, sphere: Option<u32>) -> anyhow::Result<()> {
    let camera = &scene.camera;
    let rays = u64::from(camera.width()) * u64::from(camera.height()) * u64::from(scene.samples);
    let per_ray = bytes_per_ray(scene);
    let (flag, what, fits) = match sphere {
        Some(width) => {
            // The widest sphere within the budget: W × W/2 rays.
            let most = ((2 * memory::budget()? / per_ray) as f64).sqrt() as u32 & !1;
            let fits = (most >= 8).then(|| format!("--sphere {}", most.min(MAX_SPHERE_WIDTH)));
            (
                format!("--sphere {width}"),
                "exploring a sphere of that width",
                fits,
            )
        }
        None => (
            format!(
                "{}: camera",
                scene
                    .source_path
                    .as_deref()
                    .unwrap_or(std::path::Path::new(&scene.name))
                    .display()
            ),
            "exploring frames of the scene's camera size and samples",
            None,
        ),
    };
    memory::check(&flag, what, rays.saturating_mul(per_ray), fits)
}

pub fn run(args: ExploreArgs) -> anyhow::Result<()> {
    let ip = args.serve.ip()?;
    let pool = thread_pool(args.threads)?;
    let mut scene = Scene::from_file(&args.scene)?;
    // "Render exactly" and "Record" keep views of the scene as written (issue 23).
    let keeper = crate::keep::SceneKeeper::new(scene.clone(), thread_pool(args.threads)?)?;
    if let Some(width) = args.sphere {
        scene = with_sphere(&scene, width)?;
    }
    shade::textures_for_scene(&scene)?;
    check_memory(&scene, args.sphere)?;
    let kernel = match &args.kernel {
        Some(path) => Some(std::fs::read_to_string(path).map_err(|e| {
            usage(
                &format!("--kernel {}", path.display()),
                format!("cannot read the kernel source: {e}"),
            )
        })?),
        None => None,
    };
    let frames = SceneFrames::new(scene, pool);
    // The viewer opens on the explorer's first frame at the scene's own event (the coarse
    // one, or the full one where that is already done); the page then receives the
    // explorer's frames.
    let start = frames.start();
    let explorer = Explorer::new(frames).context("cannot start the tracing thread")?;
    explorer
        .request(start)
        .map_err(|why| anyhow::anyhow!("{}: observer: {why}", args.scene.display()))?;
    let first = explorer
        .first_frame()
        .map_err(|why| anyhow::anyhow!("{}: {why}", args.scene.display()))?;
    let state =
        viewer::ViewerState::new_with(&args.scene, first.data.clone(), args.serve.options())
            .map_err(load_error)?;
    let listener = args.serve.listen(ip, "explore")?;
    eprintln!(
        "{}: change the observer's event in the Explore panel; press Ctrl-C to stop",
        args.scene.display()
    );
    let state = Arc::new(state);
    viewer::run_app(listener, |access| {
        let keep = viewer::keep_routes::router(keeper, state.work().clone(), access.clone());
        viewer::explore_routes::router(state, explorer, access, kernel).merge(keep)
    })
    .context("the viewer's server failed")
}

/// Why the page's kernel cannot trace `scene` (`gpu::input::refusal`), and that the server
/// traces it on the CPU instead.
fn kernel_refusal(scene: &scene::Scene) -> Result<(), String> {
    match gpu::input::refusal(scene) {
        Some(why) => Err(format!("{why}: the server traces it on the CPU")),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use spacetime::Event;

    fn small_scene() -> Scene {
        let text = testkit::ball_ahead(
            "explore-unit",
            &testkit::panorama(220.0, 25.0, 16, 8),
            "ball",
            r#"{ kind = "uniform", color = [0.2, 0.4, 0.6] }"#,
        );
        Scene::from_str(&text, "explore-unit.toml").unwrap()
    }

    fn event(t: f64, x: f64) -> ObserverEvent {
        ObserverEvent {
            t,
            x,
            y: 0.0,
            z: 0.0,
        }
    }

    #[test]
    fn coarse_is_the_same_camera_smaller_and_full_is_the_scene_moved() {
        let scene = small_scene();
        let coarse = scene_at(&scene, event(2.0, 0.3), Level::Coarse).unwrap();
        assert_eq!((coarse.camera.width(), coarse.camera.height()), (4, 2));
        assert_eq!(coarse.camera.kind(), scene.camera.kind());
        let full = scene_at(&scene, event(2.0, 0.3), Level::Full).unwrap();
        assert_eq!(full.observer.event, Event::new(2.0, 0.3, 0.0, 0.0));
        assert_eq!(full.camera, scene.camera);
        assert_eq!(full.samples, scene.samples);
    }

    /// A view flown away from the small scene's observer: moving, turned, another camera.
    fn flown_view() -> View {
        serde_json::from_value(serde_json::json!({
            "time": 1.5, "position": {"x": 0.2, "y": -0.1, "z": 0.3},
            "velocity": {"speed": 0.6, "direction": [0, 1, 0]},
            "forward": [0, 1, 0], "up": [0, 0, 1],
            "camera": {"kind": "pinhole", "fov_deg": 70, "width": 12, "height": 6, "samples": 4},
        }))
        .unwrap()
    }

    /// The small scene's frames, traced on one thread.
    fn one_thread_frames() -> SceneFrames {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        SceneFrames::new(small_scene(), pool)
    }

    #[test]
    fn a_view_replaces_the_observer_and_camera_and_a_bad_one_names_its_field() {
        let scene = small_scene();
        let view = flown_view();
        let moved = scene_of_view(&scene, &view).unwrap();
        let o = moved.observer;
        assert_eq!(o.event, Event::new(1.5, 0.2, -0.1, 0.3));
        assert_eq!(
            (o.velocity.speed, o.velocity.direction),
            (0.6, [0.0, 1.0, 0.0])
        );
        assert_eq!((o.forward, o.up), ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]));
        assert_eq!(moved.camera.kind(), "pinhole");
        assert_eq!((moved.camera.width(), moved.camera.height()), (12, 6));
        assert_eq!(moved.supersample(), 2);
        let mut bad = view.clone();
        bad.camera.h_fov_deg = Some(90.0);
        let e = format!("{:#}", scene_of_view(&scene, &bad).unwrap_err());
        assert!(e.contains("h_fov_deg"), "{e}");
        bad = view.clone();
        bad.velocity.speed = 1.5;
        let e = format!("{:#}", scene_of_view(&scene, &bad).unwrap_err());
        assert!(e.contains("speed"), "{e}");
    }

    #[test]
    fn a_view_keyframe_holds_the_flown_velocity_axes_and_field_of_view() {
        let frames = one_thread_frames();
        let view = flown_view();
        let text = frames.view_keyframe(&view, 3).unwrap();
        let table: toml::Table = text.parse().unwrap();
        let k = &table["keyframe"][0];
        assert_eq!(k["frame"].as_integer(), Some(3), "{text}");
        let o = &k["observer"];
        assert_eq!(o["time"].as_float(), Some(1.5), "{text}");
        assert_eq!(o["position"]["y"].as_float(), Some(-0.1), "{text}");
        assert_eq!(o["velocity"]["speed"].as_float(), Some(0.6), "{text}");
        let direction: Vec<f64> = o["velocity"]["direction"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_float().unwrap())
            .collect();
        assert_eq!(direction, [0.0, 1.0, 0.0], "{text}");
        assert_eq!(o["forward"][1].as_float(), Some(1.0), "{text}");
        assert_eq!(k["camera"]["fov_deg"].as_float(), Some(70.0), "{text}");
        let mut bad = view.clone();
        bad.velocity.speed = 1.5;
        let e = frames.view_keyframe(&bad, 0).unwrap_err();
        assert!(e.contains("speed"), "{e}");
    }

    #[test]
    fn a_cancelled_trace_gives_nothing() {
        let frames = one_thread_frames();
        let cancelled = AtomicBool::new(true);
        let traced = frames.trace(event(0.0, 0.0), Level::Full, &cancelled);
        assert!(traced.unwrap().is_none());
        let done = frames.trace(event(0.0, 0.0), Level::Coarse, &AtomicBool::new(false));
        let data = done.unwrap().unwrap();
        assert_eq!((data.width, data.height), (4, 2));
        assert!(data
            .records
            .iter()
            .all(|r| r.status != datafile::RayStatus::NotTraced));
    }
}
