//! Writing a different view into scene text: the camera and the observer's velocity and
//! camera axes replaced, everything else (objects, comments, layout) kept as written.
//! `godel look` stores the view it computed this way (and its samples per pixel,
//! [`replace_samples`]), so that its data file carries a scene
//! that describes it (read it back with [`crate::Scene::read_view`]).

use crate::camera::Camera;
use crate::error::SceneError;
use crate::model::Observer;
use spacetime::LocalVelocity;
use toml_edit::{value, Array, DocumentMut, InlineTable, Item, Table, TableLike, Value};

/// `text` with `[camera]` replaced by `camera` and `[observer]`'s `velocity`, `forward` and
/// `up` by the given ones: the velocity relative to the static observer at the same event
/// (in its frame), the camera axes in the observer's own frame. The observer's time and
/// position are kept. `file` names the text in errors. The result is not validated here:
/// read it back with [`crate::Scene::read_view`].
pub fn replace_view(
    text: &str,
    file: &str,
    camera: &Camera,
    velocity: LocalVelocity,
    forward: [f64; 3],
    up: [f64; 3],
) -> Result<String, SceneError> {
    let mut doc = parse(text, file)?;
    let not_a_table = |field: &str| not_a_table(file, field);

    let observer = table_entry(&mut doc, "observer").ok_or_else(|| not_a_table("observer"))?;
    let mut v = InlineTable::new();
    v.insert("speed", Value::from(velocity.speed));
    v.insert("direction", Value::Array(vector(velocity.direction)));
    observer.insert("velocity", value(v));
    observer.insert("forward", value(vector(forward)));
    observer.insert("up", value(vector(up)));

    let c = *camera;
    let camera = table_entry(&mut doc, "camera").ok_or_else(|| not_a_table("camera"))?;
    camera.clear();
    camera.insert("kind", value(c.kind()));
    match c {
        Camera::Pinhole { fov_deg, .. } | Camera::Fisheye { fov_deg, .. } => {
            camera.insert("fov_deg", value(fov_deg));
        }
        Camera::Panorama {
            h_fov_deg,
            v_fov_deg,
            ..
        } => {
            camera.insert("h_fov_deg", value(h_fov_deg));
            camera.insert("v_fov_deg", value(v_fov_deg));
        }
        Camera::Sphere { .. } => {}
    }
    camera.insert("width", value(i64::from(c.width())));
    camera.insert("height", value(i64::from(c.height())));
    Ok(doc.to_string())
}

/// `text` as one eye of its stereo camera sees it (`Scene::eye`): `name` and the observer's
/// time, position (x, y, z), velocity and camera axes replaced by `observer`'s, and
/// `[camera] stereo` marked with `eye`; everything else kept as written.
pub fn replace_eye(
    text: &str,
    file: &str,
    name: &str,
    observer: &Observer,
    eye: &str,
) -> Result<String, SceneError> {
    let mut doc = parse(text, file)?;
    doc.insert("name", value(name));
    let o = table_entry(&mut doc, "observer").ok_or_else(|| not_a_table(file, "observer"))?;
    let e = observer.event;
    o.insert("time", value(e.t));
    let mut position = InlineTable::new();
    for (k, v) in [("x", e.x), ("y", e.y), ("z", e.z)] {
        position.insert(k, Value::from(v));
    }
    o.insert("position", value(position));
    let mut v = InlineTable::new();
    v.insert("speed", Value::from(observer.velocity.speed));
    v.insert(
        "direction",
        Value::Array(vector(observer.velocity.direction)),
    );
    o.insert("velocity", value(v));
    o.insert("forward", value(vector(observer.forward)));
    o.insert("up", value(vector(observer.up)));
    let camera = table_entry(&mut doc, "camera").ok_or_else(|| not_a_table(file, "camera"))?;
    let stereo = camera
        .get_mut("stereo")
        .and_then(|s| s.as_table_like_mut())
        .ok_or_else(|| not_a_table(file, "camera.stereo"))?;
    stereo.insert("eye", value(eye));
    Ok(doc.to_string())
}

/// The table (or inline table) at top-level `key`, created when missing; `None` when the key
/// holds something else.
fn table_entry<'a>(doc: &'a mut DocumentMut, key: &str) -> Option<&'a mut dyn TableLike> {
    let item = doc
        .as_table_mut()
        .entry(key)
        .or_insert(Item::Table(Table::new()));
    item.as_table_like_mut()
}

/// `text` with `[camera] samples` set to `samples` (rays, or looked samples, per pixel),
/// or removed for 1 (the default); everything else kept as written.
pub fn replace_samples(text: &str, file: &str, samples: u32) -> Result<String, SceneError> {
    let mut doc = parse(text, file)?;
    let camera = table_entry(&mut doc, "camera").ok_or_else(|| not_a_table(file, "camera"))?;
    if samples > 1 {
        camera.insert("samples", value(i64::from(samples)));
    } else {
        camera.remove("samples");
    }
    Ok(doc.to_string())
}

/// The TOML document of `text`; a syntax error located in `file`.
fn parse(text: &str, file: &str) -> Result<DocumentMut, SceneError> {
    text.parse().map_err(|e: toml_edit::TomlError| SceneError {
        file: file.to_string(),
        location: e.span().map(|s| crate::error::line_column(text, s.start)),
        field: String::new(),
        message: e.message().to_string(),
    })
}

fn not_a_table(file: &str, field: &str) -> SceneError {
    SceneError {
        file: file.to_string(),
        location: None,
        field: field.to_string(),
        message: "is not a table".to_string(),
    }
}

fn vector(v: [f64; 3]) -> Array {
    v.iter().copied().collect()
}
