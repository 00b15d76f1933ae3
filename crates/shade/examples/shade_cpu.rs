//! CPU time of re-shading the benchmark's synthetic 1920×1080 data file, one shader per run:
//! wall-clock benchmarks on a shared, loaded machine are noisy, CPU time is not.
//! `RAYON_NUM_THREADS=1 cargo run --release -p shade --example shade_cpu -- frequency 20`
//! prints CPU milliseconds per frame (process user + system time / frames).

use render::datafile::{DataFile, DataHeader, FORMAT_VERSION};
use render::record::{PixelRecord, RayStatus};
use shade::{BrightnessMode, ShadeSettings, ShaderKind, Shading, TextureChoice, TimeMode};

const SCENE: &str = r#"name = "bench"
[camera]
kind = "pinhole"
fov_deg = 90.0
width = 1920
height = 1080
[[object]]
name = "earth"
radius = 0.2
texture = { kind = "image", builtin = "earth" }
temperature = 5800.0
motion = { kind = "rest", position = { r = 1.0, phi = 0.0, z = 0.0 } }
[[object]]
name = "ball"
radius = 0.2
texture = { kind = "checker", rows = 8, cols = 16 }
temperature = 4000.0
motion = { kind = "rest", position = { r = 1.0, phi = 2.0, z = 0.0 } }
"#;

/// 1920×1080: two thirds of the pixels hit one of two objects with varied u, v, g, t_emit
/// and cos_i; two light planes.
fn data() -> DataFile {
    let (w, h) = (1920usize, 1080usize);
    let mut lights = vec![Vec::with_capacity(w * h); 2];
    let records = (0..w * h)
        .map(|i| {
            let (c, r) = ((i % w) as f32, (i / w) as f32);
            lights[0].push(c / w as f32);
            lights[1].push(r / h as f32);
            if i % 3 == 2 {
                return PixelRecord::MISS;
            }
            PixelRecord {
                object: (i % 2) as i32,
                status: RayStatus::Hit,
                u: (c / 97.0).fract(),
                v: (r / 61.0).fract(),
                g: 0.3 + 3.0 * c / w as f32,
                t_emit: -30.0 * r / h as f32,
                cos_i: (c / 50.0).sin(),
                ..PixelRecord::MISS
            }
        })
        .collect();
    DataFile {
        header: DataHeader {
            format_version: FORMAT_VERSION,
            scene_name: "bench".into(),
            scene_text: SCENE.into(),
            camera: "pinhole".into(),
            observer_time: 0.0,
            metric: "godel".into(),
            godel_a: 1.0,
            method: "numeric".into(),
            object_names: vec!["earth".into(), "ball".into()],
        },
        width: w,
        height: h,
        records,
        lights,
    }
}

fn cpu_seconds() -> f64 {
    // utime and stime, fields 14 and 15 of /proc/self/stat, in clock ticks (100 per second).
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<&str> = after.split_whitespace().collect();
    let tick = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    (tick(11) + tick(12)) / 100.0
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("frequency", String::as_str);
    let frames: u32 = args.get(2).and_then(|n| n.parse().ok()).unwrap_or(20);
    let data = data();
    let mut s = ShadeSettings::defaults_for(&data);
    s.objects.get_mut("earth").unwrap().texture = TextureChoice::Earth;
    match which {
        "texture" => {}
        "frequency" => s.shaders = vec![ShaderKind::Frequency],
        "physical" => {
            s.shaders = vec![ShaderKind::Frequency];
            s.brightness = BrightnessMode::Physical;
        }
        "window" => s.shaders = vec![ShaderKind::Time],
        "travel" => {
            s.shaders = vec![ShaderKind::Time];
            s.time.mode = TimeMode::Travel;
        }
        "light" => s.shaders = vec![ShaderKind::Light],
        "frequency-time" => s.shaders = vec![ShaderKind::Frequency, ShaderKind::Time],
        other => {
            eprintln!("unknown case {other}");
            std::process::exit(2);
        }
    }
    let shading = Shading::new(&data, &s).expect("valid settings");
    let mut buffer = Vec::new();
    shading.image_into(&data, &mut buffer); // warm-up: tables, pages
    let start = cpu_seconds();
    for _ in 0..frames {
        shading.image_into(&data, &mut buffer);
    }
    let ms = (cpu_seconds() - start) * 1000.0 / f64::from(frames);
    println!("{which}: {ms:.1} ms CPU per 1920x1080 frame");
}
