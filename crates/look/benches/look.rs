//! Speed of `look`: a 1920×1080 view from a synthetic 4096×2048 full-sphere data
//! file (no tracing: the records are made up, with hits and misses in bands), for a 90°
//! pinhole at rest and at 0.9 c, and the 360°×180° sphere itself turned, read smoothly (the
//! default) and, for the pinhole at 0.9 c, by nearest neighbour and with 4 samples per pixel.
//! The look only; reading and writing files is not included.
//! Run: cargo bench -p look --bench look

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use datafile::{DataFile, PixelRecord, RayStatus};
use look::{look, look_with, Filter, LookView, Sampling};
use render::driver::header;
use scene::{Camera, Scene};
use spacetime::LocalVelocity;

/// Two balls at rest at r = 1, seen from the axis by the static observer.
fn sphere_scene() -> String {
    testkit::sphere_scene(
        "synthetic-sphere",
        4096,
        2048,
        &format!(
            "{}{}",
            testkit::ball_at_rest("a", 0.2, 1.0, 0.0),
            testkit::ball_at_rest("b", 0.2, 1.0, 2.0)
        ),
    )
}

fn sphere() -> DataFile {
    let scene = Scene::from_str(&sphere_scene(), "bench").expect("valid scene");
    let (w, h) = (4096, 2048);
    let records = (0..w * h)
        .map(|i| {
            let (col, row) = (i % w, i / w);
            if (col / 64 + row / 64) % 3 == 2 {
                return PixelRecord::MISS;
            }
            PixelRecord {
                object: ((col / 512) % 2) as i32,
                status: RayStatus::Hit,
                u: col as f32 / w as f32,
                v: row as f32 / h as f32,
                g: 0.5 + (col % 97) as f32 / 97.0,
                t_emit: -((row % 131) as f32) / 13.0,
                x: 1.0,
                y: 0.5,
                z: -0.25,
                lambda: 1.0 + (col % 13) as f32,
                dir: [0.0, 0.6, 0.8],
                cos_i: 0.5,
                view: [0.0, 0.0, 1.0],
                pol: [1.0, 0.0, 0.0],
            }
        })
        .collect();
    DataFile {
        header: header(&scene),
        width: w,
        height: h,
        records,
        lights: vec![],
        polarization: false,
    }
}

fn bench(c: &mut Criterion) {
    let data = sphere();
    let pinhole = Camera::Pinhole {
        fov_deg: 90.0,
        width: 1920,
        height: 1080,
    };
    let turned = [0.6, 0.8, 0.0];
    let up = [0.0, 0.0, 1.0];
    let views = [
        ("pinhole_1920x1080_at_rest", pinhole, LocalVelocity::REST),
        (
            "pinhole_1920x1080_0.9c",
            pinhole,
            LocalVelocity::new(0.9, [0.0, 1.0, 0.3]).unwrap(),
        ),
    ];
    let mut group = c.benchmark_group("look_from_4096x2048_sphere");
    group.sample_size(10);
    group.throughput(Throughput::Elements(1920 * 1080));
    for (name, camera, velocity) in views {
        let view = LookView::new(camera, turned, up, velocity).unwrap();
        group.bench_function(name, |b| {
            b.iter(|| look(&data, &view).unwrap().records.len())
        });
    }
    let fast = LookView::new(
        pinhole,
        turned,
        up,
        LocalVelocity::new(0.9, [0.0, 1.0, 0.3]).unwrap(),
    )
    .unwrap();
    for (name, filter, samples) in [
        ("pinhole_1920x1080_0.9c_nearest", Filter::Nearest, 1),
        ("pinhole_1920x1080_0.9c_4_samples", Filter::Smooth, 4),
    ] {
        let sampling = Sampling { filter, samples };
        group.bench_function(name, |b| {
            b.iter(|| look_with(&data, &fast, sampling).unwrap().records.len())
        });
    }
    let sphere_view = LookView::new(
        Camera::Sphere {
            width: 1920,
            height: 960,
        },
        turned,
        up,
        LocalVelocity::REST,
    )
    .unwrap();
    group.throughput(Throughput::Elements(1920 * 960));
    group.bench_function("sphere_1920x960_turned", |b| {
        b.iter(|| look(&data, &sphere_view).unwrap().records.len())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
