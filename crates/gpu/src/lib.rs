//! `gpu`: godel's exact tracer as one GLSL ES 3.00 kernel ([`KERNEL`], `src/kernel/`),
//! and its offscreen host.
//!
//! The kernel traces one sample of the camera's sample grid per fragment, as the CPU exact
//! tracer does (docs/physics.md, "The GPU kernel"), and writes the data file's channels into
//! float render targets. Two hosts run the same source: [`host::GpuTracer`] here
//! (`godel render --gpu`: an offscreen EGL / OpenGL ES 3 context, [`context::Context`], with
//! libEGL loaded at run time; [`render()`] makes a scene's data file with it) and the
//! viewer's page (WebGL2). [`input::KernelInput`] is the one packer of what the kernel reads,
//! for both. [`check`] holds every GPU render to the CPU exact tracer on a few samples.

pub mod check;
pub mod context;
pub mod host;
pub mod input;
pub mod probe;
pub mod render;

/// The kernel's source (without `#version` and the defines its host prepends): its chunks
/// in `src/kernel/`, each named after the Rust module it mirrors, in this order (a chunk uses
/// only what the chunks before it declare).
pub const KERNEL: &str = concat!(
    include_str!("kernel/gpu_input.glsl"),
    include_str!("kernel/math.glsl"),
    include_str!("kernel/spacetime_metric.glsl"),
    include_str!("kernel/spacetime_frame.glsl"),
    include_str!("kernel/scene_camera.glsl"),
    include_str!("kernel/spacetime_isometry.glsl"),
    include_str!("kernel/spacetime_closed_form.glsl"),
    include_str!("kernel/spacetime_godel_type.glsl"),
    include_str!("kernel/render_segment.glsl"),
    include_str!("kernel/render_worldline.glsl"),
    include_str!("kernel/render_target.glsl"),
    include_str!("kernel/render_reject.glsl"),
    include_str!("kernel/render_falling.glsl"),
    include_str!("kernel/render_escape.glsl"),
    include_str!("kernel/render_intersect.glsl"),
    include_str!("kernel/render_surface.glsl"),
    include_str!("kernel/render_lighting_family.glsl"),
    include_str!("kernel/render_lighting.glsl"),
    include_str!("kernel/render_tracer.glsl"),
    include_str!("kernel/render_map.glsl"),
);

pub use host::{GpuTracer, HostError, ProbeCount, Tiling, Traced};
pub use input::KernelInput;
pub use render::{render, render_with, GpuRender};
