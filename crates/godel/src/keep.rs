//! *Render exactly* and *Record* of `godel explore` (docs/guide/src/explore.md): the
//! [`viewer::keep::Keeper`] over the explored scene.
//!
//! - A view ([`View`]: the scene file's observer fields and its camera) becomes the scene
//!   with its `[observer]` and `[camera]` replaced by the view's and `[trace] method = "exact"`
//!   (Gödel's universe; Minkowski space has only the numeric tracer), `gpu` off — made where
//!   every edited scene is made (`scene_edit`), so it is exactly the scene a user would write.
//!   Its render is `godel render`'s: the same driver on all cores, the same PNG and data file
//!   bytes (`output::data_and_preview`).
//! - A recording becomes a sequence script (docs/guide/src/sequences.md, "Fly-throughs"): `[trace]
//!   scene` the scene file (absolute path), one `[[keyframe]]` per recorded view at its frame
//!   with every observer field and the camera's fields of view, linear easing; frames at the
//!   scene's own size and samples. The text is read back by the script parser and every
//!   frame's scene checked (`flight::Flight::new`) before it is given. The scene's text is
//!   read once, and each view and frame checked in the part of it that its fields' checks
//!   read (`flight::view_part`): a recording's work is its keyframe and frame counts
//!   (bounded by `viewer::keep`) times a small scene's, whatever the scene's size.

use std::path::{Path, PathBuf};
use std::time::Instant;

use render::driver::{render_plan, Progress};
use render::plan::Plan;
use scene::{Camera, Scene};
use toml::{Table, Value};
use viewer::keep::{ExactJob, Keeper, Recording, Rendered, RECORD_FPS};
use viewer::view::{CameraView, Position, Velocity, View};

use spacetime::{Event, LocalVelocity};

use crate::flight::{observer_fields, view_part};
use crate::scene_edit::{edited_table, section, table_of, EditError};

/// The keeper of explore mode: the scene as read from its file, and the exact tracer's pool.
pub struct SceneKeeper {
    scene: Scene,
    /// The scene file, as messages name it, and absolute (for scripts saved anywhere).
    file: String,
    absolute: Option<PathBuf>,
    /// The scene read as a table (once), and its part a view's fields are checked in.
    table: Table,
    part: Table,
    pool: rayon::ThreadPool,
}

impl SceneKeeper {
    pub fn new(scene: Scene, pool: rayon::ThreadPool) -> Result<SceneKeeper, EditError> {
        let file = file_of(&scene);
        let absolute = scene
            .source_path
            .as_ref()
            .and_then(|p| std::path::absolute(p).ok());
        let table = table_of(&scene.source_text, &file)?;
        Ok(SceneKeeper {
            part: view_part(&table),
            table,
            scene,
            file,
            absolute,
            pool,
        })
    }

    /// The scene seen in `view`, refused naming the view's field (`view.FIELD: why`).
    pub fn scene_of(&self, view: &View) -> Result<Scene, String> {
        view_in(self.table.clone(), &self.scene, &self.file, view)
    }

    /// Whether the scene seen in `view` passes the usual checks (as [`SceneKeeper::scene_of`]
    /// does), checked in the scene's part the view's fields are checked in.
    fn check_fields(&self, view: &View) -> Result<(), String> {
        view_in(self.part.clone(), &self.scene, &self.file, view).map(drop)
    }
}

/// The scene's file as messages name it (relative image paths are relative to it).
pub fn file_of(scene: &Scene) -> String {
    match &scene.source_path {
        Some(path) => path.display().to_string(),
        None => format!("{}.toml", scene.name),
    }
}

/// The scene `scene` (read from `file`) seen in `view`: its `[observer]` and `[camera]`
/// those of the view, the exact tracer in Gödel's universe, not on the GPU; refused naming the
/// view's field (`view.FIELD: why`). The one home of a view's scene: explore's kernel input
/// and moves, *Render exactly* and *Record*.
pub fn scene_of_view(scene: &Scene, file: &str, view: &View) -> Result<Scene, String> {
    let table = table_of(&scene.source_text, file).map_err(|e| e.to_string())?;
    view_in(table, scene, file, view)
}

/// [`scene_of_view`] made from `table`: `scene`'s own table or its [`view_part`].
fn view_in(table: Table, scene: &Scene, file: &str, view: &View) -> Result<Scene, String> {
    let godel = scene.metric.godel_a().is_some();
    edited_table(table, file, |table| {
        table.insert("observer".into(), Value::Table(observer_table(view)));
        let mut camera = Table::new();
        camera.insert("kind".into(), view.camera.kind.clone().into());
        for (k, v) in fields_of_view(&view.camera) {
            camera.insert(k.into(), v.into());
        }
        let c = &view.camera;
        for (k, v) in [
            ("width", c.width),
            ("height", c.height),
            ("samples", c.samples),
        ] {
            camera.insert(k.into(), i64::from(v).into());
        }
        table.insert("camera".into(), Value::Table(camera));
        let trace = section(table, "trace");
        if godel {
            trace.insert("method".into(), "exact".into());
        }
        trace.remove("gpu");
    })
    .map_err(|e| match e {
        EditError::Scene(e) => {
            let field = e.field.strip_prefix("observer.").unwrap_or(&e.field);
            format!("view.{field}: {}", scene::one_line(&e.message))
        }
        EditError::Text(why) => why,
    })
}

/// The view's observer as a scene's (and a keyframe's) `[observer]` table.
fn observer_table(view: &View) -> Table {
    let p = view.position;
    let velocity = LocalVelocity {
        speed: view.velocity.speed,
        direction: view.velocity.direction,
    };
    let event = Event::new(view.time, p.x, p.y, p.z);
    observer_fields(event, velocity, view.forward, view.up)
}

/// The fields of view a camera view gives (keys among `shade::CAMERA_KEYS`).
fn fields_of_view(camera: &CameraView) -> Vec<(&'static str, f64)> {
    [
        ("fov_deg", camera.fov_deg),
        ("h_fov_deg", camera.h_fov_deg),
        ("v_fov_deg", camera.v_fov_deg),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.map(|v| (k, v)))
    .collect()
}

/// The job's progress and cancel flag, as the driver reads them.
struct JobProgress<'a>(&'a ExactJob);

impl Progress for JobProgress<'_> {
    fn start(&self, pixels: u64) {
        self.0
            .total
            .store(pixels, std::sync::atomic::Ordering::SeqCst);
    }
    fn advance(&self, pixels: u64) {
        self.0
            .done
            .fetch_add(pixels, std::sync::atomic::Ordering::SeqCst);
    }
    fn cancelled(&self) -> bool {
        self.0.cancelled()
    }
}

impl Keeper for SceneKeeper {
    fn name(&self) -> String {
        self.scene.name.clone()
    }

    fn own_view(&self) -> View {
        let o = &self.scene.observer;
        let e = o.event;
        let camera = self.scene.camera;
        let (mut fov_deg, mut h_fov_deg, mut v_fov_deg) = (None, None, None);
        match camera {
            Camera::Pinhole { fov_deg: f, .. } | Camera::Fisheye { fov_deg: f, .. } => {
                fov_deg = Some(f)
            }
            Camera::Panorama {
                h_fov_deg: h,
                v_fov_deg: v,
                ..
            } => (h_fov_deg, v_fov_deg) = (Some(h), Some(v)),
            Camera::Sphere { .. } => {}
        }
        View {
            time: e.t,
            position: Position {
                x: e.x,
                y: e.y,
                z: e.z,
            },
            velocity: Velocity {
                speed: o.velocity.speed,
                direction: o.velocity.direction,
            },
            forward: o.forward,
            up: o.up,
            camera: CameraView {
                kind: camera.kind().into(),
                fov_deg,
                h_fov_deg,
                v_fov_deg,
                width: camera.width(),
                height: camera.height(),
                samples: self.scene.samples,
            },
        }
    }

    fn check(&self, view: &View) -> Result<(), String> {
        let scene = self.scene_of(view)?;
        let c = &scene.camera;
        let rays = u64::from(c.width()) * u64::from(c.height()) * u64::from(scene.samples);
        datafile::memory::check_writing(
            "an exact render of this width × height × samples",
            rays,
            scene.lights.len(),
        )
        .map_err(|why| format!("view.camera: {why}"))
    }

    fn render(&self, view: &View, job: &ExactJob) -> Result<Option<Rendered>, String> {
        let scene = self.scene_of(view)?;
        let started = Instant::now();
        let progress = JobProgress(job);
        let traced = self
            .pool
            .install(|| render_plan(&scene, &Plan::All, &progress));
        let (data, mut stats) = traced.map_err(|e| e.to_string())?;
        if job.cancelled() {
            return Ok(None);
        }
        stats.wall = started.elapsed();
        let name = scene.name.clone();
        let (exr, png) = (format!("{name}.exr"), format!("{name}.png"));
        let (exr, png) =
            crate::output::data_and_preview(&scene, &data, Path::new(&exr), Path::new(&png), false)
                .map_err(|e| format!("{e:#}"))?;
        Ok(Some(Rendered {
            name,
            png,
            exr,
            summary: stats.summary(),
        }))
    }

    fn script(&self, recording: &Recording, frames: &[u32]) -> Result<String, String> {
        let Some(scene_path) = &self.absolute else {
            return Err("recording: the scene has no file for a script to name".into());
        };
        let kind = self.scene.camera.kind();
        let mut keyframes = Vec::with_capacity(frames.len());
        for (i, (k, &frame)) in recording.keyframes.iter().zip(frames).enumerate() {
            if k.view.camera.kind != kind {
                return Err(format!(
                    "recording.keyframes[{i}].view.camera.kind: a sequence traces the scene's \
                     own {kind} camera, not {:?}",
                    k.view.camera.kind
                ));
            }
            self.check_fields(&k.view)
                .map_err(|why| format!("recording.keyframes[{i}].{why}"))?;
            let mut keyframe = Table::new();
            keyframe.insert("frame".into(), i64::from(frame).into());
            keyframe.insert("observer".into(), Value::Table(observer_table(&k.view)));
            let camera: Table = fields_of_view(&k.view.camera)
                .into_iter()
                .map(|(key, v)| (key.to_string(), Value::Float(v)))
                .collect();
            if !camera.is_empty() {
                keyframe.insert("camera".into(), Value::Table(camera));
            }
            keyframes.push(Value::Table(keyframe));
        }
        let last = frames.last().copied().unwrap_or(0);
        let name = &self.scene.name;
        let mut trace = Table::new();
        trace.insert("scene".into(), scene_path.display().to_string().into());
        trace.insert("keep_data".into(), false.into());
        let mut root = Table::new();
        root.insert("output".into(), format!("{name}-flight").into());
        root.insert("frames".into(), i64::from(last + 1).into());
        root.insert("fps".into(), RECORD_FPS.into());
        root.insert("interpolation".into(), "linear".into());
        root.insert("trace".into(), Value::Table(trace));
        root.insert("keyframe".into(), Value::Array(keyframes));
        let body = toml::to_string(&root).map_err(|e| format!("recording: {e}"))?;
        let seconds = f64::from(last) / RECORD_FPS;
        let text = format!(
            "# A flight through {file} recorded by godel explore: {n} keyframes over {seconds:.2} s.\n\
             # Render its frames (and sequence.mp4 where ffmpeg is installed) into the folder\n\
             # `output` beside this file with\n#   godel sequence THIS_FILE.toml\n\
             # (keep_data = true also keeps each frame's data file).\n{body}",
            file = self.file,
            n = frames.len(),
        );
        let script_path = Path::new("recorded-flight.toml");
        let script =
            shade::Script::parse(&text, script_path).map_err(|e| format!("recording: {e}"))?;
        crate::flight::Flight::new(&self.scene, &script).map_err(|e| format!("recording: {e}"))?;
        Ok(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use viewer::keep::RecordedView;

    fn keeper() -> SceneKeeper {
        // One file per call: the tests run at once in one process, and a file written by one
        // while another reads it was seen read empty.
        static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("godel-keep-unit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("keep-unit-{call}.toml"));
        let text = testkit::ball_ahead(
            "keep-unit",
            &testkit::panorama(220.0, 25.0, 16, 8),
            "ball",
            r#"{ kind = "uniform", color = [0.2, 0.4, 0.6] }"#,
        );
        std::fs::write(&path, text).unwrap();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        SceneKeeper::new(Scene::from_file(&path).unwrap(), pool).unwrap()
    }

    #[test]
    fn a_bad_view_is_refused_naming_its_field() {
        let k = keeper();
        let mut view = k.own_view();
        view.velocity.speed = 1.5;
        let e = k.check(&view).unwrap_err();
        assert!(e.starts_with("view.velocity.speed: "), "{e}");
        let mut view = k.own_view();
        view.camera.width = 0;
        let e = k.check(&view).unwrap_err();
        assert!(e.starts_with("view.camera.width: "), "{e}");
        let mut view = k.own_view();
        view.camera.h_fov_deg = None;
        let e = k.check(&view).unwrap_err();
        assert!(e.starts_with("view.camera"), "{e}");
        k.check(&k.own_view()).unwrap();
    }

    #[test]
    fn a_recorded_keyframe_is_the_scene_of_its_view() {
        let k = keeper();
        let mut moved = k.own_view();
        moved.time = 1.25;
        moved.position.x = 0.3;
        moved.velocity.speed = 0.4;
        moved.forward = [0.0, 1.0, 0.0];
        moved.camera.h_fov_deg = Some(180.0);
        let recording = Recording {
            keyframes: vec![
                RecordedView {
                    seconds: 0.0,
                    view: k.own_view(),
                },
                RecordedView {
                    seconds: 0.5,
                    view: moved.clone(),
                },
            ],
        };
        let frames = recording.frames().unwrap();
        assert_eq!(frames, [0, 12]);
        let text = k.script(&recording, &frames).unwrap();
        let script = shade::Script::parse(&text, Path::new("flight.toml")).unwrap();
        assert_eq!(script.frames, 13);
        let flight = crate::flight::Flight::new(&k.scene, &script).unwrap();
        let direct = k.scene_of(&moved).unwrap();
        let frame = flight.scene_at(12).unwrap();
        assert_eq!(frame.observer, direct.observer);
        assert_eq!(frame.camera, direct.camera);
        // A camera kind the scene has not cannot be keyframed.
        let mut other = recording.clone();
        other.keyframes[1].view.camera.kind = "sphere".into();
        let e = k.script(&other, &frames).unwrap_err();
        assert!(
            e.starts_with("recording.keyframes[1].view.camera.kind: "),
            "{e}"
        );
    }
}
