//! How far a light ray's rest-frame path near a local ball bends from its chords
//! (docs/physics.md, "Chord exclusion"): the measurement behind `render::chord`'s bound.
//!
//! Random balls in Gödel's universe (a from 0.5 to 2; every fifth at rest, the others falling
//! at up to 0.8 c; radius up to a/2, up to 1.8a from the axis) and rays through random points
//! within 0.45a of a centre, sampled as the property test in tests/integration/chord.rs
//! samples them. For every span of 2 to 256 samples whose ends and points are near probes:
//!
//! - the bend it needs, K = 8·(largest distance of a point from the chord, over 4f(1 − f))/h²,
//!   in units of (E·s)²/a, by speed (bins of 0.05 c) and by the larger end's distance from
//!   the centre plus 0.05a (bins of 0.05a), the ρ of the renderer's bound;
//! - for the spans the renderer's bound applies to (`chord::stray`), the largest distance
//!   from the chord as a share of that bound, by speed: the bound's margin is its inverse.
//!
//! `cargo run --release -p render --example chord_bend -- [CASES] [SEED]` (default 20000 5;
//! ~15 s).

use render::chord;
use render::target::Target;
use render::worldline::Located;
use spacetime::{Event, ExactGeodesic, Godel, LocalVelocity, Metric, Spacetime};
use std::f64::consts::TAU;

/// Bins: at rest, then falling at speeds in [0.05k, 0.05(k + 1)) c for k = 0..16.
const SPEED_BINS: usize = 17;
/// Bins of ρ = end distance + 0.05a, 0.05a wide, from 0.05a to 0.55a.
const RHO_BINS: usize = 10;

/// A seeded generator: the same cases every run.
struct Cases(u64);

impl Cases {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn signed(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }
    fn direction(&mut self) -> [f64; 3] {
        loop {
            let d = [self.signed(), self.signed(), self.signed()];
            let n = norm(d);
            if n > 0.1 && n <= 1.0 {
                return d.map(|c| c / n);
            }
        }
    }
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn main() {
    let arg = |i: usize, default: u64| {
        std::env::args()
            .nth(i)
            .and_then(|s| s.parse().ok())
            .unwrap_or(default)
    };
    let (cases, seed) = (arg(1, 20_000), arg(2, 5));
    let mut rng = Cases(seed);
    let mut need = [[0.0f64; RHO_BINS]; SPEED_BINS];
    let mut share = [0.0f64; SPEED_BINS];
    let mut spans = [0usize; SPEED_BINS];
    for case in 0..cases {
        let a = 0.5 + 1.5 * rng.unit();
        let m = Metric::Godel(Godel::new(a));
        let at_rest = case % 5 == 0;
        let speed = if at_rest { 0.0 } else { 0.8 * rng.unit() };
        let radius = (0.02 + 0.48 * rng.unit()) * a;
        let (r, phi) = (1.8 * a * rng.unit(), TAU * rng.unit());
        let position = Event::new(0.0, r * phi.cos(), r * phi.sin(), 0.3 * a * rng.signed());
        let motion = if at_rest {
            scene::Motion::Rest { position }
        } else {
            let velocity = LocalVelocity::new(speed, rng.direction()).expect("below c");
            scene::Motion::Geodesic {
                start: position,
                velocity,
            }
        };
        let object = scene::Object {
            name: "ball".into(),
            frame: scene::ObjectFrame::Local,
            shape: scene::Shape::Sphere { radius },
            texture: scene::TextureSpec::Gradient,
            temperature: 5800.0,
            motion,
            polarization: None,
        };
        let target = Target::new(m, &object, -20.0 * a, 20.0 * a).expect("a worldline");
        let Target::LocalSphere { worldline, .. } = &target else {
            unreachable!("a sphere")
        };
        // A ray through a point of the centre's rest space within 0.45a of it.
        let p = worldline.at(&m, 0.0).expect("the start");
        let (off, d) = (0.45 * a * rng.unit(), rng.direction());
        let x0 = p.event.offset(p.frame.spatial(d), off);
        let n = rng.direction();
        let k = m.static_frame(x0).vector([-1.0, n[0], n[1], n[2]]);
        let Some(ray) = ExactGeodesic::new(a, x0, k) else {
            continue;
        };
        let (energy, s) = (m.lower(x0, k).t.abs(), worldline.speed_factor());
        let h = 0.004 * a / (energy * s);
        let far = 0.25 * a + radius;
        // Rest-frame coordinates where the search's probe would be near, each match seeded by
        // the previous one.
        let mut seed = f64::NAN;
        let xi: Vec<Option<[f64; 3]>> = (-300..=300)
            .map(|i| {
                let x = ray.at(i as f64 * h).0;
                let guess = if seed.is_finite() {
                    seed
                } else {
                    worldline.tau_guess(x.t)
                };
                let near = matches!(
                    worldline.localize(&m, x, guess, far),
                    Some(Located::Near(_))
                );
                let lp = worldline
                    .localize(&m, x, guess, f64::INFINITY)
                    .and_then(|l| l.near());
                seed = lp.map_or(f64::NAN, |l| l.at.tau);
                lp.filter(|_| near).map(|l| l.xi)
            })
            .collect();
        let bin = if at_rest {
            0
        } else {
            (1 + (speed * 20.0) as usize).min(SPEED_BINS - 1)
        };
        let unit = (energy * s).powi(2) / a;
        for len in [2usize, 4, 8, 16, 32, 64, 128, 256] {
            let span = len as f64 * h;
            for i in (0..xi.len().saturating_sub(len)).step_by(3) {
                let (Some(xa), Some(xb)) = (xi[i], xi[i + len]) else {
                    continue;
                };
                let points: Option<Vec<(f64, f64)>> = (1..len)
                    .map(|j| {
                        let f = j as f64 / len as f64;
                        let x = xi[i + j]?;
                        Some((
                            norm([0, 1, 2].map(|c| x[c] - (xa[c] + f * (xb[c] - xa[c])))),
                            f,
                        ))
                    })
                    .collect();
                let Some(points) = points else { continue };
                let ends = norm(xa).max(norm(xb));
                let rho = ((ends / a) / 0.05) as usize;
                // Spans too long for any bound near these (stray ≤ 0.05a at K = 0.2) say
                // nothing the search uses.
                if rho < RHO_BINS && 0.2 * unit * span * span / 8.0 <= 0.05 * a {
                    let k = points
                        .iter()
                        .map(|&(dev, f)| 8.0 * dev / (4.0 * f * (1.0 - f)) / (span * span))
                        .fold(0.0, f64::max);
                    need[bin][rho] = need[bin][rho].max(k / unit);
                }
                if let Some(stray) = chord::stray(a, at_rest, s, energy, ends, span) {
                    let dev = points.iter().map(|p| p.0).fold(0.0, f64::max);
                    share[bin] = share[bin].max(dev / stray);
                    spans[bin] += 1;
                }
            }
        }
    }
    println!("{cases} balls (seed {seed}): the bend K spans need, in (E s)^2/a");
    print!("{:>10}", "ρ/a <");
    for r in 0..RHO_BINS {
        print!(" {:>6.2}", 0.05 * (r + 2) as f64);
    }
    println!("  | largest stray / bound (spans)");
    for (bin, row) in need.iter().enumerate() {
        let label = if bin == 0 {
            "at rest".to_string()
        } else {
            format!("< {:.2} c", 0.05 * bin as f64)
        };
        print!("{label:>10}");
        for k in row {
            print!(" {k:>6.2}");
        }
        println!("  | {:.2} ({})", share[bin], spans[bin]);
    }
}
