//! Stereo: `[camera] stereo = { separation, layout, convergence }` checked, and each eye of a
//! stereo scene as a scene of its own (docs/physics.md, "Stereo eyes").
//!
//! An eye is an observer displaced along the camera's right axis by ±separation/2 (in units
//! of a; of 1 in flat spacetime) by an isometry (`spacetime::Viewpoint::eye`), so each eye's
//! scene is an ordinary one-observer scene: it traces, shades, looks and explores as any
//! other, and its data file embeds it. With a convergence distance D the eyes turn inwards
//! (toe-in) by atan(separation/2D) about their up axis; without one they look parallel.
//!
//! Panoramas and spheres get the same two eyes, not an omnidirectional-stereo pair per
//! column: a data file holds the records of one event (look, the viewer and explore re-aim
//! its rays from that event), and an eye pair per column would make every column its own
//! event. Their depth is right straight ahead and fades to none at ±90° from it.

use crate::checker::{Checker, Result};
use crate::edit;
use crate::error::SceneError;
use crate::model::{Observer, Scene};
use crate::raw::{EyeName, LayoutName, RawStereo};
use spacetime::Viewpoint;

/// Largest separation, in units of a: the eyes stay within a small part of the horizon's
/// radius 2a, as a pair of eyes should.
pub const MAX_SEPARATION_PER_A: f64 = 1.0;

/// How the two eyes' pictures are put into one preview.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Left eye's picture on the left, right eye's on the right.
    SideBySide,
    /// Left eye's picture above the right eye's.
    OverUnder,
    /// One picture: red from the left eye, green and blue from the right (red/cyan glasses).
    Anaglyph,
}

impl Layout {
    /// The name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Layout::SideBySide => "side-by-side",
            Layout::OverUnder => "over-under",
            Layout::Anaglyph => "anaglyph",
        }
    }
}

/// `[camera] stereo`: two eyes `separation` apart (units of a), their pictures in `layout`,
/// turned to meet at `convergence` (units of a) or parallel. `eye` is set in the scene of one
/// eye ([`Scene::eye`]): its observer is that eye, and it traces as one picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stereo {
    pub separation: f64,
    pub layout: Layout,
    pub convergence: Option<f64>,
    pub eye: Option<Eye>,
}

impl Stereo {
    /// Whether this is a pair to trace (not one eye of one).
    pub fn is_pair(&self) -> bool {
        self.eye.is_none()
    }
}

/// One of the two eyes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Eye {
    Left,
    Right,
}

impl Eye {
    pub const BOTH: [Eye; 2] = [Eye::Left, Eye::Right];

    /// `left` or `right`: the eye's files are `NAME.left.exr`, `NAME.right.exr`.
    pub fn name(self) -> &'static str {
        match self {
            Eye::Left => "left",
            Eye::Right => "right",
        }
    }

    /// −1 for the left eye, +1 for the right (along the camera's right axis).
    fn side(self) -> f64 {
        match self {
            Eye::Left => -1.0,
            Eye::Right => 1.0,
        }
    }
}

/// The checked `[camera] stereo` table (lengths in units of a).
pub(crate) fn stereo(c: &Checker, raw: Option<RawStereo>) -> Result<Option<Stereo>> {
    let Some(r) = raw else { return Ok(None) };
    let separation = c.non_negative("camera.stereo.separation", r.separation)?;
    if separation > MAX_SEPARATION_PER_A {
        return c.err(
            "camera.stereo.separation",
            format!(
                "must be at most {MAX_SEPARATION_PER_A} (in units of a), got {}",
                crate::short(separation)
            ),
        );
    }
    let convergence = match r.convergence {
        None => None,
        Some(d) => {
            let d = c.positive("camera.stereo.convergence", d)?;
            if d > crate::validate::MAX_COORDINATE_PER_A {
                return c.err(
                    "camera.stereo.convergence",
                    format!(
                        "must be at most {} (in units of a), got {}",
                        crate::validate::MAX_COORDINATE_PER_A,
                        crate::short(d)
                    ),
                );
            }
            Some(d)
        }
    };
    let layout = match r.layout.unwrap_or(LayoutName::SideBySide) {
        LayoutName::SideBySide => Layout::SideBySide,
        LayoutName::OverUnder => Layout::OverUnder,
        LayoutName::Anaglyph => Layout::Anaglyph,
    };
    let eye = r.eye.map(|e| match e {
        EyeName::Left => Eye::Left,
        EyeName::Right => Eye::Right,
    });
    Ok(Some(Stereo {
        separation,
        layout,
        convergence,
        eye,
    }))
}

impl Scene {
    /// The scene one eye of this stereo pair sees: its objects and camera from the eye's
    /// event, named `NAME.left` or `NAME.right`, its `stereo` marked with the eye (it traces
    /// as one picture); its text is this scene's text with that name, observer and mark (so
    /// the eye's data file embeds a scene that traces it). `None` for a scene that is not a
    /// stereo pair.
    pub fn eye(&self, eye: Eye) -> Option<std::result::Result<Scene, SceneError>> {
        let stereo = self.stereo.filter(Stereo::is_pair)?;
        Some(self.eye_of(stereo, eye))
    }

    fn eye_of(&self, stereo: Stereo, eye: Eye) -> std::result::Result<Scene, SceneError> {
        let a = self.metric.godel_a().unwrap_or(1.0);
        let (separation, convergence) = (stereo.separation, stereo.convergence);
        let o = &self.observer;
        let here = Viewpoint {
            event: o.event,
            velocity: o.velocity,
            forward: o.forward,
            up: o.up,
        };
        let half = 0.5 * separation * a;
        let moved = here.eye(&self.metric, eye.side() * half);
        // Toe-in: the eye turns about its up axis towards the point `convergence` ahead.
        let forward = match convergence {
            Some(d) => {
                let turn = -eye.side() * (half / (d * a)).atan();
                let right = cross(moved.forward, moved.up);
                let (s, c) = turn.sin_cos();
                [0, 1, 2].map(|i| c * moved.forward[i] + s * right[i])
            }
            None => moved.forward,
        };
        let observer = Observer {
            event: moved.event,
            velocity: moved.velocity,
            forward,
            up: moved.up,
        };
        let name = format!("{}.{}", self.name, eye.name());
        let file = self
            .source_path
            .as_ref()
            .map_or("<scene>".to_string(), |p| p.display().to_string());
        let source_text =
            edit::replace_eye(&self.source_text, &file, &name, &observer, eye.name())?;
        // The observer as its text reads (the reader normalizes the axes): the eye's scene
        // is exactly what its data file will embed.
        let (observer, _) = Scene::read_view(&source_text, &file)?;
        Ok(Scene {
            name,
            source_text,
            observer,
            stereo: Some(Stereo {
                eye: Some(eye),
                ..stereo
            }),
            ..self.clone()
        })
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
