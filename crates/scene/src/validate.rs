//! Validation: turns the raw scene-file records (`raw.rs`) into the runtime types
//! (`model.rs`), checking every number and every combination of fields, each failure a
//! [`SceneError`] located at the offending value.
//!
//! Defaults for what a scene file leaves out: a missing `[spacetime]` is Gödel with a = 1; a
//! missing `[observer]` is at rest at the origin at t = 0 looking along e1 with e3 up;
//! position components left out are 0; a missing velocity direction is [1, 0, 0]; a missing
//! `[trace]` is numeric, max_past 30, tolerance 1e-11, 100000 steps; an object's frame is
//! local, its texture a checker 8×16, its temperature 5800 K; fisheye fov is 180°.
//! Bounds: tolerance in [1e-14, 1e-3], max_steps ≤ 10⁷, the name at most 100 bytes and
//! no hidden or odd file name; image sides ≤ 20000 and ≤ 5·10⁷ pixels ([`Camera::check`]);
//! `[camera] samples` a square number ≤ 256 with ≤ 5·10⁷ rays in all.
//! Objects, motions and textures are checked in `objects.rs`.

use crate::camera::Camera;
use crate::checker::{Checker, Result};
use crate::error::Locator;
use crate::model::*;
use crate::ranges::{check_m2, check_omega, member_radius_limit};
use crate::raw::*;
use spacetime::{Event, Godel, GodelType, LocalVelocity, Metric, Minkowski};
use std::collections::HashMap;
use std::path::Path;

/// The integrator tolerance's range: below 1e-14 the steps drown in rounding (f64 carries
/// ~16 digits) and every ray fails; above 1e-3 the rays are not worth tracing.
const MIN_TOLERANCE: f64 = 1e-14;
const MAX_TOLERANCE: f64 = 1e-3;
/// Most integrator steps per ray (the default is 100000).
const MAX_STEPS: u64 = 10_000_000;
/// Longest scene name in bytes: it becomes file names such as
/// `.NAME.part-12-of-64.exr.godel-PID-HOST.XXXXXX.tmp`, which must stay within 255 bytes.
const MAX_NAME_BYTES: usize = 100;
/// Most loops a Gödel light ray may make within `max_past` (the tracer's bound on loop
/// copies; a scene that would need more is refused up front).
pub const MAX_RAY_LOOPS: u64 = 100_000;
/// Largest coordinate (times, positions, sizes) in units of a (of 1 in flat spacetime):
/// beyond it the isometries that carry events to the axis, and f64 times, lose the
/// precision the tracer needs (an observer at r = 1e9·a sees only NaN).
pub const MAX_COORDINATE_PER_A: f64 = 1e6;
/// The Gödel parameter a, smallest and largest: beyond them the metric's terms (r²/a, 1/a²)
/// overflow or lose the precision of f64 (a = 1e-300 made even the axis unusable).
pub const A_RANGE: (f64, f64) = (1e-6, 1e6);

/// Largest proper radius of a local sphere in units of a (for a falling one, of γ²·radius):
/// a local object is described in its rest frame to second order in its size (Riemann
/// normal coordinates), which needs it small against the curvature scale a. Measured
/// against the flat-space Lorentz-contracted ball, exit times of rays from inside differ by
/// ~5 %·γ²R/a (curvature included), 2–3 % at the limit.
pub const MAX_LOCAL_RADIUS_PER_A: f64 = 0.5;

/// The scene of the parsed file `raw` (whose text is `source_text`), checked.
pub(crate) fn build(
    raw: RawScene,
    source_text: &str,
    loc: &Locator,
    base_dir: &Path,
) -> Result<Scene> {
    let c = Checker { loc };
    output_name(&c, &raw.name)?;
    let metric = spacetime(&c, raw.spacetime)?;
    let observer = observer(&c, raw.observer)?;
    let mut raw_camera = raw.camera;
    let samples = raw_camera.samples.unwrap_or(1);
    let stereo = crate::stereo::stereo(&c, raw_camera.stereo.take(), MAX_COORDINATE_PER_A)?;
    let camera = camera(&c, raw_camera)?;
    if let Err(message) = crate::camera::samples_per_side(samples, camera.width(), camera.height())
    {
        return c.err("camera.samples", message);
    }
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
    godel_rules(&c, &metric, &trace, &objects, &lights)?;
    coordinate_bounds(&c, &metric, &observer, &objects, &lights)?;
    Ok(Scene {
        name: raw.name,
        source_path: None,
        source_text: source_text.to_string(),
        metric,
        observer,
        camera,
        stereo,
        samples: samples as u32,
        trace,
        objects,
        lights,
    })
}

/// The scene name becomes the output files' names: nothing that would make hidden files
/// (`.`, `..`, a leading dot), look like a flag (leading `-`), hide in blanks, leave the
/// folder, or not fit a file name with its temporary suffix.
fn output_name(c: &Checker, name: &str) -> Result<()> {
    c.name("name", name)?;
    let why = "is used as the output files' name and";
    if name.contains(['/', '\\']) {
        return c.err("name", format!("{why} must not contain '/' or '\\'"));
    }
    if name.starts_with('.') {
        return c.err(
            "name",
            format!("{why} must not start with '.' (hidden files), got {name:?}"),
        );
    }
    if name.starts_with('-') {
        return c.err(
            "name",
            format!("{why} must not start with '-', got {name:?}"),
        );
    }
    if name.trim() != name {
        return c.err(
            "name",
            format!("{why} must not start or end with blanks, got {name:?}"),
        );
    }
    if name.len() > MAX_NAME_BYTES {
        return c.err(
            "name",
            format!(
                "{why} must be at most {MAX_NAME_BYTES} bytes long, got {}",
                name.len()
            ),
        );
    }
    Ok(())
}

fn spacetime(c: &Checker, raw: Option<RawSpacetime>) -> Result<Metric> {
    let Some(s) = raw else {
        return Ok(Metric::Godel(Godel::new(1.0)));
    };
    let name = s.metric.unwrap_or(MetricName::Godel);
    if name != MetricName::GodelType {
        let why = "here: m2 and omega are the constants of metric = \"godel-type\"";
        c.unused("spacetime.m2", &s.m2, why)?;
        c.unused("spacetime.omega", &s.omega, why)?;
    }
    match name {
        MetricName::Godel => {
            let a = c.positive("spacetime.a", s.a.unwrap_or(1.0))?;
            if !(A_RANGE.0..=A_RANGE.1).contains(&a) {
                return c.err(
                    "spacetime.a",
                    format!(
                        "{} is outside [{:e}, {:e}]: the metric loses the precision of f64 there \
                         (choose the unit of length so that a is moderate)",
                        crate::short(a),
                        A_RANGE.0,
                        A_RANGE.1
                    ),
                );
            }
            Ok(Metric::Godel(Godel::new(a)))
        }
        MetricName::Minkowski => {
            c.unused("spacetime.a", &s.a, "by the Minkowski metric")?;
            Ok(Metric::Minkowski(Minkowski))
        }
        MetricName::GodelType => {
            c.unused(
                "spacetime.a",
                &s.a,
                "by metric = \"godel-type\" (its constants are m2 and omega)",
            )?;
            let why = "by metric = \"godel-type\"";
            // The ranges' one home is `crate::ranges` (the command line checks with it too).
            let omega = c.required("spacetime.omega", s.omega, why)?;
            let omega = check_omega(omega).or_else(|e| c.err("spacetime.omega", e))?;
            let m2 = c.required("spacetime.m2", s.m2, why)?;
            let m2 = check_m2(m2, omega).or_else(|e| c.err("spacetime.m2", e))?;
            Ok(Metric::GodelType(GodelType::new(m2, omega)))
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

/// [`camera`] on its own, for [`crate::camera_from_str`].
pub(crate) fn camera_only(loc: &Locator, r: RawCamera) -> Result<Camera> {
    camera(&Checker { loc }, r)
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
    if !(1..=MAX_STEPS).contains(&max_steps) {
        return c.err(
            "trace.max_steps",
            format!("must be in 1..={MAX_STEPS}, got {max_steps}"),
        );
    }
    let tolerance = c.finite("trace.tolerance", t.tolerance.unwrap_or(d.tolerance))?;
    if !(MIN_TOLERANCE..=MAX_TOLERANCE).contains(&tolerance) {
        return c.err(
            "trace.tolerance",
            format!("must be in [{MIN_TOLERANCE:e}, {MAX_TOLERANCE}], got {tolerance:e}"),
        );
    }
    Ok(TraceSettings {
        method: match t.method.unwrap_or(MethodName::Numeric) {
            MethodName::Numeric => TraceMethod::Numeric,
            MethodName::Exact => TraceMethod::Exact,
        },
        max_past: c.positive("trace.max_past", t.max_past.unwrap_or(d.max_past))?,
        tolerance,
        max_steps,
        gpu: t.gpu.unwrap_or(d.gpu),
    })
}

/// Checks that need both the metric and the rest. The exact tracer and the lights use
/// closed forms, Gödel's or the Gödel-type family's, so they need one of those metrics; the
/// GPU kernel knows Gödel's only. Light rays loop with a period of at least the metric's
/// shortest loop time, so `max_past` bounds the number of loops a ray makes
/// ([`MAX_RAY_LOOPS`]); and a local sphere must be small against the curvature scale (a in
/// Gödel's universe, the member's length scale in the family).
fn godel_rules(
    c: &Checker,
    metric: &Metric,
    trace: &TraceSettings,
    objects: &[Object],
    lights: &[Light],
) -> Result<()> {
    let Some(t_loop) = metric.shortest_loop_time() else {
        // Flat spacetime.
        let need = "spacetime.metric = \"godel\" or \"godel-type\"";
        if trace.method == TraceMethod::Exact {
            return c.err(
                "trace.method",
                format!("\"exact\" uses closed-form geodesics: it needs {need}"),
            );
        }
        if !lights.is_empty() {
            return c.err(
                "light[0]",
                format!("lights are traced with closed forms (shadow rays): they need {need}"),
            );
        }
        // No curvature scale: a local ball of any size is exact.
        return Ok(());
    };
    let loops = trace.max_past / t_loop;
    let (loop_law, scale) = match metric {
        Metric::Godel(g) => ("2πa(√2 − 1)", format!("a = {}", g.a)),
        _ => (
            "π/(Ω + √max(0, Ω² − m²/4))",
            format!(
                "the length scale a = min(1/(√2 Ω), 1/|m|) = {}",
                crate::short(metric.length_scale())
            ),
        ),
    };
    if loops > MAX_RAY_LOOPS as f64 {
        let raise = match metric {
            Metric::Godel(_) => "raise spacetime.a",
            _ => "lower spacetime.omega",
        };
        return c.err(
            "trace.max_past",
            format!(
                "{} is {loops:.3e} loops of a light ray (one loop takes at least {loop_law} = {:.4}); at most {MAX_RAY_LOOPS} are followed: reduce max_past or {raise}",
                trace.max_past, t_loop
            ),
        );
    }
    local_sizes(c, objects, metric.length_scale(), &scale)
}

/// Local spheres small against the curvature scale `a` (module constants above).
/// `scale` names a for the messages.
fn local_sizes(c: &Checker, objects: &[Object], a: f64, scale: &str) -> Result<()> {
    for (i, o) in objects.iter().enumerate() {
        if let Shape::Sphere { radius } = o.shape {
            // A ball moving at γ has a rest-frame neighbourhood whose static coordinates
            // stretch by ~γ²·R: that, not R, must stay small against a.
            if let Motion::Geodesic { velocity, .. } = o.motion {
                let stretch = velocity.gamma().powi(2) * radius;
                if stretch > MAX_LOCAL_RADIUS_PER_A * a {
                    return c.err(
                        &format!("object[{i}].radius"),
                        format!(
                            "{radius} is too large for a local sphere falling at speed {} with {scale}: its rest frame is described to second order in γ²·radius = {stretch:.4}, which must be at most {MAX_LOCAL_RADIUS_PER_A}·a = {} (radius ≤ {:.4} at this speed)",
                            velocity.speed,
                            MAX_LOCAL_RADIUS_PER_A * a,
                            MAX_LOCAL_RADIUS_PER_A * a / velocity.gamma().powi(2)
                        ),
                    );
                }
            }
            if radius > MAX_LOCAL_RADIUS_PER_A * a {
                return c.err(
                    &format!("object[{i}].radius"),
                    format!(
                        "{radius} is too large for a local sphere with {scale}: a local object is described in its rest frame to second order in its size, which needs radius ≤ {MAX_LOCAL_RADIUS_PER_A}·a = {}; use frame = \"coordinates\" for a large object",
                        MAX_LOCAL_RADIUS_PER_A * a
                    ),
                );
            }
        }
    }
    Ok(())
}

/// Every time, position and size in the scene within [`MAX_COORDINATE_PER_A`] of the
/// scale (a in Gödel's universe, 1 in flat spacetime), located at the offending field.
fn coordinate_bounds(
    c: &Checker,
    metric: &Metric,
    observer: &Observer,
    objects: &[Object],
    lights: &[Light],
) -> Result<()> {
    let bound = MAX_COORDINATE_PER_A * metric.length_scale();
    let check = |path: &str, values: &[f64]| -> Result<()> {
        match values.iter().find(|v| v.abs() > bound) {
            Some(v) => c.err(
                path,
                format!(
                    "{} is beyond ±{bound:e} (1e6 times the scale a): the tracer loses precision there",
                    crate::short(*v)
                ),
            ),
            None => Ok(()),
        }
    };
    let radius_limit = metric.godel_type().and_then(member_radius_limit);
    let place = |path: &str, p: [f64; 3]| -> Result<()> {
        check(path, &p)?;
        match &radius_limit {
            Some((limit, why)) if p[0].hypot(p[1]) > *limit => c.err(
                path,
                format!(
                    "is {} from the axis, beyond {}: {why}",
                    crate::short(p[0].hypot(p[1])),
                    crate::short(*limit)
                ),
            ),
            _ => Ok(()),
        }
    };
    let event = |e: Event| [e.x, e.y, e.z];
    check("observer.time", &[observer.event.t])?;
    place("observer.position", event(observer.event))?;
    for (i, o) in objects.iter().enumerate() {
        let p = |f: &str| format!("object[{i}].{f}");
        match o.motion {
            Motion::Rest { position } => place(&p("motion.position"), event(position))?,
            Motion::Geodesic { start, .. } => {
                check(&p("motion.time"), &[start.t])?;
                place(&p("motion.position"), event(start))?;
            }
        }
        match o.shape {
            Shape::Sphere { radius } => check(&p("radius"), &[radius])?,
            Shape::CoordinateSphere { center, radius } => {
                place(&p("center"), center)?;
                check(&p("radius"), &[radius])?;
            }
            Shape::Plane { height, extent } => {
                check(&p("height"), &[height])?;
                check(&p("extent"), &[extent.unwrap_or(0.0)])?;
            }
        }
    }
    for (i, l) in lights.iter().enumerate() {
        place(&format!("light[{i}].position"), event(l.position))?;
    }
    Ok(())
}
