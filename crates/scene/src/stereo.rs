//! Stereo: `[camera] stereo = { separation, layout, convergence }` checked, and each eye of a
//! stereo scene as a scene of its own (docs/physics.md, "Stereo eyes").
//!
//! An eye is an observer displaced along the camera's right axis by ±separation/2 (in units
//! of a, a Gödel-type member's length scale min(1/(√2 Ω), 1/|m|), or 1 in flat spacetime) by
//! an isometry (`spacetime::Viewpoint::eye`), so each eye's scene is an ordinary one-observer
//! scene: it traces, shades, looks and explores as any other, and its data file embeds it. A
//! member's eye must stay within the scene's bound on distances from the axis, as the
//! observer does. With a convergence distance D the eyes turn inwards (toe-in) by
//! atan(separation/2D) about their up axis; without one they look parallel.
//!
//! Panoramas and spheres get the same two eyes, not an omnidirectional-stereo pair per
//! column: a data file holds the records of one event (look, the viewer and explore re-aim
//! its rays from that event), and an eye pair per column would make every column its own
//! event. Their depth is right straight ahead and fades to none at ±90° from it.

use crate::checker::{Checker, Result};
use crate::edit;
use crate::error::{Locator, SceneError};
use crate::model::{cross, Eye, Layout, Observer, Scene, Stereo};
use crate::raw::{EyeName, LayoutName, RawStereo};
use spacetime::Viewpoint;

/// Largest separation, in units of a: the eyes stay within a small part of the horizon's
/// radius 2a, as a pair of eyes should.
pub const MAX_SEPARATION_PER_A: f64 = 1.0;

/// The checked `[camera] stereo` table (lengths in units of a; the convergence at most
/// `max_coordinate`, the scene's bound on coordinates).
pub(crate) fn stereo(
    c: &Checker,
    raw: Option<RawStereo>,
    max_coordinate: f64,
) -> Result<Option<Stereo>> {
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
            if d > max_coordinate {
                return c.err(
                    "camera.stereo.convergence",
                    format!(
                        "must be at most {} (in units of a), got {}",
                        crate::short(max_coordinate),
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
        let a = self.metric.length_scale();
        let (separation, convergence) = (stereo.separation, stereo.convergence);
        let o = &self.observer;
        let here = Viewpoint {
            event: o.event,
            velocity: o.velocity,
            forward: o.forward,
            up: o.up,
        };
        let half = 0.5 * separation * a;
        let file = self
            .source_path
            .as_ref()
            .map_or("<scene>".to_string(), |p| p.display().to_string());
        // The isometries place an eye anywhere but on a Gödel-type member's sphere, where a
        // fast observer's eye can reach the pole opposite the axis (`Viewpoint::eye`).
        let Some(moved) = here.eye(&self.metric, eye.side() * half) else {
            let why = match self.metric.godel_type().and_then(|m| m.coordinate_radius()) {
                Some(end) => format!(
                    "the isometry that moves it there would carry it to or across the pole opposite the axis (π/μ = {}), where the coordinates end; use a smaller separation or a slower observer",
                    crate::short(end)
                ),
                None => format!("the metric {:?} has no isometry for it", self.metric.name()),
            };
            return Err(self.stereo_error(
                &file,
                format!(
                    "the {} eye, {} along the camera's right axis, cannot be placed: {why}",
                    eye.name(),
                    crate::short(half)
                ),
            ));
        };
        // A member's eye stays where scenes keep positions, as the observer does.
        let limit = self
            .metric
            .godel_type()
            .and_then(crate::ranges::member_radius_limit);
        if let Some((limit, why)) = limit {
            let rho = moved.event.r();
            if rho.is_nan() || rho > limit {
                return Err(self.stereo_error(
                    &file,
                    format!(
                        "the {} eye, {} along the camera's right axis, is {} from the axis, beyond {}: {why}; use a smaller separation or move the observer",
                        eye.name(),
                        crate::short(half),
                        crate::short(rho),
                        crate::short(limit)
                    ),
                ));
            }
        }
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

    /// An error about this scene's `[camera] stereo`, located there in its text.
    fn stereo_error(&self, file: &str, message: String) -> SceneError {
        let root = toml::de::DeTable::parse(&self.source_text).ok();
        Locator::new(file, &self.source_text, root.as_ref()).at_path("camera.stereo", message)
    }
}
