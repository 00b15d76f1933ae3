//! The GPU kernel against the CPU exact tracer on the same scenes (BENCHMARKS.md, "GPU
//! kernel"): `scenes/bench-static.toml` and the reference scene at 220×25 pixels (the
//! reference with its 4 samples per pixel), the whole trace; the GPU's context and kernel
//! compilation outside the timing (made once), as a render of many frames would.
//! Run: cargo bench -p gpu --bench kernel

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::driver::{render, NoProgress};
use scene::{Scene, TraceMethod};

fn scene(name: &str) -> Scene {
    let path = format!("{}/../../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let mut s = Scene::from_file(&path).expect("example scene");
    s.camera = s.camera.with_size(220, 25);
    s.trace.method = TraceMethod::Exact;
    s
}

fn bench(c: &mut Criterion) {
    for name in ["bench-static", "reference"] {
        let s = scene(name);
        let rays = u64::from(s.sample_camera().width()) * u64::from(s.sample_camera().height());
        let mut group = c.benchmark_group(name);
        group.sample_size(10);
        group.throughput(Throughput::Elements(rays));
        let tracer = gpu::GpuTracer::new(gpu::KernelInput::new(&s)).expect("a GL context");
        group.bench_function(
            format!(
                "gpu_{}",
                tracer.renderer().split(' ').next().unwrap_or("gpu")
            ),
            |b| b.iter(|| tracer.trace(&NoProgress).expect("GPU trace")),
        );
        group.bench_function("cpu_exact", |b| {
            b.iter(|| render(&s, &NoProgress).expect("CPU render"))
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
