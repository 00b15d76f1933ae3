//! `Data`: a traced image in memory (`datafile::DataFile`), as a render made it or a data file
//! holds it. Its channels go out exactly as the data file stores them (`DataFile::planes`:
//! NaN where there is no value), as raw native-endian bytes that the Python half views as
//! numpy arrays; shading is `godel shade`'s (`shade::Shading`, settings as a settings file);
//! reading and writing are the data file's own (`DataFile::read`, `DataFile::write`, atomic).

use std::path::PathBuf;

use datafile::{DataFile, Plane};
use pyo3::prelude::*;
use pyo3::types::PyByteArray;
use shade::hdr::PictureFormat;
use shade::{ShadeError, ShadeSettings, Shading};

use crate::errors::{argument_error, data_file_error, file_argument, value_error};

/// A traced image (use `godel.Image`, which wraps it).
#[pyclass(module = "godel._godel", frozen)]
pub struct Data {
    data: DataFile,
}

impl Data {
    pub fn new(data: DataFile) -> Data {
        Data { data }
    }

    /// The traced image.
    pub fn data(&self) -> &DataFile {
        &self.data
    }
}

/// The settings of a settings file given as JSON text (a Python dict), over the data file's
/// defaults; errors name the field as `godel shade` does.
pub fn settings(data: &DataFile, json: &str) -> Result<ShadeSettings, ShadeError> {
    let invalid = |field: String, message: String| ShadeError::Invalid { field, message };
    let partial: toml::Table =
        serde_json::from_str(json).map_err(|e| invalid(String::new(), e.to_string()))?;
    ShadeSettings::defaults_for(data)
        .overlay(&partial)
        .map_err(|(field, message)| invalid(field, message))
}

#[pymethods]
impl Data {
    /// Reads a data file that `godel` wrote (not a part file: merge parts first).
    #[staticmethod]
    fn read(py: Python<'_>, path: PathBuf) -> PyResult<Data> {
        file_argument("path", &path, "a data file")?;
        let data = py
            .detach(|| DataFile::read(&path))
            .map_err(data_file_error)?;
        Ok(Data { data })
    }

    /// Writes the data file to `path` (through a temporary file and a rename). The name must
    /// end in `.exr`, in any case: the rule by which the command line's `-o` tells a data
    /// file's name (`PictureFormat::from_path`; `.png` is a picture's).
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let what = "the name of the data file to write (.exr)";
        file_argument("path", &path, what)?;
        if PictureFormat::from_path(&path) != Some(PictureFormat::Exr) {
            let message = format!(
                "must name the data file to write (.exr), got {}; rgb() and hdr() give pictures",
                path.display()
            );
            return Err(argument_error("path", message));
        }
        py.detach(|| self.data.write(&path))
            .map_err(data_file_error)
    }

    /// Stored width and height (samples, not picture pixels).
    #[getter]
    fn size(&self) -> (usize, usize) {
        (self.data.width, self.data.height)
    }

    /// Samples per picture pixel along each side.
    #[getter]
    fn supersample(&self) -> usize {
        self.data.supersample()
    }

    /// The scene as rendered (TOML text).
    #[getter]
    fn scene(&self) -> &str {
        &self.data.header.scene_text
    }

    /// Header fields: scene name, camera, observer time, metric, a, method, object names.
    fn header<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let h = &self.data.header;
        let d = pyo3::types::PyDict::new(py);
        d.set_item("scene_name", &h.scene_name)?;
        d.set_item("camera", &h.camera)?;
        d.set_item("observer_time", h.observer_time)?;
        d.set_item("metric", &h.metric)?;
        d.set_item("a", h.godel_a)?;
        if let Some(m) = h.member {
            d.set_item("m2", m.m2)?;
            d.set_item("omega", m.omega)?;
        }
        d.set_item("method", &h.method)?;
        d.set_item("objects", h.object_names.clone())?;
        Ok(d)
    }

    /// Every channel as (name, numpy dtype, bytes), the values as the data file stores them.
    fn planes<'py>(&self, py: Python<'py>) -> Vec<(String, &'static str, Bound<'py, PyByteArray>)> {
        let planes = py.detach(|| self.data.planes());
        planes
            .into_iter()
            .map(|(name, plane)| {
                let (dtype, bytes): (_, Vec<u8>) = match plane {
                    Plane::F32(v) => ("=f4", v.iter().flat_map(|x| x.to_ne_bytes()).collect()),
                    Plane::U32(v) => ("=u4", v.iter().flat_map(|x| x.to_ne_bytes()).collect()),
                };
                (name, dtype, PyByteArray::new(py, &bytes))
            })
            .collect()
    }

    /// Shades the image as `godel shade` does with a settings file of these fields (JSON
    /// text): 8-bit sRGB as a PNG holds it, or with `linear` the linear RGB of an `.exr`
    /// picture (native f32). Returns (width, height, bytes), row 0 on top.
    fn shade<'py>(
        &self,
        py: Python<'py>,
        settings_json: &str,
        linear: bool,
    ) -> PyResult<(usize, usize, Bound<'py, PyByteArray>)> {
        let data = &self.data;
        let bytes = py
            .detach(|| -> Result<Vec<u8>, ShadeError> {
                let shading = Shading::new(data, &settings(data, settings_json)?)?;
                Ok(if linear {
                    let rgb = shading.linear(data);
                    rgb.iter().flatten().flat_map(|x| x.to_ne_bytes()).collect()
                } else {
                    shading.image(data).into_raw()
                })
            })
            .map_err(value_error)?;
        let (w, h) = data.picture_size();
        Ok((w, h, PyByteArray::new(py, &bytes)))
    }
}
