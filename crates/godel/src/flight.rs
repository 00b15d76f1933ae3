//! Fly-through sequences: the scene of each frame of a traced sequence, with the observer
//! and the camera's field of view keyframed in the script (`shade::script`,
//! docs/guide/src/sequences.md).
//!
//! [`Flight::new`] starts from the scene's own observer (time, position as x, y, z,
//! velocity, forward, up) and camera (its fields of view) and follows the script's
//! `[keyframe.observer]` and `[keyframe.camera]` tables with the script's easing
//! ([`shade::Track`]). Every number goes linearly in the eased fraction, so the position
//! moves along a straight line in the coordinates (x, y, z) between two keyframes (not a
//! geodesic, and the observer's velocity is whatever the keyframes say, not the motion
//! along that line). Forward and up are interpolated as vectors; then up is made orthogonal
//! to forward (Gram–Schmidt: up − (up·f̂)f̂), which leaves up unchanged where the
//! keyframe's own axes are orthogonal; where up becomes parallel to forward, or forward
//! vanishes, that is an error. `[trace] observer_time` (the older way, linear from the first
//! to the last frame) sets the time when no keyframe does.
//!
//! Only the fields some keyframe sets are written into the scene text (the rest of the
//! scene stays as written), and the scene is read again with the usual checks
//! (`scene::Scene::from_str`), so that frame `f` is exactly the scene a user would write
//! with that observer; a frame whose scene is refused names `keyframe[i].FIELD` of the
//! script (i: the keyframe at or after that frame). [`Flight::new`] checks every frame.
//!
//! The scene's text is read once. What a frame changes is its `[observer]` and `[camera]`,
//! whose checks read nothing of the scene but its name and `[spacetime]` (the bound on
//! coordinates); the rest passed the same checks when the scene was read. So
//! [`Flight::new`] checks each frame in a scene of just those ([`view_part`]): its work is
//! the frame count times a small scene's, whatever the size of the scene (a recorded flight
//! of an hour is 86,401 frames, `godel explore`'s *Record*), and a frame equal to the one
//! checked before it (a pause) is not checked again.
//!
//! What the interpolated fields mean is the scene's: the event in the coordinates
//! (t, x, y, z) of docs/physics.md "Conventions", the velocity relative to the static observer
//! there and the camera axes in the observer's frame ("Frames", "Pixels and cameras").

use scene::{Camera, Scene};
use shade::{FrameSource, Script, Section, ShadeError, Track};
use spacetime::{Event, LocalVelocity};
use toml::{Table, Value};

use crate::scene_edit::{edited_table, section, table_of, EditError};

/// The observer fields written into the scene when a keyframe sets one of them: position
/// as a whole, velocity as a whole, forward and up together.
const GROUPS: [&[&str]; 4] = [&["time"], &["position"], &["velocity"], &["forward", "up"]];

/// Below this length of up's part orthogonal to forward (relative to up's length), up is
/// taken as parallel to forward.
const PARALLEL: f64 = 1e-6;

/// A checked fly-through: the scene text and the tracks of the observer and the camera.
pub struct Flight {
    /// The scene as written, and its path for messages and relative image paths.
    text: String,
    name: String,
    /// The scene read as a table (once), and its part a frame's fields are checked in.
    table: Table,
    part: Table,
    /// The script (for located errors).
    script: Script,
    observer_time: Option<[f64; 2]>,
    frames: u32,
    observer: Track,
    camera: Track,
    /// The observer keys and the camera keys that any keyframe sets.
    observer_keys: Vec<&'static str>,
    camera_keys: Vec<String>,
}

impl Flight {
    /// The flight of `script` through `scene` (read from `script`'s `[trace] scene`), with
    /// the observer's time from `[trace] observer_time` when given; every frame's scene is
    /// checked.
    pub fn new(scene: &Scene, script: &Script) -> Result<Flight, ShadeError> {
        let observer_time = match script.source {
            FrameSource::Trace { observer_time, .. } => observer_time,
            FrameSource::Data(_) => None,
        };
        let observer = script.track(Section::Observer, &observer_table(scene))?;
        let camera = script.track(Section::Camera, &camera_table(&scene.camera))?;
        let set = |section: Section, key: &str| {
            script.keyframes.iter().any(|k| match section {
                Section::Observer => k.observer.contains_key(key),
                _ => k.camera.contains_key(key),
            })
        };
        let observer_keys = GROUPS
            .iter()
            .filter(|g| g.iter().any(|k| set(Section::Observer, k)))
            .flat_map(|g| g.iter().copied())
            .collect();
        let camera_keys = shade::CAMERA_KEYS
            .iter()
            .filter(|k| set(Section::Camera, k))
            .map(|k| k.to_string())
            .collect();
        let name = scene
            .source_path
            .as_ref()
            .map_or_else(|| scene.name.clone(), |p| p.display().to_string());
        let table = table_of(&scene.source_text, &name)
            .map_err(|e| script.error_at("trace.scene", e.to_string()))?;
        let flight = Flight {
            text: scene.source_text.clone(),
            name,
            part: view_part(&table),
            table,
            script: script.clone(),
            observer_time,
            frames: script.frames,
            observer,
            camera,
            observer_keys,
            camera_keys,
        };
        // The keyframes first, so that a bad keyframe is named as such, then every frame in
        // between (an interpolated up may meet forward), each in the scene's part its fields
        // are checked in (module documentation). Bounded by the frame count.
        if !(flight.observer_keys.is_empty() && flight.camera_keys.is_empty()) {
            let keyframes = script.keyframes.iter().map(|k| k.frame);
            let mut checked: Option<FrameFields> = None;
            for f in keyframes.chain(0..script.frames) {
                let fields = flight.fields(f);
                if checked.as_ref() != Some(&fields) {
                    flight.scene_of(f, flight.edited(f, &fields, flight.part.clone())?)?;
                    checked = Some(fields);
                }
            }
        }
        Ok(flight)
    }

    /// The scene of frame `frame`.
    pub fn scene_at(&self, frame: u32) -> Result<Scene, ShadeError> {
        if self.observer_keys.is_empty()
            && self.camera_keys.is_empty()
            && self.observer_time.is_none()
        {
            return Scene::from_str(&self.text, &self.name)
                .map_err(|e| self.script.error_at("trace.scene", one_line(&e)));
        }
        let fields = self.fields(frame);
        self.scene_of(frame, self.edited(frame, &fields, self.table.clone())?)
    }

    /// What frame `frame` writes into the scene.
    fn fields(&self, frame: u32) -> FrameFields {
        let time = self.observer_time.map(|[t0, t1]| {
            // As the sequence has always done: linear from the first frame to the last.
            let s = if self.frames > 1 {
                f64::from(frame) / f64::from(self.frames - 1)
            } else {
                0.0
            };
            t0 + s * (t1 - t0)
        });
        FrameFields {
            observer: self.observer.at(frame),
            camera: self.camera.at(frame),
            time,
        }
    }

    /// `table` (the scene's, or its [`view_part`]) with `fields`, frame `frame`'s, written in.
    fn edited(
        &self,
        frame: u32,
        fields: &FrameFields,
        mut table: Table,
    ) -> Result<Table, ShadeError> {
        let observer = section(&mut table, "observer");
        if let Value::Table(o) = &fields.observer {
            for key in &self.observer_keys {
                if let Some(v) = o.get(*key) {
                    observer.insert(key.to_string(), v.clone());
                }
            }
            if self.observer_keys.contains(&"forward") {
                let (forward, up) =
                    axes(o).map_err(|(f, m)| self.error_at(frame, &format!("observer.{f}"), m))?;
                observer.insert("forward".into(), vector(forward));
                observer.insert("up".into(), vector(up));
            }
        }
        if let Some(time) = fields.time {
            observer.insert("time".into(), Value::Float(time));
        }
        let camera = section(&mut table, "camera");
        if let Value::Table(c) = &fields.camera {
            for key in &self.camera_keys {
                if let Some(v) = c.get(key) {
                    camera.insert(key.clone(), v.clone());
                }
            }
        }
        Ok(table)
    }

    /// The scene of the edited table of frame `frame`, read with the usual checks; a refusal
    /// names the keyframe's field.
    fn scene_of(&self, frame: u32, table: Table) -> Result<Scene, ShadeError> {
        edited_table(table, &self.name, |_| {}).map_err(|e| match e {
            EditError::Scene(e)
                if e.field.starts_with("observer") || e.field.starts_with("camera") =>
            {
                self.error_at(frame, &e.field, e.message.clone())
            }
            EditError::Scene(e) => self.script.error_at("trace.scene", one_line(&e)),
            EditError::Text(why) => self.script.error_at("trace.scene", why),
        })
    }

    /// An error at `keyframe[i].FIELD` of the script, i the keyframe frame `frame` moves
    /// towards.
    fn error_at(&self, frame: u32, field: &str, message: String) -> ShadeError {
        let towards = self.script.keyframe_towards(frame).unwrap_or(0);
        self.script.error_at(
            &format!("keyframe[{towards}].{field}"),
            format!("{message} (frame {frame})"),
        )
    }
}

/// What a frame writes into the scene: the observer's and the camera's tables of the tracks
/// (only the keys some keyframe sets are written), and the time of `[trace] observer_time`.
#[derive(PartialEq)]
struct FrameFields {
    observer: Value,
    camera: Value,
    time: Option<f64>,
}

/// The part of a scene's table (`table`) that a frame's or a view's `[observer]` and
/// `[camera]` are checked in: those two tables as written and what their checks read (the
/// scene's name and `[spacetime]`). A scene with other observer and camera fields passes the
/// usual checks exactly when its part with those fields does and the scene as written did
/// (no other check reads the observer or the camera).
pub fn view_part(table: &Table) -> Table {
    ["name", "spacetime", "observer", "camera"]
        .into_iter()
        .filter_map(|key| Some((key.to_string(), table.get(key)?.clone())))
        .collect()
}

fn one_line(e: &scene::SceneError) -> String {
    scene::one_line(&e.to_string())
}

/// A sequence-script keyframe (TOML) at `frame` with every observer field of `scene`
/// (time, position as x, y, z, velocity, forward, up) and its camera's fields of view:
/// what `godel explore` saves for its current observer, so that a fly-through passes there.
pub fn keyframe_text(scene: &Scene, frame: u32) -> Result<String, toml::ser::Error> {
    let mut keyframe = Table::new();
    keyframe.insert("frame".into(), Value::Integer(i64::from(frame)));
    keyframe.insert("observer".into(), Value::Table(observer_table(scene)));
    keyframe.insert("camera".into(), Value::Table(camera_table(&scene.camera)));
    let mut root = Table::new();
    root.insert(
        "keyframe".into(),
        Value::Array(vec![Value::Table(keyframe)]),
    );
    toml::to_string(&root)
}

/// The scene's observer as a keyframe table: every key, position in x, y, z.
fn observer_table(scene: &Scene) -> Table {
    let o = &scene.observer;
    observer_fields(o.event, o.velocity, o.forward, o.up)
}

/// An observer as a scene's (and a keyframe's) `[observer]` table: every key, position in
/// x, y, z.
pub fn observer_fields(
    e: Event,
    velocity: LocalVelocity,
    forward: [f64; 3],
    up: [f64; 3],
) -> Table {
    let mut position = Table::new();
    for (k, v) in [("x", e.x), ("y", e.y), ("z", e.z)] {
        position.insert(k.into(), Value::Float(v));
    }
    let mut v = Table::new();
    v.insert("speed".into(), Value::Float(velocity.speed));
    v.insert("direction".into(), vector(velocity.direction));
    let mut t = Table::new();
    t.insert("time".into(), Value::Float(e.t));
    t.insert("position".into(), Value::Table(position));
    t.insert("velocity".into(), Value::Table(v));
    t.insert("forward".into(), vector(forward));
    t.insert("up".into(), vector(up));
    t
}

/// The fields of view of `camera` as a keyframe table (keys among `shade::CAMERA_KEYS`).
fn camera_table(camera: &Camera) -> Table {
    let keys: Vec<(&str, f64)> = match *camera {
        Camera::Pinhole { fov_deg, .. } | Camera::Fisheye { fov_deg, .. } => {
            vec![("fov_deg", fov_deg)]
        }
        Camera::Panorama {
            h_fov_deg,
            v_fov_deg,
            ..
        } => vec![("h_fov_deg", h_fov_deg), ("v_fov_deg", v_fov_deg)],
        Camera::Sphere { .. } => Vec::new(),
    };
    keys.into_iter()
        .map(|(k, v)| (k.to_string(), Value::Float(v)))
        .collect()
}

fn vector(v: [f64; 3]) -> Value {
    Value::Array(v.iter().map(|&c| Value::Float(c)).collect())
}

fn read_vector(o: &Table, key: &str) -> [f64; 3] {
    let mut out = [0.0; 3];
    if let Some(Value::Array(a)) = o.get(key) {
        for (c, v) in out.iter_mut().zip(a) {
            *c = v.as_float().unwrap_or(0.0);
        }
    }
    out
}

/// Forward as interpolated, and up made orthogonal to it: up − (up·f̂)f̂. Errors
/// `(field, message)` when forward vanishes or up is parallel to it.
fn axes(o: &Table) -> Result<([f64; 3], [f64; 3]), (String, String)> {
    let (f, u) = (read_vector(o, "forward"), read_vector(o, "up"));
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let nf = norm(f);
    if !(nf > 0.0 && nf.is_finite()) {
        return Err((
            "forward".into(),
            format!("forward interpolates to {f:?}, not a direction"),
        ));
    }
    let fh = [f[0] / nf, f[1] / nf, f[2] / nf];
    let d = u[0] * fh[0] + u[1] * fh[1] + u[2] * fh[2];
    let up = [u[0] - d * fh[0], u[1] - d * fh[1], u[2] - d * fh[2]];
    let apart = norm(up) > PARALLEL * norm(u);
    if !apart {
        return Err((
            "up".into(),
            format!("up {u:?} is parallel to forward {f:?} here: no camera orientation"),
        ));
    }
    Ok((f, up))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(forward: [f64; 3], up: [f64; 3]) -> Table {
        let mut t = Table::new();
        t.insert("forward".into(), vector(forward));
        t.insert("up".into(), vector(up));
        t
    }

    #[test]
    fn up_is_made_orthogonal_to_forward_and_kept_where_it_is() {
        let (f, u) = axes(&table([1.0, 1.0, 0.0], [0.0, 0.0, 2.0])).unwrap();
        assert_eq!((f, u), ([1.0, 1.0, 0.0], [0.0, 0.0, 2.0]));
        let (_, u) = axes(&table([1.0, 0.0, 0.0], [1.0, 0.0, 1.0])).unwrap();
        assert_eq!(u, [0.0, 0.0, 1.0]);
        let e = axes(&table([1.0, 0.0, 0.0], [-2.0, 0.0, 0.0])).unwrap_err();
        assert_eq!(e.0, "up");
        let e = axes(&table([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])).unwrap_err();
        assert_eq!(e.0, "forward");
    }
}
