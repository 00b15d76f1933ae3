//! The command line without traps (issue 12): `-o` is a folder or a file name (`x.exr` or
//! `x.png`, both written) for render and merge, and a file for shade; render's scene overrides are validated like the
//! scene and name their flag; shade refuses flags no chosen layer reads; negative numbers
//! reach validation as values; a closed pipe ends quietly with 0; each error is said once;
//! shade writes linear EXR or tone-mapped PNG by extension and refuses other extensions;
//! progress rates are whole numbers.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};

use crate::common::{
    assert_usage, files_in, geodesic_along_x, godel, lit_scene_text, path_arg as s, read_rgb,
    shade_lit_pair, stderr, write_scene,
};

/// A small traced data file (and its preview) in `dir`, named `lit`.
fn traced(dir: &Path) -> std::path::PathBuf {
    let scene = write_scene(dir, "lit.toml", &lit_scene_text("lit", 4.0));
    let o = godel(&["render", &scene, "-q", "-o", s(dir)]);
    assert!(o.status.success(), "{}", stderr(&o));
    dir.join("lit.exr")
}

/// One `-o` convention (issue 27): render and merge take a folder or a file name; a file
/// name `x.exr` or `x.png` writes both, the other beside it.
#[test]
fn render_and_merge_take_a_file_name_or_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_scene(dir.path(), "lit.toml", &lit_scene_text("lit", 4.0));
    let folder = dir.path().join("folder");
    let o = godel(&["render", &scene, "-q", "-o", s(&folder)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let want = datafile::DataFile::read(&folder.join("lit.exr")).unwrap();
    let preview = std::fs::read(folder.join("lit.png")).unwrap();
    for given in ["pic.png", "deeper/pic.exr"] {
        let out = dir.path().join(given);
        let o = godel(&["render", &scene, "-q", "-o", s(&out)]);
        assert!(o.status.success(), "{given}: {}", stderr(&o));
        assert!(out.is_file(), "{given} is a file, not a folder");
        // The same files as in a folder, under the given name.
        let data = datafile::DataFile::read(&out.with_extension("exr")).unwrap();
        assert_eq!(data.records, want.records);
        assert_eq!(std::fs::read(out.with_extension("png")).unwrap(), preview);
    }
    // Issue 36: `-o pic.EXR` wrote pic.exr and pic.png: the name given is the name written,
    // its partner in the same case.
    let upper = dir.path().join("upper");
    let o = godel(&["render", &scene, "-q", "-o", s(&upper.join("pic.EXR"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(files_in(&upper), ["pic.EXR", "pic.PNG"]);
    let data = datafile::DataFile::read(&upper.join("pic.EXR")).unwrap();
    assert_eq!(data.records, want.records);
    // --name chooses NAME in a folder; beside a file name it is refused, nothing written.
    let named = dir.path().join("named.png");
    let o = godel(&["render", &scene, "-q", "-o", s(&named), "--name", "x"]);
    assert_usage(&o, "--name");
    assert!(!named.exists() && !named.with_extension("exr").exists());
    // Part files go into a folder.
    let o = godel(&["render", &scene, "-q", "--part", "1/2", "-o", s(&named)]);
    assert_usage(&o, "--output");
    assert!(!named.exists());
    // Merge: the same convention.
    let parts = dir.path().join("parts");
    for part in ["1/2", "2/2"] {
        let o = godel(&["render", &scene, "-q", "--part", part, "-o", s(&parts)]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let merged = dir.path().join("merged.exr");
    let o = godel(&[
        "merge",
        s(&parts.join("lit.part-1-of-2.exr")),
        s(&parts.join("lit.part-2-of-2.exr")),
        "-o",
        s(&merged),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        datafile::DataFile::read(&merged).unwrap().records,
        want.records
    );
    assert_eq!(
        std::fs::read(merged.with_extension("png")).unwrap(),
        preview
    );
    // The help says so.
    for command in ["render", "merge"] {
        let help = godel(&[command, "--help"]);
        let text = String::from_utf8_lossy(&help.stdout);
        assert!(text.contains("FOLDER|FILE"), "{text}");
        assert!(text.contains("x.exr or x.png"), "{text}");
    }
}

#[test]
fn render_overrides_replace_the_scene_fields() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_scene(dir.path(), "lit.toml", &lit_scene_text("lit", 4.0));
    let out = dir.path().join("out");
    let o = godel(&[
        "render",
        &scene,
        "-q",
        "-o",
        s(&out),
        "--width",
        "30",
        "--height",
        "12",
        "--max-past",
        "2.5",
        "--method",
        "exact",
        "--name",
        "copy",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(files_in(&out), ["copy.exr", "copy.png"]);
    let data = datafile::DataFile::read(&out.join("copy.exr")).unwrap();
    assert_eq!((data.width, data.height), (30, 12));
    assert_eq!(data.header.scene_name, "copy");
    assert_eq!(data.header.method, "exact");
    // The embedded scene is the one rendered: it reads back with the overrides.
    let embedded = scene::Scene::from_str(&data.header.scene_text, "embedded").unwrap();
    assert_eq!(embedded.trace.max_past, 2.5);
    assert_eq!(embedded.camera.width(), 30);
    // The original scene file is untouched.
    assert_eq!(
        std::fs::read_to_string(&scene).unwrap(),
        lit_scene_text("lit", 4.0)
    );
}

#[test]
fn bad_overrides_name_their_flag_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_scene(dir.path(), "lit.toml", &lit_scene_text("lit", 4.0));
    let out = dir.path().join("out");
    for (flag, value) in [
        ("--width", "0"),
        ("--width", "-5"),
        ("--height", "30000"),
        ("--max-past", "-1"),
        ("--max-past", "nan"),
        ("--method", "fast"),
        ("--name", ".hidden"),
        ("--name", "-x"),
    ] {
        let o = godel(&["render", &scene, "-q", "-o", s(&out), flag, value]);
        assert_usage(&o, flag);
        assert!(!out.exists(), "{flag} {value}: nothing written");
    }
}

#[test]
fn shade_refuses_flags_no_chosen_layer_reads() {
    let dir = tempfile::tempdir().unwrap();
    let data = traced(dir.path());
    let out = dir.path().join("x.png");
    for (args, flag, layer) in [
        (vec!["--temperature", "4000"], "--temperature", "frequency"),
        (vec!["--exposure", "0.5"], "--exposure", "frequency"),
        (vec!["--window=-3,1"], "--window", "time"),
        (vec!["--travel", "0,5"], "--travel", "time"),
        (vec!["--ambient", "0.3"], "--ambient", "light"),
        (vec!["--light", "0=off"], "--light", "light"),
        (
            vec!["--shader", "frequency", "--rotate", "90"],
            "--rotate",
            "texture, time or light",
        ),
    ] {
        let mut all = vec!["shade", s(&data), "-o", s(&out)];
        all.extend(args);
        let o = godel(&all);
        assert_usage(&o, flag);
        assert!(stderr(&o).contains(layer), "{}", stderr(&o));
        assert!(!out.exists());
    }
    // Display settings on a linear picture are refused as well.
    let exr = dir.path().join("x.exr");
    for flag in [vec!["--grid"], vec!["--ev", "1"]] {
        let mut all = vec!["shade", s(&data), "-o", s(&exr)];
        all.extend(flag.iter().copied());
        let o = godel(&all);
        assert_usage(&o, flag[0]);
        assert!(!exr.exists());
    }
    // With the layer, the same flag works.
    let o = godel(&[
        "shade",
        s(&data),
        "-o",
        s(&out),
        "--shader",
        "frequency",
        "--temperature",
        "4000",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn negative_numbers_are_values_and_are_validated() {
    let dir = tempfile::tempdir().unwrap();
    let data = traced(dir.path());
    let out = dir.path().join("x.png");
    for (args, flag) in [
        (
            vec!["--shader", "frequency", "--temperature", "-5"],
            "--temperature",
        ),
        (
            vec!["--shader", "frequency", "--exposure", "-1"],
            "--exposure",
        ),
        (vec!["--shader", "light", "--ambient", "-0.5"], "--ambient"),
        (vec!["--ev", "-30"], "--ev"),
    ] {
        let mut all = vec!["shade", s(&data), "-o", s(&out)];
        all.extend(args);
        let o = godel(&all);
        assert_usage(&o, flag);
        // Refused as a value, not taken for an unknown flag by the parser.
        assert!(
            !stderr(&o).contains("unexpected argument"),
            "{}",
            stderr(&o)
        );
    }
    // A negative value that is fine is accepted.
    let o = godel(&["shade", s(&data), "-o", s(&out), "--ev", "-1"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_closed_pipe_ends_quietly_with_zero() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_godel"))
        .args(geodesic_along_x(&["--samples", "200000"]))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read the header line only, then close the pipe, as `| head -1` does.
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(first.starts_with("lambda,"), "{first}");
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
}

#[test]
fn each_error_is_said_once() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.exr");
    let o = godel(&["shade", s(&missing), "-o", s(&dir.path().join("x.png"))]);
    let err = stderr(&o);
    assert_ne!(o.status.code(), Some(0));
    assert_eq!(err.matches("os error").count(), 1, "{err}");
    assert_eq!(err.matches("missing.exr").count(), 1, "{err}");
    // A folder given for the data file: said as it is, not as an input/output fault (issue 36).
    let o = godel(&["shade", s(dir.path()), "-o", s(&dir.path().join("x.png"))]);
    let err = stderr(&o);
    assert_ne!(o.status.code(), Some(0));
    assert!(
        err.ends_with(": not a regular file (a directory)\n"),
        "{err}"
    );
    assert!(!err.contains("input/output"), "{err}");

    // A picture into a folder that cannot be made (a file is in the way): the path once, the
    // cause once. (A folder that does not exist yet is made: issue 36.)
    let data = traced(dir.path());
    std::fs::write(dir.path().join("no"), b"a file").unwrap();
    let out = dir.path().join("no").join("such").join("x.png");
    let o = godel(&["shade", s(&data), "-o", s(&out)]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.matches("os error").count(), 1, "{err}");
    assert_eq!(
        err.matches(".godel-").count(),
        0,
        "no temporary named: {err}"
    );
    assert_eq!(err.matches("no/such").count(), 1, "{err}");
}

#[test]
fn shade_output_type_follows_the_extension() {
    let dir = tempfile::tempdir().unwrap();
    let data_path = traced(dir.path());
    for bad in ["x.jpg", "x", "x.png.tmp"] {
        let out = dir.path().join(bad);
        let o = godel(&["shade", s(&data_path), "-o", s(&out)]);
        assert_usage(&o, "--output");
        assert!(!out.exists());
    }
    // Issue 36: missing folders are created, as render's; an output that cannot be written
    // is refused before shading (exit 2).
    let deep = dir.path().join("a/b/x.png");
    let o = godel(&["shade", s(&data_path), "-o", s(&deep)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(image::open(&deep).is_ok());
    std::fs::write(dir.path().join("file"), b"x").unwrap();
    let blocked = dir.path().join("file/x.png");
    let o = godel(&["shade", s(&data_path), "-o", s(&blocked)]);
    assert_usage(&o, "--output");
    let (exr, png) = shade_lit_pair(&data_path, dir.path(), "x");
    // The EXR holds float R, G, B; the PNG is the same colours through the display
    // transform (tone curve, sRGB) on every hit pixel.
    let linear = read_rgb(&exr);
    let data = datafile::DataFile::read(&data_path).unwrap();
    let shown = image::open(&png).unwrap().to_rgb8();
    assert_eq!(linear.len(), data.width * data.height);
    let mut hits = 0;
    for (i, rec) in data.records.iter().enumerate() {
        if rec.status != datafile::RayStatus::Hit || rec.object < 0 {
            continue;
        }
        hits += 1;
        let (col, row) = ((i % data.width) as u32, (i / data.width) as u32);
        let want = shade::colour::display_srgb8(linear[i], 1.0);
        let got = shown.get_pixel(col, row).0;
        for k in 0..3 {
            assert!(
                want[k].abs_diff(got[k]) <= 1,
                "pixel {i}: {want:?} vs {got:?}"
            );
        }
    }
    assert!(hits > 20);
}

#[test]
fn progress_rates_are_whole_numbers() {
    // The bar is drawn only on a terminal: `script` (util-linux) gives the render one.
    let dir = tempfile::tempdir().unwrap();
    let scene = write_scene(dir.path(), "lit.toml", &lit_scene_text("lit", 4.0));
    let command = format!(
        "'{}' render '{}' -o '{}'",
        env!("CARGO_BIN_EXE_godel"),
        scene,
        s(&dir.path().join("out"))
    );
    let o = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .output()
        .expect("`script` (util-linux) runs the render on a terminal");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
    let screen = String::from_utf8_lossy(&o.stdout).replace('\r', "\n");
    // Every rate the bar printed: the text between the last ", " and "/s".
    let rates: Vec<&str> = screen
        .match_indices("/s")
        .filter_map(|(i, _)| screen[..i].rsplit(", ").next())
        .filter(|r| !r.contains('\n'))
        .collect();
    assert!(!rates.is_empty(), "no progress drawn: {screen}");
    for r in rates {
        // The bar's "N px/s" and the summary's "N rays/s".
        let digits = r
            .strip_suffix(" px")
            .or_else(|| r.strip_suffix(" rays"))
            .unwrap_or_else(|| panic!("rate {r:?}"));
        assert!(
            !digits.is_empty() && digits.chars().all(|c| c.is_ascii_digit()),
            "rate {r:?} is not a whole number of px/s"
        );
    }
}
