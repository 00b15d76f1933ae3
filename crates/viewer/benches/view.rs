//! What one slider step costs the server at the issue's size, 2200×250: shading the whole
//! picture with the `shade` crate plus encoding it as RGBA (what `/api/image` answers), and
//! the PNG of "Save PNG". The data file is synthetic: an earth-textured ball covering half
//! the pixels with varied (u, v, g, t_emit), the rest empty sky.

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use render::datafile::{DataFile, DataHeader, FORMAT_VERSION};
use render::record::{PixelRecord, RayStatus};
use shade::ShaderKind;
use viewer::{encode, ViewerState};

const SCENE: &str = r#"
name = "bench"
[spacetime]
metric = "godel"
a = 1.0
[observer]
time = 0.0
position = { r = 0.0, phi = 0.0, z = 0.0 }
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "panorama"
h_fov_deg = 220.0
v_fov_deg = 25.0
width = 2200
height = 250
[trace]
method = "numeric"
max_past = 10.0
[[object]]
name = "earth"
radius = 0.2
texture = { kind = "image", builtin = "earth" }
temperature = 5800.0
motion = { kind = "rest", position = { r = 1.0, phi = 0.0, z = 0.0 } }
"#;

fn data(width: usize, height: usize) -> DataFile {
    let mut records = Vec::with_capacity(width * height);
    for row in 0..height {
        for col in 0..width {
            let (x, y) = (col as f32 / width as f32, row as f32 / height as f32);
            records.push(if (col / 50 + row / 50) % 2 == 0 {
                PixelRecord {
                    object: 0,
                    status: RayStatus::Hit,
                    u: (7.0 * x).fract(),
                    v: y,
                    g: 0.5 + x,
                    t_emit: -1.0 - 10.0 * x,
                    cos_i: 1.0 - y,
                    ..PixelRecord::MISS
                }
            } else {
                PixelRecord::MISS
            });
        }
    }
    DataFile {
        header: DataHeader {
            format_version: FORMAT_VERSION,
            scene_name: "bench".into(),
            scene_text: SCENE.into(),
            camera: "panorama".into(),
            observer_time: 0.0,
            metric: "godel".into(),
            godel_a: 1.0,
            method: "numeric".into(),
            object_names: vec!["earth".into()],
        },
        width,
        height,
        records,
        lights: Vec::new(),
    }
}

fn bench(c: &mut Criterion) {
    let state = ViewerState::new(Path::new("bench.exr"), data(2200, 250)).unwrap();
    let defaults = state.info().defaults;
    let mut group = c.benchmark_group("view 2200x250");
    group.sample_size(30);
    for layers in [
        vec![ShaderKind::Texture],
        vec![ShaderKind::Frequency],
        vec![ShaderKind::Frequency, ShaderKind::Time],
    ] {
        let mut settings = defaults.clone();
        let name: Vec<&str> = layers.iter().map(|k| k.name()).collect();
        settings.shaders = layers;
        // What one /api/image request does after parsing: prepare, shade, RGBA.
        group.bench_function(format!("{}: prepare + shade + RGBA", name.join("+")), |b| {
            let mut rgb = Vec::new();
            b.iter(|| {
                let shading = state.prepare(&settings).unwrap();
                state.shade_rgb(&shading, &mut rgb);
                encode::rgba_from_rgb(&rgb)
            })
        });
    }
    // Preparing alone: checks the settings and loads the textures (the earth map is decoded).
    let mut settings = defaults.clone();
    settings.shaders = vec![ShaderKind::Texture];
    group.bench_function("texture: prepare alone", |b| {
        b.iter(|| state.prepare(&settings).unwrap())
    });
    settings.shaders = vec![ShaderKind::Frequency];
    let shading = state.prepare(&settings).unwrap();
    let mut rgb = Vec::new();
    state.shade_rgb(&shading, &mut rgb);
    group.bench_function("RGBA encoding alone", |b| {
        b.iter(|| encode::rgba_from_rgb(&rgb))
    });
    let img = state.shade(&shading);
    group.bench_function("PNG for Save PNG", |b| b.iter(|| encode::png(&img)));
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
