//! What one slider step costs the server at the size, 2200×250: shading the whole
//! picture with the `shade` crate plus encoding it as RGBA (what `/api/image` answers), and
//! the PNG of "Save PNG". The data file is synthetic: an earth-textured ball covering half
//! the pixels with varied (u, v, g, t_emit), the rest empty sky.

mod common;

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use shade::ShaderKind;
use viewer::{encode, ViewerState};

fn bench(c: &mut Criterion) {
    let state = ViewerState::new(Path::new("bench.exr"), common::data(2200, 250)).unwrap();
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
