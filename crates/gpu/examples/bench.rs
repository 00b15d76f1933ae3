//! The GPU kernel's speed against the CPU exact tracer's on the same scene, in the same run:
//! rays per second of each (the GPU's context and kernel compilation timed apart), and the
//! kernel's work per ray (probes: one ray point, one object's distance each).
//! `cargo run --release -p gpu --example bench -- SCENE.toml [WIDTH HEIGHT]`
//! (BENCHMARKS.md, "GPU kernel").

use datafile::RayStatus;
use render::driver::{render, NoProgress};
use scene::{Scene, TraceMethod};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        eprintln!("usage: bench SCENE.toml [WIDTH HEIGHT]");
        std::process::exit(2);
    };
    let mut scene = Scene::from_file(path).unwrap_or_else(|e| panic!("{e}"));
    if let (Some(w), Some(h)) = (args.get(2), args.get(3)) {
        scene.camera = scene
            .camera
            .with_size(w.parse().expect("width"), h.parse().expect("height"));
    }
    let samples = scene.sample_camera().width() as f64 * scene.sample_camera().height() as f64;
    let started = Instant::now();
    let tracer =
        gpu::GpuTracer::new(gpu::KernelInput::new(&scene)).unwrap_or_else(|e| panic!("{e}"));
    let setup = started.elapsed().as_secs_f64();
    let started = Instant::now();
    let traced = tracer.trace(&NoProgress).expect("GPU trace");
    let gpu_time = started.elapsed().as_secs_f64();
    let counting = format!("#define COUNT_PROBES 1\n{}", gpu::KERNEL);
    let counter = gpu::GpuTracer::with_kernel(gpu::KernelInput::new(&scene), &counting)
        .unwrap_or_else(|e| panic!("{e}"));
    let counted = counter.trace(&NoProgress).expect("GPU trace");
    let traced_samples: Vec<_> = counted
        .records
        .iter()
        .filter(|r| r.status != RayStatus::NotTraced)
        .collect();
    let probes: f64 = traced_samples
        .iter()
        .map(|r| f64::from(r.view[0]))
        .sum::<f64>()
        / traced_samples.len().max(1) as f64;
    let hits = traced
        .records
        .iter()
        .filter(|r| r.status == RayStatus::Hit)
        .count();
    let mut exact = scene.clone();
    exact.trace.method = TraceMethod::Exact;
    let started = Instant::now();
    let (_, stats) = render(&exact, &NoProgress).expect("CPU render");
    let cpu_time = started.elapsed().as_secs_f64();
    println!(
        "{}: {} samples ({} hit); GPU ({}): {:.2} s, {:.0} rays/s (+{:.2} s context and compilation), {:.1} probes per ray; CPU exact ({} threads): {:.2} s, {:.0} rays/s",
        scene.name,
        samples,
        hits,
        tracer.renderer(),
        gpu_time,
        samples / gpu_time,
        setup,
        probes,
        rayon::current_num_threads(),
        cpu_time,
        stats.traced as f64 / cpu_time
    );
}
