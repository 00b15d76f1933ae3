//! The parallel render driver: one pipeline for whole renders, parts, MPI batches and
//! sequences. A [`Renderer`] (the scene's tracer and lights, built once) traces the tiles a
//! caller names on rayon's pool and hands each finished [`TileData`] to a [`Sink`]: the
//! data-file assembler (`crate::tiles::Assembler`), a part writer, an MPI sender. Progress
//! goes to a [`Progress`] consumer; statistics are counted once, here. The tracer never
//! learns about files, terminals or MPI.
//!
//! Determinism: every pixel is traced independently from the same shared, immutable
//! tracer (each tile starts with fresh per-thread state), so the records (and the files
//! written from them) are identical whatever the number of threads or ranks, or the order
//! in which tiles finish.

use crate::intersect::Intersector;
use crate::lighting::{LightSource, Lighting};
use crate::plan::{tiles, Plan, Tile};
use crate::target::Target;
use crate::tiles::{Assembler, Sink, TileData};
use crate::tracer::{Scratch, TraceOptions, Tracer};
use datafile::record::{PixelRecord, RayStatus};
use datafile::{DataFile, DataHeader, Member, FORMAT_VERSION};
use rayon::prelude::*;
use scene::{Camera, Scene, TraceMethod};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Receives progress from the driver (the tracer never learns about terminals or MPI).
pub trait Progress: Sync {
    /// The run is about to trace `pixels` pixels (samples) in all.
    fn start(&self, _pixels: u64) {}
    /// `pixels` more pixels are done.
    fn advance(&self, pixels: u64);
    /// True when the caller no longer wants the result: the driver then traces no further
    /// tile (the tiles under way finish), so a cancelled run ends within one tile's time
    /// per thread and its sink holds only the tiles done before.
    fn cancelled(&self) -> bool {
        false
    }
}

/// A progress consumer that ignores everything.
pub struct NoProgress;
impl Progress for NoProgress {
    fn advance(&self, _pixels: u64) {}
}

/// Counts of how the rays ended, and timing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub pixels: u64,
    pub traced: u64,
    pub hits: u64,
    pub escaped: u64,
    pub step_budget: u64,
    /// Rays whose bounded intersection search or loop copies ran out (status `WorkLimit`).
    pub work_limit: u64,
    pub failed: u64,
    pub wall: Duration,
}

impl RenderStats {
    /// Adds the counts of `other` (wall time left as it is).
    pub fn add(&mut self, other: &RenderStats) {
        self.pixels += other.pixels;
        self.traced += other.traced;
        self.hits += other.hits;
        self.escaped += other.escaped;
        self.step_budget += other.step_budget;
        self.work_limit += other.work_limit;
        self.failed += other.failed;
    }

    /// How the rays of these records ended (`wall` left zero).
    pub fn count(records: &[PixelRecord]) -> RenderStats {
        let mut stats = RenderStats {
            pixels: records.len() as u64,
            ..Default::default()
        };
        for r in records {
            match r.status {
                RayStatus::Hit => stats.hits += 1,
                RayStatus::Escaped => stats.escaped += 1,
                RayStatus::StepBudget => stats.step_budget += 1,
                RayStatus::WorkLimit => stats.work_limit += 1,
                RayStatus::Failed => stats.failed += 1,
                RayStatus::NotTraced => continue,
            }
            stats.traced += 1;
        }
        stats
    }

    pub fn rays_per_second(&self) -> f64 {
        self.traced as f64 / self.wall.as_secs_f64().max(1e-9)
    }
    /// One line for the end of a render.
    pub fn summary(&self) -> String {
        format!(
            "{} pixels, {} traced, {} hit, {} escaped, {} failed (step budget {}, work limit {}, integration {}), {:.2} s, {:.0} rays/s",
            self.pixels,
            self.traced,
            self.hits,
            self.escaped,
            self.step_budget + self.work_limit + self.failed,
            self.step_budget,
            self.work_limit,
            self.failed,
            self.wall.as_secs_f64(),
            self.rays_per_second()
        )
    }
}

/// Most integration steps of all free-fall worldlines together (each ~1.5 KB): a bound on
/// the memory a scene's moving objects take, checked before any tracing.
pub const MAX_TOTAL_WORLDLINE_STEPS: usize = 400_000;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("the free-fall worldlines need {steps} integration steps in all, more than {MAX_TOTAL_WORLDLINE_STEPS}: reduce trace.max_past, the number of falling objects, or raise spacetime.a")]
    WorldlinesTooLong { steps: usize },
    #[error("object {name:?}: {source}")]
    Worldline {
        name: String,
        source: crate::worldline::WorldlineError,
    },
}

/// A scene ready to trace: its tracer and lights, built once and shared by all threads.
pub struct Renderer<'a> {
    scene: &'a Scene,
    /// The camera whose pixels are the scene's samples (the scene's camera when
    /// `samples` = 1): every tile, part and record is of this sample grid.
    camera: Camera,
    tracer: Tracer,
    lighting: Lighting,
    tiles: Vec<Tile>,
}

impl<'a> Renderer<'a> {
    /// Builds the tracer (objects with their worldlines) and the lights of `scene`.
    pub fn new(scene: &'a Scene) -> Result<Renderer<'a>, RenderError> {
        let m = scene.metric;
        let obs = scene.observer;
        // Worldlines cover the traced time range plus a margin for the objects' own size,
        // and with lights the range of their shadow rays (emitted up to max_past before a
        // hit).
        let reach = if scene.lights.is_empty() { 1.0 } else { 2.0 };
        let (t_min, t_max) = (
            obs.event.t - reach * scene.trace.max_past - 1.0,
            obs.event.t + 1.0,
        );
        let targets = scene
            .objects
            .iter()
            .map(|o| {
                Target::new(m, o, t_min, t_max).map_err(|source| RenderError::Worldline {
                    name: o.name.clone(),
                    source,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let steps: usize = targets.iter().map(Target::integration_steps).sum();
        if steps > MAX_TOTAL_WORLDLINE_STEPS {
            return Err(RenderError::WorldlinesTooLong { steps });
        }
        let options = TraceOptions {
            max_past: scene.trace.max_past,
            tolerance: scene.trace.tolerance,
            max_steps: scene.trace.max_steps,
            exact: scene.trace.method == TraceMethod::Exact,
        };
        let objects = Intersector::new(m, targets);
        let tracer = Tracer::new(objects, &obs, options);
        let lighting = Lighting::new(
            scene.lights.iter().map(LightSource::from_scene).collect(),
            tracer.max_past(),
        );
        let camera = scene.sample_camera();
        Ok(Renderer {
            scene,
            camera,
            tracer,
            lighting,
            tiles: tiles(camera.width(), camera.height()),
        })
    }

    pub fn scene(&self) -> &Scene {
        self.scene
    }

    /// The camera of the sample grid (see [`Scene::sample_camera`]).
    pub fn sample_camera(&self) -> &Camera {
        &self.camera
    }

    /// All tiles of the image (of samples), row-major.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// The scene's data file with no pixel traced yet (status "not traced", no light
    /// planes): what an [`Assembler`] starts from. Its records are written on the current
    /// pool's threads: at 2200×250 they are 46 MB of fresh pages, 25 ms on one thread before
    /// any tile is traced.
    pub fn blank(&self) -> DataFile {
        let (w, h) = (self.camera.width() as usize, self.camera.height() as usize);
        let records = (0..w * h)
            .into_par_iter()
            .map(|_| PixelRecord::miss(RayStatus::NotTraced))
            .collect();
        DataFile {
            header: header(self.scene),
            width: w,
            height: h,
            records,
            lights: vec![],
            polarization: true,
        }
    }

    /// Per-thread buffers.
    pub fn scratch(&self) -> Scratch {
        self.tracer.scratch()
    }

    /// Traces tile `index`: its records (row-major within the tile) and one plane of direct
    /// light per light source.
    pub fn trace_tile(&self, index: usize, scratch: &mut Scratch) -> TileData {
        let tile = self.tiles[index];
        let n = self.lighting.lights.len();
        let pixels = (tile.cols * tile.rows) as usize;
        let mut records = Vec::with_capacity(pixels);
        let mut lights = vec![vec![0.0f32; pixels]; n];
        let mut lit = vec![0.0f32; n];
        // Each tile starts afresh (see `Scratch::reset_first_step`), so that the records do
        // not depend on which thread traced which tiles before.
        scratch.reset_first_step();
        for row in tile.row0..tile.row0 + tile.rows {
            for col in tile.col0..tile.col0 + tile.cols {
                let at = records.len();
                records.push(self.trace_sample(col, row, scratch, &mut lit));
                for (plane, &v) in lights.iter_mut().zip(&lit) {
                    plane[at] = v;
                }
            }
        }
        TileData {
            index,
            records,
            lights,
        }
    }

    /// Traces sample (`col`, `row`) of the sample grid: its record, and in `lit` (one value
    /// per light source; 0 for a sample outside the camera's field) its direct light.
    pub fn trace_sample(
        &self,
        col: u32,
        row: u32,
        scratch: &mut Scratch,
        lit: &mut [f32],
    ) -> PixelRecord {
        lit.fill(0.0);
        let Some(dir) = self.scene.observer.pixel_direction(&self.camera, col, row) else {
            return PixelRecord::miss(RayStatus::NotTraced);
        };
        let traced = self.tracer.trace(dir, scratch);
        if !self.lighting.lights.is_empty() {
            let hit = traced.hit.as_ref();
            self.lighting
                .illuminate(&self.tracer.objects, hit, &mut scratch.probes, lit);
        }
        PixelRecord {
            view: dir.map(|c| c as f32),
            ..traced.record
        }
    }

    /// Traces the tiles of `plan` on rayon's current pool, handing each to `sink` as it is
    /// done; returns what the rays did (wall time included).
    pub fn run(
        &self,
        plan: &Plan,
        sink: &mut (dyn Sink + Send),
        progress: &dyn Progress,
    ) -> RenderStats {
        let indices = plan.indices(&self.tiles);
        let tile_pixels = |&k: &usize| (self.tiles[k].cols * self.tiles[k].rows) as u64;
        progress.start(indices.iter().map(tile_pixels).sum());
        let started = Instant::now();
        let shared = Mutex::new((sink, RenderStats::default()));
        // Each thread of the pool takes the next tile not yet taken, one at a time, with its
        // own scratch. (A parallel iterator over the tiles left one of two threads idle for
        // the last 0.3 s of the reference scene's 1.8 s at 2200×250: rayon's adaptive
        // splitting hands a thread runs of tiles it cannot share, and that scene's costly
        // tiles lie in one band of rows.)
        let next = AtomicUsize::new(0);
        rayon::broadcast(|_| {
            let mut scratch = self.scratch();
            while let Some(&index) = indices.get(next.fetch_add(1, Ordering::Relaxed)) {
                if progress.cancelled() {
                    return;
                }
                let tile = self.trace_tile(index, &mut scratch);
                let stats = RenderStats::count(&tile.records);
                progress.advance(tile.records.len() as u64);
                let mut guard = shared.lock().unwrap_or_else(|e| e.into_inner());
                guard.1.add(&stats);
                guard.0.accept(tile);
            }
        });
        let (_, mut stats) = shared.into_inner().unwrap_or_else(|e| e.into_inner());
        stats.wall = started.elapsed();
        stats
    }
}

/// The header a data file of this scene carries.
pub fn header(scene: &Scene) -> DataHeader {
    DataHeader {
        format_version: FORMAT_VERSION,
        scene_name: scene.name.clone(),
        scene_text: scene.source_text.clone(),
        camera: scene.camera.describe(),
        observer_time: scene.observer.event.t,
        metric: scene.metric.name().to_string(),
        godel_a: scene.metric.godel_a().unwrap_or(0.0),
        member: scene.metric.godel_type().map(|g| Member {
            m2: g.m2,
            omega: g.omega,
        }),
        method: match scene.trace.method {
            TraceMethod::Numeric => "numeric".into(),
            TraceMethod::Exact => "exact".into(),
        },
        object_names: scene.objects.iter().map(|o| o.name.clone()).collect(),
        supersample: scene.supersample(),
    }
}

/// Renders the whole scene on rayon's thread pool.
pub fn render(
    scene: &Scene,
    progress: &dyn Progress,
) -> Result<(DataFile, RenderStats), RenderError> {
    render_plan(scene, &Plan::All, progress)
}

/// The rays (pixels × samples) the tiles of `plan` hold for `scene`: what a render of the
/// plan traces, known before any work (to size it against memory, to show progress).
pub fn plan_pixels(scene: &Scene, plan: &Plan) -> u64 {
    let camera = scene.sample_camera();
    let all = tiles(camera.width(), camera.height());
    let pixels = |&k: &usize| (all[k].cols * all[k].rows) as u64;
    plan.indices(&all).iter().map(pixels).sum()
}

/// Renders the tiles of `plan` on rayon's thread pool into a data file of the whole image
/// (pixels of other tiles "not traced"): `godel render` (whole or `--part`), its sequences
/// and the Python module's `render` all go through here. The wall time counts from the
/// building of the tracer.
pub fn render_plan(
    scene: &Scene,
    plan: &Plan,
    progress: &dyn Progress,
) -> Result<(DataFile, RenderStats), RenderError> {
    let started = Instant::now();
    let renderer = Renderer::new(scene)?;
    let mut assembler = Assembler::new(renderer.blank(), renderer.tiles());
    let mut stats = renderer.run(plan, &mut assembler, progress);
    stats.wall = started.elapsed();
    Ok((assembler.finish(), stats))
}

impl Renderer<'_> {
    /// Traces the tiles of `plan` and returns them in index order.
    pub fn trace(&self, plan: &Plan, progress: &dyn Progress) -> Vec<TileData> {
        let mut out: Vec<TileData> = Vec::new();
        self.run(plan, &mut out, progress);
        out.sort_by_key(|t| t.index);
        out
    }
}
