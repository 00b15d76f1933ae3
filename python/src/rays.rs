//! `geodesic` and `connect`: one geodesic from an event (`spacetime::curve`, as `godel
//! geodesic`) and every light ray from a source at rest to an event
//! (`spacetime::connection`, as `godel connect`), computed without holding the GIL. Inputs
//! are checked by those modules; a refusal names the keyword argument at fault. `geodesic`
//! and `connect` also work in a member of the Gödel-type family (`metric = "godel-type"`,
//! `m2`, `omega`: docs/physics.md, "The Gödel-type family"), checked as `godel geodesic` and
//! `godel connect` check it.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyByteArray;
use spacetime::connection::{
    connections, on_the_source_axis, type_connections, type_on_the_source_axis, MAX_WINDINGS,
};
use spacetime::curve::{compute, stop_name, CurveError, CurveMethod, CurveRequest, Input};
use spacetime::{Event, Godel, GodelType, Metric, TimeDirection};

use crate::errors::argument_error;

/// The metric of `geodesic`'s and `connect`'s `metric`, `a`, `m2` and `omega` (each given or None): Gödel's
/// with `a` (default 1), or the Gödel-type member (`m2`, `omega`), checked in the ranges of
/// scenes (`scene::ranges`); a constant the metric does not use is refused, naming it.
fn metric_of(
    metric: &str,
    a: Option<f64>,
    m2: Option<f64>,
    omega: Option<f64>,
) -> PyResult<Metric> {
    match metric {
        "godel" => {
            for (keyword, value) in [("m2", m2), ("omega", omega)] {
                if value.is_some() {
                    let message = "is a constant of metric=\"godel-type\": not used by \"godel\"";
                    return Err(argument_error(keyword, message));
                }
            }
            let a = scene::ranges::check_a(a.unwrap_or(1.0)).map_err(|e| argument_error("a", e))?;
            Ok(Metric::Godel(Godel::new(a)))
        }
        "godel-type" => {
            if a.is_some() {
                let message = "not used by metric=\"godel-type\": its constants are m2 and omega \
                               (Gödel's a is m2 = 1/a², omega = 1/(√2·a))";
                return Err(argument_error("a", message));
            }
            let need = "needed by metric=\"godel-type\" (with m2 and omega)";
            let omega = omega.ok_or_else(|| argument_error("omega", need))?;
            let omega =
                scene::ranges::check_omega(omega).map_err(|e| argument_error("omega", e))?;
            let m2 = m2.ok_or_else(|| argument_error("m2", need))?;
            let m2 = scene::ranges::check_m2(m2, omega).map_err(|e| argument_error("m2", e))?;
            Ok(Metric::GodelType(GodelType::new(m2, omega)))
        }
        other => Err(argument_error(
            "metric",
            format!("must be \"godel\" or \"godel-type\", got {other:?}"),
        )),
    }
}

/// The keyword argument of each input that `spacetime::curve` checks.
fn keyword(input: Input) -> &'static str {
    match input {
        Input::Start => "position",
        Input::Direction => "direction",
        Input::Speed => "speed",
        Input::UntilTime => "max_past",
        Input::Samples => "samples",
        Input::Method => "method",
    }
}

fn curve_error(e: CurveError) -> PyErr {
    match e {
        CurveError::Input { input, message } => argument_error(keyword(input), message),
        e => PyRuntimeError::new_err(e.to_string()),
    }
}

/// Named columns of native-endian f64 values.
type Columns<'py> = Vec<(&'static str, Bound<'py, PyByteArray>)>;

/// One geodesic of Gödel's universe or of a Gödel-type member; returns the stop reason and
/// the columns (name, bytes of native f64): lambda, t, x, y, z and the tangent dt/dλ, dx/dλ,
/// dy/dλ, dz/dλ. See `godel.geodesic`.
#[pyfunction]
#[pyo3(signature = (metric, a, m2, omega, position, time, direction, speed, past, method, samples, max_past))]
#[allow(clippy::too_many_arguments)]
pub fn geodesic<'py>(
    py: Python<'py>,
    metric: &str,
    a: Option<f64>,
    m2: Option<f64>,
    omega: Option<f64>,
    position: [f64; 3],
    time: f64,
    direction: [f64; 3],
    speed: Option<f64>,
    past: bool,
    method: &str,
    samples: usize,
    max_past: Option<f64>,
) -> PyResult<(String, Columns<'py>)> {
    let metric = metric_of(metric, a, m2, omega)?;
    let scale = metric.length_scale();
    let xyz: &[&str] = &["x", "y", "z"];
    for (keyword, names, values) in [("position", xyz, &position[..]), ("time", &["t"], &[time])] {
        scene::ranges::check_coordinates(names, values, scale)
            .map_err(|e| argument_error(keyword, e))?;
    }
    if let Some(g) = metric.godel_type() {
        scene::ranges::check_member_radius(g, position[0].hypot(position[1]))
            .map_err(|e| argument_error("position", e))?;
    }
    let method = match method {
        "exact" => CurveMethod::Exact,
        "numeric" => CurveMethod::Numeric,
        other => {
            let message = format!("must be \"exact\" or \"numeric\", got {other:?}");
            return Err(argument_error("method", message));
        }
    };
    let [x, y, z] = position;
    let request = CurveRequest::new(
        metric,
        method,
        Event::new(time, x, y, z),
        direction,
        speed,
        if past {
            TimeDirection::Past
        } else {
            TimeDirection::Future
        },
        max_past,
        samples,
    )
    .map_err(curve_error)?;
    let curve = py.detach(|| compute(&request)).map_err(curve_error)?;
    let mut columns: [Vec<f64>; 9] = Default::default();
    for (lambda, state) in &curve.samples {
        let e = state.x;
        let k = state.tangent(&metric);
        let row = [lambda, &e.t, &e.x, &e.y, &e.z, &k.t, &k.x, &k.y, &k.z];
        for (column, v) in columns.iter_mut().zip(row) {
            column.push(*v);
        }
    }
    let names = ["lambda", "t", "x", "y", "z", "k_t", "k_x", "k_y", "k_z"];
    let out = names
        .into_iter()
        .zip(columns)
        .map(|(name, values)| {
            let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_ne_bytes()).collect();
            (name, PyByteArray::new(py, &bytes))
        })
        .collect();
    Ok((stop_name(curve.stop).to_string(), out))
}

/// One connecting ray as a tuple: emission (t, x, y, z), travel time, winding, branch,
/// departure (x, y, z), look (x, y, z), lambda, area distance, g, miss.
type Ray = (
    [f64; 4],
    f64,
    u32,
    &'static str,
    [f64; 3],
    [f64; 3],
    f64,
    f64,
    f64,
    f64,
);

/// Every light ray from a source at rest at `source` (x, y, z) to the event `target`
/// (t, x, y, z), latest emission first, in Gödel's universe or a Gödel-type member (as
/// `geodesic`'s `metric`, `a`, `m2`, `omega`); with the event's distance from the source's
/// axis. See `godel.connect`.
#[pyfunction]
#[pyo3(signature = (source, target, metric, a, m2, omega, windings))]
#[allow(clippy::too_many_arguments)]
pub fn connect(
    py: Python<'_>,
    source: [f64; 3],
    target: [f64; 4],
    metric: &str,
    a: Option<f64>,
    m2: Option<f64>,
    omega: Option<f64>,
    windings: u32,
) -> PyResult<(f64, Vec<Ray>)> {
    let metric = metric_of(metric, a, m2, omega)?;
    let scale = metric.length_scale();
    let source_names: &[&str] = &["x", "y", "z"];
    let target_names: &[&str] = &["t", "x", "y", "z"];
    for (keyword, names, values) in [
        ("source", source_names, &source[..]),
        ("target", target_names, &target[..]),
    ] {
        scene::ranges::check_coordinates(names, values, scale)
            .map_err(|e| argument_error(keyword, e))?;
    }
    if let Some(g) = metric.godel_type() {
        for (keyword, x, y) in [
            ("source", source[0], source[1]),
            ("target", target[1], target[2]),
        ] {
            scene::ranges::check_member_radius(g, x.hypot(y))
                .map_err(|e| argument_error(keyword, e))?;
        }
    }
    if windings > MAX_WINDINGS {
        let message = format!("must be at most {MAX_WINDINGS}, got {windings}");
        return Err(argument_error("windings", message));
    }
    let [t, x, y, z] = target;
    let [sx, sy, sz] = source;
    let (source, event) = (Event::new(0.0, sx, sy, sz), Event::new(t, x, y, z));
    // Not single rays there, but cones of them: refused, as `godel connect` does.
    let axis = match metric.godel_type() {
        Some(g) => type_on_the_source_axis(g, source, event),
        None => on_the_source_axis(scale, source, event),
    };
    if let Some(why) = axis {
        return Err(argument_error("target", why));
    }
    let found = py
        .detach(|| match metric.godel_type() {
            Some(g) => type_connections(g, source, event, windings),
            None => connections(scale, source, event, windings),
        })
        .ok_or_else(|| PyRuntimeError::new_err("a connecting ray has no closed form"))?;
    let rays = found
        .rays
        .iter()
        .map(|c| {
            let e = c.ray.emission;
            (
                [e.t, e.x, e.y, e.z],
                c.travel_time,
                c.ray.winding,
                c.ray.branch.name(),
                c.departure,
                c.look,
                c.ray.lambda,
                c.area_distance,
                c.g,
                c.miss,
            )
        })
        .collect();
    Ok((found.rho, rays))
}
