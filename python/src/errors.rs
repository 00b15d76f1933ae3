//! The command line's error messages as Python exceptions (docs/guide/src/python.md): bad input
//! (a scene, a setting, an argument) is a `ValueError` with the text `godel` prints after
//! `error: `, naming the file, line and field, or the keyword argument where the command line
//! names its flag, and an empty path naming its keyword argument. A file that cannot be read
//! or written is an `OSError`: `FileNotFoundError` when missing, `IsADirectoryError` for a
//! folder where a file belongs (with a message that says so, not an input/output fault). A
//! file named inside the input (a scene's or the shade settings' image texture) is part of
//! that input: a `ValueError` naming it, as the command line refuses it.

use std::path::Path;

use datafile::{DataFileError, DataFileErrorKind};
use pyo3::exceptions::{PyFileNotFoundError, PyIsADirectoryError, PyOSError, PyValueError};
use pyo3::PyErr;

/// Bad input: `ValueError(message)`.
pub fn value_error(message: impl ToString) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// Bad input about keyword argument `keyword`: `ValueError("keyword: message")`.
pub fn argument_error(keyword: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{keyword}: {message}"))
}

/// Checks a path given as keyword argument `keyword` that must name `what` (`a data file`):
/// an empty one is a `ValueError` naming `keyword`, an existing folder `IsADirectoryError`.
pub fn file_argument(keyword: &str, path: &Path, what: &str) -> Result<(), PyErr> {
    if path.as_os_str().is_empty() {
        return Err(argument_error(
            keyword,
            format!("an empty path, not {what}"),
        ));
    }
    if path.is_dir() {
        return Err(folder_error(path, what));
    }
    Ok(())
}

/// `IsADirectoryError("PATH: is a folder, not WHAT")`.
fn folder_error(path: &Path, what: &str) -> PyErr {
    PyIsADirectoryError::new_err(format!("{}: is a folder, not {what}", path.display()))
}

/// An input/output failure: `FileNotFoundError`, `IsADirectoryError` or `OSError`.
pub fn io_error(e: &std::io::Error, message: impl ToString) -> PyErr {
    let message = message.to_string();
    match e.kind() {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
        std::io::ErrorKind::IsADirectory => PyIsADirectoryError::new_err(message),
        _ => PyOSError::new_err(message),
    }
}

/// A data file that could not be read or written: an `OSError` for input/output (a folder
/// found there meanwhile: `IsADirectoryError`), else a `ValueError` (the file is not a data
/// file, or damaged).
pub fn data_file_error(e: DataFileError) -> PyErr {
    match &e.kind {
        DataFileErrorKind::Io(_) if e.path.is_dir() => folder_error(&e.path, "a data file"),
        DataFileErrorKind::Io(io) => io_error(io, &e),
        _ => value_error(e),
    }
}
