//! The command line's error messages as Python exceptions: bad input (a scene, a setting, an
//! argument) is a `ValueError` with the text `godel` prints after `error: `, naming the file,
//! line and field, or the keyword argument where the command line names its flag; a file
//! that cannot be read or written is an `OSError` (`FileNotFoundError` when missing).

use datafile::{DataFileError, DataFileErrorKind};
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyValueError};
use pyo3::PyErr;

/// Bad input: `ValueError(message)`.
pub fn value_error(message: impl ToString) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// Bad input about keyword argument `keyword`: `ValueError("keyword: message")`.
pub fn argument_error(keyword: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{keyword}: {message}"))
}

/// An input/output failure: `FileNotFoundError` or `OSError`.
pub fn io_error(e: &std::io::Error, message: impl ToString) -> PyErr {
    match e.kind() {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message.to_string()),
        _ => PyOSError::new_err(message.to_string()),
    }
}

/// A data file that could not be read or written: an `OSError` for input/output, else a
/// `ValueError` (the file is not a data file, or damaged).
pub fn data_file_error(e: DataFileError) -> PyErr {
    match &e.kind {
        DataFileErrorKind::Io(io) => io_error(io, &e),
        _ => value_error(e),
    }
}
