//! End-to-end tests of the `godel` binary: `geodesic` output (CSV/JSON) against closed forms
//! of Gödel light rays (docs/physics.md, "Closed forms": return time 2πa(√2 − 1), sense of
//! rotation), input validation (exit code 2 naming the flag), and `plot geodesics` (valid SVG
//! with the horizon, PNG).

use std::f64::consts::{PI, SQRT_2};
use std::process::Output;

use crate::common::{geodesic_along_x, godel};

fn stdout(o: &Output) -> String {
    assert!(
        o.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout.clone()).unwrap()
}

/// Rows of a CSV output, after checking the header.
fn csv(args: &[&str]) -> Vec<[f64; 7]> {
    let mut full = vec!["geodesic"];
    full.extend_from_slice(args);
    let text = stdout(&godel(&full));
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("lambda,t,r,phi,z,x,y"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|s| s.parse().unwrap()).collect();
            v.try_into().unwrap()
        })
        .collect()
}

fn json(args: &[&str]) -> serde_json::Value {
    let mut full = vec!["geodesic", "--format", "json"];
    full.extend_from_slice(args);
    serde_json::from_str(&stdout(&godel(&full))).expect("valid JSON")
}

const T_RET: f64 = 2.0 * PI * (SQRT_2 - 1.0);

#[test]
fn csv_has_header_and_requested_sample_count() {
    assert_eq!(csv(&["--at", "0,0,0,0", "--dir", "1,0,0"]).len(), 100);
    assert_eq!(
        csv(&["--at", "0,0,0,0", "--dir", "1,0,0", "--samples", "7"]).len(),
        7
    );
    assert_eq!(
        csv(&["--at", "0,0,0,0", "--dir", "1,0,0", "--samples", "2"]).len(),
        2
    );
}

#[test]
fn first_row_is_the_start_event() {
    let rows = csv(&[
        "--at",
        "1.5,0.7,2.0,-0.3",
        "--dir",
        "0,1,0.5",
        "--samples",
        "5",
    ]);
    let [l, t, r, phi, z, x, y] = rows[0];
    assert_eq!([l, t, r, phi, z], [0.0, 1.5, 0.7, 2.0, -0.3]);
    assert!((x - 0.7 * 2f64.cos()).abs() < 1e-15 && (y - 0.7 * 2f64.sin()).abs() < 1e-15);
}

#[test]
fn until_time_stops_exactly_at_the_bound_in_both_time_directions() {
    for past in [false, true] {
        let mut args = vec![
            "--at",
            "1,0.5,0.3,0",
            "--dir",
            "0,1,0.2",
            "--until-time",
            "1.7",
            "--samples",
            "9",
        ];
        if past {
            args.push("--past");
        }
        let rows = csv(&args);
        let t_last = rows.last().unwrap()[1];
        assert!(((t_last - 1.0).abs() - 1.7).abs() < 1e-9, "t = {t_last}");
        assert_eq!(t_last > 1.0, !past);
        // The parameter grows evenly, the first sample at 0.
        let h = rows[1][0];
        for (i, row) in rows.iter().enumerate() {
            assert!((row[0] - h * i as f64).abs() < 1e-12 * (1.0 + row[0]));
        }
    }
}

#[test]
fn future_rays_turn_counter_clockwise_and_past_rays_clockwise() {
    let future = csv(&["--at", "0,0,0,0", "--dir", "1,0,0", "--samples", "101"]);
    let past = csv(&[
        "--at",
        "0,0,0,0",
        "--dir",
        "1,0,0",
        "--samples",
        "101",
        "--past",
    ]);
    let (f, p) = (future[50], past[50]);
    // Mid-loop: r = r_max = 2a, φ = ±π/2, t = ±T_ret/2 (docs/physics.md, "Closed forms").
    assert!(f[6] > 1.99 && (f[2] - 2.0).abs() < 1e-8 && (f[3] - PI / 2.0).abs() < 1e-8);
    assert!(p[6] < -1.99 && (p[2] - 2.0).abs() < 1e-8 && (p[3] + PI / 2.0).abs() < 1e-8);
    assert!((f[1] - T_RET / 2.0).abs() < 1e-8 && (p[1] + T_RET / 2.0).abs() < 1e-8);
    // φ is continuous: no jump larger than the loop's own turning.
    for w in future.windows(2) {
        assert!(
            (w[1][3] - w[0][3]).abs() < 0.5,
            "φ jumps: {:?} -> {:?}",
            w[0],
            w[1]
        );
    }
}

#[test]
fn default_godel_stop_is_one_loop_back_on_the_axis() {
    for (a, past) in [("1", false), ("1", true), ("0.7", false)] {
        let a_val: f64 = a.parse().unwrap();
        let mut args = vec!["--a", a, "--at", "0,0,0,0", "--dir", "1,0,0"];
        if past {
            args.push("--past");
        }
        let rows = csv(&args);
        let last = rows.last().unwrap();
        assert!(last[2] < 1e-6, "r = {}", last[2]);
        assert!(
            (last[1].abs() - a_val * T_RET).abs() < 1e-6,
            "t = {}",
            last[1]
        );
        assert!(
            (last[0] - 2.0 * PI * a_val).abs() < 1e-6,
            "λ_ret = 2πa, got {}",
            last[0]
        );
        // On return φ has turned by ±π (docs/physics.md, "Closed forms").
        assert!(
            (last[3] - if past { -PI } else { PI }).abs() < 1e-6,
            "φ = {}",
            last[3]
        );
    }
}

#[test]
fn json_reports_constants_with_tiny_drift() {
    let doc = json(&["--at", "0,0,0,0", "--dir", "1,0.3,0.4", "--samples", "11"]);
    assert_eq!(doc["metric"], "godel");
    assert_eq!(doc["a"], 1.0);
    assert_eq!(doc["kind"], "null");
    assert_eq!(doc["stop"], "axis_return");
    assert_eq!(doc["samples"].as_array().unwrap().len(), 11);
    assert_eq!(doc["samples"][0]["t"], 0.0);
    assert!((doc["constants"]["E"].as_f64().unwrap() - 1.0).abs() < 1e-15);
    assert!(doc["constants"]["normalization"].as_f64().unwrap().abs() < 1e-14);
    for key in ["E", "L", "p_z", "normalization", "max"] {
        let d = doc["drift"][key].as_f64().unwrap();
        assert!(d < 1e-9, "drift of {key}: {d}");
    }
    assert!(doc["steps"].as_u64().unwrap() > 0 && doc["evaluations"].as_u64().unwrap() > 0);

    let doc = json(&[
        "--at",
        "0,0.5,1,0",
        "--dir",
        "0,1,0",
        "--speed",
        "0.6",
        "--until-time",
        "3",
    ]);
    assert_eq!(doc["kind"], "timelike");
    assert_eq!(doc["stop"], "time_reached");
    assert!((doc["constants"]["normalization"].as_f64().unwrap() + 1.0).abs() < 1e-12);
    assert!(doc["drift"]["max"].as_f64().unwrap() < 1e-9);
}

#[test]
fn minkowski_rays_are_straight_and_stop_at_time_ten() {
    let rows = csv(&[
        "--metric",
        "minkowski",
        "--at",
        "0,0,0,0",
        "--dir",
        "1,2,0",
        "--samples",
        "21",
    ]);
    let last = rows.last().unwrap();
    assert!((last[1] - 10.0).abs() < 1e-12);
    let dir_phi = 2f64.atan2(1.0);
    for row in &rows[1..] {
        let [l, t, r, phi, ..] = *row;
        assert!((r - l).abs() < 1e-9 && (t - l).abs() < 1e-9, "{row:?}");
        assert!((phi - dir_phi).abs() < 1e-12);
    }
    let doc = json(&["--metric", "minkowski", "--at", "0,0,0,0", "--dir", "0,0,1"]);
    assert!(doc["a"].is_null());
}

#[test]
fn bad_input_exits_2_naming_the_flag() {
    let ok = ["--at", "0,0,0,0", "--dir", "1,0,0"];
    let cases: &[(&[&str], &str)] = &[
        (&["--a", "0"], "--a"),
        (&["--a", "-1"], "--a"),
        (&["--a", "NaN"], "--a"),
        (&["--a", "inf"], "--a"),
        (&["--speed", "1"], "--speed"),
        (&["--speed", "1.5"], "--speed"),
        (&["--speed", "-0.1"], "--speed"),
        (&["--speed", "NaN"], "--speed"),
        (&["--speed", "fast"], "--speed"),
        (&["--until-time", "NaN"], "--until-time"),
        (&["--until-time", "inf"], "--until-time"),
        (&["--until-time", "0"], "--until-time"),
        (&["--until-time", "-2"], "--until-time"),
        (&["--samples", "1"], "--samples"),
        (&["--samples", "0"], "--samples"),
        (&["--metric", "kerr"], "--metric"),
        (&["--format", "xml"], "--format"),
    ];
    let vector_cases: &[(&str, &str, &str)] = &[
        ("NaN,0,0,0", "1,0,0", "--at"),
        ("0,inf,0,0", "1,0,0", "--at"),
        ("0,0,0", "1,0,0", "--at"),
        ("0,0,0,0,0", "1,0,0", "--at"),
        ("0,-1,0,0", "1,0,0", "--at"),
        ("0,x,0,0", "1,0,0", "--at"),
        ("0,0,0,0", "0,0,0", "--dir"),
        ("0,0,0,0", "1,NaN,0", "--dir"),
        ("0,0,0,0", "1,0", "--dir"),
        ("0,0,0,0", "1,0,0,0", "--dir"),
    ];
    let mut runs: Vec<(Vec<&str>, &str)> = Vec::new();
    for (extra, flag) in cases {
        let mut args = vec!["geodesic"];
        args.extend_from_slice(&ok);
        args.extend_from_slice(extra);
        runs.push((args, flag));
    }
    for (at, dir, flag) in vector_cases {
        runs.push((vec!["geodesic", "--at", at, "--dir", dir], flag));
    }
    for (args, flag) in runs {
        let out = godel(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(flag),
            "{args:?}: stderr does not name {flag}: {err}"
        );
        assert!(err.starts_with("error: "), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?} printed output");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    // Our own validation errors are a single line.
    let out = godel(&geodesic_along_x(&["--speed", "1.5"]));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: --speed: must be in [0, 1), got 1.5\n"
    );
}

#[test]
fn an_integration_failure_exits_1_with_the_reason() {
    // Many loops: the step budget runs out long before |t| reaches the bound.
    let out = godel(&geodesic_along_x(&["--until-time", "1e7"]));
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error: integration failed: step budget spent"),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn help_documents_the_default_stop() {
    let text = stdout(&godel(&["geodesic", "--help"]));
    assert!(
        text.contains("one loop") && text.contains("|t - T| = 10"),
        "{text}"
    );
}

#[test]
fn plot_writes_an_svg_with_the_horizon_and_one_polyline_per_ray() {
    let dir = tempfile::tempdir().unwrap();
    for a in ["1", "2.5"] {
        let path = dir.path().join(format!("g{a}.svg"));
        let p = path.to_str().unwrap();
        let out = godel(&[
            "plot",
            "geodesics",
            "--a",
            a,
            "--rays",
            "8",
            "--tilted",
            "3",
            "-o",
            p,
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let svg = std::fs::read_to_string(&path).unwrap();
        resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).expect("valid SVG");
        // Plot units are units of a: the horizon r = 2a has radius 2.
        assert!(
            svg.contains(r#"<circle cx="0" cy="0" r="2" id="horizon""#),
            "no horizon circle"
        );
        assert!(svg.contains("optical horizon r = 2a"));
        assert_eq!(svg.matches("<polyline").count(), 11);
        // Every ray stays inside the horizon (within drawing precision).
        for pl in svg.split("<polyline").skip(1) {
            let points = pl.split("points=\"").nth(1).unwrap();
            for pt in points.split('"').next().unwrap().split(' ') {
                let (x, y) = pt.split_once(',').unwrap();
                let r = x.parse::<f64>().unwrap().hypot(y.parse::<f64>().unwrap());
                assert!(r <= 2.0 + 1e-3, "point at r = {r}");
            }
        }
    }
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        2,
        "temporary files left behind"
    );
}

#[test]
fn plot_writes_a_decodable_png_with_content() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("g.png");
    let out = godel(&["plot", "geodesics", "-o", path.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(&path).expect("decodable PNG").to_rgb8();
    assert!(img.width() >= 1000 && img.height() >= 600);
    let non_white = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
    let frac = non_white as f64 / (img.width() * img.height()) as f64;
    assert!(frac > 0.05 && frac < 0.8, "non-white fraction {frac}");
    // The Okabe–Ito blue of the first ray is there (colour, not just grey).
    assert!(img.pixels().any(|p| p.0 == [0x00, 0x72, 0xB2]));
}

#[test]
fn plot_rejects_bad_input_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("g.svg");
    let s = svg.to_str().unwrap();
    let pdf = dir.path().join("g.pdf");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["plot", "geodesics", "--rays", "0", "-o", s], "--rays"),
        (vec!["plot", "geodesics", "--a", "-1", "-o", s], "--a"),
        (vec!["plot", "geodesics", "--a", "NaN", "-o", s], "--a"),
        (
            vec!["plot", "geodesics", "-o", pdf.to_str().unwrap()],
            "--output",
        ),
    ];
    for (args, flag) in cases {
        let out = godel(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(flag), "{err}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    // Issue 36: an output that cannot be written failed after the work with exit 1, where
    // render refuses it before any work with exit 2; now as render: a folder where the file
    // goes, or a file where a folder must be created.
    std::fs::create_dir(dir.path().join("taken.svg")).unwrap();
    std::fs::write(dir.path().join("file"), b"x").unwrap();
    for bad in ["taken.svg", "file/sub/g.svg"] {
        let path = dir.path().join(bad);
        let out = godel(&["plot", "geodesics", "-o", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{bad}: {err}");
        assert!(err.starts_with("error: --output: cannot"), "{bad}: {err}");
    }
    let mut left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    left.sort();
    assert_eq!(left, ["file", "taken.svg"]);
}

/// Issue 36: `plot -o a/b/c.svg` failed where `render` creates missing folders.
#[test]
fn plot_creates_the_missing_folders_of_its_output() {
    let dir = tempfile::tempdir().unwrap();
    for figure in ["geodesics", "isometry"] {
        let path = dir.path().join(figure).join("b/c.svg");
        let out = godel(&["plot", figure, "-o", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{figure}: {err}");
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(
            svg.starts_with("<svg") || svg.starts_with("<?xml"),
            "{figure}"
        );
    }
}

/// Issue 10: `--samples 4000000000` aborted with SIGABRT after trying to allocate 288 GB.
#[test]
fn samples_are_bounded_up_front() {
    for n in ["4000000000", "1000001"] {
        let out = godel(&geodesic_along_x(&["--samples", n]));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{n}: {err}");
        assert!(
            err.starts_with("error: --samples: at most 1000000"),
            "{n}: {err}"
        );
        assert!(out.stdout.is_empty());
    }
    let rows = csv(&["--at", "0,0,0,0", "--dir", "1,0,0", "--samples", "1000000"]);
    assert_eq!(rows.len(), 1_000_000);
}

/// Issue 10: a start event too far from the axis was blamed on `--dir`.
#[test]
fn a_start_too_far_out_is_blamed_on_at() {
    for (r, method) in [
        ("1e300", "exact"),
        ("1e300", "numeric"),
        ("1e20", "numeric"),
        ("1000", "exact"),
    ] {
        let at = format!("0,{r},0,0");
        let out = godel(&[
            "geodesic", "--at", &at, "--dir", "1,0,0", "--method", method,
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{r} {method}: {err}");
        assert!(err.starts_with("error: --at: "), "{r} {method}: {err}");
        assert!(out.stdout.is_empty());
    }
}

/// Issue 10: `--until-time 1e15` stopped at λ = 1e6 without saying so (and the exact
/// method of Gödel's metric stopped at λ ≈ 4e-16, calling it the time bound).
#[test]
fn a_time_bound_out_of_reach_is_reported() {
    for (metric, method) in [
        ("minkowski", "numeric"),
        ("minkowski", "exact"),
        ("godel", "exact"),
    ] {
        let out = godel(&[
            "geodesic",
            "--format",
            "json",
            "--metric",
            metric,
            "--method",
            method,
            "--at",
            "0,0,0,0",
            "--dir",
            "1,0,0",
            "--until-time",
            "1e15",
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{metric} {method}: {err}");
        let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(doc["stop"], "affine_limit", "{metric} {method}");
        assert_eq!(doc["lambda_end"], 1e6, "{metric} {method}");
        let last = doc["samples"].as_array().unwrap().last().unwrap().clone();
        assert!(last["t"].as_f64().unwrap() < 1e15);
        assert!(
            err.starts_with("note: stopped at lambda = 1000000 (affine-parameter bound reached)"),
            "{metric} {method}: {err}"
        );
        assert!(err.contains("1e15"), "{err}");
    }
    // Within reach: no note.
    let out = godel(&geodesic_along_x(&[
        "--metric",
        "minkowski",
        "--until-time",
        "100",
    ]));
    assert!(out.status.success() && out.stderr.is_empty());
}

/// Issue 24: `geodesic` and `connect` took t, φ and z up to 1e300 (scenes refuse beyond
/// ±1e6·a) and printed `travel_time 0`; `geodesic --a 1e-300` said "too far from the axis";
/// numbers came back with 300 digits. Now the ranges are those of scenes, the messages short.
#[test]
fn events_and_the_scale_have_the_ranges_of_scenes() {
    let cases: [(&[&str], &str); 7] = [
        (
            &["geodesic", "--at", "1e300,0,0,0", "--dir", "1,0,0"],
            "--at: t = 1e300 is beyond ±1e6",
        ),
        (
            &["geodesic", "--at", "0,0,-2e6,0", "--dir", "1,0,0"],
            "--at: phi = -2e6 is beyond ±1e6",
        ),
        (
            &["geodesic", "--at", "0,0,0,1e300", "--dir", "1,0,0"],
            "--at: z = 1e300",
        ),
        (
            &[
                "geodesic", "--at", "0,0,0,0", "--dir", "1,0,0", "--a", "1e-300",
            ],
            "--a: 1e-300 is outside [1e-6, 1e6], as in scenes",
        ),
        (
            &["connect", "--from", "1e300,0,0,0", "--to-source", "0.5,0,0"],
            "--from: t = 1e300 is beyond ±1e6",
        ),
        (
            &["connect", "--from", "0,0,0,0", "--to-source", "0.5,0,3e6"],
            "--to-source: z = 3e6 is beyond ±1e6",
        ),
        (
            &[
                "connect",
                "--from",
                "0,0,0,0",
                "--to-source",
                "0.5,0,0",
                "--a",
                "1e300",
            ],
            "--a: 1e300 is outside",
        ),
    ];
    for (args, needle) in cases {
        let o = godel(args);
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
        assert!(e.starts_with(&format!("error: {needle}")), "{args:?}: {e}");
        assert!(e.len() < 240, "{args:?}: a short message: {e}");
        assert!(o.stdout.is_empty());
    }
    // At the bound itself, and with a small a scaled along, all is well.
    for args in [
        &["geodesic", "--at", "1e6,0,0,0", "--dir", "1,0,0"][..],
        &[
            "geodesic", "--at", "0,0,0,0", "--dir", "1,0,0", "--a", "1e-6",
        ],
        &["connect", "--from", "-1e6,0,0,0", "--to-source", "0.5,0,0"],
    ] {
        let o = godel(args);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}
