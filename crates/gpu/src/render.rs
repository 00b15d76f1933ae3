//! A scene's data file traced on the GPU: the kernel's records and light planes under the
//! same header a CPU render writes (method "gpu"), and the render statistics, as
//! `render::driver::render` gives them for the CPU.

use crate::host::{GpuTracer, HostError};
use crate::input::KernelInput;
use datafile::DataFile;
use render::driver::{header, Progress, RenderStats};
use scene::Scene;
use std::time::Instant;

/// What a GPU render produced, and what traced it.
pub struct GpuRender {
    pub data: DataFile,
    pub stats: RenderStats,
    /// The GL renderer that traced (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
    pub renderer: String,
}

/// Traces `scene` with the kernel in an offscreen context (made here, released at the end),
/// and holds the trace to the CPU exact tracer on a few samples ([`crate::check`]): a driver
/// that runs the kernel wrongly is an error, not a data file.
pub fn render(scene: &Scene, progress: &dyn Progress) -> Result<GpuRender, HostError> {
    let done = render_with(scene, crate::KERNEL, progress)?;
    if !progress.cancelled() {
        crate::check::against_cpu(scene, &done.data.records, &done.renderer)?;
    }
    Ok(done)
}

/// The same with another kernel source (see [`GpuTracer::with_kernel`]), unchecked: tests
/// hold mutated kernels to the CPU themselves.
pub fn render_with(
    scene: &Scene,
    kernel: &str,
    progress: &dyn Progress,
) -> Result<GpuRender, HostError> {
    if let Some(why) = crate::input::refusal(scene) {
        return Err(HostError::Unsupported(why));
    }
    let started = Instant::now();
    let tracer = GpuTracer::with_kernel(KernelInput::new(scene), kernel)?;
    let traced = tracer.trace(progress)?;
    let camera = scene.sample_camera();
    let data = DataFile {
        header: datafile::DataHeader {
            method: "gpu".into(),
            ..header(scene)
        },
        width: camera.width() as usize,
        height: camera.height() as usize,
        records: traced.records,
        lights: traced.lights,
        polarization: true,
    };
    let stats = RenderStats {
        wall: started.elapsed(),
        ..RenderStats::count(&data.records)
    };
    Ok(GpuRender {
        data,
        stats,
        renderer: tracer.renderer().to_string(),
    })
}
