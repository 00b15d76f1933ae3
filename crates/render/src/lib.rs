//! `render`: tracing a scene into per-pixel records, and storing them.
//!
//! - [`record`]: [`record::PixelRecord`], what one pixel's ray found.
//! - [`datafile`]: [`datafile::DataFile`], the per-pixel data file (OpenEXR).
//! - [`atomic`]: write-to-temporary-then-rename for every output file.
//! - [`tiles`]: trace any set of tiles, assemble data files from tiles (split and MPI runs).
//! - [`part`]: `--part i/N` part files and their merge.

pub mod atomic;
pub mod bounds;
pub mod datafile;
pub mod driver;
pub mod intersect;
pub mod lighting;
pub mod part;
pub mod record;
pub mod segment;
pub mod target;
pub mod tiles;
pub mod tracer;
pub mod worldline;
