//! `render`: tracing a scene into per-pixel records (stored by the `datafile` crate).
//!
//! - [`driver`]: [`driver::Renderer`] traces the tiles of a plan and hands each to a
//!   [`tiles::Sink`] (the data-file [`tiles::Assembler`] of an image or a part; a list of
//!   tiles for MPI).
//! - [`tracer`]: one pixel's backward light ray, numeric or exact, and its record;
//!   [`polarization`]: the pixel's polarization vector carried along it.
//! - [`intersect`]: the bounded intersection search shared by pixel and shadow rays, over
//!   the [`segment`]s of a ray; [`target`]: the objects' signed distances and surfaces;
//!   [`worldline`]: the objects' worldlines and body frames; [`chord`]: ruling out grazes
//!   of a local ball by its rest-frame chord; [`bounds`]: boxes;
//!   [`reject`]: whole-ray rejection of objects at rest, and loop by loop of balls in free
//!   fall ([`falling`]), with the rays' circles ([`circle`]) and their fast angles
//!   ([`angles`]).
//! - [`lighting`]: direct light from point sources by shadow rays.
//! - [`plan`]: tiles and plans of work; [`tiles`]: traced tiles and sinks; [`part`]:
//!   `--part i/N` part files and their merge.
//! - [`threads`]: the worker pool, its size checked (at most 8 threads per core).
//! - [`map`]: what the explore map draws (horizon, balls and their tracks, a pixel's ray).
//! - `probe_count` (feature `count-probes`): how many probes the objects answered, for
//!   `examples/probes.rs`.

// `!(a < b)` is how this crate writes "not a < b, NaN included" (a NaN must fail the
// test); per-axis loops over [f64; 3]; `Worldline::Free` is large, and boxing it would
// add an indirection to every probe.
#![allow(
    clippy::neg_cmp_op_on_partial_ord,
    clippy::needless_range_loop,
    clippy::large_enum_variant
)]

pub mod angles;
pub mod bounds;
pub mod chart;
pub mod chord;
pub mod circle;
pub mod driver;
pub mod falling;
pub mod intersect;
pub mod lighting;
pub mod map;
pub mod part;
pub mod plan;
pub mod polarization;
#[cfg(feature = "count-probes")]
pub mod probe_count;
pub mod reject;
pub mod segment;
pub mod target;
pub mod threads;
pub mod tiles;
pub mod tracer;
pub mod worldline;
