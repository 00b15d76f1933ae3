//! The kernel tested in pieces (docs/physics.md, "The GPU kernel"): each group of the
//! kernel's functions, compiled with the `PROBE` entry point (`src/probe.glsl`), evaluated on
//! a few hundred seeded inputs with their edge cases, and held to its Rust twin in f64.
//!
//! Tolerances: the inputs are f32 (the twin gets the same f32 values, widened), so only the
//! kernel's own rounding counts: f32 rounds each operation to 2⁻²⁴ relative (half of
//! [`ULP`]), and a function of a few dozen operations ends within a few ULP of the size of
//! the terms it adds. Each tolerance is K·ULP times that size, the size written out per
//! function (where cancellation or an ill-conditioned step makes it larger, it says so), with
//! K a small constant; the worst ratio of error to tolerance is printed per function.

use crate::common;
use gpu::input::{KernelInput, Uniforms};
use gpu::probe::{Args, Function, Prober, Results};
use render::circle::RayCircle;
use render::reject::{static_distance, Rejection, StaticBall};
use render::target::Target;
use render::worldline::Worldline;
use scene::{Camera, Motion, Scene};
use spacetime::isometry::disc;
use spacetime::transport::transport_from_origin;
use spacetime::{
    boost, gram_schmidt_static_frame, shadow_rays_from_axis, source_area_distance_sq, Branch,
    Event, FourVector, Godel, Isometry, LocalVelocity, Metric, Minkowski, OriginGeodesic,
    ShadowRay, Spacetime,
};
use std::f64::consts::{PI, SQRT_2};

/// f32's machine epsilon, 2⁻²³: twice the largest relative rounding of one operation.
const ULP: f64 = f32::EPSILON as f64;
/// The kernel's INF (a bound that is not one).
const INF: f32 = 3.0e38;

/// Seeded random numbers (fastrand's generator): the same inputs on every run.
struct Rng(fastrand::Rng);

impl Rng {
    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.0.f64()
    }
    /// A random unit vector.
    fn unit(&mut self) -> [f64; 3] {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(-PI, PI);
        let s = (1.0 - z * z).sqrt();
        [s * phi.cos(), s * phi.sin(), z]
    }
}

/// `v` as the kernel reads it: rounded to f32, widened back (the twin's input).
fn f(v: f64) -> f64 {
    f64::from(v as f32)
}
fn f4(v: [f64; 4]) -> [f64; 4] {
    v.map(f)
}
fn texel(v: [f64; 4]) -> [f32; 4] {
    v.map(|c| c as f32)
}
fn event(v: [f64; 4]) -> Event {
    Event::new(v[0], v[1], v[2], v[3])
}
fn vector(v: [f64; 4]) -> FourVector {
    FourVector::new(v[0], v[1], v[2], v[3])
}

/// The worst error of one function's outputs, as a fraction of their tolerances.
struct Compare {
    name: &'static str,
    worst: f64,
    at: String,
    count: usize,
}

impl Compare {
    fn new(name: &'static str) -> Compare {
        Compare {
            name,
            worst: 0.0,
            at: String::new(),
            count: 0,
        }
    }

    /// Notes the kernel's `got` against the twin's `want` within `tol` (NaN: never within).
    fn value(&mut self, got: f32, want: f64, tol: f64, what: impl Fn() -> String) {
        self.count += 1;
        let err = (f64::from(got) - want).abs();
        let ratio = if err == 0.0 {
            0.0
        } else if (err / tol).is_nan() {
            f64::INFINITY
        } else {
            err / tol
        };
        if ratio > self.worst || self.at.is_empty() {
            self.worst = self.worst.max(ratio);
            self.at = format!(
                "{}: kernel {got:e}, twin {want:e}, tolerance {tol:e}",
                what()
            );
        }
    }

    /// Notes a yes/no answer that must be the twin's.
    fn same(&mut self, got: f32, want: bool, what: impl Fn() -> String) {
        self.value(got, f64::from(u8::from(want)), 0.5, what);
    }

    fn assert(&self) {
        eprintln!(
            "{}: {} values, worst error {:.3} of its tolerance ({})",
            self.name, self.count, self.worst, self.at
        );
        assert!(self.count > 0, "{}: nothing compared", self.name);
        assert!(
            self.worst <= 1.0,
            "{}: the kernel differs from its Rust twin beyond f32's tolerance at {}",
            self.name,
            self.at
        );
    }
}

/// A scene's kernel input (the defines and uniforms a host gives the kernel): Gödel's
/// universe with parameter a = 1 or Minkowski space.
fn input(godel: bool) -> KernelInput {
    KernelInput::new(&scene(godel))
}

fn scene(godel: bool) -> Scene {
    if godel {
        common::example("static-sphere")
    } else {
        common::scene(common::MINKOWSKI_TWO_BALLS)
    }
}

/// The uniforms with Gödel's parameter `a` (already an f32).
fn with_a(input: &KernelInput, a: f64) -> Uniforms {
    Uniforms {
        a: a as f32,
        ..input.uniforms.clone()
    }
}

/// Evaluates `function` compiled for `input` on `args`.
fn run(
    input: &KernelInput,
    function: Function,
    uniforms: &Uniforms,
    args: &[Args],
) -> Vec<Results> {
    let prober = Prober::new(input, function).unwrap_or_else(|e| panic!("{function:?}: {e}"));
    prober
        .eval(uniforms, args)
        .unwrap_or_else(|e| panic!("{function:?}: {e}"))
}

/// Gödel parameters the physics probes run at (exact in f32).
const AS: [f64; 3] = [0.5, 1.0, 2.0];

/// An event at distance up to `r_max`·a from the axis (some on it), t and z of a few a.
fn random_event(rng: &mut Rng, a: f64, r_max: f64, i: usize) -> [f64; 4] {
    let r = if i.is_multiple_of(10) {
        0.0
    } else {
        rng.range(0.0, r_max * a)
    };
    let phi = rng.range(-PI, PI);
    f4([
        rng.range(-10.0, 10.0),
        r * phi.cos(),
        r * phi.sin(),
        rng.range(-5.0, 5.0) * a,
    ])
}

#[test]
fn elementary_functions_match_std() {
    let mut rng = Rng(fastrand::Rng::with_seed(1));
    let mut args: Vec<Args> = Vec::new();
    // Edge cases first: zeros, ±1, the range-reduction boundaries tan(π/8), tan(3π/8), large
    // and tiny magnitudes, angles at multiples of π/4 and up to the reduction's limit 8192.
    let edges = [
        0.0, 1.0, -1.0, 0.41421356, 2.41421356, 1e-6, -1e-6, 1e6, -3e4, 0.5,
    ];
    let angles = [
        0.0,
        PI / 4.0,
        -PI / 2.0,
        PI,
        3.0 * PI / 4.0,
        8000.0,
        -8191.0,
        1e-7,
    ];
    for i in 0..400 {
        let pick = |rng: &mut Rng, edge: f64| {
            if i < edges.len() {
                edge
            } else {
                let m = 10f64.powf(rng.range(-6.0, 6.0));
                if rng.range(0.0, 1.0) < 0.5 {
                    -m
                } else {
                    m
                }
            }
        };
        let x = pick(&mut rng, edges[i % edges.len()]);
        // atan2s: points at every angle and radius, the axes included (no −0: the kernel
        // and Rust place −0 differently at ±π, and the kernel is never given one).
        let (y2, x2) = match i {
            0 => (0.0, 0.0),
            1 => (0.0, -1.0),
            2 => (1.0, 0.0),
            3 => (-1.0, 0.0),
            4 => (0.0, 1.0),
            _ => {
                let t = rng.range(-PI, PI);
                let r = 10f64.powf(rng.range(-4.0, 4.0));
                (r * t.sin(), r * t.cos())
            }
        };
        let s = if i < 5 {
            [0.0, 1.0, -1.0, 0.5, -0.999][i]
        } else {
            rng.range(-1.0, 1.0)
        };
        let angle = if i < angles.len() {
            angles[i]
        } else if i.is_multiple_of(4) {
            rng.range(-8000.0, 8000.0)
        } else {
            rng.range(-20.0, 20.0)
        };
        let hyperbolic = pick(&mut rng, edges[(i + 3) % edges.len()]);
        let cosh_arg = if i < 3 {
            [1.0, 1.0 + 1e-6, 1e5][i]
        } else {
            1.0 + 10f64.powf(rng.range(-6.0, 4.0))
        };
        let tanh_arg = if i < 3 {
            [0.0, 0.9999999, -0.5][i]
        } else {
            rng.range(-0.9999, 0.9999)
        };
        let lanes = [0; 4].map(|_| pick(&mut rng, x));
        let unit = [0; 4].map(|_| if i < 2 { i as f64 } else { rng.range(0.0, 1.0) });
        args.push([
            texel([x, y2, x2, s]),
            texel([angle, hyperbolic, cosh_arg, tanh_arg]),
            texel(lanes),
            texel(unit),
        ]);
    }
    let input = input(true);
    let out = run(&input, Function::Elementary, &input.uniforms, &args);
    let mut atan = Compare::new("atanA");
    let mut atan2 = Compare::new("atan2s");
    let mut asin = Compare::new("asinA");
    let mut acos = Compare::new("acosA");
    let mut cis = Compare::new("cis, sinA, cosA");
    let mut atan4 = Compare::new("atanA4");
    let mut asin4 = Compare::new("asinA4");
    let mut asinh = Compare::new("asinh_");
    let mut acosh = Compare::new("acosh_");
    let mut atanh = Compare::new("atanh_");
    let mut half = Compare::new("halfTanh");
    for (a, r) in args.iter().zip(&out) {
        let [x, y2, x2, s] = a[0].map(f64::from);
        let [angle, h, ch, th] = a[1].map(f64::from);
        let w = || format!("{a:?}");
        // Cephes' atanf: ~2·10⁻⁷ relative; the arcsines add a square root and a division.
        atan.value(r[0][0], x.atan(), 4.0 * ULP * x.atan().abs(), w);
        atan2.value(r[0][1], y2.atan2(x2), 4.0 * ULP * y2.atan2(x2).abs(), w);
        asin.value(r[0][2], s.asin(), 4.0 * ULP * s.asin().abs(), w);
        acos.value(r[0][3], s.acos(), 4.0 * ULP * s.acos().abs(), w);
        // The reduction by π/4 in three parts is exact for |a| < 8192: ~1 ULP of 1.
        let (sn, cs) = angle.sin_cos();
        for (got, want) in [(r[1][0], cs), (r[1][1], sn), (r[1][2], sn), (r[1][3], cs)] {
            cis.value(got, want, 2.0 * ULP, w);
        }
        for (k, lane) in a[2].iter().enumerate() {
            let want = f64::from(*lane).atan();
            atan4.value(r[2][k], want, 4.0 * ULP * want.abs(), w);
        }
        for (k, lane) in a[3].iter().enumerate() {
            let want = f64::from(*lane).asin();
            asin4.value(r[3][k], want, 4.0 * ULP * want.abs(), w);
        }
        // log(|x| + √(x² + 1)) near 0 ends within an ULP of 1, not of the value.
        asinh.value(r[4][0], h.asinh(), 4.0 * ULP * (1.0 + h.asinh().abs()), w);
        // x² − 1 cancels near x = 1: its rounding ULP·x² moves acosh by ULP·x/√(x² − 1).
        let cancel = if ch > 1.0 {
            ch / (ch * ch - 1.0).sqrt()
        } else {
            0.0
        };
        acosh.value(
            r[4][1],
            ch.acosh(),
            4.0 * ULP * (1.0 + ch.acosh() + cancel),
            w,
        );
        atanh.value(r[4][2], th.atanh(), 4.0 * ULP * (1.0 + th.atanh().abs()), w);
        let want = (0.5 * h.asinh()).tanh();
        half.value(r[4][3], want, 4.0 * ULP * want.abs(), w);
    }
    for c in [
        atan, atan2, asin, acos, cis, atan4, asin4, asinh, acosh, atanh, half,
    ] {
        c.assert();
    }
}

/// A case of a physics probe: Gödel's a and three four-vectors (inputs, f32 already).
type Case = (f64, [f64; 4], [f64; 4], [f64; 4]);

/// Events at up to 3a from the axis for each a, with two random vectors.
fn events_and_vectors(seed: u64) -> Vec<Case> {
    let mut rng = Rng(fastrand::Rng::with_seed(seed));
    let mut out = Vec::new();
    for &a in &AS {
        for i in 0..100 {
            let e = random_event(&mut rng, a, 3.0, i);
            let u = f4([0; 4].map(|_| rng.range(-2.0, 2.0)));
            let v = f4([0; 4].map(|_| rng.range(-2.0, 2.0)));
            out.push((a, e, u, v));
        }
    }
    out
}

/// Runs `function` once per a over the cases of `events_and_vectors` (a first).
fn run_per_a(
    input: &KernelInput,
    function: Function,
    cases: &[Case],
    args: impl Fn(&Case) -> Args,
) -> Vec<Results> {
    let prober = Prober::new(input, function).unwrap_or_else(|e| panic!("{function:?}: {e}"));
    let mut out = Vec::new();
    for &a in &AS {
        let batch: Vec<Args> = cases.iter().filter(|c| c.0 == a).map(&args).collect();
        out.extend(
            prober
                .eval(&with_a(input, a), &batch)
                .unwrap_or_else(|e| panic!("{function:?}: {e}")),
        );
    }
    out
}

fn metric_of(godel: bool, a: f64) -> Metric {
    if godel {
        Metric::Godel(Godel::new(a))
    } else {
        Metric::Minkowski(Minkowski)
    }
}

/// g and g⁻¹: each component within 8 ULP of the size of its terms, which grow as
/// (x² + y²)/4a² away from the axis.
fn metric_matches(godel: bool) {
    let cases = events_and_vectors(2);
    let input = input(godel);
    let out = run_per_a(&input, Function::Metric, &cases, |c| {
        [texel(c.1), [0.0; 4], [0.0; 4], [0.0; 4]]
    });
    let mut g = Compare::new("metricAt");
    let mut gi = Compare::new("inverseMetricAt");
    for ((a, e, _, _), r) in cases.iter().zip(&out) {
        let m = metric_of(godel, *a);
        let (want, want_inv) = (m.metric(event(*e)), m.inverse_metric(event(*e)));
        let size = 1.0 + (e[1] * e[1] + e[2] * e[2]) / (4.0 * a * a);
        for col in 0..4 {
            for row in 0..4 {
                let w = || format!("a = {a}, event {e:?}, [{col}][{row}]");
                g.value(r[col][row], want[col][row], 4.0 * ULP * size, w);
                gi.value(r[4 + col][row], want_inv[col][row], 4.0 * ULP * size, w);
            }
        }
    }
    g.assert();
    gi.assert();
}

#[test]
fn the_metric_and_its_inverse_match_spacetime_godel() {
    metric_matches(true);
}

#[test]
fn the_metric_and_its_inverse_match_spacetime_minkowski() {
    metric_matches(false);
}

#[test]
fn christoffel_and_normal_displacement_match_spacetime() {
    let cases = events_and_vectors(3);
    let input = input(true);
    let out = run_per_a(&input, Function::Christoffel, &cases, |c| {
        [texel(c.1), texel(c.2), texel(c.3), [0.0; 4]]
    });
    let mut gamma = Compare::new("christoffel");
    let mut normal = Compare::new("normalDisplacement");
    for ((a, e, u, v), r) in cases.iter().zip(&out) {
        let g = Godel::new(*a).christoffel(event(*e));
        let contract = |u: &[f64; 4], v: &[f64; 4]| {
            std::array::from_fn::<f64, 4, _>(|mu| {
                (0..4)
                    .flat_map(|i| (0..4).map(move |j| (i, j)))
                    .map(|(i, j)| g[mu][i][j] * u[i] * v[j])
                    .sum()
            })
        };
        let (uv, uu) = (contract(u, v), contract(u, u));
        let xi = spacetime::normal::displacement(&g, *u);
        // Γ ~ (1 + (x² + y²)/a²)/a: the metric's derivatives times its inverse, summed over
        // the components of u and v (|u|, |v| ≤ 2·2).
        let r2 = (e[1] * e[1] + e[2] * e[2]) / (a * a);
        let size = (1.0 + r2) / a * 16.0;
        for mu in 0..4 {
            let w = || format!("a = {a}, event {e:?}, u {u:?}, v {v:?}, μ = {mu}");
            gamma.value(r[0][mu], uv[mu], 4.0 * ULP * size, w);
            gamma.value(r[1][mu], uu[mu], 4.0 * ULP * size, w);
            normal.value(r[2][mu], xi[mu], 4.0 * ULP * (size + 2.0), w);
        }
    }
    gamma.assert();
    normal.assert();
}

/// The static frame at events up to 3a from the axis, and it boosted to speeds up to 0.95
/// in random directions: each column within K ULP of γ²(1 + (x² + y²)/4a²) (the frame's
/// components grow as the metric's; 1 − v² loses v²/(1 − v²) ULP, the boost multiplies by γ).
fn frames_match(godel: bool) {
    let mut rng = Rng(fastrand::Rng::with_seed(4));
    let cases = events_and_vectors(4)
        .into_iter()
        .enumerate()
        .map(|(i, (a, e, _, _))| {
            let speed = if i.is_multiple_of(7) {
                0.0
            } else {
                rng.range(0.0, 0.95)
            };
            let n = rng.unit();
            (a, e, f4([speed, n[0], n[1], n[2]]), [0.0; 4])
        })
        .collect::<Vec<_>>();
    let input = input(godel);
    let out = run_per_a(&input, Function::Frame, &cases, |c| {
        [texel(c.1), texel(c.2), [0.0; 4], [0.0; 4]]
    });
    let mut stat = Compare::new("staticFrame");
    let mut boosted = Compare::new("boostFrame");
    for ((a, e, v, _), r) in cases.iter().zip(&out) {
        let m = metric_of(godel, *a);
        let frame = gram_schmidt_static_frame(&m.metric(event(*e)));
        let velocity = LocalVelocity::new(v[0], [v[1], v[2], v[3]]).expect("a velocity");
        let moved = boost(&frame, velocity);
        let size = 1.0 + (e[1] * e[1] + e[2] * e[2]) / (4.0 * a * a);
        let gamma2 = 1.0 / (1.0 - v[0] * v[0]);
        for col in 0..4 {
            let (fc, bc) = (frame.e[col].to_array(), moved.e[col].to_array());
            for row in 0..4 {
                let w = || format!("a = {a}, event {e:?}, velocity {v:?}, [{col}][{row}]");
                stat.value(r[col][row], fc[row], 4.0 * ULP * size, w);
                boosted.value(r[4 + col][row], bc[row], 4.0 * ULP * size * gamma2, w);
            }
        }
    }
    stat.assert();
    boosted.assert();
}

#[test]
fn static_and_boosted_frames_match_spacetime_frame_godel() {
    frames_match(true);
}

#[test]
fn static_and_boosted_frames_match_spacetime_frame_minkowski() {
    frames_match(false);
}

#[test]
fn camera_directions_match_scene_camera() {
    let cameras = [
        Camera::Pinhole {
            fov_deg: 60.0,
            width: 80,
            height: 60,
        },
        Camera::Pinhole {
            fov_deg: 150.0,
            width: 33,
            height: 101,
        },
        Camera::Panorama {
            h_fov_deg: 360.0,
            v_fov_deg: 90.0,
            width: 120,
            height: 30,
        },
        Camera::Panorama {
            h_fov_deg: 100.0,
            v_fov_deg: 170.0,
            width: 7,
            height: 50,
        },
        Camera::Sphere {
            width: 64,
            height: 32,
        },
        Camera::Fisheye {
            fov_deg: 180.0,
            size: 41,
        },
        Camera::Fisheye {
            fov_deg: 360.0,
            size: 64,
        },
    ];
    let input = input(true);
    let prober = Prober::new(&input, Function::Camera).expect("compiles");
    let mut rng = Rng(fastrand::Rng::with_seed(5));
    let mut dir = Compare::new("cameraDirection");
    for camera in cameras {
        let mut scene = scene(true);
        scene.camera = camera;
        let uniforms = KernelInput::new(&scene).uniforms;
        let grid = scene.sample_camera();
        let (w, h) = (f64::from(grid.width()), f64::from(grid.height()));
        // Corners, the centre, the border, then anywhere (a fisheye's corners lie outside).
        let mut points = vec![
            (0.0, 0.0),
            (w, h),
            (0.5 * w, 0.5 * h),
            (0.5, 0.5),
            (w, 0.5 * h),
        ];
        points.extend((0..200).map(|_| (rng.range(0.0, w), rng.range(0.0, h))));
        let points: Vec<(f64, f64)> = points.into_iter().map(|(x, y)| (f(x), f(y))).collect();
        let args: Vec<Args> = points
            .iter()
            .map(|&(x, y)| [texel([x, y, 0.0, 0.0]), [0.0; 4], [0.0; 4], [0.0; 4]])
            .collect();
        let out = prober.eval(&uniforms, &args).expect("evaluates");
        for (&(x, y), r) in points.iter().zip(&out) {
            let want = grid.direction_at(x, y);
            let what = || format!("{camera:?} at ({x}, {y})");
            // A fisheye's circle is decided by a rounded radius: skip positions at its rim.
            if let Camera::Fisheye { .. } = camera {
                let rho = (2.0 * x / w - 1.0).hypot(1.0 - 2.0 * y / h);
                if (rho - 1.0).abs() < 1e-5 {
                    continue;
                }
            }
            dir.same(r[0][3], want.is_some(), what);
            // Angles of up to 2π from a few roundings: 16 ULP of 1.
            for (k, c) in want.unwrap_or([0.0; 3]).iter().enumerate() {
                dir.value(r[0][k], *c, 8.0 * ULP, what);
            }
        }
    }
    dir.assert();
}

#[test]
fn isometries_match_spacetime_isometry() {
    let mut rng = Rng(fastrand::Rng::with_seed(6));
    let mut cases = Vec::new();
    for &a in &AS {
        for i in 0..100 {
            let p0 = random_event(&mut rng, a, 3.0, i);
            // One in ten a pure translation (no disc point, no rotation): its own branch.
            let rot = if i.is_multiple_of(10) {
                0.0
            } else {
                f(rng.range(-2.0 * PI, 2.0 * PI))
            };
            let at = random_event(&mut rng, a, 3.0, i + 1);
            let v = f4([0; 4].map(|_| rng.range(-2.0, 2.0)));
            cases.push((a, p0, [rot, 0.0, 0.0, 0.0], at, v));
        }
    }
    let input = input(true);
    let prober = Prober::new(&input, Function::Isometry).expect("compiles");
    let mut out = Vec::new();
    for &a in &AS {
        let batch: Vec<Args> = cases
            .iter()
            .filter(|c| c.0 == a)
            .map(|c| [texel(c.1), texel(c.2), texel(c.3), texel(c.4)])
            .collect();
        out.extend(prober.eval(&with_a(&input, a), &batch).expect("evaluates"));
    }
    let mut to = Compare::new("toOrigin");
    let mut apply = Compare::new("applyPush");
    let mut inverse = Compare::new("inverseIso");
    for ((a, p0, rot, at, v), r) in cases.iter().zip(&out) {
        let m = Isometry::to_origin(*a, event(*p0)).then_rotate(rot[0]);
        let inv = m.inverse();
        let (e, k) = m.apply_push(event(*at), vector(*v));
        let (ie, ik) = inv.apply_push(event(*at), vector(*v));
        let w = || {
            format!(
                "a = {a}, p0 {p0:?}, rotation {}, at {at:?}, v {v:?}",
                rot[0]
            )
        };
        // Parameters: disc coordinates (< 1) and shifts, a few roundings each.
        let params = |r: [f32; 4], iso: &Isometry, c: &mut Compare| {
            let want = [iso.t0, iso.w0.re, iso.w0.im, iso.z0];
            for k in 0..4 {
                c.value(r[k], want[k], 4.0 * ULP * (1.0 + want[k].abs()), w);
            }
        };
        params(r[0], &Isometry::to_origin(*a, event(*p0)), &mut to);
        params(r[3], &inv, &mut inverse);
        inverse.value(
            r[4][0],
            inv.rotation,
            4.0 * ULP * (1.0 + inv.rotation.abs()),
            w,
        );
        // The disc map's conditioning: x + iy = 2a w/√(1 − |w|²) grows as 1/(1 − |w|²) =
        // (r² + 4a²)/4a² at the image and at the source; times the values' size and the
        // times' (t includes 2√2 a arg(…)).
        let cond = |p: [f64; 4]| 1.0 + (p[1] * p[1] + p[2] * p[2]) / (4.0 * a * a);
        let check = |got_e: [f32; 4], got_k: [f32; 4], e: Event, k: FourVector, c: &mut Compare| {
            let (e, k) = (e.to_array(), k.to_array());
            let scale = cond(*at) * cond(e) * cond(*p0) * 8.0 * ULP;
            let vsize = v.iter().map(|c| c.abs()).sum::<f64>();
            for i in 0..4 {
                c.value(
                    got_e[i],
                    e[i],
                    scale * (1.0 + at[0].abs() + e[i].abs() + a),
                    w,
                );
                c.value(got_k[i], k[i], scale * (vsize + k[i].abs()), w);
            }
        };
        check(r[1], r[2], e, k, &mut apply);
        check(r[5], r[6], ie, ik, &mut apply);
    }
    to.assert();
    apply.assert();
    inverse.assert();
}

/// A light ray's tangent at the origin (|E| = 1, either sign, E² ≥ k⊥² + p_z² so that f32
/// rounding never makes it spacelike) or a particle's (κ = 1), with its edge cases: along z,
/// in the plane z = 0.
fn random_tangent(rng: &mut Rng, i: usize) -> [f64; 4] {
    let mut n = rng.unit();
    if i.is_multiple_of(11) {
        n = [0.0, 0.0, if i.is_multiple_of(2) { 1.0 } else { -1.0 }];
    } else if i % 11 == 1 {
        let l = n[0].hypot(n[1]);
        n = [n[0] / l, n[1] / l, 0.0];
    }
    let sign = if i.is_multiple_of(3) { 1.0 } else { -1.0 };
    let p = if i.is_multiple_of(5) {
        rng.range(0.1, 3.0)
    } else {
        1.0
    };
    let s = [f(p * n[0]), f(p * n[1]), f(p * n[2])];
    let p2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
    let kappa = if i.is_multiple_of(5) { 1.0 } else { 0.0 };
    // The smallest f32 E with E² ≥ p² + κ.
    let mut e = (p2 + kappa).sqrt() as f32;
    for _ in 0..4 {
        if f64::from(e) * f64::from(e) < p2 + kappa {
            e = e.next_up();
        }
    }
    [sign * f64::from(e), s[0], s[1], s[2]]
}

/// The Gödel-type family's closed forms and isometries (`spacetime_godel_type.glsl`, compiled
/// with FAMILY) against `spacetime::{TypeOriginGeodesic, TypeIsometry}` in f64, in members
/// m²/Ω² = −1, 0, 1, 2, 3.5, 4, 6 of Ω = 0.7 and 1.3. The kernel does not trace the family yet:
/// these are the pieces it will be built from, held to their twins first.
///
/// Domain: Λ away from the boundary between the regimes (|Λ| ≥ 10⁻² Ω²E²: there Λ is a
/// difference of two terms of size Ω²E², and its rounding in f32, ULP·Ω²E², decides the
/// regime and the loop), λ up to two loops (or |√−Λ λ| ≤ 2 for escaping rays, where the
/// metric's e^{mρ} stays small), events within mρ ≤ 3 (μρ ≤ π/2 on the sphere).
///
/// Tolerances, each a few ULP times the size of the terms: the closed form's angle θ = √Λ λ
/// is rounded to ULP·θ, which moves x, y by ρ_max θ ULP and t by the same times the rate
/// |ṫ| ≤ |E|(1 + Ω²A/Λ); J's plain form loses a factor 2. The isometries pass through the
/// base coordinate, whose map back grows as 1/(1 − k|ζ|²) (the disc's edge for m² > 0): the
/// tolerance carries that factor at the source, the image and P0, as Gödel's does.
#[test]
fn family_closed_forms_and_isometries_match_spacetime() {
    use spacetime::{GodelType, TypeIsometry, TypeOriginGeodesic};
    let mut rng = Rng(fastrand::Rng::with_seed(34));
    let mut cases = Vec::new();
    for omega in [0.7f64, 1.3] {
        for ratio in [-1.0, 0.0, 1.0, 2.0, 3.5, 4.0, 6.0] {
            let member = GodelType::new(f(ratio * omega * omega), f(omega));
            let m_abs = member.m2.abs().sqrt();
            // Events within mρ ≤ 3 (μρ ≤ π/2), and at most 3 in flat m² = 0.
            let reach = if member.m2 > 0.0 {
                3.0 / m_abs
            } else if member.m2 < 0.0 {
                0.5 * PI / m_abs
            } else {
                3.0
            };
            let mut i = 0;
            while cases
                .iter()
                .filter(|c: &&(GodelType, _, _, _, _, _)| c.0 == member)
                .count()
                < 60
            {
                i += 1;
                let k = random_tangent(&mut rng, i);
                let Some(geo) = TypeOriginGeodesic::new(member, vector(k)) else {
                    continue;
                };
                let spin = member.omega * k[0].abs();
                if geo.big_lambda().abs() < 1e-2 * spin * spin {
                    continue;
                }
                let lambda = match (geo.return_parameter(), i % 6) {
                    (Some(_), 0) => 0.0,
                    (Some(l), 1) => 0.5 * l,
                    (Some(l), 2) => l,
                    (Some(l), _) => rng.range(-l, 2.0 * l),
                    (None, _) => rng.range(-2.0, 2.0) / (-geo.big_lambda()).sqrt(),
                };
                let mut place = |j: usize| {
                    let r = if (i + j).is_multiple_of(7) {
                        0.0
                    } else {
                        rng.range(0.0, reach)
                    };
                    let phi = rng.range(-PI, PI);
                    f4([
                        rng.range(-5.0, 5.0),
                        r * phi.cos(),
                        r * phi.sin(),
                        rng.range(-2.0, 2.0),
                    ])
                };
                let (p0, at) = (place(0), place(1));
                let rot = if i.is_multiple_of(9) {
                    0.0
                } else {
                    f(rng.range(-2.0 * PI, 2.0 * PI))
                };
                cases.push((member, k, f(lambda), rot, p0, at));
            }
        }
    }
    let input = input(true);
    let args: Vec<Args> = cases
        .iter()
        .map(|(m, k, l, rot, p0, at)| {
            [
                texel(*k),
                texel([*l, m.m2, m.omega, *rot]),
                texel(*p0),
                texel(*at),
            ]
        })
        .collect();
    let out = run(&input, Function::Family, &input.uniforms, &args);
    let mut origin = Compare::new("typeOriginGeodesic");
    let mut ret = Compare::new("typeReturnParameter");
    let mut at_c = Compare::new("tgeoAt");
    let mut to = Compare::new("typeToOrigin");
    let mut apply = Compare::new("typeApplyPush");
    for ((member, k, lambda, rot, p0, at), r) in cases.iter().zip(&out) {
        let w =
            || format!("{member:?}, k {k:?}, λ = {lambda}, rotation {rot}, p0 {p0:?}, at {at:?}");
        let geo = TypeOriginGeodesic::new(*member, vector(*k)).expect("a causal tangent");
        origin.same(r[0][0], true, w);
        let spin = member.omega * k[0].abs();
        let lam = geo.big_lambda();
        origin.value(r[0][2], lam, 4.0 * ULP * spin * spin, w);
        match geo.return_parameter() {
            Some(l) => ret.value(r[0][1], l, 8.0 * ULP * l * spin * spin / lam, w),
            None => ret.value(r[0][1], -1.0, 0.0, w),
        }
        let theta = (lam.abs().sqrt() * lambda).abs();
        let (e, t) = geo.at(*lambda);
        let (e, t) = (e.to_array(), t.to_array());
        let a = k[1] * k[1] + k[2] * k[2];
        let rate = k[0].abs() * (1.0 + member.omega * member.omega * a / lam.abs());
        let rho = geo
            .rho_max()
            .unwrap_or_else(|| e[1].hypot(e[2]))
            .max(e[1].hypot(e[2]));
        // Λ's own rounding (ULP Ω²E² relative to Λ) moves θ by θ·ULP·Ω²E²/|Λ| as well.
        let dtheta = ULP * (1.0 + theta) * (1.0 + spin * spin / lam.abs());
        let size = 1.0 + rho * (1.0 + theta) + (k[3] * lambda).abs();
        let tsize = size + (k[0] * lambda).abs() + rate * lambda.abs();
        for i in 0..4 {
            let s = if i == 0 { tsize } else { size };
            at_c.value(r[1][i], e[i], 2.0 * s * dtheta, w);
        }
        let ksize = k.iter().map(|c| c.abs()).sum::<f64>() * (1.0 + theta) * (1.0 + rate);
        for i in 0..4 {
            at_c.value(r[2][i], t[i], 2.0 * ksize * dtheta, w);
        }
        // The isometry.
        let t0 = TypeIsometry::to_origin(*member, event(*p0)).expect("within the chart");
        let want = [t0.t0, t0.zeta0.re, t0.zeta0.im, t0.z0];
        for i in 0..4 {
            to.value(r[3][i], want[i], 8.0 * ULP * (1.0 + want[i].abs()), w);
        }
        let m = t0.then_rotate(*rot);
        let kk = 0.25 * member.m2;
        let cond = |p: [f64; 4]| {
            let z = spacetime::godel_type_symmetry::base_coordinate(*member, p[1], p[2]);
            1.0 / (1.0 - kk * z.norm_sqr()).min(1.0)
        };
        let vsize = k.iter().map(|c| c.abs()).sum::<f64>();
        for (iso, slots) in [(m, (4, 5)), (m.inverse(), (6, 7))] {
            let (e, v) = iso.apply_push(event(*at), vector(*k));
            let (e, v) = (e.to_array(), v.to_array());
            let scale = cond(*at) * cond(e) * cond(*p0) * 16.0 * ULP;
            let tsize = 1.0
                + at[0].abs()
                + e[0].abs()
                + member.omega * (1.0 + reach_of(*p0) * reach_of(*at));
            for i in 0..4 {
                let s = if i == 0 {
                    tsize
                } else {
                    1.0 + at[i].abs() + e[i].abs()
                };
                apply.value(r[slots.0][i], e[i], scale * s, w);
                apply.value(r[slots.1][i], v[i], scale * (vsize + v[i].abs()), w);
            }
        }
    }
    origin.assert();
    ret.assert();
    at_c.assert();
    to.assert();
    apply.assert();
}

/// (Ω, m²/Ω²) of the members the family's probes run in: m²/Ω² = −1, 0, 1, 2, 3.5, 4, 6 at
/// the two vorticities `omegas`, and a sphere of small vorticity (Ω = 1/4, m² = −1), whose
/// rays' circles are large against the distance of the cut.
fn family_members(omegas: [f64; 2]) -> impl Iterator<Item = (f64, f64)> {
    omegas
        .into_iter()
        .flat_map(|o| [-1.0, 0.0, 1.0, 2.0, 3.5, 4.0, 6.0].map(|r| (o, r)))
        .chain([(0.25, -16.0)])
}

/// The family's geodesic through any event (`typeExactGeodesic`, `texAt`) against
/// `spacetime::TypeExactGeodesic`, in the same members and a sphere of small vorticity
/// (m² = −1, Ω = 1/4), from events within mρ ≤ 3 and on the sphere out to μρ = 0.8π, beyond
/// |ζ| = 4Ω/μ², where the projection can cross the cut of the map back's time shift and the
/// event's t takes whole periods 8πΩ/μ² (counted: the test asks for such cases). Tolerance: the closed form's (as in the test above) at the origin frame's
/// point, times the map back's conditioning 1/(1 − k|ζ|²) at the start, that point and the
/// image, plus the time shift's size Ω(1 + ρ₀ρ) and the periods taken.
#[test]
fn family_geodesics_through_any_event_match_spacetime() {
    use spacetime::godel_type_symmetry::base_coordinate;
    use spacetime::{GodelType, TypeExactGeodesic};
    let mut rng = Rng(fastrand::Rng::with_seed(3434));
    let mut cases = Vec::new();
    let members = family_members([0.7, 1.3]);
    for (omega, ratio) in members {
        {
            let member = GodelType::new(f(ratio * omega * omega), f(omega));
            let m_abs = member.m2.abs().sqrt();
            let reach = if member.m2 > 0.0 {
                3.0 / m_abs
            } else if member.m2 < 0.0 {
                0.8 * PI / m_abs
            } else {
                3.0
            };
            let mut i: usize = 0;
            let mut made = 0;
            while made < 80 {
                i += 1;
                // On the sphere half the events lie beyond |ζ| = 4Ω/μ² (μρ > 0.72π for the
                // first two vorticities), where rays can cross the cut.
                let r = if i.is_multiple_of(7) {
                    0.0
                } else if member.m2 < 0.0 && i.is_multiple_of(2) {
                    rng.range(0.72 * PI, 0.8 * PI) / m_abs
                } else {
                    rng.range(0.0, reach)
                };
                let phi = rng.range(-PI, PI);
                let at = f4([
                    rng.range(-5.0, 5.0),
                    r * phi.cos(),
                    r * phi.sin(),
                    rng.range(-2.0, 2.0),
                ]);
                let k = random_tangent(&mut rng, i);
                let Some(geo) = TypeExactGeodesic::new(member, event(at), vector(k)) else {
                    continue;
                };
                let o = geo.origin;
                let spin = member.omega * o.energy.abs();
                if o.big_lambda().abs() < 1e-2 * spin * spin {
                    continue;
                }
                let lambda = match o.return_parameter() {
                    Some(l) => rng.range(-l, 2.0 * l),
                    None => rng.range(-2.0, 2.0) / (-o.big_lambda()).sqrt(),
                };
                cases.push((member, k, f(lambda), at));
                made += 1;
            }
        }
    }
    let input = input(true);
    let args: Vec<Args> = cases
        .iter()
        .map(|(m, k, l, at)| {
            [
                texel(*k),
                texel([*l, m.m2, m.omega, 0.0]),
                texel(*at),
                [0.0; 4],
            ]
        })
        .collect();
    let out = run(&input, Function::FamilyExact, &input.uniforms, &args);
    let mut exact = Compare::new("texAt");
    let mut crossed = 0;
    for ((member, k, lambda, at), r) in cases.iter().zip(&out) {
        let w = || format!("{member:?}, k {k:?}, λ = {lambda}, at {at:?}");
        let geo = TypeExactGeodesic::new(*member, event(*at), vector(*k)).expect("a geodesic");
        exact.same(r[0][0], true, w);
        let o = geo.origin;
        let (e0, k0) = o.at(*lambda);
        let (e, v) = geo.at(*lambda);
        let plain = geo.back.apply(e0);
        // The periods the cut's correction took (only on the sphere).
        let period = 8.0 * PI * member.omega / member.m2.abs();
        let (periods, taken) = if member.m2 < 0.0 {
            let n = ((e.t - plain.t) / period).round().abs();
            (n, n * period)
        } else {
            (0.0, 0.0)
        };
        crossed += (periods > 0.0) as usize;
        let spin = member.omega * o.energy.abs();
        let lam = o.big_lambda();
        let theta = (lam.abs().sqrt() * lambda).abs();
        let ko = k0.to_array();
        let a = ko[1] * ko[1] + ko[2] * ko[2];
        let rate = o.energy.abs() * (1.0 + member.omega * member.omega * a / lam.abs());
        let rho = o.rho_max().unwrap_or(0.0).max(e0.r());
        let dtheta = ULP * (1.0 + theta) * (1.0 + spin * spin / lam.abs());
        let kk = 0.25 * member.m2;
        let cond = |x: f64, y: f64| {
            let z = base_coordinate(*member, x, y);
            1.0 / (1.0 - kk * z.norm_sqr()).min(1.0)
        };
        let scale = cond(at[1], at[2]) * cond(e0.x, e0.y) * cond(e.x, e.y);
        let size = 1.0 + rho * (1.0 + theta) + (o.pz * lambda).abs() + e.r();
        let tsize = size
            + (o.energy * lambda).abs()
            + rate * lambda.abs()
            + at[0].abs()
            + member.omega * (1.0 + at[1].hypot(at[2]) * (1.0 + rho))
            + taken;
        let ksize = ko.iter().map(|c| c.abs()).sum::<f64>() * (1.0 + theta) * (1.0 + rate)
            + v.to_array().iter().map(|c| c.abs()).sum::<f64>();
        let (e, v) = (e.to_array(), v.to_array());
        for i in 0..4 {
            let s = if i == 0 { tsize } else { size };
            exact.value(r[1][i], e[i], 2.0 * scale * s * dtheta, w);
            exact.value(r[2][i], v[i], 2.0 * scale * ksize * dtheta, w);
        }
    }
    exact.assert();
    // Seen: 8, all from the sphere of small vorticity.
    assert!(crossed >= 5, "only {crossed} cases cross the cut");
}

/// C1, S1 and ∂S1/∂Λ of the family's closed form at Λ, λ (E = 1): the rates the shadow
/// test's tolerances need (∂S1/∂Λ = (C1λ − S1)/(2Λ), its series λ³(−1/6 + Λλ²/60) near 0).
fn family_s1(lam: f64, lambda: f64) -> (f64, f64, f64) {
    let x = lam * lambda * lambda;
    let (c1, s1) = if lam > 0.0 {
        let r = lam.sqrt();
        ((r * lambda).cos(), (r * lambda).sin() / r)
    } else if lam < 0.0 {
        let r = (-lam).sqrt();
        ((r * lambda).cosh(), (r * lambda).sinh() / r)
    } else {
        (1.0, lambda)
    };
    let ds1 = if x.abs() < 1e-3 {
        lambda.powi(3) * (-1.0 / 6.0 + x / 60.0)
    } else {
        (c1 * lambda - s1) / (2.0 * lam)
    };
    (c1, s1, ds1)
}

/// The end (t, φ) of the light ray leaving the family's axis at angle ψ to +z with E = 1, at λ.
fn family_axis_end(member: spacetime::GodelType, psi: f64, lambda: f64) -> [f64; 2] {
    let k = FourVector::new(1.0, psi.sin(), 0.0, psi.cos());
    let g = spacetime::TypeOriginGeodesic::new(member, k).expect("a light ray");
    let (e, _) = g.at(lambda);
    [e.t, e.y.atan2(e.x)]
}

/// An angle reduced to (−π, π].
fn wrap(a: f64) -> f64 {
    a - 2.0 * PI * (a / (2.0 * PI)).round()
}

/// The Gödel-type family's shadow rays (`render_lighting_family.glsl`, compiled with FAMILY)
/// against `spacetime::godel_type_connect` in f64, in members m²/Ω² = −1, 0, 1, 2, 3.5, 4, 6 of
/// Ω = 0.75 and 1.25 (m² = 4Ω² exactly in f32) and a sphere of small vorticity (m² = −1,
/// Ω = 1/4), sources on and off the axis (on the sphere half beyond |ζ_S| = 4Ω/μ², where the
/// cut's correction takes whole periods), targets within reach (ρ_P < 0.95 ρ_c in the source's
/// axis frame for m² < 4Ω², mρ_P ≤ 2.5 otherwise), in the plane z_P = 0 and on the axis (the
/// caustic's cones), windings 0..=2. For every ray of `type_shadow_rays_from_axis` at the
/// target in the source's axis frame (f32, as the kernel gets it) the kernel's λ at the ray's
/// ψ (rounded to f32), its G (≈ 0: a root), its emission event and tangent and D² (against
/// `type_source_area_distance_sq`); at four grid points of each ray's branch λ and G; and
/// each ray of `type_shadow_rays` mapped back to the scene (`typeShadowRayBack`, the cut's
/// periods included) from its axis-frame twin.
///
/// Tolerances. λ solves R(λ, ψ) = R_P: its error is the error of R's inputs over ∂R/∂λ = σC1,
/// (|∂R/∂ψ| δψ + δR + σ|∂S1/∂Λ| δΛ)/|σC1| + 8 ULP λ, with δψ the rounding of ψ to f32 and in
/// the kernel's sines (and of ψ_min, 16 ULP), δR = 8 ULP (R_P(1 + |κ|R_P²) + σ|S1|) and
/// δΛ = 4 ULP (Ω²c² + |Ω² − κ|σ²) (Λ's rounding, which decides the regime). Near the reach
/// (C1 → 0) λ is that ill-conditioned for any method; the closed form's end there moves by
/// the same. The emission time and azimuth carry λ's tolerance times their rates, ψ's times
/// their derivatives in ψ (central differences of the f64 closed form), and 8 ULP of their
/// size (the angle also the end's position error over ρ_P). The reach: a few ULP of each
/// value (c_max over c_max's own slope σ_min/c_max). D²: 8 ULP (1 + θ) times Λ's conditioning
/// times the size of what √det g(J_i, J_j) subtracts, D² + λ² + |J_ψ||J_χ|/σ (Gödel's form plus
/// the Jacobi fields' product, large where ∂θ/∂ψ = λ ∂√Λ/∂ψ is, as near m² = 4Ω²). The map
/// back: the family's isometry tolerance (16 ULP times the base coordinate's conditioning at
/// the source, the emission and the target).
#[test]
fn family_shadow_rays_match_spacetime_godel_type_connect() {
    use spacetime::godel_type_symmetry::base_coordinate;
    use spacetime::{
        type_shadow_rays, type_shadow_rays_from_axis, type_source_area_distance_sq, GodelChart,
        GodelType, TypeIsometry,
    };
    const WINDINGS: u32 = 2;
    let mut rng = Rng(fastrand::Rng::with_seed(1414));
    // (member, p in the source's axis frame (f32), the CPU's axis ray, fractions of the grid)
    // for the axis-frame probe; (member, source, target, axis ray, final ray) for the map back.
    let mut axis_cases = Vec::new();
    let mut back_cases = Vec::new();
    let members = family_members([0.75, 1.25]);
    for (omega, ratio) in members {
        let member = GodelType::new(f(ratio * omega * omega), f(omega));
        let m_abs = member.m2.abs().sqrt();
        let rho_c = member.critical_radius();
        let target_reach = rho_c.map_or(2.5 / m_abs, |r| 0.95 * r);
        // Sources: mρ ≤ 2 (ρ ≤ 2/Ω for m² = 0); on the sphere up to 0.9π/μ, half of them beyond
        // |ζ_S| = 4Ω/μ², i.e. μρ_S > 2 atan(2Ω/μ).
        let source_reach = if member.m2 > 0.0 {
            2.0 / m_abs
        } else if member.m2 == 0.0 {
            2.0 / member.omega
        } else {
            0.9 * PI / m_abs
        };
        let far = (member.m2 < 0.0).then(|| 2.0 * (2.0 * member.omega / m_abs).atan() / m_abs);
        for i in 0..24usize {
            let on_axis = i.is_multiple_of(4);
            let rs = if on_axis {
                0.0
            } else if let Some(far) = far.filter(|&r| r < source_reach && i % 2 == 1) {
                rng.range(far, source_reach)
            } else {
                rng.range(0.0, source_reach)
            };
            let ps = rng.range(-PI, PI);
            let source = f4([0.0, rs * ps.cos(), rs * ps.sin(), rng.range(-1.0, 1.0)]);
            let rp = if on_axis && i.is_multiple_of(8) {
                0.0
            } else {
                rng.range(0.0, target_reach)
            };
            let pp = rng.range(-PI, PI);
            let zp = if i % 6 == 1 {
                0.0
            } else {
                rng.range(-3.0, 3.0) / member.omega
            };
            let p = [rng.range(-5.0, 5.0), rp * pp.cos(), rp * pp.sin(), zp];
            let to = TypeIsometry::to_origin(member, event(source)).expect("within the chart");
            let target = f4(to.inverse().apply(event(p)).to_array());
            if !event(target).is_finite()
                || member
                    .coordinate_radius()
                    .is_some_and(|edge| event(target).r() >= 0.99 * edge)
            {
                continue;
            }
            let moved = to.apply(event(target));
            let p32 = f4(moved.to_array());
            for ray in type_shadow_rays_from_axis(member, event(p32), WINDINGS) {
                let fractions = [0.0, f(rng.range(0.0, 1.0)), f(rng.range(0.0, 1.0)), 1.0];
                axis_cases.push((member, p32, ray, fractions));
            }
            let axis = type_shadow_rays_from_axis(member, moved, WINDINGS);
            for ray in type_shadow_rays(member, event(source), event(target), WINDINGS) {
                let twin = axis
                    .iter()
                    .find(|r| r.lambda == ray.lambda && r.winding == ray.winding)
                    .expect("every ray has its axis-frame twin");
                back_cases.push((member, source, target, *twin, ray));
            }
        }
    }
    let input = input(true);
    let mut args: Vec<Args> = Vec::new();
    for (m, p, ray, fr) in &axis_cases {
        let k = ray.tangent;
        let psi = f(k.x.hypot(k.y).atan2(k.z.abs()));
        let psi_d = f(k.x.hypot(k.y).atan2(k.z));
        let inbound = f64::from(u8::from(ray.branch == Branch::Inbound));
        args.push([
            texel(*p),
            texel([m.m2, m.omega, 0.0, psi]),
            texel([f64::from(ray.winding), inbound, psi_d, f(ray.lambda)]),
            texel(*fr),
        ]);
    }
    for (m, source, target, twin, _) in &back_cases {
        args.push([
            texel(*target),
            texel([m.m2, m.omega, 1.0, f(twin.lambda)]),
            texel([source[1], source[2], source[3], f(twin.emission.t)]),
            texel(f4(twin.tangent.to_array())),
        ]);
    }
    let prober = Prober::new(&input, Function::FamilyShadow).expect("compiles");
    let mut out = Vec::new();
    for chunk in args.chunks(gpu::probe::MAX_EVALUATIONS) {
        out.extend(prober.eval(&input.uniforms, chunk).expect("evaluates"));
    }
    let (axis_out, back_out) = out.split_at(axis_cases.len());
    let mut reach_c = Compare::new("typeShadowReach");
    let mut lambda_c = Compare::new("typeShadowLambda");
    let mut excess_c = Compare::new("typeShadowExcess");
    let mut ray_c = Compare::new("typeShadowRay");
    let mut area_c = Compare::new("typeAreaDistanceSq");
    let mut grid_c = Compare::new("typeShadowLambda4, typeShadowExcess4");
    let mut back_c = Compare::new("typeShadowRayBack");
    let (mut in_plane, mut caustic, mut escaping, mut periods) = (0, 0, 0, 0);
    for ((member, p, ray, fr), r) in axis_cases.iter().zip(axis_out) {
        let w = || format!("{member:?}, p {p:?}, ray {ray:?}");
        let kappa = 0.25 * member.m2;
        let w2 = member.omega * member.omega;
        // The reach, as type_shadow_rays_from_axis makes it.
        let rp = GodelChart::new(*member).event(event(*p)).r();
        let smin = member.omega * base_coordinate(*member, p[1], p[2]).norm_sqr().sqrt();
        let cmax = ((1.0 - smin) * (1.0 + smin)).sqrt();
        let sesc = 2.0 * member.omega / member.m2.max(0.0).sqrt();
        let cesc = if sesc < 1.0 {
            ((1.0 - sesc) * (1.0 + sesc)).sqrt()
        } else {
            0.0
        };
        reach_c.value(r[0][0], rp, 8.0 * ULP * rp, w);
        reach_c.value(r[0][1], smin, 16.0 * ULP * smin, w);
        reach_c.value(
            r[0][2],
            cmax,
            4.0 * ULP + 16.0 * ULP * smin * smin / cmax,
            w,
        );
        reach_c.value(r[0][3], cesc, 4.0 * ULP * (1.0 + 1.0 / cesc.max(1e-3)), w);
        // λ at the ray's ψ.
        let k = ray.tangent;
        let sigma = k.x.hypot(k.y);
        let c = k.z.abs();
        let psi_cpu = sigma.atan2(c);
        let psi = f(psi_cpu);
        let psi_min = smin.atan2(cmax);
        let lam = w2 * c * c + (w2 - kappa) * sigma * sigma;
        let lam_scale = w2 * c * c + (w2 - kappa).abs() * sigma * sigma;
        let lambda = ray.lambda;
        let theta = lam.abs().sqrt() * lambda;
        let (c1, s1, ds1) = family_s1(lam, lambda);
        let d_psi = (psi - psi_cpu).abs() + 2.0 * ULP * psi + 16.0 * ULP * psi_min;
        let d_r = 8.0 * ULP * (rp * (1.0 + kappa.abs() * rp * rp) + sigma * s1.abs());
        let d_lam = 4.0 * ULP * lam_scale;
        let dr_dpsi = c * s1 + sigma * ds1 * (-2.0 * kappa * sigma * c);
        let tol_lambda = if sigma == 0.0 {
            8.0 * ULP * lambda
        } else {
            (dr_dpsi.abs() * d_psi + d_r + sigma * ds1.abs() * d_lam) / (sigma * c1).abs()
                + 8.0 * ULP * lambda
        };
        // The straight ray along the axis is no root: the kernel's λ is |z_P| there.
        if sigma > 0.0 {
            lambda_c.value(r[1][0], lambda, tol_lambda, w);
        }
        // G = |c|λ − |z_P| = 0 at a root.
        let tol_g = c * tol_lambda + lambda * sigma * d_psi + 4.0 * ULP * (p[3].abs() + c * lambda);
        if sigma > 0.0 {
            excess_c.value(r[1][1], 0.0, tol_g, w);
        }
        // The emission event and tangent in the axis frame, from the kernel's λ.
        let sign = if p[3] < 0.0 { -1.0 } else { 1.0 };
        let psi_s = if sign < 0.0 { PI - psi_cpu } else { psi_cpu };
        let h = 1e-6;
        let hl = 1e-6 * (1.0 + lambda);
        let [tp, fp] = family_axis_end(*member, psi_s + h, lambda);
        let [tm, fm] = family_axis_end(*member, psi_s - h, lambda);
        let [tl, fl] = family_axis_end(*member, psi_s, lambda + hl);
        let [tk, fk] = family_axis_end(*member, psi_s, lambda - hl);
        let [t_end, _] = family_axis_end(*member, psi_s, lambda);
        let (dt_psi, dphi_psi) = ((tp - tm) / (2.0 * h), wrap(fp - fm) / (2.0 * h));
        let (dt_l, dphi_l) = ((tl - tk) / (2.0 * hl), wrap(fl - fk) / (2.0 * hl));
        let rate = 1.0 + dt_l.abs();
        let tol_t = dt_l.abs() * tol_lambda
            + dt_psi.abs() * d_psi
            + 8.0
                * ULP
                * (p[0].abs() + t_end.abs() + rate * lambda)
                * (1.0 + theta)
                * (1.0 + lam_scale / lam.abs().max(1e-30)).min(1e6);
        ray_c.value(r[2][0], ray.emission.t, tol_t, w);
        for &x in &r[2][1..] {
            ray_c.value(x, 0.0, 0.0, w);
        }
        let rho_p = p[1].hypot(p[2]);
        let d_alpha = if rho_p == 0.0 {
            0.0
        } else {
            dphi_l.abs() * tol_lambda
                + dphi_psi.abs() * d_psi
                + 8.0 * ULP * (1.0 + theta) * (1.0 + (sigma / lam.abs().sqrt()).min(1e3) / rho_p)
        };
        let kt = k.to_array();
        ray_c.value(r[3][0], 1.0, 0.0, w);
        for i in 1..3 {
            ray_c.value(r[3][i], kt[i], sigma * d_alpha + 2.0 * d_psi + 4.0 * ULP, w);
        }
        ray_c.value(r[3][3], kt[3], 2.0 * d_psi + 4.0 * ULP, w);
        // D² of the ray at the f32 (ψ, λ) against the twin at the same.
        let psi_d = f(sigma.atan2(k.z));
        if sigma > 0.0 {
            let lambda_d = f(lambda);
            let probe = spacetime::ShadowRay {
                emission: Event::new(0.0, 0.0, 0.0, 0.0),
                tangent: FourVector::new(1.0, psi_d.sin(), 0.0, psi_d.cos()),
                lambda: lambda_d,
                winding: 0,
                branch: Branch::Outbound,
            };
            let want =
                type_source_area_distance_sq(*member, Event::new(0.0, 0.0, 0.0, 0.0), &probe);
            // √det g(J_ψ, J_χ) subtracts products of the Jacobi fields' components: their size
            // |J_ψ| |J_χ|/σ, J_ψ from the f64 closed form's derivatives in ψ (the twin's central
            // difference, h = 10⁻⁵, adds ~10⁻⁹ relative).
            let big_r = sigma * s1.abs();
            let j_chi = big_r * (1.0 + big_r * member.omega + (kappa * big_r * big_r).abs());
            let j_psi = dt_psi.abs()
                + dr_dpsi.abs()
                + big_r * dphi_psi.abs() * (1.0 + member.omega * big_r)
                + sigma * lambda;
            let cond = (1.0 + lam_scale / lam.abs().max(1e-30)).min(1e6);
            let size = want.abs() + lambda_d * lambda_d + j_psi * j_chi / sigma;
            let tol = 8.0 * ULP * size * (1.0 + theta) * cond;
            area_c.value(r[1][2], want, tol, w);
        }
        // The grid at the fractions: |c| from c_lo to c_max (c_max exactly at 1).
        let n = ray.winding;
        let inbound = ray.branch == Branch::Inbound;
        let c_lo = if n == 0 && !inbound { 0.0 } else { cesc };
        for j in 0..4 {
            let u = f64::from(r[4][j]);
            let want_u = if fr[j] == 1.0 {
                cmax
            } else {
                c_lo + (cmax - c_lo) * fr[j]
            };
            let wj = || format!("{}, lane {j} (u = {u})", w());
            grid_c.value(
                r[4][j],
                want_u,
                4.0 * ULP * (1.0 + want_u) + 16.0 * ULP * smin * smin / cmax,
                wj,
            );
            let s = ((1.0 - u) * (1.0 + u)).sqrt();
            let lam_u = w2 * u * u + (w2 - kappa) * s * s;
            let lam_u_scale = w2 * u * u + (w2 - kappa).abs() * s * s;
            let l = f64::from(r[5][j]);
            if lam_u != 0.0 && lam_u.abs() < 1e-4 * w2 {
                continue; // the regime is Λ's rounding (Λ = 0 at c = 0 for m² = 4Ω² is exact)
            }
            let exists = lam_u > 0.0 || (n == 0 && !inbound);
            grid_c.same(f32::from(u8::from(l >= 0.0)), exists, wj);
            if l < 0.0 {
                let want_g = if u > 0.0 {
                    f64::from(INF)
                } else {
                    (f64::from(n) + f64::from(u8::from(inbound))) * PI / member.omega - p[3].abs()
                };
                grid_c.value(
                    r[6][j],
                    want_g,
                    4.0 * ULP * (want_g.abs() + 2.0 * p[3].abs()),
                    wj,
                );
                continue;
            }
            grid_c.value(
                r[6][j],
                u * l - p[3].abs(),
                4.0 * ULP * (p[3].abs() + u * l),
                wj,
            );
            // The closed form at (u, s) reaches R_P at the kernel's λ, on its branch.
            let (c1u, s1u, ds1u) = family_s1(lam_u, l);
            let theta_u = lam_u.abs().sqrt() * l;
            let r_end = s * s1u;
            // c_max's rounding moves θ₀ (by d = (c_max − u)(c_max + u)) and, at c_max, R_max.
            let d_cmax = 16.0 * ULP * smin * smin / cmax + 2.0 * ULP;
            let d_r = 8.0 * ULP * (rp * (1.0 + kappa.abs() * rp * rp) + s * s1u.abs())
                + s * ds1u.abs() * 4.0 * ULP * lam_u_scale
                + rp * (1.0 + kappa.abs() * rp * rp) * cmax * d_cmax / (s * s)
                + (c1u * s1u * u / s.max(1e-30) + s * ds1u * 2.0 * kappa * u).abs() * d_cmax
                + (s * c1u).abs() * 8.0 * ULP * l;
            grid_c.value(r_end.abs() as f32, rp, d_r, wj);
            if lam_u > 0.0 {
                let start = (2.0 * f64::from(n) + f64::from(u8::from(inbound))) * PI / 2.0;
                let slack = 1e-4 * (1.0 + theta_u);
                let on_branch = theta_u >= start - slack && theta_u <= start + PI / 2.0 + slack;
                grid_c.same(f32::from(u8::from(on_branch)), true, wj);
            }
        }
        in_plane += usize::from(p[3] == 0.0);
        caustic += usize::from(rho_p == 0.0);
        escaping += usize::from(lam <= 0.0);
    }
    for ((member, source, target, twin, ray), r) in back_cases.iter().zip(back_out) {
        let w = || format!("{member:?}, source {source:?}, target {target:?}, ray {ray:?}");
        let kk = 0.25 * member.m2;
        let cond = |x: f64, y: f64| {
            let z = base_coordinate(*member, x, y);
            1.0 / (1.0 - kk * z.norm_sqr()).min(1.0)
        };
        let e = ray.emission;
        let scale = cond(source[1], source[2]) * cond(e.x, e.y) * cond(target[1], target[2]);
        let period = 8.0 * PI * member.omega / member.m2.abs();
        let plain = TypeIsometry::to_origin(*member, event(*source))
            .expect("within the chart")
            .inverse()
            .apply(twin.emission);
        let taken = if member.m2 < 0.0 {
            ((e.t - plain.t) / period).round().abs() * period
        } else {
            0.0
        };
        periods += usize::from(taken > 0.0);
        let tsize = 1.0
            + e.t.abs()
            + twin.emission.t.abs()
            + member.omega * (1.0 + source[1].hypot(source[2]) * e.r())
            + taken;
        let ea = e.to_array();
        let ka = ray.tangent.to_array();
        let ksize = 1.0 + ka.iter().map(|c| c.abs()).sum::<f64>();
        for i in 0..4 {
            let s = if i == 0 {
                tsize
            } else {
                1.0 + ea[i].abs() + source[i].abs()
            };
            back_c.value(r[0][i], ea[i], 16.0 * ULP * scale * s, w);
            back_c.value(r[1][i], ka[i], 16.0 * ULP * scale * ksize, w);
        }
    }
    reach_c.assert();
    lambda_c.assert();
    excess_c.assert();
    ray_c.assert();
    area_c.assert();
    grid_c.assert();
    back_c.assert();
    eprintln!(
        "{} axis-frame rays ({in_plane} in the plane, {caustic} caustic, {escaping} escaping), {} mapped back ({periods} across the cut)",
        axis_cases.len(),
        back_cases.len()
    );
    assert!(in_plane >= 10 && caustic >= 5 && escaping >= 10 && periods >= 5);
}

/// The distance of an event from the axis, for the time shift's size Ω ρ₀ ρ.
fn reach_of(p: [f64; 4]) -> f64 {
    p[1].hypot(p[2])
}

#[test]
fn closed_forms_match_spacetime_closed_form() {
    let mut rng = Rng(fastrand::Rng::with_seed(7));
    let mut cases = Vec::new();
    for &a in &AS {
        for i in 0..100 {
            let k = random_tangent(&mut rng, i);
            let geo = OriginGeodesic::new(a, vector(k)).expect("a causal tangent");
            let ret = geo.return_parameter();
            // λ from −2 to 4 loops, and λ = 0, half and whole loops.
            let lambda = match i % 8 {
                0 => 0.0,
                1 => 0.5 * ret,
                2 => ret,
                _ => rng.range(-2.0 * ret, 4.0 * ret),
            };
            cases.push((a, k, [f(lambda), 0.0, 0.0, 0.0], [0.0; 4]));
        }
        // Not causal, or no energy: no closed form on either side.
        cases.push((a, [1.0, 1.0, 1.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0; 4]));
        cases.push((a, [0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0; 4]));
    }
    let input = input(true);
    let out = run_per_a(&input, Function::ClosedForm, &cases, |c| {
        [texel(c.1), texel(c.2), [0.0; 4], [0.0; 4]]
    });
    let mut origin = Compare::new("originGeodesic");
    let mut at = Compare::new("ogeoAt");
    let mut ret = Compare::new("returnParameter");
    let mut flow = Compare::new("flowRotation");
    let mut dev = Compare::new("timeDeviation");
    for ((a, k, l, _), r) in cases.iter().zip(&out) {
        let lambda = l[0];
        let geo = OriginGeodesic::new(*a, vector(*k));
        let w = || format!("a = {a}, k {k:?}, λ = {lambda}");
        origin.same(r[0][0], geo.is_some(), w);
        let Some(geo) = geo else { continue };
        let lr = geo.return_parameter();
        ret.value(r[0][1], lr, 4.0 * ULP * lr, w);
        // θ = ωλ and the angles made from it grow with λ: their rounding is ULP·θ.
        let theta = (lambda / lr * PI).abs();
        let beta = geo.flow_rotation(lambda);
        flow.value(r[0][2], beta, 4.0 * ULP * (1.0 + theta + beta.abs()), w);
        // 2√2·a·atan((q − 1)/(2√q)), q within a few ULP: terms of size a.
        dev.value(r[0][3], geo.time_deviation(), 8.0 * ULP * a, w);
        let (e, t) = geo.at(lambda);
        let (e, t) = (e.to_array(), t.to_array());
        // t = sgn(E) 2√2 a Φ − Eλ: terms of size a·θ and |E λ|; x, y: r_max (≤ 2a for
        // light) times the angle's rounding.
        let size = 1.0
            + a * theta
            + (k[0] * lambda).abs()
            + geo.r_max() * (1.0 + theta)
            + (k[3] * lambda).abs();
        let tsize = k.iter().map(|c| c.abs()).sum::<f64>() * (1.0 + theta);
        for i in 0..4 {
            at.value(r[1][i], e[i], 4.0 * ULP * size, w);
            at.value(r[2][i], t[i], 4.0 * ULP * tsize, w);
        }
    }
    origin.assert();
    at.assert();
    ret.assert();
    flow.assert();
    dev.assert();
}

#[test]
fn transport_matches_spacetime_transport() {
    let mut rng = Rng(fastrand::Rng::with_seed(8));
    let mut cases = Vec::new();
    for &a in &AS {
        for i in 0..100 {
            let k = random_tangent(&mut rng, i);
            let geo = OriginGeodesic::new(a, vector(k)).expect("a causal tangent");
            let lambda = if i.is_multiple_of(9) {
                0.0
            } else {
                rng.range(0.0, 3.0 * geo.return_parameter())
            };
            let v = f4([0; 4].map(|_| rng.range(-1.0, 1.0)));
            cases.push((a, k, [f(lambda), 0.0, 0.0, 0.0], v));
        }
    }
    let input = input(true);
    let out = run_per_a(&input, Function::Transport, &cases, |c| {
        [texel(c.1), texel(c.2), texel(c.3), [0.0; 4]]
    });
    let mut tr = Compare::new("transportLegs");
    for ((a, k, l, v), r) in cases.iter().zip(&out) {
        let geo = OriginGeodesic::new(*a, vector(*k)).expect("a causal tangent");
        let (_, want) = transport_from_origin(&geo, l[0], vector(*v));
        let want = want.to_array();
        // exp(−λA) of a light ray is nearly a null rotation, whose components grow as
        // (λ|A|)², |A| ~ (|E| + k⊥ + |p_z|)/(√2 a), each rounded to ULP; the isometry back
        // from within r_max ≤ 2a of the axis (1/(1 − |w|²) ≤ 2) adds a few ULP.
        let s = l[0].abs() * (k[0].abs() + k[1].hypot(k[2]) + k[3].abs()) / (SQRT_2 * a);
        let size = v.iter().map(|c| c.abs()).sum::<f64>() * (1.0 + s) * (1.0 + s);
        let w = || format!("a = {a}, k {k:?}, λ = {}, w {v:?}", l[0]);
        for i in 0..4 {
            tr.value(r[0][i], want[i], 8.0 * ULP * size, w);
        }
    }
    tr.assert();
}

/// The light ray leaving the axis at angle ψ to the z axis with E = 1 (ψ ∈ (0, π/2]).
fn axis_ray(a: f64, psi: f64) -> OriginGeodesic {
    OriginGeodesic::new(a, FourVector::new(1.0, psi.sin(), 0.0, psi.cos())).expect("a light ray")
}

/// One case of the shadow probe: its four argument texels (f32 already) and Gödel's a.
struct ShadowCase {
    a: f64,
    args: [[f64; 4]; 4],
}

#[test]
fn shadow_rays_match_spacetime_connect() {
    let mut rng = Rng(fastrand::Rng::with_seed(9));
    // shadowTheta, shadowG, shadowG4, bigPhi: for a target at ρ, the ray leaving at ψ ≥ ψ_min
    // (its r_max ≥ ρ), a winding and a branch, against the closed form of that ray at the
    // parameter λ = θ/ω the kernel gives.
    let mut cases = Vec::new();
    for &a in &AS {
        for i in 0..100usize {
            let rho = f(if i == 0 {
                1e-4 * a
            } else {
                rng.range(0.0, 1.99) * a
            });
            // The light's set-up: s = ρ/2a and ψ_min, where r_max = ρ (sin²ψ_min = 2s²/(1 + s²)).
            let s = f(rho / (2.0 * a));
            let psi_min = f((s * SQRT_2).atan2((1.0 - s * s).sqrt()));
            // ψ from the reach to π/2, the reach itself and π/2 included.
            let psi = match i % 10 {
                1 => psi_min,
                2 => f(PI / 2.0),
                _ => f(rng.range(psi_min, PI / 2.0)),
            };
            let n = (i % 4) as f64;
            let inbound = if i.is_multiple_of(2) { 1.0 } else { 0.0 };
            let zp = f(rng.range(-8.0, 8.0) * a);
            let c = f(rng.range(0.0, 1.0));
            let q = f((2.0 / (1.0 + c * c)).sqrt());
            let theta = f(rng.range(-10.0, 10.0));
            // Grid points: three anywhere below c_max = cos ψ_min, then c_max.
            let c_max = f(psi_min.cos());
            let lanes = [0; 3].map(|_| f(rng.range(0.0, c_max)));
            cases.push(ShadowCase {
                a,
                args: [
                    [psi, n, inbound, rho],
                    [s, psi_min, zp, q],
                    [0.0, 0.0, 0.0, theta],
                    [lanes[0], lanes[1], lanes[2], c_max],
                ],
            });
        }
        // areaDistanceSq: the rays of spacetime::shadow_rays_from_axis to targets within the
        // horizon, two windings, given as (ψ, χ, λ).
        for _ in 0..25 {
            let rho = rng.range(0.05, 1.9) * a;
            let phi = rng.range(-PI, PI);
            let z = rng.range(-4.0, 4.0) * a;
            let target = Event::new(0.0, rho * phi.cos(), rho * phi.sin(), z);
            for ray in shadow_rays_from_axis(a, target, 2) {
                let k = ray.tangent;
                let psi = f(k.x.hypot(k.y).atan2(k.z));
                let chi = f(k.y.atan2(k.x));
                let area = [psi, chi, f(ray.lambda), 0.0];
                cases.push(ShadowCase {
                    a,
                    args: [[0.0; 4], [0.0; 4], area, [0.0; 4]],
                });
            }
        }
    }
    let input = input(true);
    let prober = Prober::new(&input, Function::Shadow).expect("compiles");
    let mut theta_c = Compare::new("shadowTheta");
    let mut g_c = Compare::new("shadowG, shadowG4");
    let mut phi_c = Compare::new("bigPhi");
    let mut area = Compare::new("areaDistanceSq");
    for &a in &AS {
        let batch: Vec<&ShadowCase> = cases.iter().filter(|c| c.a == a).collect();
        let args: Vec<Args> = batch.iter().map(|c| c.args.map(texel)).collect();
        let out = prober.eval(&with_a(&input, a), &args).expect("evaluates");
        for (c, r) in batch.iter().zip(&out) {
            let [[psi, n, inbound, rho], [_, _, zp, q], [area_psi, chi, lambda, theta], lanes] =
                c.args;
            let w = || format!("a = {a}, arguments {:?}", c.args);
            if area_psi > 0.0 {
                // D² against spacetime::source_area_distance_sq of the ray from the origin.
                let tangent = FourVector::new(
                    1.0,
                    area_psi.sin() * chi.cos(),
                    area_psi.sin() * chi.sin(),
                    area_psi.cos(),
                );
                let ray = ShadowRay {
                    emission: Event::new(0.0, 0.0, 0.0, 0.0),
                    tangent,
                    lambda,
                    winding: 0,
                    branch: Branch::Outbound,
                };
                let want = source_area_distance_sq(a, Event::new(0.0, 0.0, 0.0, 0.0), &ray);
                // D² ~ λ² near the source: a determinant of Jacobi fields of size λ(1 + θ)
                // each, which cancels near a refocusing; the twin's central difference adds
                // ~10⁻¹⁰ relative.
                let th = lambda * (1.0 + area_psi.cos().powi(2)).sqrt() / (2.0 * a);
                let tol = 8.0 * ULP * (want.abs() + lambda * lambda) * (1.0 + th);
                area.value(r[0][2], want, tol, w);
                continue;
            }
            // θ: the ray reaches distance ρ at λ = θ/ω (r = r_max sin θ: dr/dθ ≤ r_max, θ up
            // to 4π rounded to ULP·θ), in winding n, on its branch.
            let geo = axis_ray(a, psi);
            let omega = PI / geo.return_parameter();
            let th = f64::from(r[0][0]);
            let (e, _) = geo.at(th / omega);
            theta_c.value(e.r() as f32, rho, 4.0 * ULP * geo.r_max() * (1.0 + th), w);
            // Outbound: θ ∈ [nπ, nπ + π/2]; inbound: [nπ + π/2, (n + 1)π] (to rounding).
            let start = (2.0 * n + inbound) * PI / 2.0;
            let on_branch = th >= start - 1e-5 && th <= start + PI / 2.0 + 1e-5;
            theta_c.same(f32::from(u8::from(on_branch)), true, w);
            // G = the height at that λ minus |z_P| (c ≥ 0: the ray climbs as c λ).
            let g_tol = 4.0 * ULP * (1.0 + zp.abs() + e.z.abs() * (1.0 + th));
            g_c.value(r[0][1], e.z - zp.abs(), g_tol, w);
            // shadowG4 at |c| = u: the same from θ₀ = asin(ρ/r_max(u)), or π/2 at the grid's
            // last point c_max, where r_max = ρ (asin's slope 1/√(1 − (ρ/r_max)²) there).
            for (k, u) in lanes.iter().enumerate() {
                let g = axis_ray(a, u.acos());
                let ratio = (rho / g.r_max()).min(1.0);
                let th0 = if k == 3 { PI / 2.0 } else { ratio.asin() };
                let th = n * PI + if inbound > 0.5 { PI - th0 } else { th0 };
                let (e, _) = g.at(th / (PI / g.return_parameter()));
                let slope = if k == 3 {
                    1.0
                } else {
                    1.0 / (1.0 - ratio * ratio).max(1e-12).sqrt()
                };
                let tol = 4.0 * ULP * (1.0 + zp.abs() + e.z.abs() * (1.0 + th) * slope);
                g_c.value(r[1][k], e.z - zp.abs(), tol, || {
                    format!("{}, lane {k}", w())
                });
            }
            // Φ(θ): from the closed form's t = 2√2 a Φ − λ of the light ray with this q
            // (E = 1, q² = 2/(1 + c²)).
            let cq = (2.0 / (q * q) - 1.0).clamp(0.0, 1.0).sqrt();
            let g = axis_ray(a, cq.acos());
            let l = theta / (PI / g.return_parameter());
            let (e, _) = g.at(l);
            let want = (e.t + l) / (2.0 * SQRT_2 * a);
            phi_c.value(r[0][3], want, 2.0 * ULP * (1.0 + 2.0 * theta.abs()), w);
        }
    }
    theta_c.assert();
    g_c.assert();
    phi_c.assert();
    area.assert();
}

/// render::reject's ball at rest with centre `centre` (Cartesian x, y, z), searched out to
/// `reach` (its radius is then immaterial), seen from the origin.
fn ball_at_rest(a: f64, centre: [f64; 3], reach: f64) -> StaticBall {
    let target = Target::LocalSphere {
        radius: reach / 1.25,
        worldline: Worldline::new(
            Metric::Godel(Godel::new(a)),
            &Motion::Rest {
                position: Event::new(0.0, centre[0], centre[1], centre[2]),
            },
            0.0,
            0.0,
        )
        .expect("a worldline at rest"),
    };
    StaticBall::new(a, Event::new(0.0, 0.0, 0.0, 0.0), &target)
        .expect("a ball")
        .with_reach(reach)
}

#[test]
fn rejections_are_safe_and_match_render_reject() {
    let mut rng = Rng(fastrand::Rng::with_seed(10));
    struct Case {
        a: f64,
        k: [f64; 4],
        centre: [f64; 3],
        reach: f64,
        from: f64,
        until: f64,
        plane: f64,
    }
    let mut cases = Vec::new();
    for &a in &AS {
        for i in 0..120 {
            // Past-directed light rays, as the kernel's pixel rays.
            let mut k = random_tangent(&mut rng, 5 * i + 1);
            k[0] = -k[0].abs();
            let geo = OriginGeodesic::new(a, vector(k)).expect("a light ray");
            let ret = geo.return_parameter();
            let r = rng.range(0.0, 3.0) * a;
            let phi = rng.range(-PI, PI);
            let centre = [
                f(r * phi.cos()),
                f(r * phi.sin()),
                f(rng.range(-4.0, 4.0) * a),
            ];
            let reach = f(rng.range(0.05, 0.6) * a);
            let from = if i % 4 == 3 {
                f(rng.range(0.0, ret))
            } else {
                0.0
            };
            let until = if i.is_multiple_of(3) {
                f64::from(INF)
            } else {
                f(from + rng.range(0.0, 3.0 * ret))
            };
            let plane = if i.is_multiple_of(10) {
                0.0
            } else {
                f(rng.range(-6.0, 6.0) * a)
            };
            cases.push(Case {
                a,
                k,
                centre,
                reach,
                from,
                until,
                plane,
            });
        }
    }
    let input = input(true);
    let prober = Prober::new(&input, Function::Reject).expect("compiles");
    let mut ball_safe = Compare::new("ballMisses: safe");
    let mut ball_same = 0usize;
    let mut ball_rust = 0usize;
    let mut plane_safe = Compare::new("planeMisses: safe");
    let mut plane_same = Compare::new("planeMisses: as render::reject");
    let mut balls = 0usize;
    let mut glsl_misses = 0usize;
    for &a in &AS {
        let batch: Vec<&Case> = cases.iter().filter(|c| c.a == a).collect();
        let args: Vec<Args> = batch
            .iter()
            .map(|c| {
                let w = disc(a, c.centre[0], c.centre[1]);
                [
                    texel(c.k),
                    texel([w.re, w.im, c.centre[2], c.reach]),
                    texel([c.from, c.until, c.plane, 0.0]),
                    [0.0; 4],
                ]
            })
            .collect();
        let out = prober.eval(&with_a(&input, a), &args).expect("evaluates");
        for (c, r) in batch.iter().zip(&out) {
            let geo = OriginGeodesic::new(a, vector(c.k)).expect("a light ray");
            let until = if c.until >= f64::from(INF) {
                f64::INFINITY
            } else {
                c.until
            };
            let w = || {
                format!(
                    "a = {a}, k {:?}, centre {:?}, reach {}, λ ∈ [{}, {until}], plane z = {}",
                    c.k, c.centre, c.reach, c.from, c.plane
                )
            };
            // The ball: where the kernel says it misses, the ray sampled every 10⁻³ a of
            // static distance (the static speed of a light ray of E = 1 is 1) over the λ
            // window where |p_z λ − z_C| ≤ reach (one loop of it: later loops retrace it)
            // stays beyond the reach, less the sampling's half step and f32 rounding.
            let misses = r[0][0] > 0.5;
            balls += 1;
            glsl_misses += usize::from(misses);
            if misses {
                let (mut lo, mut hi) = (c.from, until);
                if geo.pz != 0.0 {
                    let (l1, l2) = (
                        (c.centre[2] - c.reach) / geo.pz,
                        (c.centre[2] + c.reach) / geo.pz,
                    );
                    lo = lo.max(l1.min(l2));
                    hi = hi.min(l1.max(l2));
                }
                hi = hi.min(lo + geo.return_parameter());
                // (An empty window: no λ within reach in z.)
                let mut nearest = f64::INFINITY;
                if hi >= lo {
                    let steps = ((hi - lo) / (1e-3 * a)).ceil().clamp(1.0, 1e5) as usize;
                    for s in 0..=steps {
                        let l = lo + (hi - lo) * s as f64 / steps as f64;
                        let (e, _) = geo.at(l);
                        nearest = nearest.min(static_distance(a, [e.x, e.y, e.z], c.centre));
                    }
                }
                let short = (c.reach - nearest).max(0.0);
                ball_safe.value(short as f32, 0.0, 1e-3 * a, w);
            }
            // render::reject decides the same for rays searched from λ = 0 (its window).
            if c.from == 0.0 {
                let ball = ball_at_rest(a, c.centre, c.reach);
                ball_rust += 1;
                ball_same += usize::from(ball.misses(&geo, until) == misses);
                let plane = Rejection::Plane { z: c.plane }.misses(&geo, until);
                plane_same.same(r[0][1], plane, w);
            }
            // The plane: where the kernel says it misses, p_z λ − z keeps one side at both
            // ends of the window (it is linear in λ).
            if r[0][1] > 0.5 {
                let f0 = geo.pz * c.from - c.plane;
                let f1 = if until.is_finite() {
                    geo.pz * until - c.plane
                } else {
                    geo.pz * 1e30 - c.plane
                };
                let apart = f0 != 0.0 && (f0 > 0.0) == (f1 > 0.0);
                plane_safe.same(f32::from(u8::from(apart)), true, w);
            }
        }
    }
    // Not vacuous: the kernel rejects as render::reject does but for a few rays at the edge
    // of the reach, and it rejects a good share of the rays at all.
    eprintln!("ballMisses: {glsl_misses} of {balls} rays missed; the same as render::reject on {ball_same} of {ball_rust}");
    assert!(
        glsl_misses * 4 >= balls,
        "the kernel rejects too few rays to test: {glsl_misses} of {balls}"
    );
    assert!(
        ball_same as f64 >= 0.98 * ball_rust as f64,
        "ballMisses decides unlike render::reject on {} of {ball_rust} rays",
        ball_rust - ball_same
    );
    ball_safe.assert();
    plane_safe.assert();
    plane_same.assert();
}

/// A segment of a ray near a ball at rest (the kernel's per-segment test, `objectMisses`):
/// where the height differs along the whole segment, the circle must come within
/// √(reach² − Δz²) of the centre on the disc. Balls placed near a random point of each ray,
/// segments of about a sixteenth of a loop around it: the kernel's rejection must be safe
/// (the segment sampled densely stays beyond the reach) and decide as the CPU's
/// `render::circle::Stretches::meets` does.
#[test]
fn segment_rejections_are_safe_and_match_render_stretches() {
    let mut rng = Rng(fastrand::Rng::with_seed(12));
    let input = input(true);
    let prober = Prober::new(&input, Function::Reject).expect("compiles");
    let mut safe = Compare::new("ballMisses over a segment: safe");
    let (mut cases, mut misses, mut same, mut shrunk) = (0usize, 0usize, 0usize, 0usize);
    for &a in &AS {
        let mut batch = Vec::new();
        for i in 0..200 {
            let mut k = random_tangent(&mut rng, 5 * i + 2);
            k[0] = -k[0].abs();
            let geo = OriginGeodesic::new(a, vector(k)).expect("a light ray");
            let ret = geo.return_parameter();
            let seg = ret / 16.0;
            let at = rng.range(0.0, 2.0) * ret;
            let (e, _) = geo.at(at);
            let reach = f(rng.range(0.05, 0.4) * a);
            let d = rng.unit();
            let off = rng.range(0.2, 2.0) * reach;
            let centre = [
                f(e.x + off * d[0]),
                f(e.y + off * d[1]),
                f(e.z + off * d[2]),
            ];
            let from = f((at + rng.range(-1.5, 0.5) * seg).max(0.0));
            let until = f(from + rng.range(0.25, 1.0) * seg);
            batch.push((k, centre, reach, from, until));
        }
        let args: Vec<Args> = batch
            .iter()
            .map(|&(k, c, reach, from, until)| {
                let w = disc(a, c[0], c[1]);
                [
                    texel(k),
                    texel([w.re, w.im, c[2], reach]),
                    texel([from, until, 0.0, 0.0]),
                    [0.0; 4],
                ]
            })
            .collect();
        let out = prober.eval(&with_a(&input, a), &args).expect("evaluates");
        for (&(k, c, reach, from, until), r) in batch.iter().zip(&out) {
            let geo = OriginGeodesic::new(a, vector(k)).expect("a light ray");
            let w =
                || format!("a = {a}, k {k:?}, centre {c:?}, reach {reach}, λ ∈ [{from}, {until}]");
            let kernel = r[0][0] > 0.5;
            cases += 1;
            misses += usize::from(kernel);
            if kernel {
                let steps = ((until - from) / (1e-3 * a)).ceil().clamp(1.0, 1e5) as usize;
                let nearest = (0..=steps)
                    .map(|s| {
                        let (e, _) = geo.at(from + (until - from) * s as f64 / steps as f64);
                        static_distance(a, [e.x, e.y, e.z], c)
                    })
                    .fold(f64::INFINITY, f64::min);
                safe.value((reach - nearest).max(0.0) as f32, 0.0, 1e-3 * a, w);
            }
            // The CPU's stretches of the same ball (its reach the kernel's), over the segment.
            let near = ball_at_rest(a, c, reach).near(&RayCircle::new(&geo), until);
            same += usize::from(near.is_none_or(|n| !n.meets(from, until)) == kernel);
            // Rejected only for the height: the whole reach on the disc would not reject it.
            let flat = r[0][3] > 0.5;
            shrunk += usize::from(kernel && !flat);
        }
    }
    eprintln!(
        "segments: {misses} of {cases} rejected ({shrunk} only for their height); the same \
         as render::circle::Stretches on {same}"
    );
    assert!(
        misses * 4 >= cases && shrunk * 40 >= cases,
        "too few segments rejected to test: {misses} of {cases}, {shrunk} for their height"
    );
    assert!(
        same as f64 >= 0.98 * cases as f64,
        "ballMisses decides unlike render::circle::Stretches on {} of {cases} segments",
        cases - same
    );
    safe.assert();
}

#[test]
fn texture_coordinates_match_render_target() {
    let mut rng = Rng(fastrand::Rng::with_seed(11));
    let mut dirs: Vec<[f64; 3]> = vec![
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [-1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [3.0, -4.0, 12.0],
        [1e-3, 2e-3, -5e-4],
    ];
    dirs.extend((0..300usize).map(|i| {
        let u = rng.unit();
        let s = 10f64.powf(rng.range(-3.0, 3.0)) * if i.is_multiple_of(5) { 1.0 } else { 0.2 };
        u.map(|c| c * s)
    }));
    let dirs: Vec<[f64; 3]> = dirs.into_iter().map(|d| d.map(f)).collect();
    let args: Vec<Args> = dirs
        .iter()
        .map(|d| [texel([d[0], d[1], d[2], 0.0]), [0.0; 4], [0.0; 4], [0.0; 4]])
        .collect();
    let input = input(true);
    let out = run(&input, Function::Surface, &input.uniforms, &args);
    let mut uv = Compare::new("lonLat");
    for (d, r) in dirs.iter().zip(&out) {
        let (u, v) = render::target::lon_lat(*d);
        let w = || format!("direction {d:?}");
        // Angles over 2π and π of a normalization and an arctangent: a few ULP of 1; v's
        // arcsine near the poles multiplies n_z's rounding by 1/√(1 − n_z²).
        let nz = d[2] / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let pole = 1.0 / (1.0 - nz * nz).max(1e-30).sqrt();
        uv.value(r[0][0], u, 4.0 * ULP, w);
        uv.value(r[0][1], v, 4.0 * ULP * (1.0 + pole), w);
    }
    uv.assert();
}
