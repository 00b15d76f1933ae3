//! Probes a ray of the CPU tracer (BENCHMARKS.md, "Probes a ray"): traces a scene on one
//! thread with the objects' probes counted, once as it is and once without its lights, and
//! prints the probes per traced pixel (with the shadow rays, and of the pixel rays alone).
//!
//! `cargo run --release -p render --features count-probes --example probes -- SCENE.toml
//! [WIDTH HEIGHT] [exact|numeric]` (one ray a pixel; the scene's own size and method unless
//! given).

use render::driver::Renderer;
use scene::{Scene, TraceMethod};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        eprintln!("usage: probes SCENE.toml [WIDTH HEIGHT] [exact|numeric]");
        std::process::exit(2);
    };
    let mut scene = Scene::from_file(path).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(2)
    });
    let number = |i: usize| args.get(i).and_then(|s| s.parse::<u32>().ok());
    if let (Some(w), Some(h)) = (number(1), number(2)) {
        scene.camera = scene.camera.with_size(w, h);
    }
    scene.samples = 1;
    match args
        .iter()
        .find(|a| *a == "exact" || *a == "numeric")
        .map(String::as_str)
    {
        Some("exact") => scene.trace.method = TraceMethod::Exact,
        Some("numeric") => scene.trace.method = TraceMethod::Numeric,
        _ => {}
    }
    let lit = count(&scene);
    let mut dark = scene.clone();
    dark.lights.clear();
    let pixel = count(&dark);
    println!(
        "{} {}x{} {:?}: {:.1} probes a pixel ({:.1} of them the pixel rays', {} lights)",
        scene.name,
        scene.camera.width(),
        scene.camera.height(),
        scene.trace.method,
        lit,
        pixel,
        scene.lights.len()
    );
}

/// Probes per pixel of `scene`, traced tile by tile on this thread.
fn count(scene: &Scene) -> f64 {
    let renderer = Renderer::new(scene).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(2)
    });
    let mut scratch = renderer.scratch();
    render::probe_count::take();
    for k in 0..renderer.tiles().len() {
        renderer.trace_tile(k, &mut scratch);
    }
    let pixels = scene.camera.width() as f64 * scene.camera.height() as f64;
    render::probe_count::take() as f64 / pixels
}
