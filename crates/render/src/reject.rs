//! Whole-ray rejection of objects at rest: one O(1) test per ray and object, in place of
//! the per-segment search, for every loop of the ray at once (docs/physics.md, "Whole-ray
//! rejection").
//!
//! In the disc coordinate w of the static observers' space (docs/physics.md, "The Gödel
//! metric": the Poincaré disc of curvature −1/a², times the z line), the spatial
//! projection of a light ray through the origin is a hyperbolic circle through the origin:
//! its farthest point w_max (θ = π/2 in "Closed forms") lies at proper distance
//! 2a·asinh(r_max/2a), the circle's hyperbolic centre h halfway, its radius
//! ρ = a·asinh(r_max/2a). The ray moves along it at the constant h-speed √(E² − p_z²), so
//! the angle about h grows linearly in λ, one turn per return parameter λ_ret; later loops
//! retrace it. The observer's isometry to the origin (the exact tracer's) carries each
//! ball's centre C to the origin frame once per render. Then the static distance
//! D = √(d_H² + Δz²) (d_H = 2a·atanh|(w − w_C)/(1 − w̄_C w)|) from the ray to C satisfies,
//! with δ the angle at h between the ray point and C (hyperbolic law of cosines),
//!
//!   cosh(d_H/a) = cosh(d_hC/a)·cosh(ρ/a) − sinh(d_hC/a)·sinh(ρ/a)·cos δ,
//!
//! and Δz = p_z λ − z_C is linear in λ. The ray is rejected when, over the λ window where
//! |Δz| ≤ reach, the least d_H exceeds the [`reach`] R·(1 + [`REACH_CURVATURE`]·(R/a)²):
//! the renderer's ball (second-order normal coordinates, `worldline.rs`) lies within that
//! static distance of its centre (a property test measures the ratio).
//!
//! A ball the test keeps is searched, by the exact tracer and the shadow rays, only on the
//! stretches of the ray that may come within the reach ([`StaticBall::near`], docs/physics.md
//! "The stretches near a ball"): the z window, on the arcs of the circle ([`crate::circle`]).
//!
//! Planes z = h (coordinate objects, static): along a closed-form ray z is linear in λ, so
//! the ray crosses the plane at most once, where p_z λ = h − z_0; a ray that keeps a clear
//! side over the whole stretch searched never crosses it.

use crate::circle::{moved, RayCircle, Stretches};
use crate::falling::FallingBall;
use crate::intersect::Probes;
use crate::target::Target;
use crate::worldline::Worldline;
use spacetime::isometry::disc;
use spacetime::{Complex, Event, Godel, Isometry, Metric, OriginGeodesic};
use std::f64::consts::{PI, TAU};

/// How much farther than |ξ| a point of the renderer's ball at rest lies in static distance
/// D, per (|ξ|/a)²: the ball |ξ| ≤ R (ξ in second-order normal coordinates, R ≤ a/2 by scene
/// validation) lies within D ≤ (1 + c·(R/a)²)·R of its centre, where c = 0.104 was the worst
/// found (centres out to 40a; the property test `a_static_ball_lies_within_its_reach`
/// asserts c = 0.15). The reach takes 0.25: a ray kept out by it stays outside the ball by
/// at least 0.1·(R/a)²·R.
pub const REACH_CURVATURE: f64 = 0.25;

/// The reach of a ball at rest of radius `radius` in Gödel's universe with parameter `a`:
/// the static distance from its centre beyond which no ray point is inside it.
pub fn reach(radius: f64, a: f64) -> f64 {
    radius * (1.0 + REACH_CURVATURE * (radius / a).powi(2)) + REACH_PER_A * a
}

/// Added to the reach, per a: covers the numeric tracer's deviation from the closed form
/// (it rejects only at tolerances ≤ [`NUMERIC_TOLERANCE`]) for balls of any size.
pub const REACH_PER_A: f64 = 1e-6;

/// The numeric tracer uses the rejection only at integration tolerances up to this.
pub const NUMERIC_TOLERANCE: f64 = 1e-9;

/// An object whose whole-ray test [`Rejection::misses`] can leave it out of a ray's search.
#[derive(Clone, Debug)]
pub enum Rejection {
    Ball(StaticBall),
    /// A plane at height `z` in the origin frame (its extent ignored: conservative).
    Plane {
        z: f64,
    },
    /// A ball in free fall: rejected loop by loop (`crate::falling`).
    Falling(FallingBall),
}

impl Rejection {
    /// The rejection test of `target` for rays from the place of `from` (see
    /// [`StaticBall::new`]; for a ball in free fall also its time), in Gödel's universe with
    /// parameter `a`; None for coordinate spheres.
    pub fn new(a: f64, from: Event, target: &Target) -> Option<Rejection> {
        match target {
            Target::Plane { height, .. } => Some(Rejection::Plane { z: height - from.z }),
            _ => StaticBall::new(a, from, target)
                .map(Rejection::Ball)
                .or_else(|| {
                    FallingBall::new(a, &Metric::Godel(Godel::new(a)), from, target)
                        .map(Rejection::Falling)
                }),
        }
    }

    /// Whether the closed-form light ray `geo` from the origin, over λ ∈ [0, until], provably
    /// never enters the object's surface (see [`StaticBall::misses`]). A plane: the
    /// signed height p_z λ − z keeps one side, clear of the plane by more than rounding, at
    /// both ends (it is linear in λ).
    /// A ball in free fall: never (see [`set_ray`] for its test, loop by loop).
    pub fn misses(&self, geo: &OriginGeodesic, until: f64) -> bool {
        match *self {
            Rejection::Ball(b) => b.misses(geo, until),
            Rejection::Falling(_) => false,
            Rejection::Plane { z } => {
                let f0 = -z;
                let (f1, span) = if until.is_finite() {
                    (geo.pz * until - z, (geo.pz * until).abs())
                } else if geo.pz == 0.0 {
                    (f0, 0.0)
                } else {
                    (geo.pz * f64::INFINITY, 0.0)
                };
                let clear = 1e-9 * (1.0 + z.abs() + span);
                f0.abs() > clear && f1.abs() > clear && (f0 > 0.0) == (f1 > 0.0)
            }
        }
    }
}

/// A ball at rest, seen from the observer's origin frame.
#[derive(Clone, Copy, Debug)]
pub struct StaticBall {
    a: f64,
    /// Disc coordinate and height of the centre in the origin frame.
    w: Complex,
    z: f64,
    /// Static distance beyond which no ray point is inside.
    reach: f64,
}

/// The static distance √(d_H² + Δz²) between two points (x, y, z) of the static observers'
/// space (H² × R; docs/physics.md, "The Gödel metric").
pub fn static_distance(a: f64, p: [f64; 3], q: [f64; 3]) -> f64 {
    let m = moved(disc(a, p[0], p[1]), disc(a, q[0], q[1]));
    let dh = 2.0 * a * m.norm_sqr().sqrt().atanh();
    dh.hypot(q[2] - p[2])
}

impl StaticBall {
    /// The ball of `target` as seen from the origin frame of `from` (the start of the rays:
    /// an observer, or a light at rest: only its place matters), if it is a local ball at
    /// rest in Gödel's universe with parameter `a` (None otherwise).
    pub fn new(a: f64, from: Event, target: &Target) -> Option<StaticBall> {
        let Target::LocalSphere {
            radius,
            worldline: Worldline::Rest { position, .. },
        } = target
        else {
            return None;
        };
        let c = Isometry::to_origin(a, from).apply(*position);
        Some(StaticBall {
            a,
            w: disc(a, c.x, c.y),
            z: c.z,
            reach: reach(*radius, a),
        })
    }

    /// The same ball searched out to the static distance `reach` (the GPU kernel's, for
    /// comparing their tests).
    pub fn with_reach(self, reach: f64) -> StaticBall {
        StaticBall { reach, ..self }
    }

    /// The stretches of the light ray of circle `ray` (through the origin), over
    /// λ ∈ [0, until], that may come within the reach of the centre: the λ window where
    /// |p_z λ − z_C| ≤ reach, on the arcs of the circle within the reach of w_C (the static
    /// distance is at least the disc's). None where it provably stays farther; everywhere
    /// when unsure (NaN).
    pub fn near(&self, ray: &RayCircle, until: f64) -> Option<Stretches> {
        let (lo, hi) = if ray.pz == 0.0 {
            if self.z.abs() > self.reach {
                return None;
            }
            (0.0, until)
        } else {
            let (l1, l2) = (
                (self.z - self.reach) / ray.pz,
                (self.z + self.reach) / ray.pz,
            );
            (l1.min(l2).max(0.0), l1.max(l2).min(until))
        };
        if hi < lo {
            return None;
        }
        let nw = 1.0 - self.w.norm_sqr();
        let arc = ray.arc(self.w, nw, (self.reach / self.a).cosh())?;
        let near = Stretches {
            arc,
            lo,
            hi,
            pz: ray.pz,
            z: self.z,
            reach: self.reach,
            a: self.a,
        };
        (lo.is_nan() || hi.is_nan() || near.meets(lo, hi)).then_some(near)
    }

    /// Whether the light ray `geo` (through the origin), over λ ∈ [0, until] (all its loops
    /// with `until` = ∞), provably stays farther than the reach from the centre. False when
    /// unsure (NaN included).
    pub fn misses(&self, geo: &OriginGeodesic, until: f64) -> bool {
        let (a, reach) = (self.a, self.reach);
        // The λ window where |p_z λ − z_C| ≤ reach.
        let (lo, hi) = if geo.pz == 0.0 {
            if self.z.abs() > reach {
                return true;
            }
            (0.0, until)
        } else {
            let (l1, l2) = ((self.z - reach) / geo.pz, (self.z + reach) / geo.pz);
            (l1.min(l2).max(0.0), l1.max(l2).min(until))
        };
        if hi < lo {
            return true;
        }
        // The ray's circle: farthest point in the direction χ + sgn(E)·π/2.
        let sg = geo.energy.signum();
        let (c, s) = geo.cis_chi();
        let dir = Complex::new(-sg * s, sg * c);
        let (sinh_rho, cosh_rho, h_abs) = geo.circle();
        let rho = a * sinh_rho.asinh(); // d(0, w_max)/2
        let h = dir.scale(h_abs);
        let mc = moved(h, self.w);
        let d_hc = 2.0 * a * mc.norm_sqr().sqrt().atanh();
        let nearest = (d_hc - rho).abs();
        if nearest > reach {
            return true;
        }
        let l_ret = geo.return_parameter();
        if !(hi - lo < l_ret) {
            return false;
        }
        // Angle about h: the origin's at λ = 0, then sgn(E)·2π per loop.
        let alpha0 = (Complex::new(0.0, 0.0) - h).arg();
        let delta = |l: f64| alpha0 + sg * TAU * l / l_ret - mc.arg();
        let (d1, d2) = (delta(lo), delta(hi));
        let (dmin, dmax) = (d1.min(d2), d1.max(d2));
        if (dmin / TAU).ceil() * TAU <= dmax {
            return false; // the window passes the circle's point nearest the centre
        }
        let cos = |d: f64| (d - TAU * (d / TAU).round()).clamp(-PI, PI).cos();
        let cos_d = cos(d1).max(cos(d2));
        let x = d_hc / a;
        let cosh_d = x.cosh() * cosh_rho - x.sinh() * sinh_rho * cos_d;
        a * cosh_d.max(1.0).acosh() > reach
    }
}

/// The only stretch of the closed-form light ray `geo` from the origin (λ from its start)
/// where it can cross the plane at height `z` of the origin frame: its z = p_z λ is linear,
/// so around λ = z/p_z, widened far beyond rounding (10⁻⁹ of the height's scale, in z). None
/// (all along) for a ray that keeps its height.
fn plane_crossing(z: f64, geo: &OriginGeodesic) -> Option<(f64, f64)> {
    if !(geo.pz != 0.0 && geo.pz.is_finite() && z.is_finite()) {
        return None;
    }
    let margin = 1e-9 * (geo.a + z.abs());
    let (l1, l2) = ((z - margin) / geo.pz, (z + margin) / geo.pz);
    Some((l1.min(l2), l1.max(l2)))
}

/// Sets, for the closed-form ray `geo` from the start of the rays (its time `t_start`
/// after the `from` event of the tests), over λ ∈ [0, until], which objects it searches
/// ([`Probes::on_ray`]), for balls in free fall which stretch of each loop
/// ([`Probes::loops`]) and, with `stretches` (rays whose λ is the closed form's: the exact
/// tracer's and the shadow rays), for balls at rest in which stretches ([`Probes::near`])
/// and for planes around which λ ([`Probes::crossing`]).
/// A loop's stretch of a ball in free fall starts where the ray may first come near it with
/// `stretches`, at the loop's start otherwise.
/// With no closed form (`None`: not Gödel's universe) or no test, an object is searched all
/// along.
pub fn set_ray(
    rejections: &[Option<Rejection>],
    geo: Option<&OriginGeodesic>,
    t_start: f64,
    until: f64,
    stretches: bool,
    probes: &mut Probes,
) {
    let circle = geo
        .filter(|_| {
            rejections.iter().any(|r| match r {
                Some(Rejection::Falling(_)) => true,
                Some(Rejection::Ball(_)) => stretches,
                _ => false,
            })
        })
        .map(RayCircle::new);
    probes.loop_length = match &circle {
        Some(c) if stretches => c.l_ret,
        _ => f64::NAN,
    };
    for i in 0..probes.on_ray.len() {
        let (on, by_loop, near) = match (rejections.get(i).and_then(Option::as_ref), geo, &circle) {
            (Some(Rejection::Falling(f)), Some(_), _) => {
                let sure = circle
                    .as_ref()
                    .is_some_and(|c| f.loops(c, t_start, until, !stretches, &mut probes.loops[i]));
                (!sure || !probes.loops[i].is_empty(), sure, None)
            }
            // A ball at rest: only its stretches, which are its whole-ray test too (none:
            // left out).
            (Some(Rejection::Ball(b)), Some(_), Some(c)) if stretches => {
                let near = b.near(c, until);
                (near.is_some(), false, near)
            }
            (Some(r), Some(g), _) => (!r.misses(g, until), false, None),
            _ => (true, false, None),
        };
        probes.crossing[i] = match (rejections.get(i).and_then(Option::as_ref), geo) {
            (Some(Rejection::Plane { z }), Some(g)) if stretches && on => plane_crossing(*z, g),
            _ => None,
        };
        probes.near[i] = near;
        probes.on_ray[i] = on;
        probes.by_loop[i] = by_loop;
    }
}
