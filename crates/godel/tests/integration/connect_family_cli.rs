//! `godel connect --metric godel-type --m2 M2 --omega OMEGA` (issue 34): the Gödel member's
//! rays are `godel connect --a a`'s through r = 2a sinh(ρ/2a); a member's JSON records it,
//! its rays land and count as the geometry dictates (two per winding in the source's plane,
//! one escaping ray for causal members); beyond ρ_c there is none, with a note; bad flag
//! combinations exit 2 naming the flag.

use crate::common::{assert_usage, godel, stderr};

fn json(args: &[&str]) -> serde_json::Value {
    let o = godel(args);
    assert!(o.status.success(), "godel {args:?}: {}", stderr(&o));
    serde_json::from_slice(&o.stdout).expect("valid JSON")
}

fn num(v: &serde_json::Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

fn vector(v: &serde_json::Value, key: &str) -> Vec<f64> {
    v[key]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_f64().unwrap())
        .collect()
}

/// `godel connect` in JSON from the event (T, R, PHI, Z) to the source (R, PHI, Z).
fn connect(metric: &[&str], from: [f64; 4], source: [f64; 3], windings: &str) -> serde_json::Value {
    let from = format!("{},{},{},{}", from[0], from[1], from[2], from[3]);
    let to = format!("{},{},{}", source[0], source[1], source[2]);
    let args = [
        &["connect", "--from", &from, "--to-source", &to][..],
        metric,
        &["--windings", windings, "--format", "json"],
    ]
    .concat();
    json(&args)
}

/// Gödel's r of the Gödel member's proper radius ρ.
fn godel_r(a: f64, rho: f64) -> f64 {
    2.0 * a * (rho / (2.0 * a)).sinh()
}

/// Source and event on the x axis (φ = 0 or π), where the member's static frame and Gödel's
/// have the same axes (the chart only stretches x and y there), so directions compare too.
#[test]
fn the_godel_member_connects_as_godel_through_the_proper_radius() {
    let a = 0.8;
    let (m2, omega) = (1.0 / (a * a), 1.0 / (2f64.sqrt() * a));
    let (m2s, omegas) = (m2.to_string(), omega.to_string());
    let member = ["--metric", "godel-type", "--m2", &m2s, "--omega", &omegas];
    let a_s = a.to_string();
    let mut compared = 0;
    for (from, source) in [
        ([0.5, 0.9, 0.0, 0.7], [0.3, 0.0, -0.2]),
        ([-1.0, 0.4, std::f64::consts::PI, -0.5], [0.6, 0.0, 0.1]),
        ([2.0, 1.1, 0.0, 0.0], [0.0, 0.0, 0.0]),
    ] {
        let mine = connect(&member, from, source, "2");
        let from_g = [from[0], godel_r(a, from[1]), from[2], from[3]];
        let source_g = [godel_r(a, source[0]), source[1], source[2]];
        let theirs = connect(&["--a", &a_s], from_g, source_g, "2");
        assert_eq!(mine["metric"], "godel-type");
        assert_eq!((num(&mine, "m2"), num(&mine, "omega")), (m2, omega));
        assert_eq!(mine["within_horizon"], true);
        let (r1, r2) = (
            mine["rays"].as_array().unwrap(),
            theirs["rays"].as_array().unwrap(),
        );
        assert_eq!(r1.len(), r2.len(), "{from:?} {source:?}");
        assert!(r1.len() >= 6);
        for (p, q) in r1.iter().zip(r2) {
            assert_eq!((&p["winding"], &p["branch"]), (&q["winding"], &q["branch"]));
            for key in ["travel_time", "lambda"] {
                assert!(
                    (num(p, key) - num(q, key)).abs() < 1e-9,
                    "{key}: {p} vs {q}"
                );
            }
            let (e1, e2) = (&p["emission"], &q["emission"]);
            assert!((num(e1, "t") - num(e2, "t")).abs() < 1e-9);
            for key in ["departure", "look"] {
                let (u, v) = (vector(p, key), vector(q, key));
                let d = u
                    .iter()
                    .zip(&v)
                    .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
                assert!(d < 1e-8, "{key}: {u:?} vs {v:?}");
            }
            let (d1, d2) = (num(p, "area_distance"), num(q, "area_distance"));
            assert!((d1 - d2).abs() < 1e-6 * d2, "D {d1} vs Gödel's {d2}");
            assert!(num(p, "miss") < 1e-9 && (num(p, "g") - 1.0).abs() < 1e-9);
            compared += 1;
        }
    }
    eprintln!("{compared} rays of the Gödel member equal Gödel's");
}

#[test]
fn members_rays_land_and_count_as_the_geometry_dictates() {
    // (m², Ω, rays to an event in the source's plane with windings ≤ 2)
    for (m2, omega, in_plane) in [(0.0, 1.0, 6), (-0.5, 0.8, 6), (3.0, 1.0, 6), (6.0, 1.0, 1)] {
        let (m2s, omegas) = (m2.to_string(), omega.to_string());
        let member = ["--metric", "godel-type", "--m2", &m2s, "--omega", &omegas];
        let source = [0.4, 1.0, 0.2];
        for (from, want) in [
            ([1.0, 0.7, 0.5, 0.2], Some(in_plane)),
            ([1.0, 0.6, -0.4, 1.5], None),
        ] {
            let doc = connect(&member, from, source, "2");
            assert_eq!((num(&doc, "m2"), num(&doc, "omega")), (m2, omega));
            let rays = doc["rays"].as_array().unwrap();
            if let Some(want) = want {
                assert_eq!(rays.len(), want, "m² = {m2}: {doc}");
            }
            assert!(!rays.is_empty(), "m² = {m2}");
            for r in rays {
                assert!(num(r, "miss") < 1e-9, "m² = {m2}: {r}");
                assert!((num(r, "g") - 1.0).abs() < 1e-9 && num(r, "area_distance") > 0.0);
                assert!(num(r, "travel_time") > 0.0);
            }
            // ρ_c is recorded as the reach, none for the causal member.
            assert_eq!(doc["reach"].is_null(), m2 >= 4.0 * omega * omega);
        }
    }
}

#[test]
fn no_ray_beyond_the_critical_radius_and_a_note_says_why() {
    // m² = Ω² = 1: ρ_c = 2 atanh(1/2) ≈ 1.0986 from the source on the axis.
    let args = [
        "connect",
        "--metric",
        "godel-type",
        "--m2",
        "1",
        "--omega",
        "1",
        "--from",
        "0,1.2,0,0.3",
        "--to-source",
        "0,0,0",
    ];
    let o = godel(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(out.lines().count(), 1, "only the header: {out}");
    assert!(
        stderr(&o).contains("beyond ρ_c = 1.098612"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn bad_connect_flags_exit_2_naming_the_flag() {
    let family = ["--metric", "godel-type", "--m2", "1", "--omega", "1"];
    let cases: &[(&[&str], &str)] = &[
        (&["--metric", "godel-type", "--omega", "1"], "--m2"),
        (&["--metric", "godel-type", "--m2", "1"], "--omega"),
        (&[&family[..], &["--a", "1"]].concat(), "--a"),
        (
            &["--metric", "godel-type", "--m2", "1", "--omega", "0"],
            "--omega",
        ),
        (
            &["--metric", "godel-type", "--m2", "-101", "--omega", "1"],
            "--m2",
        ),
        (&["--m2", "1"], "--m2"),
        (&["--omega", "1"], "--omega"),
        (&["--metric", "minkowski"], "--metric"),
    ];
    for (extra, flag) in cases {
        let args = [
            &["connect", "--from", "0,0.5,0,0", "--to-source", "0,0,0"][..],
            extra,
        ]
        .concat();
        let out = godel(&args);
        assert_usage(&out, flag);
        assert!(out.stdout.is_empty());
    }
    // Positions beyond the bound on proper radii (m² = −1, Ω = 1: π − ρ_c ≈ 2.21), and an
    // event on the source's axis (cones of rays, not single rays).
    let sphere = ["--metric", "godel-type", "--m2", "-1", "--omega", "1"];
    for (from, source, flag) in [
        ("0,2.5,0,0", "0,0,0", "--from"),
        ("0,0.5,0,0", "2.5,0,0", "--to-source"),
        ("1,0,0,2", "0,0,0", "--from/--to-source"),
        ("1,0.3,0.2,0.4", "0.3,0.2,0.4", "--from/--to-source"),
    ] {
        let args = [
            &["connect", "--from", from, "--to-source", source][..],
            &sphere,
        ]
        .concat();
        let out = godel(&args);
        assert_usage(&out, flag);
    }
}
