//! A real render through the data file: written and read back unchanged, and the same
//! bytes whatever the number of worker threads.

use crate::common::*;
use datafile::DataFile;

/// A small Gödel scene with a static and a free-falling sphere (both images, Doppler
/// shifts, several emission times), so that the records vary from pixel to pixel.
fn scene_text() -> String {
    testkit::axis_panorama(
        "determinism",
        96,
        20,
        8.0,
        r#"[[object]]
name = "still"
radius = 0.2
motion = { kind = "rest", position = { r = 1.0, phi = 0.7, z = 0.0 } }
[[object]]
name = "falling"
radius = 0.25
motion = { kind = "geodesic", time = -1.0, position = { x = -0.8, y = 0.2, z = 0.0 }, speed = 0.6, direction = [0, 1, 0] }
"#,
    )
}

fn render_with_threads(n: usize) -> DataFile {
    let s = scene(&scene_text());
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(|| render_scene(&s).0)
}

#[test]
fn rendered_data_file_round_trips_and_is_thread_count_independent() {
    let one = render_with_threads(1);
    let two = render_with_threads(2);
    // The scene is not trivial: both objects are seen, with shifted frequencies.
    for obj in 0..2 {
        assert!(
            one.records.iter().any(|r| r.object == obj),
            "object {obj} not seen"
        );
    }
    assert!(one
        .records
        .iter()
        .any(|r| r.is_hit() && (r.g - 1.0).abs() > 0.01));
    assert_eq!(one, two, "records differ between 1 and 2 threads");

    let dir = tempfile::tempdir().unwrap();
    let (p1, p2) = (dir.path().join("one.exr"), dir.path().join("two.exr"));
    one.write(&p1).unwrap();
    two.write(&p2).unwrap();
    let (b1, b2) = (std::fs::read(&p1).unwrap(), std::fs::read(&p2).unwrap());
    assert!(b1 == b2, "EXR files differ between 1 and 2 threads");

    let back = DataFile::read(&p1).unwrap();
    assert_eq!(back, one, "data file did not read back unchanged");
    assert_eq!(back.header.scene_text, scene_text());
    assert_eq!(back.header.object_names, ["still", "falling"]);
    // Rendering again gives the same bytes (no state kept between renders).
    let again = render_with_threads(2);
    assert!(again.to_bytes().unwrap() == b1);
}
