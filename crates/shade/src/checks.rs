//! Checks of settings values shared by the prepared shader: each failure is a
//! [`ShadeError::Invalid`] naming the settings field.

use crate::error::ShadeError;

/// An invalid settings value.
pub(crate) fn invalid(field: impl Into<String>, message: impl Into<String>) -> ShadeError {
    ShadeError::Invalid {
        field: field.into(),
        message: message.into(),
    }
}

pub(crate) fn finite(field: &str, v: f64) -> Result<f64, ShadeError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(invalid(field, format!("must be finite, got {v}")))
    }
}

pub(crate) fn positive(field: &str, v: f64) -> Result<f64, ShadeError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(invalid(
            field,
            format!("must be positive and finite, got {v}"),
        ))
    }
}

pub(crate) fn non_negative(field: &str, v: f64) -> Result<f64, ShadeError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(invalid(field, format!("must be finite and ≥ 0, got {v}")))
    }
}

pub(crate) fn colour(field: &str, c: [f64; 3]) -> Result<[f32; 3], ShadeError> {
    for (i, v) in c.iter().enumerate() {
        non_negative(&format!("{field}[{i}]"), *v)?;
    }
    Ok(c.map(|v| v as f32))
}

pub(crate) fn nonzero(field: &str, v: f64) -> Result<f64, ShadeError> {
    if v.is_finite() && v != 0.0 {
        Ok(v)
    } else {
        Err(invalid(
            field,
            format!("must be finite and non-zero, got {v}"),
        ))
    }
}
