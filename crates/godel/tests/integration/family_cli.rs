//! End-to-end tests of the Gödel-type family (docs/physics.md, "The Gödel-type family") on
//! the command line: `godel geodesic --metric godel-type` against Gödel's universe (the
//! member m² = 1/a², Ω = 1/(√2 a), carried through r = 2a sinh(ρ/2a)) and against the
//! turning radius ρ_c of in-plane rays from the axis; the refusals of --m2, --omega and --a,
//! each naming its flag.

use std::f64::consts::SQRT_2;

use crate::common::{godel, stderr};

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
        (
            &[
                &family[..],
                &["--m2", "1", "--omega", "1", "--method", "exact"],
            ]
            .concat(),
            "--method",
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
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.starts_with(&format!("error: {flag}: ")),
            "{args:?}: {err}"
        );
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
