//! `datafile`: what a traced image stores, apart from the tracer that fills it, so that the
//! shaders and the viewer read it without compiling the tracer.
//!
//! - [`record`]: [`PixelRecord`] and [`RayStatus`], what one pixel's ray found.
//! - The data file ([`DataFile`], [`DataHeader`]): one OpenEXR file per traced image with one
//!   named channel per record field, read back without re-tracing (see [`attr`] for its
//!   header attributes, part files of split renders included).
//! - [`DataFile::planes`]: every channel as a named [`Plane`] of values, NaN where there is
//!   none, exactly as the file stores them (`planes.rs`).
//! - Samples (`samples.rs`): an anti-aliased file keeps s×s records per picture pixel;
//!   [`DataFile::picture_size`], [`DataFile::sample_indices`] and the box filter
//!   [`DataFile::box_filter`] that every shader applies after colouring each sample.
//! - [`exr_bytes`]: an OpenEXR image written into memory, deterministically (the data file's
//!   and the shaders' linear pictures).
//! - [`memory`]: work sized against the memory the machine has, before it starts.
//! - [`atomic`]: every output file is written to a temporary file and renamed, several files
//!   together where they belong together; temporaries are removed on signals and swept.
//! - [`folders`]: output folders a run creates, removed again where a failed run left them empty.

pub mod atomic;
mod codec;
mod exr_write;
pub mod folders;
pub mod memory;
mod planes;
pub mod record;
mod samples;

pub use codec::*;
pub use exr_write::exr_bytes;
pub use planes::{light_channel_name, Plane};
pub use record::{PixelRecord, RayStatus};
pub use samples::MAX_SUPERSAMPLE;
