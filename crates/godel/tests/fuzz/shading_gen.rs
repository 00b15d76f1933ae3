//! Random shade settings files (docs/guide/src/shading.md; `shade::settings`) and sequence scripts
//! (docs/guide/src/sequences.md; `shade::script`) as TOML text: any subset of the fields, values
//! ordinary and extreme, object names from the data file and unknown ones, image textures
//! that exist, are damaged, or are not images.

use crate::gen::{num, vec3, Gen};
use std::fmt::Write;

/// Texture choices in settings form; `images` are paths of image files to refer to.
fn texture(g: &mut Gen, images: &[String]) -> String {
    match g.index(8) {
        0 => "{ kind = \"scene\" }".into(),
        1 => {
            let rows: u64 = g.pick(&[0, 1, 3, 64, 4294967295]);
            let cols: u64 = g.pick(&[1, 2, 16, 1000, 4294967295]);
            format!("{{ kind = \"checker\", rows = {rows}, cols = {cols} }}")
        }
        2 => "{ kind = \"gradient\" }".into(),
        3 => {
            let c = [g.unit(), g.pick(&[0.0, 1.0, 1e30, -1.0]), g.unit()];
            format!("{{ kind = \"uniform\", color = {} }}", vec3(c))
        }
        4 if !images.is_empty() => {
            let p = g.pick(images);
            format!("{{ kind = \"image\", path = {p:?} }}")
        }
        5 => "{ kind = \"earth\" }".into(),
        6 => "{ kind = \"scene\" }".into(),
        _ if g.chance(0.3) => {
            let k = g.pick(&["Scene", "bogus", "", "image", "checker"]);
            format!("{{ kind = \"{k}\" }}")
        }
        _ => "{ kind = \"gradient\" }".into(),
    }
}

/// A number for a field: mostly ordinary, sometimes at or past its edges.
fn value(g: &mut Gen, lo: f64, hi: f64) -> String {
    match g.index(40) {
        0 => g.extreme(),
        1..=3 => num(g.pick(&[0.0, -0.0, lo, hi, -hi, 1e-300, 1e300])),
        _ => num(g.range(lo, hi)),
    }
}

fn lamp(g: &mut Gen) -> String {
    format!(
        "{{ u = {}, v = {}, radius_deg = {}, period = {}, phase = {}, duty = {}, color = {} }}",
        value(g, 0.0, 1.0),
        value(g, 0.0, 1.0),
        value(g, 0.1, 90.0),
        value(g, 0.01, 10.0),
        value(g, -5.0, 5.0),
        value(g, 0.0, 1.0),
        vec3([g.unit(), g.unit(), g.unit()])
    )
}

/// A partial settings document. `objects` are the data file's object names; `lights` its
/// light count.
pub fn settings(g: &mut Gen, objects: &[String], lights: usize, images: &[String]) -> String {
    let mut s = String::new();
    if g.chance(0.7) {
        let mut kinds: Vec<&str> = ["texture", "frequency", "time", "light"]
            .into_iter()
            .filter(|_| g.chance(0.4))
            .collect();
        if g.chance(0.1) {
            kinds.push(g.pick(&["texture", "bogus", "", "Light"]));
        }
        let list: Vec<String> = kinds.iter().map(|k| format!("{k:?}")).collect();
        writeln!(s, "shaders = [{}]", list.join(", ")).unwrap();
    }
    if g.chance(0.3) {
        writeln!(
            s,
            "brightness = \"{}\"",
            g.pick(&["normalized", "physical", "normalized", "physical", "bright"])
        )
        .unwrap();
    }
    if g.chance(0.3) {
        writeln!(s, "exposure = {}", value(g, 0.0, 10.0)).unwrap();
    }
    if g.chance(0.2) {
        writeln!(
            s,
            "reference_squares = {}",
            g.pick(&["true", "false", "true", "false", "1"])
        )
        .unwrap();
    }
    if g.chance(0.5) {
        writeln!(s, "[time]").unwrap();
        for (key, lo, hi) in [
            ("t0", -40.0, 5.0),
            ("dt", 0.0, 20.0),
            ("travel_min", -5.0, 20.0),
            ("travel_max", -5.0, 60.0),
        ] {
            if g.chance(0.5) {
                writeln!(s, "{key} = {}", value(g, lo, hi)).unwrap();
            }
        }
        if g.chance(0.4) {
            writeln!(
                s,
                "mode = \"{}\"",
                g.pick(&["window", "travel", "window", "travel", "Window"])
            )
            .unwrap();
        }
        if g.chance(0.3) {
            writeln!(s, "legend = {}", g.pick(&["true", "false"])).unwrap();
        }
    }
    if g.chance(0.4) {
        writeln!(s, "[light]").unwrap();
        if g.chance(0.6) {
            writeln!(s, "ambient = {}", value(g, 0.0, 1.0)).unwrap();
        }
        if g.chance(0.6) {
            let n = g.pick(&[0, lights, lights, lights + 1, 65]);
            let sources: Vec<String> = (0..n)
                .map(|_| {
                    format!(
                        "{{ on = {}, intensity = {}, color = {} }}",
                        g.pick(&["true", "false"]),
                        value(g, 0.0, 5.0),
                        vec3([g.unit(), g.unit(), g.unit()])
                    )
                })
                .collect();
            writeln!(s, "sources = [{}]", sources.join(", ")).unwrap();
        }
    }
    let mut names: Vec<String> = objects.iter().filter(|_| g.chance(0.5)).cloned().collect();
    if g.chance(0.1) {
        names.push(g.pick(&["moon", "o0 ", "", "a\\nb", "\u{e9}"]).to_string());
    }
    for name in names {
        writeln!(s, "[objects.{name:?}]").unwrap();
        if g.chance(0.5) {
            writeln!(s, "texture = {}", texture(g, images)).unwrap();
        }
        if g.chance(0.3) {
            writeln!(s, "window_texture = {}", texture(g, images)).unwrap();
        }
        for (key, lo, hi) in [
            ("offset_u", -2.0, 2.0),
            ("offset_v", -2.0, 2.0),
            ("scale_u", -4.0, 4.0),
            ("scale_v", -4.0, 4.0),
            ("rotation_deg", -720.0, 720.0),
            ("temperature", 1.0, 1e5),
        ] {
            if g.chance(0.25) {
                writeln!(s, "{key} = {}", value(g, lo, hi)).unwrap();
            }
        }
        if g.chance(0.3) {
            let n = g.pick(&[0, 1, 2, 3, 65]);
            let lamps: Vec<String> = (0..n).map(|_| lamp(g)).collect();
            writeln!(s, "lamps = [{}]", lamps.join(", ")).unwrap();
        }
    }
    s
}

/// The settings document as the body of `[prefix]`: every table header prefixed (a
/// script's `[settings]` and `[keyframe.settings]`).
fn nested(doc: &str, prefix: &str) -> String {
    let mut out = format!("[{prefix}]\n");
    for line in doc.lines() {
        match line.strip_prefix('[') {
            Some(rest) => writeln!(out, "[{prefix}.{rest}").unwrap(),
            None => writeln!(out, "{line}").unwrap(),
        }
    }
    out
}

/// A sequence script on the data file `data` (a path relative to the script), writing
/// frames into `output`, with 1 to 6 frames mostly.
pub fn script(g: &mut Gen, data: &str, objects: &[String], lights: usize) -> String {
    let mut s = String::new();
    writeln!(s, "data = {data:?}").unwrap();
    writeln!(s, "output = \"frames\"").unwrap();
    let frames: u64 = match g.index(12) {
        0 => g.pick(&[0, 100_000, 100_001, 4294967295]),
        _ => g.int(1, 6),
    };
    writeln!(s, "frames = {frames}").unwrap();
    if g.chance(0.5) {
        writeln!(s, "fps = {}", value(g, 0.5, 60.0)).unwrap();
    }
    if g.chance(0.4) {
        writeln!(
            s,
            "interpolation = \"{}\"",
            g.pick(&["linear", "smooth", "cubic"])
        )
        .unwrap();
    }
    writeln!(s, "mp4 = false").unwrap();
    if g.chance(0.5) {
        s.push_str(&nested(&settings(g, objects, lights, &[]), "settings"));
    }
    let mut frame = 0u64;
    for _ in 0..g.pick(&[0, 1, 2, 3]) {
        writeln!(s, "[[keyframe]]").unwrap();
        match g.index(8) {
            0 => writeln!(s, "time = {}", value(g, 0.0, 1.0)).unwrap(),
            1 => writeln!(s, "frame = {}", g.int(0, frames.max(1))).unwrap(),
            _ => {
                writeln!(s, "frame = {frame}").unwrap();
                frame += g.int(1, 3);
            }
        }
        if g.chance(0.3) {
            writeln!(s, "interpolation = \"{}\"", g.pick(&["linear", "smooth"])).unwrap();
        }
        // Keyframes move numbers between values that are each valid: where an in-between
        // frame breaks, the timeline is at fault.
        let mut k = String::new();
        if g.chance(0.5) {
            let any = g.unit();
            writeln!(k, "exposure = {}", num(g.pick(&[0.0, 1.0, 1e300, any]))).unwrap();
        }
        if g.chance(0.5) {
            writeln!(
                k,
                "[time]\nt0 = {}\ndt = {}",
                num(g.range(-30.0, 0.0)),
                num(g.pick(&[1e-300, 0.5, 1e300]))
            )
            .unwrap();
        }
        if let Some(name) = objects.first().filter(|_| g.chance(0.6)) {
            writeln!(k, "[objects.{name:?}]").unwrap();
            writeln!(
                k,
                "scale_u = {}",
                num(g.pick(&[-1.0, 1.0, 2.0, -1e300, 1e300]))
            )
            .unwrap();
            writeln!(k, "offset_u = {}", num(g.pick(&[-1e308, 0.5, 1e308]))).unwrap();
            writeln!(k, "temperature = {}", num(g.pick(&[1e-300, 5800.0, 1e300]))).unwrap();
        }
        if g.chance(0.2) {
            k.push_str(&settings(g, objects, lights, &[]));
        }
        s.push_str(&nested(&k, "keyframe.settings"));
    }
    s
}
