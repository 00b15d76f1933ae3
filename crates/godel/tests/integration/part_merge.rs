//! `godel render --part i/N` and `godel merge`: the parts of a render, merged in any
//! order, give the very bytes of a single run (data file and preview); parts that do not
//! belong together (missing, repeated, overlapping, other scene, not a part) are refused
//! with a message naming the file and nothing is written; light planes survive a split.

use datafile::DataFile;
use render::driver::Renderer;
use render::part::{fingerprint, merge, read_part, write_part};
use render::plan::Part;
use render::tiles::{extract, insert};
use scene::Scene;
use std::path::Path;

use crate::common::{self, assert_same_files, godel, godel_ok as render_ok, stderr, write_scene};

/// The shared lit test scene, named "split".
fn scene_text(max_past: f64) -> String {
    common::lit_scene_text("split", max_past)
}

/// Renders parts i/3 of `scene` into `dir`; returns their paths, part 1 first.
fn parts(scene: &str, dir: &Path) -> Vec<String> {
    let d = dir.display().to_string();
    (1..=3)
        .map(|i| {
            render_ok(&["render", scene, "--part", &format!("{i}/3"), "-o", &d, "-q"]);
            dir.join(format!("split.part-{i}-of-3.exr"))
                .display()
                .to_string()
        })
        .collect()
}

#[test]
fn three_parts_merged_in_any_order_equal_the_single_run_byte_for_byte() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(tmp.path(), "split.toml", &scene_text(8.0));
    let single = tmp.path().join("single");
    render_ok(&["render", &scene, "-o", single.to_str().unwrap(), "-q"]);
    let p = parts(&scene, &tmp.path().join("parts"));

    // Each part alone is incomplete: it traced about a third of the pixels, and reading
    // it as a whole data file (as `godel shade` would) is refused.
    let whole = DataFile::read(&single.join("split.exr")).unwrap();
    assert!(whole.records.iter().any(|r| r.is_hit()));
    assert_eq!(whole.lights.len(), 1);
    assert!(
        whole.lights[0].iter().any(|&l| l > 0.0),
        "the light lit nothing"
    );
    for path in &p {
        let err = DataFile::read(Path::new(path)).unwrap_err().to_string();
        assert!(
            err.contains("godel merge") && err.contains(path.as_str()),
            "{err}"
        );
        let part = read_part(Path::new(path)).unwrap().data;
        let traced = part.records.iter().filter(|r| r.status.code() != 4).count();
        assert!(
            traced > 0 && traced < whole.records.len() / 2,
            "{path}: {traced}"
        );
        assert_ne!(part, whole);
    }

    let merged = tmp.path().join("merged");
    render_ok(&["merge", &p[2], &p[0], &p[1], "-o", merged.to_str().unwrap()]);
    assert_same_files(
        &single,
        &merged,
        &["split.exr", "split.png"],
        "the single run and the merge",
    );
}

/// Runs a merge that must fail; checks the message and that nothing was written.
fn refused(parts: &[&str], dir: &Path, expect: &[&str]) {
    let out_dir = dir.join("refused");
    let mut args = vec!["merge"];
    args.extend_from_slice(parts);
    args.extend_from_slice(&["-o", out_dir.to_str().unwrap()]);
    let out = godel(&args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
    for e in expect {
        assert!(err.contains(e), "{args:?}: expected {e:?} in: {err}");
    }
    assert!(!out_dir.exists(), "output written by a refused merge");
}

#[test]
fn missing_repeated_foreign_and_overlapping_parts_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let a = write_scene(tmp.path(), "a.toml", &scene_text(8.0));
    let b = write_scene(tmp.path(), "b.toml", &scene_text(7.0));
    let pa = parts(&a, &tmp.path().join("a"));
    let pb = parts(&b, &tmp.path().join("b"));

    refused(&[&pa[0], &pa[2]], tmp.path(), &["part(s) 2 of 3 missing"]);
    refused(
        &[&pa[0], &pa[1], &pa[1], &pa[2]],
        tmp.path(),
        &["part 2/3 given twice", &pa[1]],
    );
    refused(
        &[&pa[0], &pb[1], &pa[2]],
        tmp.path(),
        &["not parts of the same render", &pa[0], &pb[1]],
    );

    // A part of a split into 2 does not join a split into 3.
    let two = tmp.path().join("two");
    render_ok(&[
        "render",
        &a,
        "--part",
        "2/2",
        "-o",
        two.to_str().unwrap(),
        "-q",
    ]);
    let two = two.join("split.part-2-of-2.exr").display().to_string();
    refused(&[&pa[0], &two, &pa[2]], tmp.path(), &["part counts differ"]);

    // A complete data file is not a part.
    let whole = tmp.path().join("whole");
    render_ok(&["render", &a, "-o", whole.to_str().unwrap(), "-q"]);
    let whole_exr = whole.join("split.exr").display().to_string();
    refused(&[&whole_exr], tmp.path(), &["not a part file", &whole_exr]);

    // A file that claims part 1/3 but holds every pixel overlaps parts 2 and 3.
    let scene = Scene::from_file(&a).unwrap();
    let fake = tmp.path().join("fake.exr");
    let data = DataFile::read(Path::new(&whole_exr)).unwrap();
    write_part(
        &fake,
        &data,
        Part { index: 1, count: 3 },
        &fingerprint(&scene),
        &a,
    )
    .unwrap();
    let fake = fake.display().to_string();
    refused(
        &[&fake, &pa[1], &pa[2]],
        tmp.path(),
        &["belongs to another part", &fake],
    );

    // Not an EXR file at all.
    refused(
        &[&a, &pa[1], &pa[2]],
        tmp.path(),
        &["a.toml", "not an OpenEXR file"],
    );
}

#[test]
fn bad_part_flags_are_usage_errors() {
    for bad in ["0/3", "4/3", "3", "a/b", "1/0", ""] {
        let out = godel(&["render", "--part", bad, "-q", "-o", "/nonexistent/x"]);
        assert_eq!(
            out.status.code(),
            Some(2),
            "--part {bad:?}: {}",
            stderr(&out)
        );
        assert!(stderr(&out).contains("--part"), "{}", stderr(&out));
    }
}

#[test]
fn light_planes_travel_through_parts_and_merge() {
    // Synthetic light values (the tracer does not fill them yet): the split and the
    // merge must carry every plane to the same pixels.
    let scene = Scene::from_str(&scene_text(8.0), "split.toml").unwrap();
    let renderer = Renderer::new(&scene).unwrap();
    let mut whole = renderer.blank();
    let pixels = whole.width * whole.height;
    // Light values belong to hits (the data file stores NaN elsewhere): synthetic hits.
    for (i, r) in whole.records.iter_mut().enumerate() {
        r.object = 0;
        r.status = datafile::RayStatus::Hit;
        r.u = i as f32 / pixels as f32;
    }
    whole.lights = (0..2)
        .map(|k| {
            (0..pixels)
                .map(|i| (i * 7 + k * 1000) as f32 * 0.25)
                .collect()
        })
        .collect();
    let tiles = renderer.tiles();
    let tmp = tempfile::tempdir().unwrap();
    let read = (1..=3u32)
        .map(|index| {
            let part = Part { index, count: 3 };
            let mut data = renderer.blank();
            for k in part.tiles(tiles.len()) {
                insert(&mut data, tiles[k], &extract(&whole, tiles[k], k));
            }
            let path = tmp.path().join(format!("p{index}.exr"));
            write_part(&path, &data, part, &fingerprint(&scene), "").unwrap();
            read_part(&path).unwrap()
        })
        .collect::<Vec<_>>();
    assert_eq!(merge(&read).unwrap(), whole);
}
