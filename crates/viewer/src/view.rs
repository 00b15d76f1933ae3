//! A view of the explored scene: the observer and the camera with exactly the fields of the
//! scene file's `[observer]` and `[camera]` (docs/guide/src/scenes.md), as the explore page's
//! `viewer.explore.view()` gives it, so that a scene with these fields traces the view. The
//! flying page's kernel input and moves (`crate::explore_routes`) and *Render exactly* and
//! *Record* (`crate::keep`) all read this one shape.

use serde::{Deserialize, Serialize};

/// A position in pseudo-Cartesian coordinates (`observer.position = { x, y, z }`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Position {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// The observer's velocity relative to the static observer, in its frame
/// (`observer.velocity`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Velocity {
    pub speed: f64,
    pub direction: [f64; 3],
}

/// The camera of a view: the scene file's `[camera]` fields, every one given (`fov_deg` for
/// pinhole and fisheye, `h_fov_deg` and `v_fov_deg` for a panorama, none for a sphere).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraView {
    pub kind: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov_deg: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub h_fov_deg: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v_fov_deg: Option<f64>,
    pub width: u32,
    pub height: u32,
    pub samples: u32,
}

/// A view: the scene file's `[observer]` fields and its `[camera]`, every field given.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct View {
    pub time: f64,
    pub position: Position,
    pub velocity: Velocity,
    pub forward: [f64; 3],
    pub up: [f64; 3],
    pub camera: CameraView,
}

impl View {
    /// The first number that is not finite, as `view.FIELD: why`, or `None`. (JSON has no
    /// NaN: the page's NaN arrives as `null` and is refused when the body is read.)
    pub fn refusal(&self) -> Option<String> {
        let v = |k: &'static str, a: [f64; 3]| (0..3).map(move |i| (format!("{k}[{i}]"), a[i]));
        let c = &self.camera;
        let numbers = [
            ("time".to_string(), self.time),
            ("position.x".into(), self.position.x),
            ("position.y".into(), self.position.y),
            ("position.z".into(), self.position.z),
            ("velocity.speed".into(), self.velocity.speed),
        ]
        .into_iter()
        .chain(v("velocity.direction", self.velocity.direction))
        .chain(v("forward", self.forward))
        .chain(v("up", self.up))
        .chain(
            [
                ("camera.fov_deg", c.fov_deg),
                ("camera.h_fov_deg", c.h_fov_deg),
                ("camera.v_fov_deg", c.v_fov_deg),
            ]
            .into_iter()
            .filter_map(|(k, x)| x.map(|x| (k.to_string(), x))),
        );
        numbers
            .into_iter()
            .find(|(_, x)| !x.is_finite())
            .map(|(k, x)| format!("view.{k}: {x} is not a finite number"))
    }
}
