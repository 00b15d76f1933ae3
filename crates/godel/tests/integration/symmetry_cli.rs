//! End-to-end tests of the symmetry commands: `geodesic --method exact` against the numeric
//! integrator, `connect` checked by integrating its rays numerically (forward from the
//! emission, and backward from the event along the printed viewing direction), and
//! `plot isometry` (each image of the ray closes on its own start, which lies on the field's
//! orbit of the origin).

use crate::common::godel;

/// The two samples (start and end) of `godel geodesic` as JSON from `at` along `dir`
/// (`extra` flags) until coordinate time `until`.
fn end_points(at: &str, dir: &str, extra: &[&str], until: &str) -> serde_json::Value {
    let base = [
        "geodesic",
        "--format",
        "json",
        "--samples",
        "2",
        "--at",
        at,
        "--dir",
        dir,
    ];
    json(&[&base[..], extra, &["--until-time", until]].concat())
}

fn json(args: &[&str]) -> serde_json::Value {
    let o = godel(args);
    assert!(
        o.status.success(),
        "godel {args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("valid JSON")
}

fn num(v: &serde_json::Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

/// The (t, x, y, z) of every sample of a `geodesic --format json` document.
fn samples(doc: &serde_json::Value) -> Vec<[f64; 4]> {
    doc["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| [num(s, "t"), num(s, "x"), num(s, "y"), num(s, "z")])
        .collect()
}

#[test]
fn exact_geodesics_follow_the_numeric_integrator() {
    let cases: &[&[&str]] = &[
        &["--at", "0,0,0,0", "--dir", "1,0,0"],
        &["--at", "0.5,0.7,1.1,-0.2", "--dir", "0.3,-1,0.4"],
        &["--at", "0,2.5,0.3,0", "--dir", "-1,0.2,0.1"], // beyond the origin's horizon
        &["--at", "1,1.2,0,0", "--dir", "0,1,0", "--past"],
        &["--at", "0,0.4,2,0", "--dir", "1,1,0", "--speed", "0.6"],
        &["--at", "0,1,0,0", "--dir", "0,1,1", "--until-time", "7.5"],
        &["--at", "0,0,0,0", "--dir", "0,0,1"], // along the axis: stops on time
        &["--metric", "minkowski", "--at", "0,1,0,0", "--dir", "1,1,0"],
    ];
    for case in cases {
        let mut base = vec!["geodesic", "--format", "json", "--samples", "40"];
        base.extend_from_slice(case);
        let numeric = json(&base);
        base.extend_from_slice(&["--method", "exact"]);
        let exact = json(&base);
        assert_eq!(exact["method"], "exact");
        assert_eq!(exact["stop"], numeric["stop"], "{case:?}");
        let (a, b) = (samples(&numeric), samples(&exact));
        assert_eq!(a.len(), b.len());
        let worst = a
            .iter()
            .zip(&b)
            .flat_map(|(p, q)| p.iter().zip(q).map(|(u, v)| (u - v).abs()))
            .fold(0.0_f64, f64::max);
        assert!(
            worst < 1e-8,
            "{case:?}: exact vs numeric differ by {worst:e}"
        );
        // The closed form conserves the constants to rounding.
        let drift = num(&exact["drift"], "max");
        assert!(drift < 1e-12, "{case:?}: exact drift {drift:e}");
    }
}

/// Cylindrical "T,R,PHI,Z" of a JSON event {t, x, y, z}.
fn cylindrical(e: &serde_json::Value) -> String {
    let (x, y) = (num(e, "x"), num(e, "y"));
    format!(
        "{},{},{},{}",
        num(e, "t"),
        x.hypot(y),
        y.atan2(x),
        num(e, "z")
    )
}

fn list(v: &serde_json::Value) -> String {
    let a: Vec<String> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_f64().unwrap().to_string())
        .collect();
    a.join(",")
}

#[test]
fn connecting_rays_land_on_the_event_and_point_back_at_the_source() {
    // Receiving event and source position (cylindrical); a = 1.
    let (event, source): ([f64; 4], [f64; 3]) = ([0.3, 0.4, 2.0, 0.1], [1.1, -0.6, 0.35]);
    let from = format!("{},{},{},{}", event[0], event[1], event[2], event[3]);
    let to = format!("{},{},{}", source[0], source[1], source[2]);
    let doc = json(&[
        "connect",
        "--from",
        &from,
        "--to-source",
        &to,
        "--windings",
        "1",
        "--format",
        "json",
    ]);
    assert_eq!(doc["within_horizon"], true);
    let rays = doc["rays"].as_array().unwrap();
    assert!(
        rays.len() >= 4,
        "at least two rays per winding: {}",
        rays.len()
    );
    let ev = [
        event[0],
        event[1] * event[2].cos(),
        event[1] * event[2].sin(),
        event[3],
    ];
    let src = [
        source[0] * source[1].cos(),
        source[0] * source[1].sin(),
        source[2],
    ];
    let mut previous = f64::INFINITY;
    for ray in rays {
        let travel = num(ray, "travel_time");
        let t_emit = num(&ray["emission"], "t");
        assert!(t_emit < previous, "latest emission first");
        previous = t_emit;
        assert!(num(ray, "miss") < 1e-10);
        let e = &ray["emission"];
        let on_source = [
            num(e, "x") - src[0],
            num(e, "y") - src[1],
            num(e, "z") - src[2],
        ];
        assert!(on_source.iter().all(|d| d.abs() < 1e-10), "{on_source:?}");
        // Forward from the emission along the departure direction, numerically.
        let travel = travel.to_string();
        let fwd = end_points(&cylindrical(e), &list(&ray["departure"]), &[], &travel);
        let end = *samples(&fwd).last().unwrap();
        let miss = end
            .iter()
            .zip(&ev)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        assert!(miss < 1e-7, "forward ray misses the event by {miss:e}");
        // Backward from the event along the viewing direction: lands on the source.
        let back = end_points(&from, &list(&ray["look"]), &["--past"], &travel);
        let end = *samples(&back).last().unwrap();
        let miss = [end[1] - src[0], end[2] - src[1], end[3] - src[2]]
            .iter()
            .fold(0.0_f64, |m, d| m.max(d.abs()));
        assert!(miss < 1e-7, "backward ray misses the source by {miss:e}");
        assert!((end[0] - t_emit).abs() < 1e-7);
    }
}

#[test]
fn connect_counts_and_the_horizon() {
    // In the source's plane (equal z): exactly two rays per winding (docs/physics.md, "Light
    // rays between a source and an event").
    for w in [0, 2] {
        let doc = json(&[
            "connect",
            "--from",
            "0,0.5,0,0",
            "--to-source",
            "0.8,1,0",
            "--windings",
            &w.to_string(),
            "--format",
            "json",
        ]);
        assert_eq!(doc["rays"].as_array().unwrap().len(), 2 * (w + 1));
    }
    // Beyond the source's horizon: no ray, a note, success.
    let o = godel(&["connect", "--from", "0,0,0,0", "--to-source", "2.2,0,0"]);
    assert!(o.status.success());
    let out = String::from_utf8(o.stdout).unwrap();
    assert_eq!(out.lines().count(), 1, "header only: {out}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("beyond its horizon"));
    // Bad input names the flag and exits 2.
    for (args, flag) in [
        (vec!["--from", "0,0,0", "--to-source", "1,0,0"], "--from"),
        (
            vec!["--from", "0,0,0,0", "--to-source", "1,x,0"],
            "--to-source",
        ),
        (
            vec!["--from", "0,0,0,0", "--to-source", "-1,0,0"],
            "--to-source",
        ),
        (
            vec!["--from", "0,0,0,0", "--to-source", "1,0,0", "--a", "-1"],
            "--a",
        ),
    ] {
        let mut full = vec!["connect"];
        full.extend(args);
        let o = godel(&full);
        assert_eq!(o.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&o.stderr).contains(flag));
    }
}

/// Issue 36: with the source at the event's place, `connect` printed a ray of travel time 0
/// in an arbitrary direction. It is refused (exit 2, naming both flags, nothing printed),
/// as is an event elsewhere on the source's axis,
/// at any time of the event and wherever the two are given, in either coordinate form of the
/// same place; a source a little away still gets its rays.
#[test]
fn connect_refuses_the_source_at_the_event() {
    for (from, source) in [
        ("0,0,0,0", "0,0,0"),
        ("-3.5,0.7,1.2,0.4", "0.7,1.2,0.4"),
        ("2,1.1,-0.3,0", "1.1,5.983185307179586,0"),
        ("1,0,0,0.2", "0,2.5,0.2"),
    ] {
        let o = godel(&["connect", "--from", from, "--to-source", source]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{from} {source}: {err}");
        assert!(
            err.starts_with("error: --from/--to-source: the source is at the event's place"),
            "{err}"
        );
        assert!(o.stdout.is_empty());
    }
    // On the source's axis elsewhere: cones of rays, every azimuth at once (it printed a ray
    // of travel time 0 that missed the event by 1).
    let o = godel(&["connect", "--from", "0,0,0,1", "--to-source", "0,0,0"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("the event is on the source's axis"), "{err}");
    let doc = json(&[
        "connect",
        "--from",
        "0,0.7,1.2,0.4",
        "--to-source",
        "0.71,1.2,0.4",
        "--format",
        "json",
    ]);
    let rays = doc["rays"].as_array().unwrap();
    assert!(!rays.is_empty());
    assert!(rays.iter().all(|r| num(r, "travel_time") > 0.0));
}

/// The points of each `<g id="image-k" data-s="S">` polyline of the figure.
fn images(svg: &str) -> Vec<(f64, Vec<(f64, f64)>)> {
    svg.split("<g id=\"image-")
        .skip(1)
        .map(|chunk| {
            let s: f64 = chunk
                .split("data-s=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            let pts = chunk
                .split("points=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            let points = pts
                .split(' ')
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect();
            (s, points)
        })
        .collect()
}

#[test]
fn isometry_plot_moves_the_ray_along_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let svg_path = dir.path().join("iso.svg");
    let plot = |flags: &[&str], out: &std::path::Path| {
        godel(&[&["plot", "isometry", "-o", out.to_str().unwrap()], flags].concat())
    };
    let o = plot(&["--images", "5"], &svg_path);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(svg.contains("id=\"original\"") && svg.contains("id=\"field\""));
    let imgs = images(&svg);
    assert_eq!(imgs.len(), 5);
    for (s, pts) in &imgs {
        // K_x moves the origin along the x axis to 2a sinh(s/2a) (a = 1), without rotation.
        let (x0, y0) = pts[0];
        assert!(
            (x0 - 2.0 * (s / 2.0).sinh()).abs() < 2e-4 && y0.abs() < 2e-4,
            "{s}: {x0},{y0}"
        );
        // The image is again a loop that returns to its own start.
        let (x1, y1) = *pts.last().unwrap();
        assert!(
            (x1 - x0).abs() < 1e-3 && (y1 - y0).abs() < 1e-3,
            "{s}: open loop"
        );
    }
    // ∂φ rotates about the origin: every image starts there.
    let png_path = dir.path().join("iso.png");
    let o = plot(&["--field", "phi"], &svg_path);
    assert!(o.status.success());
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    for (_, pts) in images(&svg) {
        assert!(pts[0].0.abs() < 1e-4 && pts[0].1.abs() < 1e-4);
    }
    let o = plot(&[], &png_path);
    assert!(o.status.success());
    assert!(std::fs::read(&png_path).unwrap().starts_with(b"\x89PNG"));
    let o = plot(&["--images", "0"], &svg_path);
    assert_eq!(o.status.code(), Some(2));
}
