//! What the shading, script and data-file cases start from, made once per test process:
//! three small data files traced here (lit balls with a light channel; a floor, a globe
//! and a falling earth traced exactly; a ball beyond the horizon that no ray reaches), and
//! image files for image textures (a good PNG, a truncated one, text named `.png`).

use datafile::DataFile;
use render::driver::NoProgress;
use scene::Scene;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Lit balls with a light channel.
fn lit() -> String {
    format!(
        "name = \"lit\"\n{}{}",
        testkit::panorama(360.0, 60.0, 10, 5),
        r#"[trace]
max_past = 8.0
[[object]]
name = "ball"
radius = 0.2
texture = { kind = "uniform", color = [0.9, 0.9, 0.9] }
motion = { kind = "rest", position = { x = 1.0, y = 0.0, z = 0.0 } }
[[object]]
name = "blocker"
radius = 0.08
motion = { kind = "rest", position = { x = 0.686, y = 0.444, z = 0.0 } }
[[light]]
position = { x = 1.0, y = 1.0, z = 0.0 }
power = 12.0
"#
    )
}

const MANY: &str = r#"
name = "many"
[observer]
position = { r = 0.0, phi = 0.0, z = 0.2 }
[camera]
kind = "sphere"
width = 12
height = 6
[trace]
method = "exact"
max_past = 10.0
[[object]]
name = "floor"
frame = "coordinates"
shape = "plane"
height = -0.5
extent = 3.0
[[object]]
name = "globe"
frame = "coordinates"
shape = "sphere"
radius = 0.3
center = { x = 0.0, y = 1.0, z = 0.0 }
texture = { kind = "gradient" }
temperature = 3000.0
[[object]]
name = "earth"
radius = 0.2
texture = { kind = "image", builtin = "earth" }
motion = { kind = "geodesic", time = 0.0, position = { x = -1.0, y = 0.3, z = 0.0 }, speed = 0.7, direction = [1, 0, 0] }
"#;

/// A ball beyond the horizon that no ray reaches.
fn empty() -> String {
    format!(
        "name = \"empty\"\n{}{}",
        testkit::pinhole(90.0, 4, 2),
        testkit::ball_at_rest("far", 0.2, 2.5, 0.0)
    )
}

/// A traced data file and its encoding.
pub struct Fixture {
    pub data: DataFile,
    pub bytes: Vec<u8>,
}

impl Fixture {
    pub fn objects(&self) -> Vec<String> {
        self.data.header.object_names.clone()
    }
}

pub struct Fixtures {
    pub data: Vec<Fixture>,
    /// Paths of image files and non-images for image textures, absolute.
    pub images: Vec<String>,
    /// The folder holding them.
    pub dir: PathBuf,
}

/// The fixtures, made on first use.
pub fn get() -> &'static Fixtures {
    static FIXTURES: OnceLock<Fixtures> = OnceLock::new();
    FIXTURES.get_or_init(make)
}

/// A folder for this process's files under cargo's temporary folder for tests.
pub fn scratch_root() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create the fuzz folder");
    dir
}

fn make() -> Fixtures {
    let data = [lit(), MANY.to_string(), empty()]
        .iter()
        .map(|text| {
            let scene = Scene::from_str(text, "fixture.toml").expect("fixture scene is valid");
            let (data, _) = render::driver::render(&scene, &NoProgress).expect("fixture traces");
            let bytes = data.to_bytes().expect("fixture encodes");
            Fixture { data, bytes }
        })
        .collect();
    let dir = scratch_root().join("images");
    std::fs::create_dir_all(&dir).unwrap();
    let good = dir.join("good.png");
    let img = image::RgbImage::from_fn(4, 2, |x, y| {
        image::Rgb([(x * 60) as u8, (y * 120) as u8, 200])
    });
    img.save(&good).unwrap();
    let bytes = std::fs::read(&good).unwrap();
    let truncated = dir.join("truncated.png");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    let text = dir.join("text.png");
    std::fs::write(&text, "not an image\n").unwrap();
    let images = [good, truncated, text, dir.clone(), dir.join("missing.png")]
        .iter()
        .map(|p| p.display().to_string())
        .collect();
    Fixtures { data, images, dir }
}
