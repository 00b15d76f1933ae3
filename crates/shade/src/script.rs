//! Sequence scripts: image sequences from one data file (or from a scene traced at several
//! observer times) with shader parameters keyframed over the frames.
//!
//! ```toml
//! data = "../out/reference.exr"      # a data file (paths relative to the script), or:
//! # [trace]                          # trace a scene per frame, the observer time advancing
//! # scene = "../scenes/static-sphere.toml"
//! # observer_time = [0.0, 2.0]       # first and last frame, linear in between
//! # keep_data = true                 # also write frame_NNNN.exr, each frame's data file
//! output = "frames"                  # folder for frame_0000.png, … and sequence.mp4
//! frames = 48                        # 1 to 100000
//! fps = 24.0                         # at most 1000
//! interpolation = "smooth"           # default for every keyframe: "linear" | "smooth"
//! mp4 = true                         # also encode an MP4 when ffmpeg is on PATH
//!
//! [settings]                         # base settings (any ShadeSettings fields)
//! shaders = ["frequency"]
//!
//! [[keyframe]]
//! frame = 0                          # or time = 0.0 (seconds; frame = round(time·fps))
//! [keyframe.settings]
//! objects.earth.temperature = 3000.0
//!
//! [[keyframe]]
//! frame = 47
//! interpolation = "linear"           # how this keyframe goes on to the next (default: the script's)
//! [keyframe.settings]
//! objects.earth.temperature = 9000.0
//! ```
//!
//! Keyframe k's settings are the data file's defaults, overlaid with `[settings]`, then with
//! keyframes 0..=k in turn (a field keeps its value until a keyframe changes it). Between
//! keyframes k and k+1 at frames f_k < f_{k+1}, frame f takes s = (f − f_k)/(f_{k+1} − f_k),
//! eased by keyframe k's interpolation (linear: s; smooth: 3s² − 2s³), and every float field
//! is a + e(s)·(b − a); other fields (names, switches, integers) hold keyframe k's value.
//! Before the first keyframe and after the last, their settings hold.
//!
//! A traced sequence's keyframes may also set the observer and the camera's field of view:
//!
//! ```toml
//! [keyframe.observer]                # any observer field of a scene; position in x, y, z
//! time = 2.0
//! position = { x = 0.5, y = 0.0, z = 0.1 }
//! velocity = { speed = 0.3, direction = [0, 1, 0] }
//! forward = [0, 1, 0]
//! up = [0, 0, 1]
//! [keyframe.camera]                  # the field of view keys of the scene's camera kind
//! fov_deg = 60.0                     # (CAMERA_KEYS)
//! ```
//!
//! Every such section is a [`Track`] ([`Script::track`]): the same rule as the settings,
//! starting from a given table (the scene's own observer and camera).
//!
//! [`keyframe_toml`] writes one keyframe from complete settings: its text pastes into a script.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::ShadeError;
use crate::settings::ShadeSettings;
use crate::tree::{lerp, merge};
use scene::line_of_path;

/// How a keyframe goes on to the next.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Default)]
#[serde(rename_all = "lowercase")]
pub enum Interpolation {
    /// s.
    Linear,
    /// 3s² − 2s³: starts and ends at rest.
    #[default]
    Smooth,
}

impl Interpolation {
    /// The eased fraction for `s` ∈ [0, 1] (clamped).
    pub fn ease(self, s: f64) -> f64 {
        let s = s.clamp(0.0, 1.0);
        match self {
            Interpolation::Linear => s,
            Interpolation::Smooth => s * s * (3.0 - 2.0 * s),
        }
    }
}

/// Where frames get their per-pixel data.
#[derive(Clone, Debug, PartialEq)]
pub enum FrameSource {
    /// Every frame shades this data file.
    Data(PathBuf),
    /// Every frame traces this scene; with `observer_time` the observer's time goes linearly
    /// from the first value (frame 0) to the second (last frame); with `keep_data` each
    /// frame's data file is written beside its picture.
    Trace {
        scene: PathBuf,
        observer_time: Option<[f64; 2]>,
        keep_data: bool,
    },
}

/// A keyframe as written: its frame, interpolation, and the fields it sets.
#[derive(Clone, Debug, PartialEq)]
pub struct Keyframe {
    pub frame: u32,
    pub interpolation: Interpolation,
    /// A partial settings table.
    pub settings: toml::Table,
    /// A partial observer table (keys as in a scene's `[observer]`, position in x, y, z),
    /// numbers as floats.
    pub observer: toml::Table,
    /// A partial camera table (keys among [`CAMERA_KEYS`]), numbers as floats.
    pub camera: toml::Table,
}

/// A keyframe section that a [`Track`] follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Section {
    Settings,
    Observer,
    Camera,
}

impl Section {
    /// Its key in a keyframe.
    pub fn name(self) -> &'static str {
        match self {
            Section::Settings => "settings",
            Section::Observer => "observer",
            Section::Camera => "camera",
        }
    }

    fn of(self, k: &Keyframe) -> &toml::Table {
        match self {
            Section::Settings => &k.settings,
            Section::Observer => &k.observer,
            Section::Camera => &k.camera,
        }
    }
}

/// The camera keys a keyframe may set: the fields of view, as the camera kinds use them
/// (pinhole and fisheye `fov_deg`, panorama `h_fov_deg` and `v_fov_deg`).
pub const CAMERA_KEYS: [&str; 3] = ["fov_deg", "h_fov_deg", "v_fov_deg"];

/// A parsed, checked sequence script.
#[derive(Clone, Debug, PartialEq)]
pub struct Script {
    /// The script file (for messages).
    pub file: String,
    /// Its text (to locate errors found later).
    text: String,
    pub source: FrameSource,
    /// Output folder.
    pub output: PathBuf,
    /// Number of frames (≥ 1).
    pub frames: u32,
    /// Frames per second (> 0).
    pub fps: f64,
    /// Encode an MP4 when ffmpeg is available.
    pub mp4: bool,
    /// The base settings fields.
    pub settings: toml::Table,
    /// In increasing frame order.
    pub keyframes: Vec<Keyframe>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScript {
    data: Option<PathBuf>,
    trace: Option<RawTrace>,
    output: Option<PathBuf>,
    frames: u32,
    #[serde(default = "default_fps")]
    fps: f64,
    #[serde(default)]
    interpolation: Interpolation,
    #[serde(default = "yes")]
    mp4: bool,
    #[serde(default)]
    settings: toml::Table,
    #[serde(default)]
    keyframe: Vec<RawKeyframe>,
}

fn default_fps() -> f64 {
    24.0
}

fn yes() -> bool {
    true
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTrace {
    scene: PathBuf,
    observer_time: Option<[f64; 2]>,
    #[serde(default)]
    keep_data: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawKeyframe {
    frame: Option<u32>,
    time: Option<f64>,
    interpolation: Option<Interpolation>,
    #[serde(default)]
    settings: toml::Table,
    #[serde(default)]
    observer: toml::Table,
    #[serde(default)]
    camera: toml::Table,
}

/// The shape of a keyframe's `[keyframe.observer]`: every key it may hold, with a number
/// (0.0) or an array of three numbers where one goes.
fn observer_shape() -> toml::Table {
    let v3 = || toml::Value::Array(vec![toml::Value::Float(0.0); 3]);
    let table = |keys: &[(&str, toml::Value)]| {
        toml::Value::Table(
            keys.iter()
                .map(|(k, v)| (k.to_string(), v.clone()))
                .collect(),
        )
    };
    let f = toml::Value::Float(0.0);
    let mut t = toml::Table::new();
    t.insert("time".into(), f.clone());
    t.insert(
        "position".into(),
        table(&[("x", f.clone()), ("y", f.clone()), ("z", f.clone())]),
    );
    t.insert(
        "velocity".into(),
        table(&[("speed", f.clone()), ("direction", v3())]),
    );
    t.insert("forward".into(), v3());
    t.insert("up".into(), v3());
    t
}

/// The shape of a keyframe's `[keyframe.camera]`.
fn camera_shape() -> toml::Table {
    CAMERA_KEYS
        .iter()
        .map(|k| (k.to_string(), toml::Value::Float(0.0)))
        .collect()
}

/// `value` checked against `shape` (every key known, every number finite, arrays of the
/// shape's length) with integers turned into floats; an error is `(field path, message)`.
fn conform(
    value: &toml::Table,
    shape: &toml::Table,
    prefix: &str,
) -> Result<toml::Table, (String, String)> {
    let mut out = toml::Table::new();
    for (key, v) in value {
        let path = format!("{prefix}.{key}");
        let Some(want) = shape.get(key) else {
            let known: Vec<&str> = shape.keys().map(String::as_str).collect();
            return Err((
                path,
                format!(
                    "unknown field '{key}' (expected one of: {})",
                    known.join(", ")
                ),
            ));
        };
        out.insert(key.clone(), conform_value(v, want, &path)?);
    }
    Ok(out)
}

fn conform_value(
    v: &toml::Value,
    want: &toml::Value,
    path: &str,
) -> Result<toml::Value, (String, String)> {
    match (want, v) {
        (toml::Value::Table(shape), toml::Value::Table(t)) => {
            Ok(toml::Value::Table(conform(t, shape, path)?))
        }
        (toml::Value::Array(shape), toml::Value::Array(a)) if a.len() == shape.len() => a
            .iter()
            .zip(shape)
            .enumerate()
            .map(|(i, (x, w))| conform_value(x, w, &format!("{path}[{i}]")))
            .collect::<Result<Vec<_>, _>>()
            .map(toml::Value::Array),
        (toml::Value::Float(_), toml::Value::Float(x)) if x.is_finite() => {
            Ok(toml::Value::Float(*x))
        }
        (toml::Value::Float(_), toml::Value::Integer(i)) => Ok(toml::Value::Float(*i as f64)),
        (toml::Value::Float(_), toml::Value::Float(x)) => {
            Err((path.to_string(), format!("must be finite, got {x}")))
        }
        (toml::Value::Float(_), _) => Err((path.to_string(), "must be a number".into())),
        (toml::Value::Array(shape), _) => Err((
            path.to_string(),
            format!("must be an array of {} numbers", shape.len()),
        )),
        _ => Err((path.to_string(), "must be a table".into())),
    }
}

/// The keyframe block that [`keyframe_toml`] writes.
#[derive(Serialize)]
struct KeyframeOut<'a> {
    keyframe: [KeyframeEntry<'a>; 1],
}

#[derive(Serialize)]
struct KeyframeEntry<'a> {
    frame: u32,
    settings: &'a ShadeSettings,
}

/// One keyframe at `frame` holding all of `settings`, as TOML text that pastes into a script
/// (append it after the keyframes with smaller frames).
pub fn keyframe_toml(frame: u32, settings: &ShadeSettings) -> String {
    toml::to_string(&KeyframeOut {
        keyframe: [KeyframeEntry { frame, settings }],
    })
    .expect("settings always serialize to TOML")
}

/// Most frames in a sequence (over an hour at 24 fps).
pub const MAX_FRAMES: u32 = 100_000;
/// Highest frame rate.
pub const MAX_FPS: f64 = 1000.0;

impl Script {
    /// Reads and checks a script file (a regular file of at most
    /// [`scene::input::MAX_TEXT_BYTES`]).
    pub fn from_file(path: &Path) -> Result<Script, ShadeError> {
        let text = scene::input::read_text(path, scene::input::MAX_TEXT_BYTES).map_err(|e| {
            ShadeError::Script {
                file: path.display().to_string(),
                line: 0,
                field: String::new(),
                message: format!("cannot read the script: {e}"),
            }
        })?;
        Script::parse(&text, path)
    }

    /// Parses script text read from `path` (relative paths in it are resolved against the
    /// path's folder). Checks the layout, the source, the frame count, and that keyframes are
    /// in increasing frame order within the sequence; settings fields are checked against a
    /// data file by [`Script::timeline`].
    pub fn parse(text: &str, path: &Path) -> Result<Script, ShadeError> {
        let file = path.display().to_string();
        let error = |field: &str, message: String| ShadeError::Script {
            file: file.clone(),
            line: line_of_path(text, field).unwrap_or(0),
            field: field.to_string(),
            message,
        };
        let raw: RawScript = toml::from_str(text).map_err(|e| ShadeError::Script {
            file: file.clone(),
            line: e
                .span()
                .map(|s| scene::line_column(text, s.start).line)
                .unwrap_or(0),
            field: String::new(),
            message: e.message().trim().to_string(),
        })?;
        let base = path.parent().unwrap_or(Path::new(""));
        let source =
            match (raw.data, raw.trace) {
                (Some(d), None) => FrameSource::Data(base.join(d)),
                (None, Some(t)) => {
                    if let Some(ot) = t.observer_time {
                        if !ot.iter().all(|v| v.is_finite()) {
                            return Err(error(
                                "trace.observer_time",
                                format!("must be finite, got {ot:?}"),
                            ));
                        }
                    }
                    FrameSource::Trace {
                        scene: base.join(t.scene),
                        observer_time: t.observer_time,
                        keep_data: t.keep_data,
                    }
                }
                _ => return Err(error(
                    "data",
                    "give either `data = \"FILE.exr\"` or a [trace] table with `scene`, not both"
                        .into(),
                )),
            };
        if !(1..=MAX_FRAMES).contains(&raw.frames) {
            return Err(error(
                "frames",
                format!(
                    "must be at least 1 and at most {MAX_FRAMES}, got {}",
                    raw.frames
                ),
            ));
        }
        if !(raw.fps.is_finite() && raw.fps > 0.0 && raw.fps <= MAX_FPS) {
            return Err(error(
                "fps",
                format!("must be positive and at most {MAX_FPS}, got {}", raw.fps),
            ));
        }
        let mut keyframes: Vec<Keyframe> = Vec::new();
        for (i, k) in raw.keyframe.into_iter().enumerate() {
            let field = format!("keyframe[{i}]");
            let frame = match (k.frame, k.time) {
                (Some(f), None) => f,
                (None, Some(t)) if t.is_finite() && t >= 0.0 => (t * raw.fps).round() as u32,
                (None, Some(t)) => {
                    return Err(error(
                        &format!("{field}.time"),
                        format!("must be finite and ≥ 0, got {t}"),
                    ))
                }
                (Some(_), Some(_)) => {
                    return Err(error(
                        &field,
                        "give either `frame` or `time` (seconds), not both".into(),
                    ))
                }
                (None, None) => {
                    return Err(error(
                        &field,
                        "says neither when it is: give `frame` (a frame number) or `time` \
                         (seconds)"
                            .into(),
                    ))
                }
            };
            let at = if k.frame.is_some() { "frame" } else { "time" };
            if frame >= raw.frames {
                return Err(error(
                    &format!("{field}.{at}"),
                    format!(
                        "frame {frame} is past the sequence's last frame {}",
                        raw.frames - 1
                    ),
                ));
            }
            if let Some(prev) = keyframes.last() {
                if frame <= prev.frame {
                    return Err(error(
                        &format!("{field}.{at}"),
                        format!(
                            "keyframes out of order: keyframe {i} is at frame {frame}, \
                             keyframe {} at frame {}; list keyframes in increasing frame order",
                            i - 1,
                            prev.frame
                        ),
                    ));
                }
            }
            let observer = conform(&k.observer, &observer_shape(), &format!("{field}.observer"))
                .map_err(|(f, m)| error(&f, m))?;
            let camera = conform(&k.camera, &camera_shape(), &format!("{field}.camera"))
                .map_err(|(f, m)| error(&f, m))?;
            for (section, table) in [("observer", &observer), ("camera", &camera)] {
                if let (FrameSource::Data(_), Some(key)) = (&source, table.keys().next()) {
                    return Err(error(
                        &format!("{field}.{section}.{key}"),
                        format!(
                            "this sequence re-shades one data file, so its {section} cannot \
                             change; trace a scene instead ([trace] scene = \"…\")"
                        ),
                    ));
                }
            }
            let old_time = matches!(
                source,
                FrameSource::Trace {
                    observer_time: Some(_),
                    ..
                }
            );
            if old_time && observer.contains_key("time") {
                return Err(error(
                    &format!("{field}.observer.time"),
                    "the observer's time is already set by [trace] observer_time; give it \
                     either there or in keyframes, not both"
                        .into(),
                ));
            }
            keyframes.push(Keyframe {
                frame,
                interpolation: k.interpolation.unwrap_or(raw.interpolation),
                settings: k.settings,
                observer,
                camera,
            });
        }
        Ok(Script {
            file,
            text: text.to_string(),
            source,
            output: base.join(raw.output.unwrap_or_else(|| PathBuf::from("frames"))),
            frames: raw.frames,
            fps: raw.fps,
            mp4: raw.mp4,
            settings: raw.settings,
            keyframes,
        })
    }

    /// An error about `field` of this script, located at its line.
    pub fn error_at(&self, field: &str, message: impl Into<String>) -> ShadeError {
        ShadeError::Script {
            file: self.file.clone(),
            line: line_of_path(&self.text, field).unwrap_or(0),
            field: field.to_string(),
            message: message.into(),
        }
    }

    /// The track of one keyframe section: keyframe k's table is `start` overlaid with that
    /// section of keyframes 0..=k in turn. A key that `start` lacks is an error naming the
    /// script line and `keyframe[k].SECTION.KEY`.
    pub fn track(&self, section: Section, start: &toml::Table) -> Result<Track, ShadeError> {
        let mut current = start.clone();
        let mut keys = Vec::new();
        for (i, k) in self.keyframes.iter().enumerate() {
            let field = format!("keyframe[{i}].{}", section.name());
            current = merge(&current, section.of(k), "")
                .map_err(|(f, m)| self.error_at(&format!("{field}.{f}"), m))?;
            keys.push((
                k.frame,
                k.interpolation,
                toml::Value::Table(current.clone()),
            ));
        }
        Ok(Track {
            start: toml::Value::Table(start.clone()),
            keys,
        })
    }

    /// Whether any keyframe sets something in `section`.
    pub fn sets(&self, section: Section) -> bool {
        self.keyframes.iter().any(|k| !section.of(k).is_empty())
    }

    /// The keyframe whose values a frame `frame` shows or moves towards: the first keyframe
    /// at or after it, else the last (for messages about an interpolated frame).
    pub fn keyframe_towards(&self, frame: u32) -> Option<usize> {
        let last = self.keyframes.len().checked_sub(1)?;
        Some(
            self.keyframes
                .iter()
                .position(|k| k.frame >= frame)
                .unwrap_or(last),
        )
    }

    /// The complete settings at each keyframe, starting from `defaults` (those of the data
    /// file); errors name the script line and field of an unknown field or object, or of a
    /// value of the wrong type.
    pub fn timeline(&self, defaults: &ShadeSettings) -> Result<Timeline, ShadeError> {
        let start = toml::Table::try_from(defaults).expect("settings serialize to a table");
        let start = merge(&start, &self.settings, "")
            .map_err(|(f, m)| self.error_at(&format!("settings.{f}"), m))?;
        let check = |table: &toml::Table, field: &str| {
            ShadeSettings::from_table(table.clone()).map_err(|(path, message)| {
                let at = if path.is_empty() {
                    field.to_string()
                } else {
                    format!("{field}.{path}")
                };
                self.error_at(&at, message)
            })
        };
        let base = check(&start, "settings")?;
        let track = self.track(Section::Settings, &start)?;
        for (i, (_, _, tree)) in track.keys.iter().enumerate() {
            if let toml::Value::Table(t) = tree {
                check(t, &format!("keyframe[{i}].settings"))?;
            }
        }
        Ok(Timeline { base, track })
    }
}

/// One keyframe section over the frames: a complete table at every keyframe, interpolated in
/// between by the module docs' rule.
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    /// Used when there are no keyframes.
    start: toml::Value,
    /// (frame, interpolation to the next, complete tree), frames increasing.
    keys: Vec<(u32, Interpolation, toml::Value)>,
}

impl Track {
    /// The complete tree (a table) at frame `frame`.
    pub fn at(&self, frame: u32) -> toml::Value {
        match self.keys.iter().position(|k| k.0 > frame) {
            _ if self.keys.is_empty() => self.start.clone(),
            Some(0) => self.keys[0].2.clone(),
            None => self.keys[self.keys.len() - 1].2.clone(),
            Some(j) => {
                let (fa, interp, a) = &self.keys[j - 1];
                let (fb, _, b) = &self.keys[j];
                let s = f64::from(frame - fa) / f64::from(fb - fa);
                lerp(a, b, interp.ease(s))
            }
        }
    }
}

/// Complete settings at every keyframe, ready to interpolate.
#[derive(Clone, Debug, PartialEq)]
pub struct Timeline {
    /// Used when there are no keyframes.
    base: ShadeSettings,
    track: Track,
}

impl Timeline {
    /// The settings of frame `frame` (module docs give the rule).
    pub fn settings_at(&self, frame: u32) -> ShadeSettings {
        if self.track.keys.is_empty() {
            return self.base.clone();
        }
        // Both ends deserialized when the timeline was built, and interpolation keeps every
        // leaf's type, so this cannot fail; the base is the safe answer if it ever did.
        ShadeSettings::deserialize(self.track.at(frame)).unwrap_or_else(|_| self.base.clone())
    }
}
