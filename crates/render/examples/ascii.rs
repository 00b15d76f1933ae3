//! Renders a scene at its own resolution and prints the hit mask as text with the stats:
//! a quick look without writing files. `cargo run -p render --example ascii -- scene.toml`

fn main() {
    let path = std::env::args().nth(1).expect("usage: ascii SCENE.toml");
    let scene = scene::Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let (data, stats) = render::driver::render(&scene, &render::driver::NoProgress).unwrap();
    let step = (data.width / 150).max(1);
    for row in (0..data.height).step_by(step * 2) {
        let line: String = (0..data.width)
            .step_by(step)
            .map(|c| {
                let r = data.records[row * data.width + c];
                match r.status {
                    datafile::record::RayStatus::Hit => {
                        char::from_digit((r.object as u32) % 10, 10).unwrap()
                    }
                    datafile::record::RayStatus::Escaped => '.',
                    datafile::record::RayStatus::NotTraced => ' ',
                    _ => '!',
                }
            })
            .collect();
        println!("{line}");
    }
    println!("{}", stats.summary());
}
