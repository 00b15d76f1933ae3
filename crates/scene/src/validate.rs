//! Validation: turns the raw scene-file records (`raw.rs`) into the runtime types
//! (`model.rs`), checking every number and every combination of fields, each failure a
//! [`SceneError`] located at the offending value.
//!
//! Defaults where DESIGN.md is silent: a missing `[spacetime]` is Gödel with a = 1; a
//! missing `[observer]` is at rest at the origin at t = 0 looking along e1 with e3 up;
//! position components left out are 0; a missing velocity direction is [1, 0, 0]; a missing
//! `[trace]` is numeric, max_past 30, tolerance 1e-11, 100000 steps; an object's frame is
//! local, its texture a checker 8×16, its temperature 5800 K; fisheye fov is 180°.
//! Objects, motions and textures are checked in `objects.rs`.

use crate::camera::Camera;
use crate::error::{Locator, SceneError};
use crate::model::*;
use crate::raw::*;
use spacetime::{Event, Godel, LocalVelocity, Metric, Minkowski};
use std::collections::HashMap;
use std::path::Path;

pub(crate) type Result<T> = std::result::Result<T, SceneError>;

/// Everything of a [`Scene`] that comes from the file's contents.
pub(crate) struct Parts {
    pub name: String,
    pub metric: Metric,
    pub observer: Observer,
    pub camera: Camera,
    pub trace: TraceSettings,
    pub objects: Vec<Object>,
    pub lights: Vec<Light>,
}

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
            self.err(path, format!("must be positive, got {v}"))
        }
    }

    pub(crate) fn non_negative(&self, path: &str, v: f64) -> Result<f64> {
        let v = self.finite(path, v)?;
        if v >= 0.0 {
            Ok(v)
        } else {
            self.err(path, format!("must not be negative, got {v}"))
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
        if !(n > 0.0 && n.is_finite()) {
            return self.err(path, format!("must be a non-zero direction, got {v:?}"));
        }
        Ok([v[0] / n, v[1] / n, v[2] / n])
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
                format!("must be in [0, 1) (a fraction of light speed), got {speed}"),
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

pub(crate) fn build(raw: RawScene, loc: &Locator, base_dir: &Path) -> Result<Parts> {
    let c = Checker { loc };
    c.name("name", &raw.name)?;
    if raw.name.contains(['/', '\\']) {
        return c.err(
            "name",
            "is used as an output file name and must not contain '/' or '\\'",
        );
    }
    let metric = spacetime(&c, raw.spacetime)?;
    let observer = observer(&c, raw.observer)?;
    let camera = camera(&c, raw.camera)?;
    let trace = trace(&c, raw.trace)?;
    let mut objects = Vec::with_capacity(raw.object.len());
    let mut seen: HashMap<String, usize> = HashMap::new();
    for (i, o) in raw.object.into_iter().enumerate() {
        let path = format!("object[{i}]");
        if let Some(first) = seen.insert(o.name.clone(), i) {
            return c.err(
                &format!("{path}.name"),
                format!("duplicate object name {:?} (also object[{first}])", o.name),
            );
        }
        objects.push(crate::objects::object(&c, &path, o, base_dir)?);
    }
    let mut lights = Vec::with_capacity(raw.light.len());
    for (i, l) in raw.light.into_iter().enumerate() {
        let path = format!("light[{i}]");
        lights.push(Light {
            position: c.position(&format!("{path}.position"), l.position, 0.0)?,
            color: c.color(&format!("{path}.color"), l.color.unwrap_or([1.0; 3]))?,
            power: c.non_negative(&format!("{path}.power"), l.power.unwrap_or(1.0))?,
        });
    }
    Ok(Parts {
        name: raw.name,
        metric,
        observer,
        camera,
        trace,
        objects,
        lights,
    })
}

fn spacetime(c: &Checker, raw: Option<RawSpacetime>) -> Result<Metric> {
    let Some(s) = raw else {
        return Ok(Metric::Godel(Godel::new(1.0)));
    };
    match s.metric.unwrap_or(MetricName::Godel) {
        MetricName::Godel => Ok(Metric::Godel(Godel::new(
            c.positive("spacetime.a", s.a.unwrap_or(1.0))?,
        ))),
        MetricName::Minkowski => {
            c.unused("spacetime.a", &s.a, "by the Minkowski metric")?;
            Ok(Metric::Minkowski(Minkowski))
        }
    }
}

pub(crate) fn observer(c: &Checker, raw: Option<RawObserver>) -> Result<Observer> {
    let Some(o) = raw else {
        return Ok(Observer {
            event: Event::default(),
            velocity: LocalVelocity::REST,
            forward: [1.0, 0.0, 0.0],
            up: [0.0, 0.0, 1.0],
        });
    };
    let t = c.finite("observer.time", o.time.unwrap_or(0.0))?;
    let event = c.position("observer.position", o.position.unwrap_or_default(), t)?;
    let velocity = match o.velocity {
        Some(v) => c.velocity("observer.velocity", v.speed, v.direction)?,
        None => LocalVelocity::REST,
    };
    let forward = c.direction("observer.forward", o.forward.unwrap_or([1.0, 0.0, 0.0]))?;
    let up = c.direction("observer.up", o.up.unwrap_or([0.0, 0.0, 1.0]))?;
    Observer::check_axes(forward, up).or_else(|message| c.err("observer.up", message))?;
    Ok(Observer {
        event,
        velocity,
        forward,
        up,
    })
}

pub(crate) fn camera(c: &Checker, r: RawCamera) -> Result<Camera> {
    let (width, height) = (r.width, r.height);
    let camera = match r.kind {
        CameraKind::Pinhole => {
            c.unused(
                "camera.h_fov_deg",
                &r.h_fov_deg,
                "by a pinhole camera (use fov_deg)",
            )?;
            c.unused(
                "camera.v_fov_deg",
                &r.v_fov_deg,
                "by a pinhole camera (its vertical fov follows from the aspect ratio)",
            )?;
            Camera::Pinhole {
                fov_deg: c.required("camera.fov_deg", r.fov_deg, "for a pinhole camera")?,
                width,
                height,
            }
        }
        CameraKind::Panorama => {
            c.unused(
                "camera.fov_deg",
                &r.fov_deg,
                "by a panorama (use h_fov_deg and v_fov_deg)",
            )?;
            Camera::Panorama {
                h_fov_deg: c.required("camera.h_fov_deg", r.h_fov_deg, "for a panorama")?,
                v_fov_deg: c.required("camera.v_fov_deg", r.v_fov_deg, "for a panorama")?,
                width,
                height,
            }
        }
        CameraKind::Sphere => {
            let why = "by a sphere camera (always 360°×180°)";
            c.unused("camera.fov_deg", &r.fov_deg, why)?;
            c.unused("camera.h_fov_deg", &r.h_fov_deg, why)?;
            c.unused("camera.v_fov_deg", &r.v_fov_deg, why)?;
            Camera::Sphere { width, height }
        }
        CameraKind::Fisheye => {
            c.unused(
                "camera.h_fov_deg",
                &r.h_fov_deg,
                "by a fisheye (use fov_deg)",
            )?;
            c.unused(
                "camera.v_fov_deg",
                &r.v_fov_deg,
                "by a fisheye (use fov_deg)",
            )?;
            if width != height {
                return c.err("camera.height", format!("a fisheye image is square: height must equal width ({width}), got {height}"));
            }
            Camera::Fisheye {
                fov_deg: r.fov_deg.unwrap_or(180.0),
                size: width,
            }
        }
    };
    camera
        .check()
        .or_else(|(field, message)| c.err(field, message))?;
    Ok(camera)
}

fn trace(c: &Checker, raw: Option<RawTrace>) -> Result<TraceSettings> {
    let d = TraceSettings::default();
    let Some(t) = raw else { return Ok(d) };
    let max_steps = t.max_steps.unwrap_or(d.max_steps);
    if max_steps == 0 {
        return c.err("trace.max_steps", "must be at least 1");
    }
    Ok(TraceSettings {
        method: match t.method.unwrap_or(MethodName::Numeric) {
            MethodName::Numeric => TraceMethod::Numeric,
            MethodName::Exact => TraceMethod::Exact,
        },
        max_past: c.positive("trace.max_past", t.max_past.unwrap_or(d.max_past))?,
        tolerance: c.positive("trace.tolerance", t.tolerance.unwrap_or(d.tolerance))?,
        max_steps,
    })
}
