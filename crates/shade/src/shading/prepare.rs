//! [`Shading::new`]: shade settings checked against one data file, before any pixel is
//! shaded: the shaders named, objects and lights known to the file, each field in its range
//! (errors name the settings field, e.g. `objects.ball.temperature`), the caps
//! ([`MAX_LAMPS`], [`MAX_LIGHT_SOURCES`]), textures loaded once. The per-pixel rule is
//! `super`'s.

use std::collections::HashMap;

use datafile::DataFile;

use super::{Shading, MAX_EV};
use crate::blackbody::table;
use crate::body::{prepare_lamp, PreparedObject};
use crate::checks::{colour, direction, finite, first_unknown, invalid, non_negative, positive};
use crate::error::ShadeError;
use crate::frequency_shader::Brightness;
use crate::settings::{
    BrightnessMode, ObjectSettings, ShadeSettings, ShaderKind, TextureChoice, MAX_LAMPS,
    MAX_LIGHT_SOURCES,
};
use crate::texture::{ImageTexture, Texture};
use crate::texture_source::TextureSource;

impl Shading {
    /// Checks `settings` against `data` and loads the textures, image files from anywhere
    /// ([`TextureSource::any`]: the command line). Errors name the settings field (e.g.
    /// `objects.ball.temperature`), the unknown object, the image file, or the missing light
    /// channels.
    pub fn new(data: &DataFile, settings: &ShadeSettings) -> Result<Shading, ShadeError> {
        Shading::with_textures(data, settings, &TextureSource::any())
    }

    /// [`Shading::new`] with image textures, and the embedded scene's textures, from `textures`
    /// (the viewer restricts them to a few folders).
    pub fn with_textures(
        data: &DataFile,
        settings: &ShadeSettings,
        textures: &TextureSource,
    ) -> Result<Shading, ShadeError> {
        if settings.shaders.is_empty() {
            return Err(invalid("shaders", "name at least one shader"));
        }
        for (i, s) in settings.shaders.iter().enumerate() {
            if settings.shaders[..i].contains(s) {
                return Err(invalid("shaders", format!("'{}' is named twice", s.name())));
            }
        }
        let has = |k: ShaderKind| settings.shaders.contains(&k);
        // The polarization layer alone draws its ticks over the texture layer.
        let texture_layer =
            has(ShaderKind::Texture) || settings.shaders.as_slice() == [ShaderKind::Polarization];
        if has(ShaderKind::Polarization) && !data.polarization {
            return Err(invalid(
                "shaders",
                "the polarization shader needs the data file's pol_x, pol_y, pol_z channels \
                 (this file was traced without them: render it again)",
            ));
        }
        let names = &data.header.object_names;
        if let Some(name) = first_unknown(names, settings.objects.keys()) {
            return Err(invalid(
                format!("objects.{name}"),
                format!(
                    "unknown object '{name}' (the data file's objects: {})",
                    name_list(names)
                ),
            ));
        }
        let exposure = non_negative("exposure", settings.exposure)?;
        let brightness = match settings.brightness {
            BrightnessMode::Normalized => Brightness::Normalized,
            BrightnessMode::Physical => Brightness::Physical { exposure },
        };
        let time = &settings.time;
        let t0 = finite("time.t0", time.t0)?;
        let dt = positive("time.dt", time.dt)?;
        let tmin = finite("time.travel_min", time.travel_min)?;
        let tmax = finite("time.travel_max", time.travel_max)?;
        if tmax <= tmin {
            return Err(invalid(
                "time.travel_max",
                format!("must exceed travel_min ({tmin}), got {tmax}"),
            ));
        }
        let ambient = non_negative("light.ambient", settings.light.ambient)? as f32;
        let ev = finite("ev", settings.ev)?;
        if ev.abs() > MAX_EV {
            return Err(invalid(
                "ev",
                format!("must be within ±{MAX_EV} stops, got {ev}"),
            ));
        }
        let marks = if settings.grid {
            Some(crate::marks::data_camera(data).ok_or_else(|| {
                invalid(
                    "grid",
                    "the data file's embedded scene has no usable camera",
                )
            })?)
        } else {
            None
        };
        let sources = &settings.light.sources;
        if has(ShaderKind::Light) && data.lights.is_empty() {
            return Err(ShadeError::NoLightChannels);
        }
        // Extra sources only matter when the light layer would use them.
        if has(ShaderKind::Light) && sources.len() > data.lights.len() {
            return Err(invalid(
                format!("light.sources[{}]", data.lights.len()),
                format!(
                    "the data file has {} light channel(s), the settings {} source(s)",
                    data.lights.len(),
                    sources.len()
                ),
            ));
        }
        let most = MAX_LIGHT_SOURCES.max(data.lights.len());
        if sources.len() > most {
            return Err(invalid(
                "light.sources",
                format!(
                    "at most {most} sources (the data file has {} light channel(s)), got {}",
                    data.lights.len(),
                    sources.len()
                ),
            ));
        }
        let mut lights = Vec::new();
        for k in 0..data.lights.len() {
            let w = match sources.get(k) {
                Some(s) => {
                    let field = format!("light.sources[{k}]");
                    let i = non_negative(&format!("{field}.intensity"), s.intensity)? as f32;
                    let c = colour(&format!("{field}.color"), s.color)?;
                    if s.on {
                        c.map(|c| c * i)
                    } else {
                        [0.0; 3]
                    }
                }
                None => [1.0; 3],
            };
            lights.push(w);
        }

        // The scene's own textures, only when a layer paints textures.
        let paints = texture_layer || has(ShaderKind::Time) || has(ShaderKind::Light);
        // The data file's defaults only for objects the settings leave out (reading them
        // parses the embedded scene: the page sends every object, and skips that).
        let defaults =
            (settings.objects.len() < names.len()).then(|| ShadeSettings::defaults_for(data));
        let mut scene_textures: Option<Vec<Texture>> = None;
        let mut earth: Option<Texture> = None;
        // Each image file decoded once, however many objects show it.
        let mut images = HashMap::new();
        let mut objects = Vec::with_capacity(names.len());
        let mut axes = Vec::with_capacity(names.len());
        for (k, name) in names.iter().enumerate() {
            let o = settings
                .objects
                .get(name)
                .or_else(|| defaults.as_ref().and_then(|d| d.objects.get(name)))
                .cloned()
                .unwrap_or_else(|| ObjectSettings::new(crate::settings::DEFAULT_TEMPERATURE));
            let field = format!("objects.{name}");
            let temperature = positive(&format!("{field}.temperature"), o.temperature)?;
            let scale = [
                finite(&format!("{field}.scale_u"), o.scale_u)?,
                finite(&format!("{field}.scale_v"), o.scale_v)?,
            ];
            let rotation = finite(&format!("{field}.rotation_deg"), o.rotation_deg)?;
            let offset = [
                finite(&format!("{field}.offset_u"), o.offset_u)? - rotation / 360.0,
                finite(&format!("{field}.offset_v"), o.offset_v)?,
            ];
            if o.lamps.len() > MAX_LAMPS {
                return Err(invalid(
                    format!("{field}.lamps"),
                    format!(
                        "at most {MAX_LAMPS} lamps per object, got {}",
                        o.lamps.len()
                    ),
                ));
            }
            let lamps = o
                .lamps
                .iter()
                .enumerate()
                .map(|(i, l)| prepare_lamp(&format!("{field}.lamps[{i}]"), l))
                .collect::<Result<Vec<_>, _>>()?;
            let mut load = |choice: &TextureChoice, which: &str| -> Result<Texture, ShadeError> {
                let f = format!("{field}.{which}");
                if !paints {
                    return Ok(Texture::Uniform([1.0; 3]));
                }
                Ok(match choice {
                    TextureChoice::Scene => {
                        if scene_textures.is_none() {
                            scene_textures = Some(textures.scene_textures(data)?);
                        }
                        scene_textures
                            .as_ref()
                            .and_then(|t| t.get(k))
                            .cloned()
                            .ok_or_else(|| invalid(f, "the embedded scene has no such object"))?
                    }
                    TextureChoice::Checker { rows, cols } => {
                        if *rows == 0 || *cols == 0 {
                            return Err(invalid(f, "checker rows and cols must be at least 1"));
                        }
                        Texture::Checker {
                            rows: *rows,
                            cols: *cols,
                        }
                    }
                    TextureChoice::Gradient => Texture::Gradient,
                    TextureChoice::Uniform { color } => {
                        Texture::Uniform(colour(&format!("{f}.color"), *color)?)
                    }
                    TextureChoice::Image { path } => {
                        Texture::Image(textures.image_cached(path, &mut images)?)
                    }
                    TextureChoice::Earth => {
                        if earth.is_none() {
                            earth = Some(Texture::Image(ImageTexture::earth()?));
                        }
                        earth.clone().expect("just loaded")
                    }
                })
            };
            axes.push(match o.polarization {
                Some(axis) => Some(direction(&format!("{field}.polarization"), axis)?),
                None => None,
            });
            let first = load(&o.texture, "texture")?;
            let second = if has(ShaderKind::Time) {
                load(&o.window_texture, "window_texture")?
            } else {
                Texture::Uniform([1.0; 3])
            };
            objects.push(PreparedObject {
                first,
                second,
                scale,
                offset,
                temperature,
                luminance: table().luminance(temperature),
                lamps,
            });
        }
        Ok(Shading {
            texture: texture_layer,
            frequency: has(ShaderKind::Frequency),
            time: has(ShaderKind::Time),
            light: has(ShaderKind::Light),
            objects,
            brightness,
            time_mode: time.mode,
            window: (t0, t0 + dt),
            travel: (tmin, tmax),
            legend: time.legend,
            reference_squares: settings.reference_squares,
            ambient,
            lights,
            observer_time: data.header.observer_time,
            gain: 2f64.powf(ev) as f32,
            marks,
            polarization: has(ShaderKind::Polarization),
            axes,
        })
    }
}

/// The data file's object names for a message: all of them, or the first few and the count.
fn name_list(names: &[String]) -> String {
    const SHOWN: usize = 10;
    if names.len() <= SHOWN {
        names.join(", ")
    } else {
        format!("{}, … ({} in all)", names[..SHOWN].join(", "), names.len())
    }
}
