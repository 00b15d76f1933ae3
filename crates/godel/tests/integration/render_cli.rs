//! End-to-end tests of `godel render`: a small scene renders to DIR/NAME.png and
//! DIR/NAME.exr with a summary line; every bad scene in `scenes/bad/` is refused with the
//! file, line and field named and no output left behind; bad flags exit 2.
//!
//! Bad scenes declare what they expect (see crates/scene/tests/integration/scene_files.rs): a line
//! `# expect field: PATH` (empty for TOML syntax errors) and `# <- error here` on the line
//! the error must point at.

use datafile::DataFile;
use std::path::{Path, PathBuf};

use crate::common::{render, stderr};

const W: u32 = 120;
const H: u32 = 15;

fn small_scene() -> String {
    testkit::axis_panorama(
        "small",
        W as usize,
        H as usize,
        6.0,
        r#"[[object]]
name = "ball"
radius = 0.2
texture = { kind = "checker", rows = 4, cols = 8 }
motion = { kind = "rest", position = { r = 1.0, phi = 0.7, z = 0.0 } }
"#,
    )
}

/// Writes [`small_scene`] as `dir/scene.toml`; returns its path and the output folder
/// `dir/out`.
fn small_scene_in(dir: &Path) -> (PathBuf, PathBuf) {
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, small_scene()).unwrap();
    (scene, dir.join("out"))
}

/// The first number before `word` in `line` (e.g. "1800 pixels").
fn count_before(line: &str, word: &str) -> u64 {
    let words: Vec<&str> = line.split_whitespace().collect();
    let i = words
        .iter()
        .position(|w| w.trim_end_matches(',') == word)
        .unwrap_or_else(|| panic!("no `{word}` in {line:?}"));
    words[i - 1]
        .parse()
        .unwrap_or_else(|_| panic!("no count before `{word}` in {line:?}"))
}

fn output_files(dir: &Path) -> Vec<PathBuf> {
    match std::fs::read_dir(dir) {
        Ok(entries) => entries.map(|e| e.unwrap().path()).collect(),
        Err(_) => vec![],
    }
}

#[test]
fn render_writes_png_and_exr_and_a_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, out) = small_scene_in(tmp.path());
    let o = render(&scene, &out, &["--quiet", "--threads", "2"]);
    let err = stderr(&o);
    assert!(o.status.success(), "exit {:?}: {err}", o.status);

    let (png, exr) = (out.join("small.png"), out.join("small.exr"));
    let mut files = output_files(&out);
    files.sort();
    assert_eq!(files, [exr.clone(), png.clone()], "{err}");
    let image = image::open(&png).expect("a decodable PNG");
    assert_eq!((image.width(), image.height()), (W, H));
    let data = DataFile::read(&exr).expect("a readable data file");
    assert_eq!((data.width, data.height), (W as usize, H as usize));
    let hits = data.records.iter().filter(|r| r.is_hit()).count() as u64;
    assert!(hits > 0);

    // The summary line: pixels, hit, failed, rays/s, with the counts of the data file.
    let line = err
        .lines()
        .find(|l| l.contains("rays/s"))
        .unwrap_or_else(|| panic!("no summary line in {err:?}"));
    assert_eq!(count_before(line, "pixels"), (W * H) as u64, "{line}");
    assert_eq!(count_before(line, "hit"), hits, "{line}");
    assert_eq!(count_before(line, "failed"), 0, "{line}");

    // One thread gives the same data file, byte for byte.
    let out1 = tmp.path().join("out1");
    let o = render(&scene, &out1, &["-q", "--threads", "1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read(out1.join("small.exr")).unwrap() == std::fs::read(&exr).unwrap());
}

#[test]
fn bad_scenes_exit_2_naming_file_line_and_field_and_leave_no_output() {
    let files = testkit::toml_files(&testkit::scenes_dir().join("bad"));
    assert!(files.len() >= 10, "{files:?}");
    let tmp = tempfile::tempdir().unwrap();
    for (i, f) in files.iter().enumerate() {
        let text = std::fs::read_to_string(f).unwrap();
        let (field, line) = testkit::bad_scene_expectation(&text);
        let out = tmp.path().join(format!("out{i}"));
        let o = render(f, &out, &["-q"]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{}: {err}", f.display());
        let located = format!("{}:{line}:", f.display());
        assert!(
            err.contains(&located),
            "{}: expected {located} in {err}",
            f.display()
        );
        if !field.is_empty() {
            assert!(
                err.contains(&field),
                "{}: expected {field} in {err}",
                f.display()
            );
        }
        assert_eq!(err.lines().count(), 1, "{}: {err}", f.display());
        let left: Vec<PathBuf> = output_files(&out)
            .into_iter()
            .filter(|p| {
                let name = p.file_name().unwrap().to_string_lossy();
                name.ends_with(".png") || name.ends_with(".exr") || name.contains("tmp")
            })
            .collect();
        assert!(left.is_empty(), "{}: left {left:?}", f.display());
    }
    // Nothing was written next to the bad scenes either.
    let dir = files[0].parent().unwrap();
    assert!(output_files(dir)
        .iter()
        .all(|p| p.extension().is_some_and(|e| e == "toml")));
}

#[test]
fn zero_threads_and_missing_scene_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, out) = small_scene_in(tmp.path());
    let o = render(&scene, &out, &["--threads", "0"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--threads"), "{}", stderr(&o));
    assert!(output_files(&out).is_empty());

    let missing = tmp.path().join("no-such-scene.toml");
    let o = render(&missing, &out, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("no-such-scene.toml"), "{}", stderr(&o));
    assert!(output_files(&out).is_empty());
}
