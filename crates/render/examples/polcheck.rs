use render::driver::{render, NoProgress};
fn main() {
    let text = scene::BUILTIN_SCENE_TEXT
        .replace("width = 880", "width = 220")
        .replace("height = 100", "height = 25")
        .replace("samples = 4", "samples = 1");
    let n = scene::Scene::from_str(&text, "r.toml").unwrap();
    let e = scene::Scene::from_str(
        &text.replace("method = \"numeric\"", "method = \"exact\""),
        "r.toml",
    )
    .unwrap();
    let t = std::time::Instant::now();
    let (dn, _) = render(&n, &NoProgress).unwrap();
    eprintln!("numeric {:?}", t.elapsed());
    let t = std::time::Instant::now();
    let (de, _) = render(&e, &NoProgress).unwrap();
    eprintln!("exact {:?}", t.elapsed());
    let mut worst = 0f32;
    let mut cnt = 0;
    for (a, b) in dn.records.iter().zip(&de.records) {
        if a.is_hit() && a.object == b.object {
            cnt += 1;
            let d = (0..3)
                .map(|i| (a.pol[i] - b.pol[i]).abs())
                .fold(0f32, f32::max);
            if d > worst {
                worst = d;
                eprintln!("{:?} {:?} {:?} {:?}", a.pol, b.pol, a.dir, a.t_emit);
            }
        }
    }
    eprintln!("{cnt} hits, worst {worst:e}");
    for (a, b) in dn
        .records
        .iter()
        .zip(&de.records)
        .filter(|(a, _)| a.is_hit())
        .step_by(40)
    {
        eprintln!("{:?} {:?} {:?} {}", a.pol, b.pol, a.dir, a.t_emit);
    }
}
#[allow(dead_code)]
fn unused() {}
