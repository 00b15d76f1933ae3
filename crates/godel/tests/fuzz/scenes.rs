//! Random valid-looking scene files (docs/guide/src/scenes.md; the schema of `scene`'s raw records),
//! always tiny: at most 8×4 pixels (a fisheye at most 6×6) and a few loops of a light ray
//! into the past. They aim where the tracer is weakest: an observer inside, on, or just
//! outside a sphere (local at rest, free fall from the observer's event, coordinate), planes
//! through the observer, balls that are huge, tiny, or beyond the horizon r = 2a, lights
//! inside balls, fast observers (up to 0.9999999), extreme scales of `a`, tolerances and
//! step budgets at their limits. Some fields are left out to test the defaults.

use crate::gen::{num, vec3, Gen};
use std::f64::consts::{PI, SQRT_2};
use std::fmt::Write;

/// Where things are placed: the observer's event and the scale a.
struct Frame {
    a: f64,
    godel: bool,
    t: f64,
    p: [f64; 3],
}

/// A random scene as TOML text.
pub fn scene(g: &mut Gen) -> String {
    let mut s = String::new();
    let godel = g.chance(0.85);
    let a = match g.index(10) {
        0..=3 => 1.0,
        4..=8 => g.log(0.01, 100.0),
        _ => g.pick(&[1e-4, 1e-3, 1e3, 1e4, 0.37]),
    };
    let name = g.pick(&["fuzz", "ball", "a-b_c", "Gödel", "x", "scene 1", "UPPER"]);
    writeln!(s, "name = \"{name}\"").unwrap();
    if godel {
        if a != 1.0 || g.chance(0.7) {
            writeln!(s, "[spacetime]\nmetric = \"godel\"\na = {}", num(a)).unwrap();
        }
    } else {
        writeln!(s, "[spacetime]\nmetric = \"minkowski\"").unwrap();
    }
    let f = observer(g, &mut s, a, godel);
    camera(g, &mut s);
    trace(g, &mut s, &f);
    let mut centres = Vec::new();
    for i in 0..g.pick(&[0, 1, 1, 1, 2, 2, 3, 4]) {
        object(g, &mut s, &f, i, &mut centres);
    }
    if godel && g.chance(0.3) {
        for _ in 0..g.pick(&[1, 1, 2]) {
            light(g, &mut s, &f, &centres);
        }
    }
    s
}

fn observer(g: &mut Gen, s: &mut String, a: f64, godel: bool) -> Frame {
    let t = match g.index(6) {
        0..=2 => 0.0,
        3 | 4 => g.range(-5.0, 5.0) * a,
        _ => g.pick(&[1e6, -1e9, 1e12, 123.456]),
    };
    let p = match g.index(6) {
        0..=2 => [0.0; 3],
        3 => {
            let r = g.log(1e-6, 4.0) * a;
            let phi = g.range(-PI, PI);
            [r * phi.cos(), r * phi.sin(), g.range(-1.0, 1.0) * a]
        }
        4 => [g.range(-1.0, 1.0) * a, g.range(-1.0, 1.0) * a, 0.0],
        _ => [0.0, 0.0, g.pick(&[1e-9, -3.0, 1e6])],
    };
    let f = Frame { a, godel, t, p };
    if g.chance(0.15) {
        return Frame {
            t: 0.0,
            p: [0.0; 3],
            ..f
        }; // no [observer]: the defaults
    }
    writeln!(s, "[observer]\ntime = {}", num(t)).unwrap();
    writeln!(s, "position = {}", position(g, p)).unwrap();
    if g.chance(0.6) {
        let any = g.unit();
        let speed = g.pick(&[0.0, 0.3, 0.7, 0.9, 0.999, 0.9999999, any]);
        let dir = if g.chance(0.1) {
            [1e-300, 0.0, 0.0]
        } else {
            g.direction()
        };
        writeln!(
            s,
            "velocity = {{ speed = {}, direction = {} }}",
            num(speed),
            vec3(dir)
        )
        .unwrap();
    }
    if g.chance(0.7) {
        let (forward, up) = orthonormal_pair(g);
        writeln!(s, "forward = {}\nup = {}", vec3(forward), vec3(up)).unwrap();
    }
    f
}

/// Two random orthogonal unit vectors (up made orthogonal to forward by Gram–Schmidt).
fn orthonormal_pair(g: &mut Gen) -> ([f64; 3], [f64; 3]) {
    if g.chance(0.3) {
        let axes = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [-1.0, 0.0, 0.0],
        ];
        let f = g.pick(&axes);
        let u = if f[2] == 0.0 {
            [0.0, 0.0, 1.0]
        } else {
            [1.0, 0.0, 0.0]
        };
        return (f, u);
    }
    let f = g.direction();
    loop {
        let v = g.direction();
        let d = v[0] * f[0] + v[1] * f[1] + v[2] * f[2];
        let u = [v[0] - d * f[0], v[1] - d * f[1], v[2] - d * f[2]];
        let n = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
        if n > 0.1 {
            return (f, u.map(|c| c / n));
        }
    }
}

/// A position, pseudo-Cartesian or cylindrical (half each), with zero components sometimes
/// left out.
fn position(g: &mut Gen, p: [f64; 3]) -> String {
    let z = if p[2] == 0.0 && g.chance(0.5) {
        String::new()
    } else {
        format!(", z = {}", num(p[2]))
    };
    if g.chance(0.5) {
        format!("{{ x = {}, y = {}{z} }}", num(p[0]), num(p[1]))
    } else {
        let r = p[0].hypot(p[1]);
        format!("{{ r = {}, phi = {}{z} }}", num(r), num(p[1].atan2(p[0])))
    }
}

fn camera(g: &mut Gen, s: &mut String) {
    let (w, h) = (g.int(1, 8), g.int(1, 4));
    let fov = |g: &mut Gen, max: f64| match g.index(8) {
        0 => max,
        1 => g.pick(&[1e-6, 0.01, max - 1e-9]),
        _ => g.range(0.0, max).max(1e-3),
    };
    match g.index(4) {
        0 => {
            let fov = fov(g, 179.999);
            writeln!(s, "[camera]\nkind = \"pinhole\"\nfov_deg = {}\nwidth = {w}\nheight = {h}", num(fov))
        }
        1 => {
            let (hf, vf) = (fov(g, 360.0), fov(g, 180.0));
            writeln!(s, "[camera]\nkind = \"panorama\"\nh_fov_deg = {}\nv_fov_deg = {}\nwidth = {w}\nheight = {h}", num(hf), num(vf))
        }
        2 => writeln!(s, "[camera]\nkind = \"sphere\"\nwidth = {w}\nheight = {h}"),
        _ => {
            let n = g.int(1, 6);
            let fov = if g.chance(0.3) {
                String::new()
            } else {
                format!("fov_deg = {}\n", num(fov(g, 360.0)))
            };
            writeln!(s, "[camera]\nkind = \"fisheye\"\n{fov}width = {n}\nheight = {n}")
        }
    }
    .unwrap();
}

fn trace(g: &mut Gen, s: &mut String, f: &Frame) {
    if g.chance(0.1) {
        return; // the defaults: numeric, 30 into the past (11 loops at a = 1)
    }
    writeln!(s, "[trace]").unwrap();
    let exact = if f.godel {
        g.chance(0.5)
    } else {
        g.chance(0.05)
    };
    writeln!(
        s,
        "method = \"{}\"",
        if exact { "exact" } else { "numeric" }
    )
    .unwrap();
    let max_past = if f.godel {
        // In loops of a light ray, the shortest taking 2πa(√2 − 1).
        let loops = if g.chance(0.95) {
            g.log(0.05, 6.0)
        } else {
            g.log(6.0, 30.0)
        };
        loops * 2.0 * PI * f.a * (SQRT_2 - 1.0)
    } else {
        g.log(0.1, 50.0) * f.a
    };
    writeln!(s, "max_past = {}", num(max_past)).unwrap();
    if g.chance(0.4) {
        let tol = if g.chance(0.3) {
            g.pick(&[1e-14, 1e-3])
        } else {
            g.log(1e-14, 1e-3)
        };
        writeln!(s, "tolerance = {}", num(tol)).unwrap();
    }
    if g.chance(0.2) {
        let any = g.int(1, 5000);
        writeln!(s, "max_steps = {}", g.pick(&[1, 2, 10, 100, 1000, any])).unwrap();
    }
}

/// A point at distance `d` from `c` in a random direction.
fn offset(g: &mut Gen, c: [f64; 3], d: f64) -> [f64; 3] {
    let u = g.direction();
    [c[0] + d * u[0], c[1] + d * u[1], c[2] + d * u[2]]
}

/// A centre for an object of (proper or coordinate) radius `radius` relative to the
/// observer: containing it, touching it, just outside, anywhere near, or beyond the horizon.
fn centre(g: &mut Gen, f: &Frame, radius: f64, local: bool) -> [f64; 3] {
    let on_axis = f.p[0] == 0.0 && f.p[1] == 0.0;
    // Coordinate distance from the axis at which a local ball around the axis touches it:
    // the proper radial distance from the axis is 2a·asinh(r/2a).
    let touch = if local && f.godel && on_axis {
        2.0 * f.a * (radius / (2.0 * f.a)).sinh()
    } else {
        radius
    };
    match g.index(9) {
        0 => f.p,
        1 => {
            let d = radius * g.range(0.0, 0.999);
            offset(g, f.p, d)
        }
        2 if on_axis => {
            let phi = g.range(-PI, PI);
            let k = g.pick(&[1.0, 1.0 - 1e-12, 1.0 + 1e-12, 1.0 + 1e-6]);
            [touch * k * phi.cos(), touch * k * phi.sin(), f.p[2]]
        }
        2 => offset(g, f.p, touch),
        3 => {
            // beyond the observer's horizon (on the axis: r > 2a)
            let r = f.a * g.range(2.0, 5.0);
            let phi = g.range(-PI, PI);
            [
                r * phi.cos(),
                r * phi.sin(),
                f.p[2] + g.range(-1.0, 1.0) * f.a,
            ]
        }
        _ => {
            let d = f.a * g.log(1e-3, 3.0);
            offset(g, f.p, d)
        }
    }
}

fn object(g: &mut Gen, s: &mut String, f: &Frame, i: usize, centres: &mut Vec<[f64; 3]>) {
    let name = if g.chance(0.1) {
        g.pick(&["Ünïcødé", "with space", "a.b", "[x]", "=", "#"])
            .to_string()
    } else {
        format!("o{i}")
    };
    writeln!(s, "[[object]]\nname = \"{name}\"").unwrap();
    // Free fall only where the worldline is cheap to build: its integration uses absolute
    // scales (steps of at most 0.25, a margin of 1 time unit), so at a ≪ 1 or a ≫ 1 one
    // falling ball costs up to 400,000 integrator steps (seconds, ~600 MB; BENCHMARKS.md,
    // "Fuzzing").
    let fall_ok = (0.05..=20.0).contains(&f.a);
    let kind = loop {
        let k = g.index(10);
        if fall_ok || !(4..=6).contains(&k) {
            break k;
        }
    };
    match kind {
        0..=3 => {
            // local sphere at rest
            let radius = local_radius(g, f);
            let c = centre(g, f, radius, true);
            centres.push(c);
            if g.chance(0.3) {
                writeln!(s, "frame = \"local\"").unwrap();
            }
            writeln!(s, "radius = {}", num(radius)).unwrap();
            writeln!(
                s,
                "motion = {{ kind = \"rest\", position = {} }}",
                position(g, c)
            )
            .unwrap();
        }
        4..=6 => {
            // local sphere in free fall, sometimes from the observer's own event
            let radius = local_radius(g, f);
            let (time, c) = if g.chance(0.3) {
                (f.t, f.p)
            } else {
                (f.t + g.range(-3.0, 1.0) * f.a, centre(g, f, radius, true))
            };
            centres.push(c);
            let any = g.unit();
            let speed = g.pick(&[0.0, 0.5, 0.7, 0.99, 0.999, any]);
            writeln!(s, "radius = {}", num(radius)).unwrap();
            writeln!(
                s,
                "motion = {{ kind = \"geodesic\", time = {}, position = {}, speed = {}, direction = {} }}",
                num(time),
                position(g, c),
                num(speed),
                vec3(g.direction())
            )
            .unwrap();
        }
        7 | 8 => {
            let radius = match g.index(5) {
                0 => g.pick(&[1e-9, 1e-6, 1e3 * f.a, 1e6 * f.a]),
                _ => f.a * g.log(1e-3, 10.0),
            };
            let c = centre(g, f, radius, false);
            centres.push(c);
            writeln!(
                s,
                "frame = \"coordinates\"\nshape = \"sphere\"\nradius = {}\ncenter = {}",
                num(radius),
                position(g, c)
            )
            .unwrap();
        }
        _ => {
            let height = match g.index(4) {
                0 => f.p[2],
                1 => f.p[2] + g.pick(&[1e-12, -1e-12, 1e-6]),
                _ => f.p[2] + g.range(-2.0, 2.0) * f.a,
            };
            writeln!(
                s,
                "frame = \"coordinates\"\nshape = \"plane\"\nheight = {}",
                num(height)
            )
            .unwrap();
            if g.chance(0.6) {
                writeln!(s, "extent = {}", num(f.a * g.log(1e-6, 1e3))).unwrap();
            }
        }
    }
    if g.chance(0.7) {
        let texture = match g.index(6) {
            0 => {
                let (r, c) = (g.int(1, 1000), g.int(1, 1000));
                let rows = g.pick(&[1, 2, 8, 63, r, 4294967295]);
                let cols = g.pick(&[1, 3, 16, c, 4294967295]);
                format!("{{ kind = \"checker\", rows = {rows}, cols = {cols} }}")
            }
            1 => "{ kind = \"checker\" }".to_string(),
            2 => "{ kind = \"gradient\" }".to_string(),
            3 => {
                let (r, gr, b) = (g.unit(), g.unit(), g.unit());
                let b = g.pick(&[0.0, 1.0, 1e30, b]);
                format!("{{ kind = \"uniform\", color = {} }}", vec3([r, gr, b]))
            }
            4 => "{ kind = \"image\", builtin = \"earth\" }".to_string(),
            _ => "{ kind = \"checker\", rows = 4 }".to_string(),
        };
        writeln!(s, "texture = {texture}").unwrap();
    }
    if g.chance(0.3) {
        let t = match g.index(4) {
            0 => g.pick(&[1e-300, 1e-3, 1.0, 1e300, 1e9]),
            _ => g.log(1.0, 1e6),
        };
        writeln!(s, "temperature = {}", num(t)).unwrap();
    }
}

/// A local sphere's proper radius: up to the largest allowed, 0.5a (sometimes just over).
fn local_radius(g: &mut Gen, f: &Frame) -> f64 {
    match g.index(10) {
        0 => 0.5 * f.a,
        1 => g.pick(&[1e-9, 1e-6, 0.5 * f.a * (1.0 + 1e-9)]),
        _ => f.a * g.log(1e-3, 0.5),
    }
}

fn light(g: &mut Gen, s: &mut String, f: &Frame, centres: &[[f64; 3]]) {
    let p = match g.index(4) {
        0 if !centres.is_empty() => g.pick(centres),
        1 => f.p,
        _ => centre(g, f, 0.1 * f.a, false),
    };
    writeln!(s, "[[light]]\nposition = {}", position(g, p)).unwrap();
    if g.chance(0.5) {
        writeln!(s, "color = {}", vec3([g.unit(), g.unit(), g.unit()])).unwrap();
    }
    if g.chance(0.7) {
        let any = g.log(1e-3, 1e3);
        writeln!(s, "power = {}", num(g.pick(&[0.0, 1.0, 12.0, any]))).unwrap();
    }
}
