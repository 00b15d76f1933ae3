//! Shading cases in process: a settings document over a data file's defaults
//! (`ShadeSettings::overlay_toml`, `Shading::new`, `Shading::image`), a sequence script
//! (`Script::parse`, `Script::timeline`, every frame's settings), and a data file's bytes
//! (`DataFile::from_bytes`, then shading in every layer). Refusals must be one line;
//! accepted settings must shade the whole picture and read back from their own TOML; a
//! script's frames must all shade once its keyframes do.

use datafile::DataFile;
use datafile::record::{PixelRecord, RayStatus};
use shade::{Script, ShadeSettings, ShaderKind, Shading};
use std::path::Path;

use crate::gen::Gen;

/// The name settings texts are read under in process.
pub const SETTINGS_FILE: &str = "fuzz-settings.toml";

/// A refusal's message must be one line.
pub fn one_line(what: &str, e: &dyn std::fmt::Display) -> Result<(), String> {
    let shown = e.to_string();
    if shown.contains(['\n', '\r']) {
        return Err(format!("{what} error is not one line: {shown:?}"));
    }
    if shown.trim().is_empty() {
        return Err(format!("{what} error says nothing"));
    }
    Ok(())
}

/// Prepares and shades `settings`; refusals are fine (one line), accepted settings must
/// give the whole picture and read back from their own TOML.
pub fn shade(data: &DataFile, settings: &ShadeSettings) -> Result<String, String> {
    let shading = match Shading::new(data, settings) {
        Ok(s) => s,
        Err(e) => {
            one_line("shading", &e)?;
            return Ok("refused by Shading::new".into());
        }
    };
    let img = shading.image(data);
    let size = (data.width as u32, data.height as u32);
    if img.dimensions() != size {
        return Err(format!(
            "image {:?} for a {size:?} data file",
            img.dimensions()
        ));
    }
    let text = settings.to_toml();
    match ShadeSettings::defaults_for(data).overlay_toml(&text, "written.toml") {
        Ok(back) if back.to_toml() == text => {}
        Ok(back) => {
            return Err(format!(
                "settings do not read back from their TOML:\n{text}\nread back as\n{}",
                back.to_toml()
            ))
        }
        Err(e) => return Err(format!("settings' own TOML is refused: {e}\n{text}")),
    }
    Ok("shaded".into())
}

/// A settings document over the data file's defaults.
pub fn settings(data: &DataFile, text: &str) -> Result<String, String> {
    match ShadeSettings::defaults_for(data).overlay_toml(text, SETTINGS_FILE) {
        Ok(s) => shade(data, &s),
        Err(e) => {
            one_line("settings", &e)?;
            Ok("refused".into())
        }
    }
}

/// A sequence script on `data`, read as if from `path`.
pub fn script(data: &DataFile, text: &str, path: &Path) -> Result<String, String> {
    let script = match Script::parse(text, path) {
        Ok(s) => s,
        Err(e) => {
            one_line("script", &e)?;
            return Ok("refused".into());
        }
    };
    let defaults = ShadeSettings::defaults_for(data);
    let timeline = match script.timeline(&defaults) {
        Ok(t) => t,
        Err(e) => {
            one_line("script", &e)?;
            return Ok("refused (settings)".into());
        }
    };
    // Keyframe k's settings are the defaults overlaid with [settings] and keyframes 0..=k,
    // computed here without the timeline (compared as TOML: NaN is not equal to itself).
    let mut current = defaults
        .overlay(&script.settings)
        .map_err(|e| format!("the timeline took [settings] that overlay refuses: {e:?}"))?;
    for (i, k) in script.keyframes.iter().enumerate() {
        current = current
            .overlay(&k.settings)
            .map_err(|e| format!("the timeline took keyframe {i} that overlay refuses: {e:?}"))?;
        let at = timeline.settings_at(k.frame);
        if at.to_toml() != current.to_toml() {
            return Err(format!(
                "frame {} (keyframe {i}) has settings\n{}\nexpected\n{}",
                k.frame,
                at.to_toml(),
                current.to_toml()
            ));
        }
    }
    // `godel sequence` checks the keyframes and frame 0 before writing any frame; once they
    // pass, every frame in between must shade too, or a run stops half-way.
    let checked: Vec<u32> = script
        .keyframes
        .iter()
        .map(|k| k.frame)
        .chain([0])
        .collect();
    for &f in &checked {
        if let Err(e) = Shading::new(data, &timeline.settings_at(f)) {
            one_line("shading", &e)?;
            return Ok("refused (keyframe settings)".into());
        }
    }
    let last = script.frames - 1;
    let frames: Vec<u32> = if script.frames <= 12 {
        (0..script.frames).collect()
    } else {
        vec![0, 1, last / 3, last / 2, last - 1, last]
    };
    for f in frames {
        let settings = timeline.settings_at(f);
        let shading = Shading::new(data, &settings).map_err(|e| {
            format!(
                "frame {f} is refused ({e}) although frame 0 and every keyframe ({checked:?}) were accepted: a sequence stops half-way"
            )
        })?;
        let img = shading.image(data);
        if img.dimensions() != (data.width as u32, data.height as u32) {
            return Err(format!("frame {f}: image {:?}", img.dimensions()));
        }
    }
    Ok("frames shaded".into())
}

/// A data file's bytes: read, then shaded in every layer with its defaults.
pub fn data_bytes(bytes: &[u8]) -> Result<String, String> {
    match DataFile::from_bytes(bytes) {
        Ok(data) => {
            data.validate()
                .map_err(|e| format!("from_bytes accepted a data file that fails validate: {e}"))?;
            every_layer(&data)
        }
        Err(e) => {
            one_line("data file", &e)?;
            Ok("refused".into())
        }
    }
}

/// Shades `data` with its defaults in each layer (refusals must be one line).
pub fn every_layer(data: &DataFile) -> Result<String, String> {
    let defaults = ShadeSettings::defaults_for(data);
    let mut shaded = 0;
    for kind in ShaderKind::ALL {
        let s = ShadeSettings {
            shaders: vec![kind],
            ..defaults.clone()
        };
        if shade(data, &s)? == "shaded" {
            shaded += 1;
        }
    }
    Ok(format!("read, {shaded} of 4 layers shaded"))
}

/// An f32 that stresses a shader.
fn odd_f32(g: &mut Gen) -> f32 {
    let any = (g.unit() * 2.0 - 1.0) as f32;
    g.pick(&[
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        -0.0,
        0.0,
        1.0,
        -1.0,
        1e-30,
        4.0e9,
        -4.0e9,
        any,
    ])
}

/// `data` with odd values written into its records, light planes and header: what a
/// damaged or hand-made data file can hold that the codec reads back. Returns what changed.
pub fn odd_values(g: &mut Gen, data: &mut DataFile) -> Vec<String> {
    let mut log = Vec::new();
    let n = data.records.len();
    let objects = data.header.object_names.len() as i32;
    for _ in 0..g.int(1, 8) {
        let i = g.index(n);
        let r = &mut data.records[i];
        match g.index(5) {
            0 => {
                let status = g.pick(&RayStatus::ALL);
                *r = PixelRecord::miss(status);
                if status == RayStatus::Hit && objects > 0 {
                    r.object = g.int(0, objects as u64 - 1) as i32;
                }
                log.push(format!("pixel {i}: status {status:?}, object {}", r.object));
            }
            _ => {
                let field = g.index(12);
                let v = odd_f32(g);
                let slot = match field {
                    0 => &mut r.u,
                    1 => &mut r.v,
                    2 => &mut r.g,
                    3 => &mut r.t_emit,
                    4 => &mut r.x,
                    5 => &mut r.y,
                    6 => &mut r.z,
                    7 => &mut r.lambda,
                    8 => &mut r.cos_i,
                    k => &mut r.dir[k - 9],
                };
                *slot = v;
                log.push(format!("pixel {i}: field {field} = {v}"));
            }
        }
    }
    if !data.lights.is_empty() && g.chance(0.5) {
        let k = g.index(data.lights.len());
        let i = g.index(n);
        let v = odd_f32(g);
        data.lights[k][i] = v;
        log.push(format!("light_{k}[{i}] = {v}"));
    }
    if g.chance(0.3) {
        let t = g.pick(&[1e300, -1e300, 1e15, f64::MIN_POSITIVE]);
        data.header.observer_time = t;
        log.push(format!("observer_time = {t}"));
    }
    if g.chance(0.2) {
        let a = g.pick(&[1e-300, 1e300, -1.0, 0.0]);
        data.header.godel_a = a;
        log.push(format!("godel_a = {a}"));
    }
    if g.chance(0.3) && !data.header.object_names.is_empty() {
        let k = g.index(data.header.object_names.len());
        let name = g.pick(&[
            "x",
            "é ö",
            " ",
            "a.b",
            "[x]",
            "very long name that goes on and on",
        ]);
        data.header.object_names[k] = name.to_string();
        log.push(format!("object {k} renamed {name:?}"));
    }
    if g.chance(0.2) {
        let text = g.pick(&[
            "",
            "garbage = [",
            "name = \"other\"\n[camera]\nkind = \"sphere\"\nwidth = 1\nheight = 1\n",
        ]);
        data.header.scene_text = text.to_string();
        log.push(format!("scene text {text:?}"));
    }
    log
}

/// Whether `godel shade DATA -o PIC` with no flags must succeed: the bytes read and the
/// defaults (texture layer) shade.
pub fn texture_layer_shades(bytes: &[u8]) -> bool {
    DataFile::from_bytes(bytes)
        .is_ok_and(|d| Shading::new(&d, &ShadeSettings::defaults_for(&d)).is_ok())
}
