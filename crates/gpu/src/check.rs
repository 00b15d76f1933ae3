//! Holds a GPU trace to the CPU exact tracer on a few of its samples before its records are
//! used: a driver that compiles the kernel but runs it wrongly (as one NVIDIA driver did,
//! docs/physics.md "The GPU kernel") is refused, never written as godel's result.
//!
//! The check samples are spread at a fixed stride over the samples the GPU saw an object in
//! and over the others it traced ([`CHECKS_PER_SIDE`] at most of each, so the check is the
//! same on every run and costs a few hundred CPU rays). Each is traced again by
//! `render::driver::Renderer` with the exact method, and its status and object compared.
//! Single precision may move a grazing sample across an edge; more disagreements than
//! [`allowed`] mark the trace as wrong. A sample the GPU marked as out of work where the CPU
//! finished counts as a disagreement: the kernel's bounds are the CPU's (docs/physics.md,
//! "Bounds of a GPU").

use datafile::{PixelRecord, RayStatus};
use render::driver::{RenderError, Renderer};
use scene::{Scene, TraceMethod};

/// Most check samples among the GPU's hits, and among its other traced samples.
pub const CHECKS_PER_SIDE: usize = 128;

/// What the check found wrong.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    #[error("the CPU check could not be set up: {0}")]
    Setup(#[from] RenderError),
    #[error(
        "the GPU ({renderer}) disagrees with the CPU exact tracer on {differ} of {checked} check samples \
         (e.g. sample column {col}, row {row}: GPU {gpu}, CPU {cpu})"
    )]
    Disagrees {
        renderer: String,
        checked: usize,
        differ: usize,
        col: u32,
        row: u32,
        gpu: String,
        cpu: String,
    },
}

/// Disagreements tolerated among `checked` samples: 2 %, and at least 2.
pub fn allowed(checked: usize) -> usize {
    (checked / 50).max(2)
}

/// Checks the GPU's `records` (the sample grid of `scene`, row-major) traced on `renderer`.
pub fn against_cpu(
    scene: &Scene,
    records: &[PixelRecord],
    renderer: &str,
) -> Result<(), CheckError> {
    let mut exact = scene.clone();
    exact.trace.method = TraceMethod::Exact;
    let cpu = Renderer::new(&exact)?;
    let width = cpu.sample_camera().width() as usize;
    // The two sides by a predicate each, counted first: the strides follow, without a list
    // of indices as long as the image (up to `scene::camera::MAX_RAYS`).
    let hit = |r: &PixelRecord| r.status == RayStatus::Hit;
    let other = |r: &PixelRecord| !matches!(r.status, RayStatus::Hit | RayStatus::NotTraced);
    let mut scratch = cpu.scratch();
    let mut lit = vec![0.0f32; scene.lights.len()];
    let (mut checked, mut differ, mut first) = (0, 0, None);
    for side in [&hit as &dyn Fn(&PixelRecord) -> bool, &other] {
        let count = records.iter().filter(|r| side(r)).count();
        let stride = count.div_ceil(CHECKS_PER_SIDE).max(1);
        let chosen = records
            .iter()
            .enumerate()
            .filter(|(_, r)| side(r))
            .step_by(stride);
        for (i, gpu) in chosen {
            let (col, row) = ((i % width) as u32, (i / width) as u32);
            let cpu = cpu.trace_sample(col, row, &mut scratch, &mut lit);
            checked += 1;
            if gpu.status != cpu.status || gpu.object != cpu.object {
                differ += 1;
                first.get_or_insert((col, row, describe(gpu), describe(&cpu)));
            }
        }
    }
    match first {
        Some((col, row, gpu, cpu)) if differ > allowed(checked) => Err(CheckError::Disagrees {
            renderer: renderer.to_string(),
            checked,
            differ,
            col,
            row,
            gpu,
            cpu,
        }),
        _ => Ok(()),
    }
}

/// A record's outcome in words: "hit object 1" or the status.
fn describe(r: &PixelRecord) -> String {
    match r.status {
        RayStatus::Hit => format!("hit object {}", r.object),
        RayStatus::WorkLimit => "out of work (work limit)".to_string(),
        RayStatus::NotTraced => "not traced".to_string(),
        s => format!("{s:?}").to_lowercase(),
    }
}
