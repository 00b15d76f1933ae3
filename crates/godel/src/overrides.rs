//! `godel render --width --height --max-past --method --name --samples`: scene fields set from
//! the command line. The values are written into the scene's TOML (`camera.width`,
//! `camera.height`, `trace.max_past`, `trace.method`, `name`, `camera.samples`) and the result is validated by
//! the scene crate exactly like a scene file, so the same rules hold; a refusal names the
//! flag. The data file then embeds the scene as rendered (overrides included).

use std::path::PathBuf;

use scene::{Scene, BUILTIN_SCENE_NAME, BUILTIN_SCENE_TEXT};
use toml::{Table, Value};

use crate::args::usage;

/// The overridable scene fields, as given on the command line (unchecked).
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    pub width: Option<i64>,
    pub height: Option<i64>,
    pub max_past: Option<f64>,
    pub method: Option<String>,
    pub name: Option<String>,
    pub samples: Option<i64>,
}

/// Each override: its flag, its scene field path, and its TOML value.
fn entries(o: &Overrides) -> Vec<(&'static str, [&'static str; 2], Value)> {
    let mut out = Vec::new();
    if let Some(w) = o.width {
        out.push(("--width", ["camera", "width"], Value::Integer(w)));
    }
    if let Some(h) = o.height {
        out.push(("--height", ["camera", "height"], Value::Integer(h)));
    }
    if let Some(m) = o.max_past {
        out.push(("--max-past", ["trace", "max_past"], Value::Float(m)));
    }
    if let Some(m) = &o.method {
        out.push(("--method", ["trace", "method"], Value::String(m.clone())));
    }
    if let Some(n) = &o.name {
        out.push(("--name", ["", "name"], Value::String(n.clone())));
    }
    if let Some(n) = o.samples {
        out.push(("--samples", ["camera", "samples"], Value::Integer(n)));
    }
    out
}

/// The scene of `path` (or the built-in one) with the overrides applied and validated.
pub fn load_with_overrides(path: &Option<PathBuf>, o: &Overrides) -> anyhow::Result<Scene> {
    // The file on its own first: its own mistakes are located in it.
    let scene = crate::args::load_scene(path)?;
    let set = entries(o);
    if set.is_empty() {
        return Ok(scene);
    }
    let file = match path {
        Some(p) => p.display().to_string(),
        None => BUILTIN_SCENE_NAME.to_string(),
    };
    let text = if path.is_some() {
        scene.source_text.clone()
    } else {
        BUILTIN_SCENE_TEXT.to_string()
    };
    let mut table: Table = text
        .parse()
        .map_err(|e| anyhow::anyhow!("{file}: cannot re-read the scene: {e}"))?;
    for (_, [section, key], value) in &set {
        let target = if section.is_empty() {
            &mut table
        } else {
            match table
                .entry(section.to_string())
                .or_insert_with(|| Value::Table(Table::new()))
            {
                Value::Table(t) => t,
                _ => return Err(anyhow::anyhow!("{file}: [{section}] is not a table")),
            }
        };
        target.insert(key.to_string(), value.clone());
    }
    let new_text = toml::to_string(&table)?;
    let flags: Vec<&str> = set.iter().map(|(f, _, _)| *f).collect();
    let mut scene = Scene::from_str(&new_text, &file).map_err(|e| {
        // The flag whose field the scene crate refused, else all the flags given.
        let flag = set
            .iter()
            .find(|(_, [section, key], _)| {
                let field = if section.is_empty() {
                    key.to_string()
                } else {
                    format!("{section}.{key}")
                };
                e.field == field || e.field.starts_with(&format!("{field}."))
            })
            .map_or_else(|| flags.join("/"), |(f, _, _)| f.to_string());
        let what = if e.field.is_empty() {
            e.message.clone()
        } else {
            format!("{}: {}", e.field, e.message)
        };
        usage(&flag, what)
    })?;
    scene.source_path = path.clone();
    Ok(scene)
}
