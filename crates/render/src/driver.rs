//! The parallel render driver: builds the tracer from a scene, traces all pixels in tiles
//! with rayon, reports progress to a consumer, and assembles the data file.
//!
//! Determinism: every pixel is traced independently from the same shared, immutable
//! tracer, so the records (and the files written from them) are identical whatever the
//! number of threads or the order in which tiles finish.

use crate::datafile::{DataFile, DataHeader, FORMAT_VERSION};
use crate::lighting::LightSource;
use crate::record::{PixelRecord, RayStatus};
use crate::target::Target;
use crate::tracer::Tracer;
use rayon::prelude::*;
use scene::{Scene, TraceMethod};
use spacetime::Spacetime;
use std::time::{Duration, Instant};

/// Tile edge in pixels: small enough to balance rays of very different cost.
const TILE: u32 = 16;

/// Receives progress from the driver (the tracer never learns about terminals or MPI).
pub trait Progress: Sync {
    /// `pixels` more pixels are done.
    fn advance(&self, pixels: u64);
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
    #[error("trace.method = \"exact\" uses the Gödel closed forms: it needs metric = \"godel\"")]
    ExactNeedsGodel,
    #[error("[[light]] sources are traced with the Gödel closed forms (shadow rays): they need metric = \"godel\"")]
    LightsNeedGodel,
}

/// Builds the shared tracer of a scene.
pub fn build_tracer(scene: &Scene) -> Result<Tracer, RenderError> {
    if scene.trace.method == TraceMethod::Exact && scene.metric.godel_a().is_none() {
        return Err(RenderError::ExactNeedsGodel);
    }
    if !scene.lights.is_empty() && scene.metric.godel_a().is_none() {
        return Err(RenderError::LightsNeedGodel);
    }
    let m = scene.metric;
    let obs = scene.observer;
    let frame = m.observer_frame(obs.event, obs.velocity);
    // Worldlines cover the traced time range plus a margin for the objects' own size, and
    // with lights the range of their shadow rays (emitted up to max_past before a hit).
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
    Ok(Tracer::new(
        m,
        obs.event,
        frame,
        targets,
        scene.trace.max_past,
        scene.trace.tolerance,
        scene.trace.max_steps,
        scene.trace.method == TraceMethod::Exact,
    )
    .with_lights(scene.lights.iter().map(LightSource::from_scene).collect()))
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
        method: match scene.trace.method {
            TraceMethod::Numeric => "numeric".into(),
            TraceMethod::Exact => "exact".into(),
        },
        object_names: scene.objects.iter().map(|o| o.name.clone()).collect(),
    }
}

/// The rectangle of pixels of one tile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    pub col0: u32,
    pub row0: u32,
    pub cols: u32,
    pub rows: u32,
}

/// All tiles of a width × height image, in row-major order.
pub fn tiles(width: u32, height: u32) -> Vec<Tile> {
    let mut out = Vec::new();
    for row0 in (0..height).step_by(TILE as usize) {
        for col0 in (0..width).step_by(TILE as usize) {
            out.push(Tile {
                col0,
                row0,
                cols: TILE.min(width - col0),
                rows: TILE.min(height - row0),
            });
        }
    }
    out
}

/// Traces the pixels of `tile` (row-major within the tile).
pub fn trace_tile(
    scene: &Scene,
    tracer: &Tracer,
    tile: Tile,
    scratch: &mut crate::tracer::Scratch,
) -> Vec<PixelRecord> {
    let mut out = Vec::with_capacity((tile.cols * tile.rows) as usize);
    // Each tile starts afresh (see `Scratch::first_step`), so that the records do not depend
    // on which thread traced which tiles before.
    scratch.reset_first_step();
    for row in tile.row0..tile.row0 + tile.rows {
        for col in tile.col0..tile.col0 + tile.cols {
            out.push(
                match scene.observer.pixel_direction(&scene.camera, col, row) {
                    Some(n) => tracer.trace(n, scratch),
                    None => PixelRecord::miss(RayStatus::NotTraced),
                },
            );
        }
    }
    out
}

/// Traces the pixels of `tile` with direct illumination: the records, and the light
/// values pixel-major (`scene.lights.len()` per pixel, in the records' order).
pub fn trace_tile_lit(
    scene: &Scene,
    tracer: &Tracer,
    tile: Tile,
    scratch: &mut crate::tracer::Scratch,
) -> (Vec<PixelRecord>, Vec<f32>) {
    let n = scene.lights.len();
    if n == 0 {
        return (trace_tile(scene, tracer, tile, scratch), Vec::new());
    }
    let pixels = (tile.cols * tile.rows) as usize;
    let (mut records, mut lights) = (Vec::with_capacity(pixels), vec![0.0; pixels * n]);
    scratch.reset_first_step();
    let mut i = 0;
    for row in tile.row0..tile.row0 + tile.rows {
        for col in tile.col0..tile.col0 + tile.cols {
            records.push(
                match scene.observer.pixel_direction(&scene.camera, col, row) {
                    Some(dir) => {
                        let r = tracer.trace(dir, scratch);
                        tracer.illuminate(scratch, &mut lights[i * n..(i + 1) * n]);
                        r
                    }
                    None => PixelRecord::miss(RayStatus::NotTraced),
                },
            );
            i += 1;
        }
    }
    (records, lights)
}

/// Renders the whole scene on rayon's thread pool.
pub fn render(
    scene: &Scene,
    progress: &dyn Progress,
) -> Result<(DataFile, RenderStats), RenderError> {
    let started = Instant::now();
    let tracer = build_tracer(scene)?;
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let tiles = tiles(w, h);
    let n = scene.lights.len();
    // Each tile goes into the image as soon as it is traced, so that its buffers are
    // reused by the next tile: collecting every tile first held a second copy of all
    // records (kept by the allocator after it was freed), ~56 bytes a pixel.
    let image = std::sync::Mutex::new((
        vec![PixelRecord::MISS; (w * h) as usize],
        vec![vec![0.0f32; (w * h) as usize]; n],
    ));
    tiles.par_iter().for_each_init(
        || tracer.scratch(),
        |scratch, &tile| {
            let (recs, lit) = trace_tile_lit(scene, &tracer, tile, scratch);
            progress.advance(recs.len() as u64);
            let mut guard = image.lock().unwrap_or_else(|e| e.into_inner());
            let (records, lights) = &mut *guard;
            for (i, r) in recs.into_iter().enumerate() {
                let (c, rr) = (
                    tile.col0 + i as u32 % tile.cols,
                    tile.row0 + i as u32 / tile.cols,
                );
                let at = (rr * w + c) as usize;
                records[at] = r;
                for (k, plane) in lights.iter_mut().enumerate() {
                    plane[at] = lit[i * n + k];
                }
            }
        },
    );
    let (records, lights) = image.into_inner().unwrap_or_else(|e| e.into_inner());
    let mut stats = RenderStats::count(&records);
    stats.wall = started.elapsed();
    let data = DataFile {
        header: header(scene),
        width: w as usize,
        height: h as usize,
        records,
        lights,
    };
    Ok((data, stats))
}
