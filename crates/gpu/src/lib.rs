//! `gpu`: godel's exact tracer as one GLSL ES 3.00 kernel ([`KERNEL`], `src/kernel.glsl`),
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

/// The kernel's source (without `#version` and the defines its host prepends).
pub const KERNEL: &str = include_str!("kernel.glsl");

pub use host::{GpuTracer, HostError, Tiling, Traced};
pub use input::KernelInput;
pub use render::{render, render_with, GpuRender};
