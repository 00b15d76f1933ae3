//! Re-shading a synthetic 1920×1080 data file with each shader (and two combinations): the
//! post-render stage's speed target is under 20 ms per frame on 2 cores (BENCHMARKS.md).
//! `cargo bench -p shade --bench shade -- --measurement-time 3 --warm-up-time 1`

use criterion::{criterion_group, criterion_main, Criterion};
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

fn bench(c: &mut Criterion) {
    let data = data();
    let base = ShadeSettings::defaults_for(&data);
    let mut cases: Vec<(&str, ShadeSettings)> = Vec::new();
    let mut s = base.clone();
    s.objects.get_mut("earth").unwrap().texture = TextureChoice::Earth;
    cases.push(("texture (earth image + checker)", s));
    let mut s = base.clone();
    s.shaders = vec![ShaderKind::Frequency];
    cases.push(("frequency normalized", s.clone()));
    s.brightness = BrightnessMode::Physical;
    cases.push(("frequency physical", s));
    let mut s = base.clone();
    s.shaders = vec![ShaderKind::Time];
    s.objects.get_mut("earth").unwrap().texture = TextureChoice::Earth;
    cases.push(("time window", s.clone()));
    s.time.mode = TimeMode::Travel;
    cases.push(("time travel false colour", s));
    let mut s = base.clone();
    s.shaders = vec![ShaderKind::Light];
    s.objects.get_mut("earth").unwrap().texture = TextureChoice::Earth;
    cases.push(("light (2 sources)", s));
    let mut s = base.clone();
    s.shaders = vec![ShaderKind::Frequency, ShaderKind::Time];
    cases.push(("frequency × time window", s));

    let mut group = c.benchmark_group("shade 1920x1080");
    group.sample_size(20);
    let mut buffer = Vec::new();
    for (name, settings) in cases {
        let shading = Shading::new(&data, &settings).expect("valid settings");
        group.bench_function(name, |b| b.iter(|| shading.image_into(&data, &mut buffer)));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
