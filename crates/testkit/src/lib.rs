//! Fixtures shared by the tests, benches and examples of the workspace's crates: the pieces
//! of scene text that every small test scene repeats, the header and the hit records of a
//! synthetic data file, the example scenes and what a bad one expects,
//! running a command-line binary, the viewer's refusal of a texture from elsewhere, and a
//! seeded stream of uniform numbers. Only a dev-dependency; never published.
//!
//! The binary to run is passed in (`env!("CARGO_BIN_EXE_godel")` is known only inside the
//! `godel` package).

use std::process::{Command, Output};

use datafile::record::{PixelRecord, RayStatus};
use datafile::{DataHeader, FORMAT_VERSION};

/// `[spacetime]`: Gödel's universe with a = 1.
pub const GODEL: &str = "[spacetime]\nmetric = \"godel\"\na = 1.0\n";

/// `[observer]`: at rest at the origin (on the Gödel axis) at time 0, looking along +x with +z
/// up, so that the camera's right is −y.
pub const OBSERVER_AT_ORIGIN: &str = "[observer]
time = 0.0
position = { r = 0.0, phi = 0.0, z = 0.0 }
forward = [1, 0, 0]
up = [0, 0, 1]
";

/// `[camera]`: a panorama of `h_fov_deg` × `v_fov_deg` at `width` × `height` pixels.
pub fn panorama(h_fov_deg: f64, v_fov_deg: f64, width: usize, height: usize) -> String {
    format!(
        "[camera]\nkind = \"panorama\"\nh_fov_deg = {h_fov_deg:?}\nv_fov_deg = {v_fov_deg:?}\n\
         width = {width}\nheight = {height}\n"
    )
}

/// `[camera]`: a pinhole of `fov_deg` horizontally at `width` × `height` pixels.
pub fn pinhole(fov_deg: f64, width: usize, height: usize) -> String {
    format!(
        "[camera]\nkind = \"pinhole\"\nfov_deg = {fov_deg:?}\nwidth = {width}\nheight = {height}\n"
    )
}

/// `[camera]`: the full sphere (360° × 180°) at `width` × `height` pixels.
pub fn sphere(width: usize, height: usize) -> String {
    format!("[camera]\nkind = \"sphere\"\nwidth = {width}\nheight = {height}\n")
}

/// `[observer]`: at rest at time `time` at (r, φ, z) = (`r`, `phi`, 0), looking along +x with
/// +z up ([`OBSERVER_AT_ORIGIN`] at time 0 and r = 0).
pub fn observer_at(time: f64, r: f64, phi: f64) -> String {
    format!(
        "[observer]\ntime = {time:?}\nposition = {{ r = {r:?}, phi = {phi:?}, z = 0.0 }}\n\
         forward = [1, 0, 0]\nup = [0, 0, 1]\n"
    )
}

/// `[trace]`: with `method` (`"numeric"`, `"exact"`) back to t = −`max_past`.
pub fn trace(method: &str, max_past: f64) -> String {
    format!("[trace]\nmethod = \"{method}\"\nmax_past = {max_past:?}\n")
}

/// `[[object]]`: a sphere named `name` of `radius` at rest at (r, φ, z) = (`r`, `phi`, 0),
/// with the default texture and temperature.
pub fn ball_at_rest(name: &str, radius: f64, r: f64, phi: f64) -> String {
    format!(
        "[[object]]\nname = \"{name}\"\nradius = {radius:?}\n\
         motion = {{ kind = \"rest\", position = {{ r = {r:?}, phi = {phi:?}, z = 0.0 }} }}\n"
    )
}

/// The message of a viewer refusing the image texture at `path` (shown as `P` in it) that
/// lies outside the folders textures may come from: asserts that `error` is exactly that.
pub fn assert_texture_refused(error: &str, path: &std::path::Path) {
    let message = error.replace(&path.display().to_string(), "P");
    assert_eq!(
        message,
        "settings: image texture P: no image file of that name in the folders textures \
         may come from",
        "{path:?}"
    );
}

/// A scene named `name` in Gödel's universe (a = 1) seen by [`OBSERVER_AT_ORIGIN`] through
/// `camera` ([`panorama`], [`pinhole`]); `rest` (the `[trace]` table, objects, lights) follows.
pub fn godel_scene(name: &str, camera: &str, rest: &str) -> String {
    format!("name = \"{name}\"\n{GODEL}{OBSERVER_AT_ORIGIN}{camera}{rest}")
}

/// A [`godel_scene`] through a 360° × 40° panorama of `width` × `height` pixels, tracing back
/// `max_past`; `objects` (TOML `[[object]]` and `[[light]]` tables) follow.
pub fn axis_panorama(
    name: &str,
    width: usize,
    height: usize,
    max_past: f64,
    objects: &str,
) -> String {
    godel_scene(
        name,
        &panorama(360.0, 40.0, width, height),
        &format!("[trace]\nmax_past = {max_past:?}\n{objects}"),
    )
}

/// A [`godel_scene`] through `camera`, traced numerically back to t = −10, of one sphere
/// `object` of radius 0.2 at 5800 K wearing `texture` (an inline TOML table), at rest at r = 1
/// straight ahead (φ = 0): the scene of the viewer's tests and benchmarks.
pub fn ball_ahead(name: &str, camera: &str, object: &str, texture: &str) -> String {
    godel_scene(
        name,
        camera,
        &format!(
            "{}{}",
            trace("numeric", 10.0),
            textured_ball_at(object, 0.2, texture, 5800.0, 1.0, 0.0)
        ),
    )
}

/// `[[object]]`: a sphere named `name` of `radius` wearing `texture` (an inline TOML table)
/// at `temperature` kelvin, at rest at `position` (an inline TOML table).
pub fn textured_ball(
    name: &str,
    radius: f64,
    texture: &str,
    temperature: f64,
    position: &str,
) -> String {
    format!(
        "[[object]]\nname = \"{name}\"\nradius = {radius:?}\ntexture = {texture}\n\
         temperature = {temperature:?}\nmotion = {{ kind = \"rest\", position = {position} }}\n"
    )
}

/// [`textured_ball`] at rest at (r, φ, z) = (`r`, `phi`, 0).
pub fn textured_ball_at(
    name: &str,
    radius: f64,
    texture: &str,
    temperature: f64,
    r: f64,
    phi: f64,
) -> String {
    textured_ball(
        name,
        radius,
        texture,
        temperature,
        &format!("{{ r = {r:?}, phi = {phi:?}, z = 0.0 }}"),
    )
}

/// The inline TOML table of a checker texture of `rows` × `cols` cells.
pub fn checker(rows: u32, cols: u32) -> String {
    format!("{{ kind = \"checker\", rows = {rows}, cols = {cols} }}")
}

/// A [`godel_scene`] through the full sphere (360° × 180°) of `width` × `height` pixels;
/// `rest` follows.
pub fn sphere_scene(name: &str, width: usize, height: usize, rest: &str) -> String {
    godel_scene(name, &sphere(width, height), rest)
}

/// The header of a synthetic data file: traced numerically in Gödel's universe (a = 1) with
/// the observer at time 0, by a camera described as `camera`, seeing `objects`.
pub fn godel_header(
    scene_name: &str,
    scene_text: &str,
    camera: &str,
    objects: &[impl AsRef<str>],
) -> DataHeader {
    DataHeader {
        format_version: FORMAT_VERSION,
        scene_name: scene_name.into(),
        scene_text: scene_text.into(),
        camera: camera.into(),
        observer_time: 0.0,
        metric: "godel".into(),
        godel_a: 1.0,
        member: None,
        method: "numeric".into(),
        object_names: objects.iter().map(|o| o.as_ref().to_string()).collect(),
        supersample: 1,
    }
}

/// The record of a pixel that hit `object` at texture coordinates (`u`, `v`) with frequency
/// ratio `g`, emission time `t_emit` and light cosine `cos_i` (every other field zero).
pub fn hit(object: i32, u: f32, v: f32, g: f32, t_emit: f32, cos_i: f32) -> PixelRecord {
    PixelRecord {
        object,
        status: RayStatus::Hit,
        u,
        v,
        g,
        t_emit,
        cos_i,
        ..PixelRecord::MISS
    }
}

/// Runs the binary `bin` with `args` to its end, collecting its output.
pub fn run(bin: &str, args: &[&str]) -> Output {
    Command::new(bin)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("run {bin}: {e}"))
}

/// A command's standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The workspace's `scenes/` folder (the example scenes; `bad/` below it holds the scenes
/// that must be refused).
pub fn scenes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

/// The `.toml` files directly in `dir`, sorted.
pub fn toml_files(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("read {}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

/// What a bad scene's text declares it must be refused with: the field of its line
/// `# expect field: PATH` (empty for TOML syntax errors) and the 1-based number of the line
/// marked `# <- error here`.
pub fn bad_scene_expectation(text: &str) -> (String, usize) {
    let field = text
        .lines()
        .find_map(|l| l.strip_prefix("# expect field:"))
        .expect("a `# expect field:` line")
        .trim()
        .to_string();
    let line = text
        .lines()
        .position(|l| l.contains("# <- error here"))
        .expect("a `# <- error here` marker")
        + 1;
    (field, line)
}

/// Uniform numbers in [0, 1) from a seed, the same on every run and machine (xorshift64, the
/// top 53 bits): for tests that sample many random cases and assert on their totals, where a
/// property test's per-case shrinking does not fit.
pub struct Uniform(u64);

impl Uniform {
    /// The stream of `seed` (not 0).
    pub fn new(seed: u64) -> Uniform {
        Uniform(seed)
    }

    /// The next number of the stream.
    pub fn draw(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}
