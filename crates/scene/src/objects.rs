//! Validation of objects: shape and frame combinations, worldlines (`motion`) and
//! textures, each failure located at the offending value. Part of `validate.rs`.
//!
//! Defaults: frame local, texture a checker with 8 rows and 16 columns, temperature 5800 K,
//! checker rows 8 and cols 16 when only one is given, geodesic start time 0, unpolarized.

use crate::checker::{Checker, Result};
use crate::model::*;
use crate::raw::*;
use spacetime::Event;
use std::path::Path;

pub(crate) fn object(c: &Checker, path: &str, o: RawObject, base_dir: &Path) -> Result<Object> {
    let p = |f: &str| format!("{path}.{f}");
    c.name(&p("name"), &o.name)?;
    let frame = match o.frame.unwrap_or(FrameName::Local) {
        FrameName::Local => ObjectFrame::Local,
        FrameName::Coordinates => ObjectFrame::Coordinates,
    };
    let (shape, motion) = match frame {
        ObjectFrame::Local => {
            let why = "by a local object (only for frame = \"coordinates\")";
            if o.shape == Some(ShapeName::Plane) {
                return c.err(
                    &p("shape"),
                    "a local object must be a sphere; planes need frame = \"coordinates\"",
                );
            }
            c.unused(
                &p("center"),
                &o.center,
                "by a local object (give its position in `motion`)",
            )?;
            c.unused(&p("height"), &o.height, why)?;
            c.unused(&p("extent"), &o.extent, why)?;
            let radius = c.required(
                &p("radius"),
                o.radius,
                "for a local sphere (its proper radius)",
            )?;
            let radius = c.positive(&p("radius"), radius)?;
            let Some(m) = o.motion else {
                return c.err(
                    &p("motion"),
                    "missing, required for a local object (kind = \"rest\" or \"geodesic\")",
                );
            };
            (Shape::Sphere { radius }, motion(c, &p("motion"), m)?)
        }
        ObjectFrame::Coordinates => {
            c.unused(
                &p("motion"),
                &o.motion,
                "by a coordinate object (it is fixed in coordinates)",
            )?;
            let shape = c.required(
                &p("shape"),
                o.shape,
                "for a coordinate object (\"sphere\" or \"plane\")",
            )?;
            match shape {
                ShapeName::Sphere => {
                    let why = "by a coordinate sphere (only for planes)";
                    c.unused(&p("height"), &o.height, why)?;
                    c.unused(&p("extent"), &o.extent, why)?;
                    let radius = c.required(&p("radius"), o.radius, "for a coordinate sphere")?;
                    let radius = c.positive(&p("radius"), radius)?;
                    let center = c.required(&p("center"), o.center, "for a coordinate sphere")?;
                    let e = c.position(&p("center"), center, 0.0)?;
                    (
                        Shape::CoordinateSphere {
                            center: [e.x, e.y, e.z],
                            radius,
                        },
                        Motion::Rest { position: e },
                    )
                }
                ShapeName::Plane => {
                    c.unused(&p("radius"), &o.radius, "by a plane")?;
                    c.unused(&p("center"), &o.center, "by a plane (it is z = height)")?;
                    let height =
                        c.required(&p("height"), o.height, "for a plane (it is z = height)")?;
                    let height = c.finite(&p("height"), height)?;
                    let extent = match o.extent {
                        Some(e) => Some(c.positive(&p("extent"), e)?),
                        None => None,
                    };
                    (
                        Shape::Plane { height, extent },
                        Motion::Rest {
                            position: Event::new(0.0, 0.0, 0.0, height),
                        },
                    )
                }
            }
        }
    };
    let texture = match o.texture {
        Some(t) => texture(c, &p("texture"), t, base_dir)?,
        None => TextureSpec::default(),
    };
    let temperature = c.positive(
        &p("temperature"),
        o.temperature.unwrap_or(DEFAULT_TEMPERATURE),
    )?;
    let polarization = match o.polarization {
        Some(pol) => Some(c.direction(&p("polarization.axis"), pol.axis)?),
        None => None,
    };
    Ok(Object {
        name: o.name,
        frame,
        shape,
        texture,
        temperature,
        motion,
        polarization,
    })
}

pub(crate) fn motion(c: &Checker, path: &str, m: RawMotion) -> Result<Motion> {
    let p = |f: &str| format!("{path}.{f}");
    let position = c.required(&p("position"), m.position, "for a motion")?;
    match m.kind {
        MotionKind::Rest => {
            let why = "by kind = \"rest\" (only for \"geodesic\")";
            c.unused(&p("time"), &m.time, why)?;
            c.unused(&p("speed"), &m.speed, why)?;
            c.unused(&p("direction"), &m.direction, why)?;
            Ok(Motion::Rest {
                position: c.position(&p("position"), position, 0.0)?,
            })
        }
        MotionKind::Geodesic => {
            let t = c.finite(&p("time"), m.time.unwrap_or(0.0))?;
            let start = c.position(&p("position"), position, t)?;
            let speed = c.required(&p("speed"), m.speed, "for kind = \"geodesic\"")?;
            let velocity = c.velocity(path, speed, m.direction)?;
            Ok(Motion::Geodesic { start, velocity })
        }
    }
}

pub(crate) fn texture(
    c: &Checker,
    path: &str,
    t: RawTexture,
    base_dir: &Path,
) -> Result<TextureSpec> {
    let p = |f: &str| format!("{path}.{f}");
    let kind = match t.kind {
        TextureKind::Checker => "checker",
        TextureKind::Image => "image",
        TextureKind::Gradient => "gradient",
        TextureKind::Uniform => "uniform",
    };
    let why = format!("by kind = \"{kind}\"");
    if t.kind != TextureKind::Checker {
        c.unused(&p("rows"), &t.rows, &why)?;
        c.unused(&p("cols"), &t.cols, &why)?;
    }
    if t.kind != TextureKind::Image {
        c.unused(&p("path"), &t.path, &why)?;
        c.unused(&p("builtin"), &t.builtin, &why)?;
    }
    if t.kind != TextureKind::Uniform {
        c.unused(&p("color"), &t.color, &why)?;
    }
    match t.kind {
        TextureKind::Checker => {
            let rows = t.rows.unwrap_or(8);
            let cols = t.cols.unwrap_or(16);
            for (f, v) in [("rows", rows), ("cols", cols)] {
                if v == 0 {
                    return c.err(&p(f), "must be at least 1");
                }
            }
            Ok(TextureSpec::Checker { rows, cols })
        }
        TextureKind::Gradient => Ok(TextureSpec::Gradient),
        TextureKind::Uniform => {
            let color = c.required(&p("color"), t.color, "for kind = \"uniform\"")?;
            Ok(TextureSpec::Uniform {
                color: c.color(&p("color"), color)?,
            })
        }
        TextureKind::Image => match (t.path, t.builtin) {
            (Some(_), Some(_)) => c.err(&p("builtin"), "give either `path` or `builtin`, not both"),
            (None, None) => c.err(
                path,
                "an image texture needs `path = \"...\"` or `builtin = \"earth\"`",
            ),
            (None, Some(b)) => match b.as_str() {
                "earth" => Ok(TextureSpec::Image(ImageSource::Builtin(
                    BuiltinImage::Earth,
                ))),
                other => c.err(
                    &p("builtin"),
                    format!("unknown built-in image {other:?}, expected \"earth\""),
                ),
            },
            (Some(file), None) => {
                if file.is_empty() {
                    return c.err(&p("path"), "must not be empty");
                }
                let full = base_dir.join(&file);
                if full.is_file() {
                    Ok(TextureSpec::Image(ImageSource::File(full)))
                } else {
                    c.err(
                        &p("path"),
                        format!("image file {} not found", full.display()),
                    )
                }
            }
        },
    }
}
