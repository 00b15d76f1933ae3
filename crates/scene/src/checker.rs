//! Located checks of single values (finite, positive, a direction, a velocity, a
//! position, a name…), each failure a [`SceneError`] at the offending value: the pieces
//! `validate.rs` and `objects.rs` build the scene with.

use crate::error::{Locator, SceneError};
use crate::raw::RawPosition;
use spacetime::{Event, LocalVelocity};

pub(crate) type Result<T> = std::result::Result<T, SceneError>;

pub(crate) struct Checker<'a> {
    pub loc: &'a Locator<'a>,
}

impl Checker<'_> {
    pub(crate) fn err<T>(&self, path: &str, message: impl Into<String>) -> Result<T> {
        Err(self.loc.at_path(path, message))
    }

    pub(crate) fn finite(&self, path: &str, v: f64) -> Result<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            self.err(path, format!("must be a finite number, got {v}"))
        }
    }

    pub(crate) fn positive(&self, path: &str, v: f64) -> Result<f64> {
        let v = self.finite(path, v)?;
        if v > 0.0 {
            Ok(v)
        } else {
            self.err(path, format!("must be positive, got {}", crate::short(v)))
        }
    }

    pub(crate) fn non_negative(&self, path: &str, v: f64) -> Result<f64> {
        let v = self.finite(path, v)?;
        if v >= 0.0 {
            Ok(v)
        } else {
            self.err(
                path,
                format!("must not be negative, got {}", crate::short(v)),
            )
        }
    }

    pub(crate) fn color(&self, path: &str, c: [f64; 3]) -> Result<[f64; 3]> {
        for (i, v) in c.iter().enumerate() {
            self.non_negative(&format!("{path}[{i}]"), *v)?;
        }
        Ok(c)
    }

    /// A non-zero finite vector, normalized.
    pub(crate) fn direction(&self, path: &str, v: [f64; 3]) -> Result<[f64; 3]> {
        for (i, c) in v.iter().enumerate() {
            self.finite(&format!("{path}[{i}]"), *c)?;
        }
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.0 && n.is_finite() {
            return Ok([v[0] / n, v[1] / n, v[2] / n]);
        }
        // Components whose squares overflow or vanish (1e200, 1e-200): scaled first.
        match spacetime::scaled_unit(v) {
            Some(unit) => Ok(unit),
            None => self.err(path, format!("must be a non-zero direction, got {v:?}")),
        }
    }

    pub(crate) fn velocity(
        &self,
        path: &str,
        speed: f64,
        direction: Option<[f64; 3]>,
    ) -> Result<LocalVelocity> {
        let speed_path = format!("{path}.speed");
        let speed = self.finite(&speed_path, speed)?;
        if !(0.0..1.0).contains(&speed) {
            return self.err(
                &speed_path,
                format!(
                    "must be in [0, 1) (a fraction of light speed), got {}",
                    crate::short(speed)
                ),
            );
        }
        let dir = self.direction(
            &format!("{path}.direction"),
            direction.unwrap_or([1.0, 0.0, 0.0]),
        )?;
        match LocalVelocity::new(speed, dir) {
            Some(v) => Ok(v),
            None => self.err(path, "is not a valid velocity"),
        }
    }

    pub(crate) fn position(&self, path: &str, p: RawPosition, t: f64) -> Result<Event> {
        let cyl = p.r.is_some() || p.phi.is_some();
        let cart = p.x.is_some() || p.y.is_some();
        if cyl && cart {
            return self.err(path, "give either { r, phi, z } (cylindrical) or { x, y, z } (pseudo-Cartesian), not both");
        }
        let z = self.finite(&format!("{path}.z"), p.z.unwrap_or(0.0))?;
        if cyl {
            let r = self.non_negative(&format!("{path}.r"), p.r.unwrap_or(0.0))?;
            let phi = self.finite(&format!("{path}.phi"), p.phi.unwrap_or(0.0))?;
            Ok(Event::new(t, r * phi.cos(), r * phi.sin(), z))
        } else {
            let x = self.finite(&format!("{path}.x"), p.x.unwrap_or(0.0))?;
            let y = self.finite(&format!("{path}.y"), p.y.unwrap_or(0.0))?;
            Ok(Event::new(t, x, y, z))
        }
    }

    pub(crate) fn name(&self, path: &str, name: &str) -> Result<()> {
        if name.trim().is_empty() {
            return self.err(path, "must not be empty");
        }
        if name.chars().any(|c| c.is_control()) {
            return self.err(path, "must not contain control characters");
        }
        Ok(())
    }

    /// Reports a field given where it has no meaning.
    pub(crate) fn unused<T>(&self, path: &str, v: &Option<T>, why: &str) -> Result<()> {
        match v {
            Some(_) => self.err(path, format!("not used {why}")),
            None => Ok(()),
        }
    }

    pub(crate) fn required<T: Copy>(&self, path: &str, v: Option<T>, why: &str) -> Result<T> {
        match v {
            Some(v) => Ok(v),
            None => self.err(path, format!("missing, required {why}")),
        }
    }
}
