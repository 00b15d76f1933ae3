//! Per-tile tracing cost of a scene (BENCHMARKS.md, "Scale-out"): traces every tile once
//! on one thread and prints min / median / p99 / max time per tile, the cost of the
//! dearest 10 % of tiles as a share of the total, and the whole single-thread time.
//!
//! `cargo run --release -p render --example tile_costs -- [SCENE.toml]` (default: the
//! built-in reference scene).

use render::driver::Renderer;
use scene::Scene;
use std::time::Instant;

fn main() {
    let scene = match std::env::args().nth(1) {
        Some(path) => Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}")),
        None => Scene::builtin(),
    };
    let renderer = Renderer::new(&scene).expect("tracer");
    let mut scratch = renderer.scratch();
    let mut ms: Vec<f64> = (0..renderer.tiles().len())
        .map(|k| {
            let t = Instant::now();
            renderer.trace_tile(k, &mut scratch);
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    let total: f64 = ms.iter().sum();
    ms.sort_by(|a, b| a.total_cmp(b));
    let at = |q: f64| ms[((ms.len() - 1) as f64 * q).round() as usize];
    let top: f64 = ms[ms.len() * 9 / 10..].iter().sum();
    println!(
        "{}: {} tiles of 16×16, ms per tile: min {:.2}, median {:.2}, p99 {:.2}, max {:.2}; \
         dearest 10 % of tiles: {:.0} % of the time; total {:.2} s on one thread",
        scene.name,
        ms.len(),
        at(0.0),
        at(0.5),
        at(0.99),
        at(1.0),
        100.0 * top / total,
        total / 1e3
    );
}
