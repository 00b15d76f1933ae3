//! End-to-end tests of the Gödel-type family (docs/physics.md, "The Gödel-type family") on
//! the command line: `godel geodesic --metric godel-type` against Gödel's universe (the
//! member m² = 1/a², Ω = 1/(√2 a), carried through r = 2a sinh(ρ/2a)) and against the
//! turning radius ρ_c of in-plane rays from the axis; the refusals of --m2, --omega and --a,
//! each naming its flag; `godel plot geodesics` of one member and of several (`--members`):
//! the circle ρ_c where a member has one and of the right radius, none where m² ≥ 4Ω², rays
//! that turn there or leave the frame, the same bytes on a second run, bad flags refused.

use std::f64::consts::SQRT_2;

use crate::common::{assert_usage, godel, stderr};

/// Rows (lambda, t, r, phi, z, x, y) of `godel geodesic` with `args`.
fn rows(args: &[&str]) -> Vec<[f64; 7]> {
    let out = godel(&[&["geodesic"], args].concat());
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("lambda,t,r,phi,z,x,y"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|s| s.parse().unwrap()).collect();
            v.try_into().unwrap()
        })
        .collect()
}

/// ρ_c of a member with 0 < m² < 4Ω²: tanh(mρ_c/2) = m/(2Ω).
fn critical_radius(m2: f64, omega: f64) -> f64 {
    let m = m2.sqrt();
    2.0 * (m / (2.0 * omega)).atanh() / m
}

#[test]
fn the_godel_member_traces_godels_rays_through_the_proper_radius() {
    let a = 0.8_f64;
    let (m2, omega) = (1.0 / (a * a), 1.0 / (SQRT_2 * a));
    let (m2, omega) = (m2.to_string(), omega.to_string());
    // From the axis the two charts' local frames agree, so one direction is one ray; one in
    // the plane and one tilted out of it, each one loop back to the axis.
    for dir in ["1,0,0", "0.3,-1,0.6"] {
        let common = ["--at", "0.5,0,0.25,-0.1", "--dir", dir, "--samples", "41"];
        let member = rows(
            &[
                &["--metric", "godel-type", "--m2", &m2, "--omega", &omega][..],
                &common,
            ]
            .concat(),
        );
        let godel_rows = rows(&[&["--metric", "godel", "--a", "0.8"][..], &common].concat());
        assert_eq!(member.len(), godel_rows.len());
        let mut widest = 0.0_f64;
        for (p, q) in member.iter().zip(&godel_rows) {
            let r_of_rho = 2.0 * a * (p[2] / (2.0 * a)).sinh();
            for (what, x, y) in [
                ("lambda", p[0], q[0]),
                ("t", p[1], q[1]),
                ("r", r_of_rho, q[2]),
                ("phi", p[3], q[3]),
                ("z", p[4], q[4]),
            ] {
                assert!(
                    (x - y).abs() < 1e-7,
                    "{dir}: {what} {x} vs {y}\n{p:?}\n{q:?}"
                );
            }
            widest = widest.max(p[2]);
        }
        // The comparison covers the far side of the loop (ρ_c = 2a asinh 1 in the plane).
        assert!(widest > 0.5 * a, "{dir}: {widest}");
    }
}

#[test]
fn in_plane_rays_from_the_axis_turn_at_the_critical_radius() {
    for (m2, omega) in [(1.0, 1.0), (0.5, 0.6)] {
        let rho_c = critical_radius(m2, omega);
        let (m2s, omegas) = (m2.to_string(), omega.to_string());
        let args = [
            "--metric",
            "godel-type",
            "--m2",
            &m2s,
            "--omega",
            &omegas,
            "--at",
            "0,0,0,0",
            "--dir",
            "0,1,0",
            "--samples",
            "20001",
        ];
        let r = rows(&args);
        let widest = r.iter().fold(0.0_f64, |m, row| m.max(row[2]));
        assert!(
            (widest - rho_c).abs() < 1e-5,
            "m² = {m2}: {widest} vs ρ_c = {rho_c}"
        );
        // One loop: back on the axis at the end.
        assert!(r.last().unwrap()[2] < 1e-8, "{:?}", r.last());
    }
}

/// In a causal member an in-plane ray from the axis escapes, and its integration fails far
/// out (mρ ≈ 14, where the metric's e^{mρ} terms cancel): the error says where and why, and
/// names `--method exact`, which follows the ray to the time limit.
#[test]
fn a_numeric_ray_lost_far_out_says_why_and_what_follows_it() {
    let args = [
        "--metric",
        "godel-type",
        "--m2",
        "4.5",
        "--omega",
        "1",
        "--at",
        "0,0,0,0",
        "--dir",
        "1,0,0",
    ];
    let out = godel(&[&["geodesic"], &args[..]].concat());
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.starts_with("error: integration failed: step budget spent")
            && err.contains("m·R = ")
            && err.contains("--method exact"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    let r = rows(&[&args[..], &["--method", "exact"]].concat());
    let last = r.last().unwrap();
    // To the default limit |t| = 2√2·π/(√2 Ω) = 2π, far beyond where the integration failed.
    assert!(
        (last[1] - 2.0 * std::f64::consts::PI).abs() < 1e-9,
        "{last:?}"
    );
    assert!(4.5f64.sqrt() * last[2] > 30.0, "{last:?}");
}

#[test]
fn json_records_the_member() {
    let out = godel(&[
        "geodesic",
        "--metric",
        "godel-type",
        "--m2",
        "-0.5",
        "--omega",
        "0.75",
        "--at",
        "0,0.2,0,0",
        "--dir",
        "1,0,0",
        "--format",
        "json",
        "--samples",
        "3",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["metric"], "godel-type");
    assert_eq!(
        (doc["m2"].as_f64(), doc["omega"].as_f64()),
        (Some(-0.5), Some(0.75))
    );
    assert!(doc["a"].is_null());
    let out = godel(&[
        "geodesic", "--at", "0,0,0,0", "--dir", "1,0,0", "--format", "json",
    ]);
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(doc["m2"].is_null() && doc["omega"].is_null() && doc["a"] == 1.0);
}

#[test]
fn bad_family_flags_exit_2_naming_the_flag() {
    let family = ["--metric", "godel-type"];
    let cases: &[(&[&str], &str)] = &[
        (&[&family[..], &["--omega", "1"]].concat(), "--m2"),
        (&[&family[..], &["--m2", "1"]].concat(), "--omega"),
        (
            &[&family[..], &["--m2", "1", "--omega", "1", "--a", "1"]].concat(),
            "--a",
        ),
        (
            &[&family[..], &["--m2", "1", "--omega", "0"]].concat(),
            "--omega",
        ),
        (
            &[&family[..], &["--m2", "1", "--omega", "-1"]].concat(),
            "--omega",
        ),
        (
            &[&family[..], &["--m2", "1", "--omega", "NaN"]].concat(),
            "--omega",
        ),
        (
            &[&family[..], &["--m2", "1", "--omega", "1e300"]].concat(),
            "--omega",
        ),
        (
            &[&family[..], &["--m2", "NaN", "--omega", "1"]].concat(),
            "--m2",
        ),
        (
            &[&family[..], &["--m2", "inf", "--omega", "1"]].concat(),
            "--m2",
        ),
        (
            &[&family[..], &["--m2", "-101", "--omega", "1"]].concat(),
            "--m2",
        ),
        (&["--m2", "1"], "--m2"),
        (&["--omega", "1"], "--omega"),
        (&["--metric", "minkowski", "--m2", "1"], "--m2"),
        (&["--metric", "minkowski", "--a", "1"], "--a"),
    ];
    for (extra, flag) in cases {
        let args = [
            &["geodesic", "--at", "0,0,0,0", "--dir", "1,0,0"][..],
            extra,
        ]
        .concat();
        let out = godel(&args);
        assert_usage(&out, flag);
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    // Starts beyond the bounds of scenes: mρ > 30 for m² > 0; for m² = −1, Ω = 1/2 beyond
    // π/μ − ρ_c = π/2.
    for (m2, omega, r) in [("4", "1", "15.01"), ("-1", "0.5", "1.58")] {
        let at = format!("0,{r},0,0");
        let args = [
            "geodesic",
            "--metric",
            "godel-type",
            "--m2",
            m2,
            "--omega",
            omega,
            "--at",
            &at,
            "--dir",
            "1,0,0",
        ];
        let out = godel(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with("error: --at: R = "), "{args:?}: {err}");
    }
    let ok = rows(&[
        "--metric",
        "godel-type",
        "--m2",
        "-1",
        "--omega",
        "0.5",
        "--at",
        "0,1.57,0,0",
        "--dir",
        "1,0,0",
        "--samples",
        "2",
    ]);
    assert_eq!(ok.len(), 2);
}

/// Runs `godel plot geodesics` with `args` into `name` in `dir`; returns the SVG text.
fn plot(dir: &std::path::Path, name: &str, args: &[&str]) -> String {
    let path = dir.join(name);
    let out = godel(
        &[
            &["plot", "geodesics"],
            args,
            &["-o", path.to_str().unwrap()],
        ]
        .concat(),
    );
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    let svg = std::fs::read_to_string(&path).unwrap();
    resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).expect("valid SVG");
    svg
}

/// The radii (in the data layer's units) of the circles ρ = ρ_c in `svg`, in order.
fn critical_circles(svg: &str) -> Vec<f64> {
    svg.split("<circle")
        .skip(1)
        .filter(|c| c.contains(r#"id="critical-radius""#))
        .map(|c| {
            let r = c.split(" r=\"").nth(1).unwrap().split('"').next().unwrap();
            r.parse().unwrap()
        })
        .collect()
}

/// The points of every polyline in the data layers (units of 1/Ω).
fn polylines(svg: &str) -> Vec<Vec<(f64, f64)>> {
    svg.split("<polyline")
        .skip(1)
        .map(|pl| {
            let points = pl
                .split("points=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            points
                .split(' ')
                .map(|pt| {
                    let (x, y) = pt.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect()
}

#[test]
fn a_member_is_drawn_with_its_critical_circle_and_rays_turning_there() {
    let dir = tempfile::tempdir().unwrap();
    // m² = Ω² at Ω = 0.5: ρ_c·Ω = 2 atanh(1/2) = 1.0986; plot units are 1/Ω.
    let svg = plot(
        dir.path(),
        "one.svg",
        &[
            "--metric",
            "godel-type",
            "--m2",
            "0.25",
            "--omega",
            "0.5",
            "--rays",
            "6",
        ],
    );
    let expected = critical_radius(0.25, 0.5) * 0.5;
    let circles = critical_circles(&svg);
    assert_eq!(circles.len(), 1);
    assert!(
        (circles[0] - expected).abs() < 1e-4,
        "{circles:?} vs {expected}"
    );
    let rays = polylines(&svg);
    assert_eq!(rays.len(), 6);
    for ray in &rays {
        let widest = ray.iter().fold(0.0_f64, |m, (x, y)| m.max(x.hypot(*y)));
        assert!((widest - expected).abs() < 2e-3, "{widest} vs {expected}");
        let (x, y) = *ray.last().unwrap();
        assert!(
            x.hypot(y) < 1e-3,
            "the ray ends at ({x}, {y}), not at the origin"
        );
    }
    assert!(svg.contains("ρ = ρ_c, where the rays turn"));
    assert!(svg.contains("closed timelike curves"));
    // m² = 0: ρ_c = 1/Ω. m² = −Ω² (μ = Ω): ρ_c·Ω = 2 atan(1/2).
    for (m2, expected) in [("0", 1.0), ("-1", 2.0 * 0.5_f64.atan())] {
        let svg = plot(
            dir.path(),
            "x.svg",
            &["--metric", "godel-type", "--m2", m2, "--omega", "1"],
        );
        let circles = critical_circles(&svg);
        assert!(
            circles.len() == 1 && (circles[0] - expected).abs() < 1e-4,
            "{m2}: {circles:?}"
        );
    }
}

#[test]
fn a_causal_member_has_no_critical_circle_and_its_rays_leave_the_frame() {
    let dir = tempfile::tempdir().unwrap();
    for m2 in ["4", "4.5", "30"] {
        let svg = plot(
            dir.path(),
            "c.svg",
            &["--metric", "godel-type", "--m2", m2, "--rays", "4"],
        );
        assert!(critical_circles(&svg).is_empty(), "{m2}");
        assert!(!svg.contains("closed timelike curves (ρ > ρ_c)"), "{m2}");
        // The frame shows [−2, 2]² (units of 1/Ω): each ray ends beyond its corner, unless
        // stopped at mρ = 12 (m² = 30: Ωρ = 12/√30 = 2.19 < 2√2, said in the caption).
        let m = m2.parse::<f64>().unwrap().sqrt();
        let end = (2.0 * 2f64.sqrt()).min(12.0 / m);
        for ray in polylines(&svg) {
            let (x, y) = *ray.last().unwrap();
            assert!(x.hypot(y) > end * 0.999, "{m2}: the ray ends at ({x}, {y})");
        }
        assert_eq!(svg.contains("drawn to mρ = 12"), m2 == "30", "{m2}");
    }
}

#[test]
fn members_side_by_side_have_their_own_circles_and_are_reproducible() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["--members", "0,2,4.5", "--omega", "0.5", "--rays", "8"];
    let svg = plot(dir.path(), "a.svg", &args);
    // Units of 1/Ω: ρ_c·Ω = 1 (m² = 0), 2 asinh(1)/√2 (Gödel: ρ_c = 2a asinh 1, a = 1/(√2 Ω)).
    let circles = critical_circles(&svg);
    assert_eq!(circles.len(), 2, "{circles:?}");
    assert!((circles[0] - 1.0).abs() < 1e-4, "{circles:?}");
    assert!(
        (circles[1] - 2.0 * 1f64.asinh() / 2f64.sqrt()).abs() < 1e-4,
        "{circles:?}"
    );
    assert_eq!(polylines(&svg).len(), 24);
    for label in [
        "m² = 0 (Som–Raychaudhuri)",
        "m² = 2Ω² (Gödel)",
        "m² = 4.5Ω² (causal)",
    ] {
        assert!(svg.contains(label), "no label {label}");
    }
    // Each panel clips to its own frame.
    for i in 0..3 {
        assert!(
            svg.contains(&format!(r#"clip-path="url(#frame-{i})""#)),
            "{i}"
        );
    }
    let again = plot(dir.path(), "b.svg", &args);
    assert!(svg == again, "a second run differs");
    // PNG too.
    let path = dir.path().join("a.png");
    let out = godel(&[
        "plot",
        "geodesics",
        "--members",
        "0,2,4.5",
        "-o",
        path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let first = std::fs::read(&path).unwrap();
    let out = godel(&[
        "plot",
        "geodesics",
        "--members",
        "0,2,4.5",
        "-o",
        path.to_str().unwrap(),
    ]);
    assert!(out.status.success() && std::fs::read(&path).unwrap() == first);
}

#[test]
fn bad_plot_flags_exit_2_naming_the_flag_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("g.svg");
    let s = svg.to_str().unwrap();
    let family = ["--metric", "godel-type"];
    let cases: &[(&[&str], &str)] = &[
        (&family, "--m2"),
        (&[&family[..], &["--m2", "1", "--a", "1"]].concat(), "--a"),
        (
            &[&family[..], &["--m2", "1", "--tilted", "2"]].concat(),
            "--tilted",
        ),
        (&[&family[..], &["--m2", "NaN"]].concat(), "--m2"),
        (&[&family[..], &["--m2", "101"]].concat(), "--m2"),
        (
            &[&family[..], &["--m2", "1", "--omega", "0"]].concat(),
            "--omega",
        ),
        (&["--members", "0,2,4.5,6"], "--members"),
        (&["--members", "0,x"], "--members"),
        (&["--members", "0,inf"], "--members"),
        (&["--members", "200"], "--members"),
        (&["--members", ""], "--members"),
        (&["--members", "1", "--m2", "1"], "--m2"),
        (&["--members", "1", "--omega", "-2"], "--omega"),
        (&["--metric", "godel", "--members", "1"], "--members"),
        (&["--m2", "1"], "--m2"),
        (&["--omega", "1"], "--omega"),
    ];
    for (extra, flag) in cases {
        let args = [&["plot", "geodesics"][..], extra, &["-o", s]].concat();
        let out = godel(&args);
        assert_usage(&out, flag);
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn render_takes_a_member_for_the_scene_and_names_the_flag_at_fault() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().to_str().unwrap();
    let tiny = [
        "--width",
        "22",
        "--height",
        "4",
        "--samples",
        "1",
        "-q",
        "-o",
        out_dir,
    ];
    let member = ["--metric", "godel-type", "--m2", "0.5", "--omega", "0.7"];
    let out = godel(&[&["render"][..], &member, &tiny].concat());
    assert!(out.status.success(), "{}", stderr(&out));
    // The data file embeds the scene as rendered: the member, without the scene's a.
    let exr = dir.path().join("reference.exr");
    let data = datafile::DataFile::read(&exr).unwrap();
    let text = &data.header.scene_text;
    assert!(
        text.contains("godel-type") && text.contains("m2 = 0.5"),
        "{text}"
    );
    assert!(!text.contains("a = 1.0"), "{text}");
    let cases: &[(&[&str], &str)] = &[
        (&["--m2", "0.5"], "error: --m2: spacetime.m2: "),
        (
            &["--metric", "godel-type", "--m2", "0.5"],
            "error: --metric: spacetime.omega: ",
        ),
        (
            &[&member[..], &["--a", "1"]].concat(),
            "error: --a: spacetime.a: ",
        ),
        (
            &["--metric", "godel-type", "--m2", "500", "--omega", "1"],
            "error: --m2: ",
        ),
    ];
    for (extra, start) in cases {
        let out = godel(&[&["render"][..], extra, &tiny].concat());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.starts_with(start), "{extra:?}: {err}");
    }
}
