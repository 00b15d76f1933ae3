//! The synthetic data file shared by the viewer's benchmark (`benches/view.rs`) and the
//! concurrent-requests example (`examples/concurrent_requests.rs`): an earth-textured ball
//! covering half the pixels (a 50-pixel checkerboard) with varied (u, v, g, t_emit), the rest
//! empty sky.

use datafile::record::PixelRecord;
use datafile::DataFile;

/// The scene the data file claims to come from: the earth-textured ball.
fn scene() -> String {
    testkit::ball_ahead(
        "bench",
        &testkit::panorama(220.0, 25.0, 2200, 250),
        "earth",
        r#"{ kind = "image", builtin = "earth" }"#,
    )
}

/// The synthetic data file at `width` × `height`.
pub fn data(width: usize, height: usize) -> DataFile {
    let mut records = Vec::with_capacity(width * height);
    for row in 0..height {
        for col in 0..width {
            let (x, y) = (col as f32 / width as f32, row as f32 / height as f32);
            records.push(if (col / 50 + row / 50) % 2 == 0 {
                testkit::hit(0, (7.0 * x).fract(), y, 0.5 + x, -1.0 - 10.0 * x, 1.0 - y)
            } else {
                PixelRecord::MISS
            });
        }
    }
    DataFile {
        header: testkit::godel_header("bench", &scene(), "panorama", &["earth"]),
        width,
        height,
        records,
        lights: Vec::new(),
        polarization: false,
    }
}
