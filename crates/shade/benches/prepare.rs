//! Preparing settings ([`shade::Shading::new`]) for data files with many objects: the check of
//! the settings' object names and the per-object preparation must stay linear in the number of
//! objects (it was quadratic: 100,000 objects took over 20 s). Frequency layer, every object
//! listed in the settings (as the viewer's page sends them), a 4×1 image.
//! `cargo bench -p shade --bench prepare -- --measurement-time 5 --warm-up-time 1`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use datafile::record::PixelRecord;
use datafile::DataFile;
use shade::{ShadeSettings, ShaderKind, Shading};

/// A data file with `n` objects named `o0`, `o1`, … (its embedded scene lists them).
fn data(n: usize) -> DataFile {
    let names: Vec<String> = (0..n).map(|k| format!("o{k}")).collect();
    let mut scene = String::from(
        "name = \"many\"\n[camera]\nkind = \"pinhole\"\nfov_deg = 90.0\nwidth = 4\nheight = 1\n",
    );
    for name in &names {
        scene.push_str(&format!(
            "[[object]]\nname = \"{name}\"\nradius = 0.1\ntexture = {{ kind = \"checker\" }}\n\
             motion = {{ kind = \"rest\", position = {{ r = 1.0, phi = 0.0, z = 0.0 }} }}\n"
        ));
    }
    DataFile {
        header: testkit::godel_header("many", &scene, "pinhole", &names),
        width: 4,
        height: 1,
        records: vec![PixelRecord::MISS; 4],
        lights: Vec::new(),
        polarization: false,
    }
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("prepare");
    group.sample_size(10);
    for n in [10_000, 100_000] {
        let data = data(n);
        let mut settings = ShadeSettings::defaults_for(&data);
        settings.shaders = vec![ShaderKind::Frequency];
        group.bench_with_input(BenchmarkId::new("objects", n), &settings, |b, s| {
            b.iter(|| Shading::new(&data, s).expect("valid settings"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
