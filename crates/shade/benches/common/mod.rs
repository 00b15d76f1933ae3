//! The synthetic 1920×1080 data file and the shader cases shared by the shading benchmark
//! (`benches/shade.rs`) and the CPU-time example (`examples/shade_cpu.rs`).

use datafile::record::PixelRecord;
use datafile::DataFile;
use shade::{BrightnessMode, ShadeSettings, ShaderKind, TextureChoice, TimeMode};

/// The scene the data file claims to come from: an earth-textured and a checkered ball.
fn scene(w: usize, h: usize) -> String {
    let earth = "{ kind = \"image\", builtin = \"earth\" }";
    format!(
        "name = \"bench\"\n{}{}{}",
        testkit::pinhole(90.0, w, h),
        testkit::textured_ball_at("earth", 0.2, earth, 5800.0, 1.0, 0.0),
        testkit::textured_ball_at("ball", 0.2, &testkit::checker(8, 16), 4000.0, 1.0, 2.0),
    )
}

/// 1920×1080: two thirds of the pixels hit one of two objects with varied u, v, g, t_emit
/// and cos_i; two light planes.
#[allow(dead_code)] // the tests use the smaller `data_of`
pub fn data() -> DataFile {
    data_of(1920, 1080)
}

/// [`data`] at `w` × `h` (the tests' smaller copies).
pub fn data_of(w: usize, h: usize) -> DataFile {
    let mut lights: Vec<Vec<f32>> = (0..2).map(|_| Vec::with_capacity(w * h)).collect();
    let records = (0..w * h)
        .map(|i| {
            let (c, r) = ((i % w) as f32, (i / w) as f32);
            lights[0].push(c / w as f32);
            lights[1].push(r / h as f32);
            if i % 3 == 2 {
                return PixelRecord::MISS;
            }
            testkit::hit(
                (i % 2) as i32,
                (c / 97.0).fract(),
                (r / 61.0).fract(),
                0.3 + 3.0 * c / w as f32,
                -30.0 * r / h as f32,
                (c / 50.0).sin(),
            )
        })
        .collect();
    DataFile {
        header: testkit::godel_header("bench", &scene(w, h), "pinhole", &["earth", "ball"]),
        width: w,
        height: h,
        records,
        lights,
        polarization: false,
    }
}

/// The benchmarked cases: (short name for the example, description, settings).
pub fn cases(data: &DataFile) -> Vec<(&'static str, &'static str, ShadeSettings)> {
    let mut base = ShadeSettings::defaults_for(data);
    if let Some(earth) = base.objects.get_mut("earth") {
        earth.texture = TextureChoice::Earth;
    }
    let with = |shaders: Vec<ShaderKind>, edit: fn(&mut ShadeSettings)| {
        let mut s = base.clone();
        s.shaders = shaders;
        edit(&mut s);
        s
    };
    use ShaderKind::{Frequency, Light, Texture, Time};
    vec![
        (
            "texture",
            "texture (earth image + checker)",
            with(vec![Texture], |_| {}),
        ),
        (
            "frequency",
            "frequency normalized",
            with(vec![Frequency], |_| {}),
        ),
        (
            "physical",
            "frequency physical",
            with(vec![Frequency], |s| s.brightness = BrightnessMode::Physical),
        ),
        ("window", "time window", with(vec![Time], |_| {})),
        (
            "travel",
            "time travel false colour",
            with(vec![Time], |s| s.time.mode = TimeMode::Travel),
        ),
        ("light", "light (2 sources)", with(vec![Light], |_| {})),
        (
            "frequency-time",
            "frequency × time window",
            with(vec![Frequency, Time], |_| {}),
        ),
    ]
}
