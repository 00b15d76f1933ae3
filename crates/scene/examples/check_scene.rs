//! Checks scene files given on the command line and prints each error (a small debugging aid).
fn main() {
    for p in std::env::args().skip(1) {
        match scene::Scene::from_file(&p) {
            Ok(s) => println!(
                "{p}: ok ({}, {} objects)",
                s.camera.describe(),
                s.objects.len()
            ),
            Err(e) => println!("{e}"),
        }
    }
}
