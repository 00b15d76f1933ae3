//! `godel._godel`: the native half of the Python package `godel` (python/godel), calling the
//! workspace's crates directly. The Python half shapes the API (numpy arrays, the progress
//! bar, docstrings and type hints); this half does the work, through the same code paths as
//! the command line:
//!
//! - [`job`]: `RenderJob`, a render on its own thread (`render::driver::render`, as `godel
//!   render`), with progress and cancellation between tiles;
//! - [`data`]: `Data`, a traced image (`datafile::DataFile`): its channels as the file stores
//!   them, shading as `godel shade`, reading and writing the data file;
//! - [`stereo`]: `shade_pair`, a stereo pair's picture in its layout, as `godel shade`;
//! - [`rays`]: `geodesic` and `connect` (`spacetime::curve`, `spacetime::connection`, as
//!   `godel geodesic` and `godel connect`), computed without the GIL;
//! - [`errors`]: the command line's messages as Python exceptions.

use pyo3::prelude::*;

mod data;
mod errors;
mod job;
mod rays;
mod stereo;

/// The native half of `godel`: use the functions of the `godel` package instead.
#[pymodule]
fn _godel(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<job::RenderJob>()?;
    m.add_class::<data::Data>()?;
    m.add_function(wrap_pyfunction!(rays::geodesic, m)?)?;
    m.add_function(wrap_pyfunction!(rays::connect, m)?)?;
    m.add_function(wrap_pyfunction!(stereo::shade_pair, m)?)?;
    Ok(())
}
