//! The GPU kernel's speed against the CPU exact tracer's on the same scene, in the same run:
//! rays per second of each (the GPU's context and kernel compilation timed apart), and the
//! kernel's work per ray (probes: one ray point, one object's distance each).
//! `cargo run --release -p gpu --example bench -- SCENE.toml [WIDTH HEIGHT [SAMPLES]] [--gpu-only]`
//! (BENCHMARKS.md, "GPU kernel"); `--gpu-only` leaves out the CPU's trace. The GPU traces the frame three times: the first trace and
//! the fastest are both reported (a real GPU's first frame pays for warming its clocks and
//! caches; a live view traces frame after frame).

use datafile::RayStatus;
use render::driver::{render, NoProgress};
use scene::{Scene, TraceMethod};
use std::time::Instant;

fn main() {
    let mut args: Vec<String> = std::env::args().collect();
    let gpu_only = args.iter().any(|a| a == "--gpu-only");
    args.retain(|a| a != "--gpu-only");
    let Some(path) = args.get(1) else {
        eprintln!("usage: bench SCENE.toml [WIDTH HEIGHT [SAMPLES]] [--gpu-only]");
        std::process::exit(2);
    };
    let mut scene = Scene::from_file(path).unwrap_or_else(|e| panic!("{e}"));
    if let (Some(w), Some(h)) = (args.get(2), args.get(3)) {
        scene.camera = scene
            .camera
            .with_size(w.parse().expect("width"), h.parse().expect("height"));
    }
    if let Some(n) = args.get(4) {
        scene.samples = n.parse().expect("samples");
    }
    let samples = scene.sample_camera().width() as f64 * scene.sample_camera().height() as f64;
    let started = Instant::now();
    let tracer =
        gpu::GpuTracer::new(gpu::KernelInput::new(&scene)).unwrap_or_else(|e| panic!("{e}"));
    let setup = started.elapsed().as_secs_f64();
    let mut times = Vec::new();
    let mut traced = None;
    for _ in 0..3 {
        let started = Instant::now();
        traced = Some(tracer.trace(&NoProgress).expect("GPU trace"));
        times.push(started.elapsed().as_secs_f64());
    }
    let traced = traced.expect("three traces");
    let first_time = times[0];
    let renderer = tracer.renderer().to_string();
    // One EGL context at a time in a process (gpu::context): the counting tracer's waits
    // for this one's to go.
    drop(tracer);
    let gpu_time = times.iter().copied().fold(f64::INFINITY, f64::min);
    let probes = gpu::GpuTracer::count_probes(gpu::KernelInput::new(&scene), gpu::KERNEL)
        .unwrap_or_else(|e| panic!("{e}"))
        .per_sample();
    let hits = traced
        .records
        .iter()
        .filter(|r| r.status == RayStatus::Hit)
        .count();
    print!(
        "{}: {} samples ({} hit); GPU ({}): {:.4} s, {:.0} rays/s (first of three: {:.4} s; +{:.2} s context and compilation), {:.1} probes per ray",
        scene.name,
        samples,
        hits,
        renderer,
        gpu_time,
        samples / gpu_time,
        first_time,
        setup,
        probes,
    );
    if gpu_only {
        println!();
        return;
    }
    let mut exact = scene.clone();
    exact.trace.method = TraceMethod::Exact;
    let started = Instant::now();
    let (_, stats) = render(&exact, &NoProgress).expect("CPU render");
    let cpu_time = started.elapsed().as_secs_f64();
    println!(
        "; CPU exact ({} threads): {:.2} s, {:.0} rays/s",
        rayon::current_num_threads(),
        cpu_time,
        stats.traced as f64 / cpu_time
    );
}
