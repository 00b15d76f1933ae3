//! `shade_pair`: a stereo pair's picture as `godel shade NAME.left.exr -o x.png` makes it:
//! both eyes shaded with the settings over the left eye's defaults, composed in the pair's
//! layout by `shade::stereo::compose`, the command line's own composition.

use pyo3::prelude::*;
use pyo3::types::PyByteArray;
use scene::Layout;
use shade::{ShadeError, Shading};

use crate::data::{settings, Data};
use crate::errors::{argument_error, value_error};

/// The layouts by the names scene files give them.
const LAYOUTS: [Layout; 3] = [Layout::SideBySide, Layout::OverUnder, Layout::Anaglyph];

/// The picture of the pair `left`, `right` (8-bit sRGB, row 0 on top) in `layout`, shaded
/// with the settings of a settings file (JSON text). Returns (width, height, bytes).
#[pyfunction]
pub fn shade_pair<'py>(
    py: Python<'py>,
    left: &Data,
    right: &Data,
    layout: &str,
    settings_json: &str,
) -> PyResult<(u32, u32, Bound<'py, PyByteArray>)> {
    let Some(layout) = LAYOUTS.into_iter().find(|l| l.name() == layout) else {
        let names: Vec<&str> = LAYOUTS.iter().map(|l| l.name()).collect();
        let message = format!("must be one of {}, got {layout:?}", names.join(", "));
        return Err(argument_error("layout", message));
    };
    let (left, right) = (left.data(), right.data());
    if left.picture_size() != right.picture_size() {
        return Err(value_error("the two eyes' pictures differ in size"));
    }
    let picture = py
        .detach(|| -> Result<_, ShadeError> {
            // As `godel shade` of the left eye's file: its defaults, for both eyes.
            let settings = settings(left, settings_json)?;
            let ours = Shading::new(left, &settings)?.image(left);
            let theirs = Shading::new(right, &settings)?.image(right);
            Ok(shade::stereo::compose(layout, &ours, &theirs))
        })
        .map_err(value_error)?;
    let (w, h) = picture.dimensions();
    Ok((w, h, PyByteArray::new(py, &picture.into_raw())))
}
