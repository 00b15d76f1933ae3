//! `render`: tracing a scene into per-pixel records, and storing them.
//!
//! - [`record`]: [`record::PixelRecord`], what one pixel's ray found.
//! - [`datafile`]: [`datafile::DataFile`], the per-pixel data file (OpenEXR).
//! - [`atomic`]: write-to-temporary-then-rename for every output file.
//! - [`tiles`]: trace any set of tiles, assemble data files from tiles (split and MPI runs).
//! - [`part`]: `--part i/N` part files and their merge.
//! - [`look`]: any camera of any observer at the event of a full-sphere trace, without
//!   tracing (aberration and Doppler shift of the static observer's records).

pub mod atomic;
pub mod bounds;
pub mod datafile;
pub mod driver;
pub mod lighting;
pub mod look;
pub mod part;
pub mod record;
pub mod target;
pub mod tiles;
pub mod tracer;
pub mod worldline;
