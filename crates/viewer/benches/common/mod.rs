//! The synthetic data file shared by the viewer's benchmark (`benches/view.rs`) and the
//! concurrent-requests example (`examples/concurrent_requests.rs`): an earth-textured ball
//! covering half the pixels (a 50-pixel checkerboard) with varied (u, v, g, t_emit), the rest
//! empty sky.

use datafile::{DataFile, DataHeader, FORMAT_VERSION};
use datafile::record::{PixelRecord, RayStatus};

const SCENE: &str = r#"
name = "bench"
[spacetime]
metric = "godel"
a = 1.0
[observer]
time = 0.0
position = { r = 0.0, phi = 0.0, z = 0.0 }
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "panorama"
h_fov_deg = 220.0
v_fov_deg = 25.0
width = 2200
height = 250
[trace]
method = "numeric"
max_past = 10.0
[[object]]
name = "earth"
radius = 0.2
texture = { kind = "image", builtin = "earth" }
temperature = 5800.0
motion = { kind = "rest", position = { r = 1.0, phi = 0.0, z = 0.0 } }
"#;

/// The synthetic data file at `width` × `height`.
pub fn data(width: usize, height: usize) -> DataFile {
    let mut records = Vec::with_capacity(width * height);
    for row in 0..height {
        for col in 0..width {
            let (x, y) = (col as f32 / width as f32, row as f32 / height as f32);
            records.push(if (col / 50 + row / 50) % 2 == 0 {
                PixelRecord {
                    object: 0,
                    status: RayStatus::Hit,
                    u: (7.0 * x).fract(),
                    v: y,
                    g: 0.5 + x,
                    t_emit: -1.0 - 10.0 * x,
                    cos_i: 1.0 - y,
                    ..PixelRecord::MISS
                }
            } else {
                PixelRecord::MISS
            });
        }
    }
    DataFile {
        header: DataHeader {
            format_version: FORMAT_VERSION,
            scene_name: "bench".into(),
            scene_text: SCENE.into(),
            camera: "panorama".into(),
            observer_time: 0.0,
            metric: "godel".into(),
            godel_a: 1.0,
            method: "numeric".into(),
            object_names: vec!["earth".into()],
        },
        width,
        height,
        records,
        lights: Vec::new(),
    }
}
