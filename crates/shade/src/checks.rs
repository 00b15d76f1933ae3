//! Checks of settings values shared by the prepared shader: each failure is a
//! [`ShadeError::Invalid`] naming the settings field.

use std::collections::HashSet;
use std::hash::Hash;

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

/// `v` normalized: finite components, not all zero (the polarization axis).
pub(crate) fn direction(field: &str, v: [f64; 3]) -> Result<[f64; 3], ShadeError> {
    for (i, c) in v.iter().enumerate() {
        finite(&format!("{field}[{i}]"), *c)?;
    }
    match spacetime::scaled_unit(v) {
        Some(unit) => Ok(unit),
        None => Err(invalid(
            field,
            format!("must be a non-zero direction, got {v:?}"),
        )),
    }
}

/// The first of `keys` that is not among `known`, or `None`: one pass over each through a
/// hash set, so that the settings of 100,000 objects are checked in linear time (a search of
/// the name list per key was quadratic).
pub(crate) fn first_unknown<'a, K: Hash + Eq + ?Sized>(
    known: impl IntoIterator<Item = &'a K>,
    keys: impl IntoIterator<Item = &'a K>,
) -> Option<&'a K> {
    let known: HashSet<&K> = known.into_iter().collect();
    keys.into_iter().find(|k| !known.contains(k))
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;
    use std::hash::{Hash, Hasher};

    use super::first_unknown;

    thread_local! {
        /// Equality tests and hashes done on [`Counted`] keys.
        static OPERATIONS: Cell<usize> = const { Cell::new(0) };
    }

    /// A key that counts the work done with it.
    #[derive(Debug)]
    struct Counted(String);

    impl PartialEq for Counted {
        fn eq(&self, other: &Counted) -> bool {
            OPERATIONS.with(|c| c.set(c.get() + 1));
            self.0 == other.0
        }
    }
    impl Eq for Counted {}
    impl Hash for Counted {
        fn hash<H: Hasher>(&self, state: &mut H) {
            OPERATIONS.with(|c| c.set(c.get() + 1));
            self.0.hash(state);
        }
    }

    /// The check of N object names against N settings keys does O(N) work: a few operations
    /// per key, where a search of the name list per key would do ~N²/2 = 5·10⁷ at N = 10⁴.
    #[test]
    fn unknown_object_names_are_found_in_linear_work() {
        let n = 10_000;
        let known: Vec<Counted> = (0..n).map(|k| Counted(format!("object{k}"))).collect();
        // The settings list every object in reverse order, then one unknown name.
        let mut keys: Vec<Counted> = (0..n)
            .rev()
            .map(|k| Counted(format!("object{k}")))
            .collect();
        keys.push(Counted("moon".into()));
        OPERATIONS.with(|c| c.set(0));
        let unknown = first_unknown(&known, &keys);
        let operations = OPERATIONS.with(Cell::get);
        assert_eq!(unknown.map(|k| k.0.as_str()), Some("moon"));
        assert!(
            operations <= 10 * (2 * n + 1),
            "{operations} operations for {n} names: not linear"
        );
        // Every key known: none reported.
        assert!(first_unknown(&known, &keys[..n]).is_none());
    }
}
