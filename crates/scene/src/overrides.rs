//! Scene fields set for one run (`godel render --width --height --max-past --method --name
//! --samples`, and the same keywords of the Python module's `render`): the values are
//! written into the scene's TOML (`camera.width`, `camera.height`, `trace.max_past`,
//! `trace.method`, `name`, `camera.samples`) and the result is validated exactly like a
//! scene file, so the same rules hold; a refusal names the setting that caused it. The data
//! file then embeds the scene as rendered (overrides included).
//!
//! The spacetime too (`--metric --a --m2 --omega`: `spacetime.metric`, `spacetime.a`,
//! `spacetime.m2`, `spacetime.omega`), e.g. a member of the Gödel-type family for a Gödel
//! scene: a new metric takes its constants from the overrides alone (the scene's `a`, `m2`
//! and `omega` are dropped first, since each metric refuses the others' constants); without
//! one, a constant replaces the scene's.

use std::fmt;
use std::path::Path;

use toml::{Table, Value};

use crate::{Scene, SceneError, BUILTIN_SCENE_NAME, BUILTIN_SCENE_TEXT};

/// Where a scene comes from.
#[derive(Clone, Copy, Debug)]
pub enum SceneSource<'a> {
    /// The built-in reference scene.
    Builtin,
    /// A scene file; relative image paths are resolved against its folder.
    File(&'a Path),
    /// Scene text; `name` stands for the file in messages (relative image paths are
    /// resolved against the current folder).
    Text { text: &'a str, name: &'a str },
}

/// An overridable scene field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    Width,
    Height,
    MaxPast,
    Method,
    Name,
    Samples,
    Metric,
    A,
    M2,
    Omega,
}

impl Setting {
    /// The command-line flag that sets it (`--max-past`).
    pub fn flag(self) -> &'static str {
        match self {
            Setting::Width => "--width",
            Setting::Height => "--height",
            Setting::MaxPast => "--max-past",
            Setting::Method => "--method",
            Setting::Name => "--name",
            Setting::Samples => "--samples",
            Setting::Metric => "--metric",
            Setting::A => "--a",
            Setting::M2 => "--m2",
            Setting::Omega => "--omega",
        }
    }

    /// The keyword argument that sets it in the Python module (`max_past`).
    pub fn keyword(self) -> &'static str {
        match self {
            Setting::Width => "width",
            Setting::Height => "height",
            Setting::MaxPast => "max_past",
            Setting::Method => "method",
            Setting::Name => "name",
            Setting::Samples => "samples",
            Setting::Metric => "metric",
            Setting::A => "a",
            Setting::M2 => "m2",
            Setting::Omega => "omega",
        }
    }

    /// Its place in the scene file: (section, key), the section empty at the top level.
    fn field(self) -> (&'static str, &'static str) {
        match self {
            Setting::Width => ("camera", "width"),
            Setting::Height => ("camera", "height"),
            Setting::MaxPast => ("trace", "max_past"),
            Setting::Method => ("trace", "method"),
            Setting::Name => ("", "name"),
            Setting::Samples => ("camera", "samples"),
            Setting::Metric => ("spacetime", "metric"),
            Setting::A => ("spacetime", "a"),
            Setting::M2 => ("spacetime", "m2"),
            Setting::Omega => ("spacetime", "omega"),
        }
    }

    /// Its field path as scene errors name it (`camera.width`, `name`).
    fn path(self) -> String {
        match self.field() {
            ("", key) => key.to_string(),
            (section, key) => format!("{section}.{key}"),
        }
    }
}

/// The overridable scene fields, as given (unchecked).
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    pub width: Option<i64>,
    pub height: Option<i64>,
    pub max_past: Option<f64>,
    pub method: Option<String>,
    pub name: Option<String>,
    pub samples: Option<i64>,
    pub metric: Option<String>,
    pub a: Option<f64>,
    pub m2: Option<f64>,
    pub omega: Option<f64>,
}

impl Overrides {
    /// Each override given, with its TOML value.
    fn entries(&self) -> Vec<(Setting, Value)> {
        let mut out = Vec::new();
        let mut put = |setting, value: Option<Value>| {
            if let Some(v) = value {
                out.push((setting, v));
            }
        };
        put(Setting::Width, self.width.map(Value::Integer));
        put(Setting::Height, self.height.map(Value::Integer));
        put(Setting::MaxPast, self.max_past.map(Value::Float));
        put(Setting::Method, self.method.clone().map(Value::String));
        put(Setting::Name, self.name.clone().map(Value::String));
        put(Setting::Samples, self.samples.map(Value::Integer));
        put(Setting::Metric, self.metric.clone().map(Value::String));
        put(Setting::A, self.a.map(Value::Float));
        put(Setting::M2, self.m2.map(Value::Float));
        put(Setting::Omega, self.omega.map(Value::Float));
        out
    }
}

/// A scene refused with its overrides.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadError {
    /// The scene itself is wrong (before any override): located in its file.
    Scene(SceneError),
    /// An override made it invalid: the settings to blame (the one whose field was refused,
    /// else all that were given) and what is wrong (`camera.width: must be …`).
    Override {
        settings: Vec<Setting>,
        message: String,
    },
}

impl LoadError {
    /// The message with the settings named by `name` (e.g. [`Setting::flag`]) and joined
    /// by `/`: `--width: camera.width: must be …`.
    pub fn describe(&self, name: impl Fn(Setting) -> &'static str) -> String {
        match self {
            LoadError::Scene(e) => e.to_string(),
            LoadError::Override { settings, message } => {
                let names: Vec<&str> = settings.iter().map(|s| name(*s)).collect();
                format!("{}: {message}", names.join("/"))
            }
        }
    }
}

impl fmt::Display for LoadError {
    /// As the command line says it (settings named by their flags).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe(Setting::flag))
    }
}

impl std::error::Error for LoadError {}

/// The scene of `source` with the overrides applied and validated.
pub fn load(source: SceneSource, o: &Overrides) -> Result<Scene, LoadError> {
    // The scene on its own first: its own mistakes are located in it.
    let (mut scene, text, file) = match source {
        SceneSource::Builtin => (
            Scene::builtin(),
            BUILTIN_SCENE_TEXT.to_string(),
            BUILTIN_SCENE_NAME.to_string(),
        ),
        SceneSource::File(path) => {
            let scene = Scene::from_file(path).map_err(LoadError::Scene)?;
            let text = scene.source_text.clone();
            (scene, text, path.display().to_string())
        }
        SceneSource::Text { text, name } => (
            Scene::from_str(text, name).map_err(LoadError::Scene)?,
            text.to_string(),
            name.to_string(),
        ),
    };
    let set = o.entries();
    if set.is_empty() {
        return Ok(scene);
    }
    let all: Vec<Setting> = set.iter().map(|(s, _)| *s).collect();
    let refuse = |message: String| LoadError::Override {
        settings: all.clone(),
        message,
    };
    let mut table: Table = text
        .parse()
        .map_err(|e| refuse(format!("{file}: cannot re-read the scene: {e}")))?;
    if o.metric.is_some() {
        // A new metric's constants are the overrides' alone (module documentation).
        if let Some(Value::Table(spacetime)) = table.get_mut("spacetime") {
            for key in ["a", "m2", "omega"] {
                spacetime.remove(key);
            }
        }
    }
    for (setting, value) in &set {
        let (section, key) = setting.field();
        let target = if section.is_empty() {
            &mut table
        } else {
            match table
                .entry(section.to_string())
                .or_insert_with(|| Value::Table(Table::new()))
            {
                Value::Table(t) => t,
                _ => return Err(refuse(format!("{file}: [{section}] is not a table"))),
            }
        };
        target.insert(key.to_string(), value.clone());
    }
    let new_text =
        toml::to_string(&table).map_err(|e| refuse(format!("{file}: cannot write: {e}")))?;
    let source_path = scene.source_path.take();
    scene = Scene::from_str(&new_text, &file).map_err(|e| {
        // The setting whose field the scene crate refused (a constant the new metric lacks:
        // the metric), else all those given.
        let blamed = all
            .iter()
            .find(|s| {
                let field = s.path();
                e.field == field || e.field.starts_with(&format!("{field}."))
            })
            .or_else(|| {
                all.iter()
                    .find(|s| **s == Setting::Metric && e.field.starts_with("spacetime."))
            });
        let message = if e.field.is_empty() {
            e.message.clone()
        } else {
            format!("{}: {}", e.field, e.message)
        };
        LoadError::Override {
            settings: blamed.map_or_else(|| all.clone(), |s| vec![*s]),
            message,
        }
    })?;
    scene.source_path = source_path;
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_replace_fields_and_refusals_name_the_setting() {
        let o = Overrides {
            width: Some(44),
            samples: Some(4),
            ..Default::default()
        };
        let scene = load(SceneSource::Builtin, &o).unwrap();
        assert_eq!((scene.camera.width(), scene.samples), (44, 4));
        assert!(scene.source_text.contains("width = 44"));

        let bad = Overrides {
            width: Some(0),
            max_past: Some(3.0),
            ..Default::default()
        };
        let e = load(SceneSource::Builtin, &bad).unwrap_err();
        let flags = e.to_string();
        assert!(flags.starts_with("--width: camera.width: "), "{flags}");
        let keywords = e.describe(Setting::keyword);
        assert_eq!(keywords, flags.replacen("--width", "width", 1));
    }

    #[test]
    fn a_bad_scene_is_located_in_its_own_text_before_any_override() {
        let source = SceneSource::Text {
            text: "name = 3\n",
            name: "<text>",
        };
        let o = Overrides {
            width: Some(10),
            ..Default::default()
        };
        match load(source, &o).unwrap_err() {
            LoadError::Scene(e) => {
                assert_eq!((e.file.as_str(), e.line()), ("<text>", Some(1)));
                assert_eq!(e.field, "name");
            }
            other => panic!("expected a scene error, got {other:?}"),
        }
    }

    #[test]
    fn the_metric_and_its_constants_are_overridden() {
        // The built-in Gödel scene as a Gödel-type member: its a is dropped.
        let o = Overrides {
            metric: Some("godel-type".into()),
            m2: Some(0.5),
            omega: Some(0.6),
            ..Default::default()
        };
        let scene = load(SceneSource::Builtin, &o).unwrap();
        assert_eq!(
            scene.metric.godel_type(),
            Some(spacetime::GodelType::new(0.5, 0.6))
        );
        // Without a metric, a constant replaces the scene's: a of the Gödel scene.
        let o = Overrides {
            a: Some(2.0),
            ..Default::default()
        };
        let scene = load(SceneSource::Builtin, &o).unwrap();
        assert_eq!(scene.metric.godel_a(), Some(2.0));
        // Refusals name the setting: m2 on a Gödel scene, a bad omega, a with the family.
        let cases = [
            (
                Overrides {
                    m2: Some(1.0),
                    ..Default::default()
                },
                "m2: spacetime.m2: ",
            ),
            (
                Overrides {
                    metric: Some("godel-type".into()),
                    m2: Some(1.0),
                    omega: Some(-1.0),
                    ..Default::default()
                },
                "omega: spacetime.omega: ",
            ),
            (
                Overrides {
                    metric: Some("godel-type".into()),
                    a: Some(1.0),
                    m2: Some(1.0),
                    omega: Some(1.0),
                    ..Default::default()
                },
                "a: spacetime.a: ",
            ),
        ];
        let missing = Overrides {
            metric: Some("godel-type".into()),
            m2: Some(1.0),
            width: Some(20),
            ..Default::default()
        };
        let text = load(SceneSource::Builtin, &missing)
            .unwrap_err()
            .describe(Setting::keyword);
        assert!(text.starts_with("metric: spacetime.omega: "), "{text}");
        for (o, start) in cases {
            let e = load(SceneSource::Builtin, &o).unwrap_err();
            let text = e.describe(Setting::keyword);
            assert!(text.starts_with(start), "{text}");
        }
    }
}
