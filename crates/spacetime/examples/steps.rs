//! Prints the step sizes DOP853 takes over one loop of a Gödel light ray:
//! `cargo run --release -p spacetime --example steps`.
use spacetime::*;
fn main() {
    let m = Metric::Godel(Godel::new(1.0));
    let o = Event::default();
    let g = Geodesic::launch(
        &m,
        o,
        &m.static_frame(o),
        [1.0, 0.0, 0.0],
        1.0,
        TimeDirection::Past,
    )
    .unwrap();
    let tr = trace(m, &g, &TraceLimits::one_loop(1.0));
    let hs: Vec<String> = tr.steps.iter().map(|s| format!("{:.3}", s.h)).collect();
    println!(
        "{} steps, rejected {}: {}",
        tr.steps.len(),
        tr.rejected_steps,
        hs.join(" ")
    );
}
