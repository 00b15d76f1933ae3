//! Traces a scene with the GPU kernel only (optionally another kernel source from the file
//! named by KERNEL), for instruction counts under callgrind:
//! `LP_NUM_THREADS=0 valgrind --tool=callgrind --toggle-collect='*GpuTracer*trace*' \
//!  target/release/examples/gpu_only SCENE.toml [WIDTH HEIGHT]`.

use render::driver::NoProgress;
use scene::Scene;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut scene = Scene::from_file(&args[1]).unwrap_or_else(|e| panic!("{e}"));
    if let (Some(w), Some(h)) = (args.get(2), args.get(3)) {
        scene.camera = scene
            .camera
            .with_size(w.parse().unwrap(), h.parse().unwrap());
    }
    let kernel = std::env::var("KERNEL")
        .map(|p| std::fs::read_to_string(p).expect("kernel file"))
        .unwrap_or_else(|_| gpu::KERNEL.to_string());
    let tracer = gpu::GpuTracer::with_kernel(gpu::KernelInput::new(&scene), &kernel)
        .unwrap_or_else(|e| panic!("{e}"));
    let traced = tracer.trace(&NoProgress).expect("trace");
    let hits = traced.records.iter().filter(|r| r.object >= 0).count();
    println!("{} samples, {hits} hit", traced.records.len());
}
