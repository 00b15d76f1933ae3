//! A Gödel light ray's spatial projection as a circle of the hyperbolic disc, with the
//! λ-stretches where it may pass within a given distance of a point (docs/physics.md,
//! "Whole-ray rejection" for the circle, "Balls in free fall" for the stretches).
//!
//! In the disc coordinate w of the static observers' space (curvature −1/a²), the light ray
//! through the origin with the closed form of "Closed forms" runs along the hyperbolic
//! circle with centre h (halfway to its farthest point) and radius ρ = a·asinh(r_max/2a),
//! its angle about h growing by sgn(E)·2π per return parameter λ_ret. A point w at
//! distance d from h and a ray point at angle δ from w's direction (seen from h) are at
//! distance d_H with cosh(d_H/a) = cosh(d/a)·cosh(ρ/a) − sinh(d/a)·sinh(ρ/a)·cos δ, so
//! d_H ≤ m exactly on an arc |δ| ≤ A of every turn.

use crate::angles;
use spacetime::{Complex, OriginGeodesic};
use std::f64::consts::{PI, SQRT_2, TAU};

/// Added to the half-width of an arc (radians): the error of its centre's direction (within
/// [`angles::ERROR`]) and the rounding of the angles.
const ARC_SLACK: f64 = angles::ERROR + 1e-9;

/// The Möbius image (w − c)/(1 − c̄ w) of w (c moved to the disc's centre).
pub fn moved(c: Complex, w: Complex) -> Complex {
    (w - c) / (Complex::new(1.0, 0.0) - c.conj() * w)
}

/// The circle of one light ray through the origin (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub struct RayCircle {
    h: Complex,
    /// 1 − |h|².
    nh: f64,
    cosh_rho: f64,
    sinh_rho: f64,
    /// sgn(E) times the angle of the origin about h (λ = 0).
    psi0: f64,
    /// sgn(E).
    sg: f64,
    /// Return parameter λ_ret: one turn.
    pub l_ret: f64,
    /// 1/λ_ret: an arc's copies are counted by products.
    per_turn: f64,
    /// dz/dλ.
    pub pz: f64,
    /// Coordinate time gained per turn in the origin frame:
    /// sgn(E)·2√2·a·π − E·λ_ret (t = sgn(E)·2√2·a·Φ(θ) − Eλ, Φ gains π per turn).
    pub dt_loop: f64,
    /// The closed form itself: its time along the ray (`crate::falling`).
    pub geo: OriginGeodesic,
}

impl RayCircle {
    pub fn new(geo: &OriginGeodesic) -> RayCircle {
        let a = geo.a;
        let sg = geo.energy.signum();
        let (c, s) = geo.cis_chi();
        // The farthest point lies in the direction χ + sgn(E)·π/2.
        let dir = Complex::new(-sg * s, sg * c);
        let (sinh_rho, cosh_rho, h_abs) = geo.circle();
        let h = dir.scale(h_abs);
        let l_ret = geo.return_parameter();
        RayCircle {
            h,
            nh: 1.0 - h.norm_sqr(),
            cosh_rho,
            sinh_rho,
            psi0: sg * (Complex::new(0.0, 0.0) - h).arg(),
            sg,
            l_ret,
            per_turn: 1.0 / l_ret,
            pz: geo.pz,
            dt_loop: sg * 2.0 * SQRT_2 * a * PI - geo.energy * l_ret,
            geo: *geo,
        }
    }

    /// Where the ray's projection may lie within hyperbolic distance m of the disc point `w`
    /// (given `nw` = 1 − |w|² and `cosh_m` = cosh(m/a)), in λ from the ray's start: None
    /// only when it provably lies farther all round the circle; everywhere when unsure (NaN).
    pub fn arc(&self, w: Complex, nw: f64, cosh_m: f64) -> Option<Arc> {
        self.arc_of(self.passes(w, nw, cosh_m)?, cosh_m)
    }

    /// The disc point `w` (given `nw` = 1 − |w|²) unless the ray's projection provably lies
    /// farther than m (given `cosh_m` = cosh(m/a)) from it all round: the cheap half of
    /// [`RayCircle::arc`], before the angles (most points are rejected here).
    pub fn passes(&self, w: Complex, nw: f64, cosh_m: f64) -> Option<Passing> {
        let (nearest, spread) = self.law_of_cosines(w, nw);
        (!beyond_all_round(nearest, spread, cosh_m)).then_some(Passing { w, nearest, spread })
    }

    /// [`RayCircle::arc`] of a point that [`RayCircle::passes`] kept, for the same m.
    pub fn arc_of(&self, p: Passing, cosh_m: f64) -> Option<Arc> {
        // ψ(λ) = sgn(E)·δ(λ) = ψ₀ − sgn(E)·β + 2πλ/λ_ret, β the angle of w about h: the ray
        // is nearest w where ψ is a whole number of turns.
        // arg((w − h)/(1 − h̄w)) = arg((w − h)·conj(1 − h̄w)): no division.
        let d = Complex::new(1.0, 0.0) - self.h.conj() * p.w;
        let m = (p.w - self.h) * d.conj();
        let beta = angles::atan2(m.im, m.re);
        let turns = (self.sg * beta - self.psi0) * (1.0 / TAU);
        let arc = Arc {
            centre: (turns - turns.floor()) * self.l_ret,
            half: f64::INFINITY,
            period: self.l_ret,
            per_turn: self.per_turn,
            nearest: p.nearest,
            spread: p.spread,
        };
        arc.within(cosh_m)
    }

    /// Whether the ray's projection provably lies farther than m from the disc point `w` all
    /// round (given `nw` = 1 − |w|² and `cosh_m` = cosh(m/a)): [`RayCircle::arc`]'s None,
    /// without the angle it finds otherwise.
    pub fn beyond(&self, w: Complex, nw: f64, cosh_m: f64) -> bool {
        self.passes(w, nw, cosh_m).is_none()
    }

    /// cosh(d/a)·cosh(ρ/a) and sinh(d/a)·sinh(ρ/a), d the distance from h to `w`
    /// ([`Arc`]'s `nearest` and `spread`), with cosh(d/a) = 1 + 2|h − w|²/((1 − |h|²)(1 − |w|²)).
    fn law_of_cosines(&self, w: Complex, nw: f64) -> (f64, f64) {
        let ch = 1.0 + 2.0 * (w - self.h).norm_sqr() / (self.nh * nw);
        let sh = (ch * ch - 1.0).max(0.0).sqrt();
        (ch * self.cosh_rho, sh * self.sinh_rho)
    }
}

/// A disc point near which a ray's circle may pass ([`RayCircle::passes`]), with its law of
/// cosines' terms ([`Arc`]'s `nearest` and `spread`).
#[derive(Clone, Copy, Debug)]
pub struct Passing {
    w: Complex,
    nearest: f64,
    spread: f64,
}

/// Whether a ray's circle lies beyond distance m (given cosh(m/a)) of a point all round, from
/// the law of cosines' `nearest` and `spread` ([`Arc`]): cos δ would have to exceed 1.
fn beyond_all_round(nearest: f64, spread: f64, cosh_m: f64) -> bool {
    let num = nearest - cosh_m;
    num.is_finite() && spread.is_finite() && num > spread
}

/// The λ-stretches of a ray (from its start) near a point: [c − half, c + half] and its
/// copies a loop apart ([`RayCircle::arc`]).
#[derive(Clone, Copy, Debug)]
pub struct Arc {
    centre: f64,
    half: f64,
    period: f64,
    /// 1/period: the arcs' copies are counted by products.
    per_turn: f64,
    /// cosh(d(h, w)/a)·cosh(ρ/a) and sinh(d(h, w)/a)·sinh(ρ/a): by the law of cosines
    /// cosh(d_H/a) = nearest − spread·cos δ ([`Arc::within`]).
    nearest: f64,
    spread: f64,
}

impl Arc {
    /// The arc of the same ray and point for the distance m (given cosh(m/a)): |δ| ≤ A with
    /// cos A = (cosh(d(h, w)/a)·cosh(ρ/a) − cosh(m/a))/(sinh(d(h, w)/a)·sinh(ρ/a)). None when
    /// the ray lies farther all round; everywhere when unsure (NaN).
    pub fn within(&self, cosh_m: f64) -> Option<Arc> {
        let everywhere = Arc {
            half: f64::INFINITY,
            ..*self
        };
        let num = self.nearest - cosh_m;
        let den = self.spread;
        if !(num.is_finite() && den.is_finite()) {
            return Some(everywhere);
        }
        if num <= -den {
            return Some(everywhere); // within m all round the circle
        }
        if beyond_all_round(self.nearest, den, cosh_m) {
            return None;
        }
        let half = (num / den).clamp(-1.0, 1.0).acos() + ARC_SLACK;
        let arc = Arc {
            half: half * self.period * (1.0 / TAU),
            ..*self
        };
        if arc.centre.is_finite() && arc.half.is_finite() && arc.period > 0.0 {
            Some(arc)
        } else {
            Some(everywhere)
        }
    }

    /// Whether the stretches lie apart, each shorter than half a loop (false when unsure:
    /// NaN); else a stretch is taken to cover every λ.
    fn apart(&self) -> bool {
        self.half < 0.5 * self.period
    }

    /// The number n of the first copy (centred at centre + n·period) whose stretch ends at
    /// or after lo.
    fn first_copy(&self, lo: f64) -> f64 {
        ((lo - self.half - self.centre) * self.per_turn).ceil()
    }

    /// The number n of the last copy whose stretch starts at or before hi.
    fn last_copy(&self, hi: f64) -> f64 {
        ((hi + self.half - self.centre) * self.per_turn).floor()
    }

    /// The centre of copy n.
    fn copy_centre(&self, n: f64) -> f64 {
        self.centre + n * self.period
    }

    /// Whether [lo, hi] meets a stretch (true when unsure: NaN).
    pub fn meets(&self, lo: f64, hi: f64) -> bool {
        if !self.apart() {
            return true;
        }
        !(self.copy_centre(self.first_copy(lo)) - self.half > hi)
    }

    /// The smallest λ in [lo, hi] on a stretch.
    pub fn first_in(&self, lo: f64, hi: f64) -> Option<f64> {
        if !self.apart() {
            return Some(lo);
        }
        let l = lo.max(self.copy_centre(self.first_copy(lo)) - self.half);
        if l.is_nan() {
            Some(lo)
        } else {
            (l <= hi).then_some(l)
        }
    }

    /// The largest λ in [lo, hi] on a stretch.
    pub fn last_in(&self, lo: f64, hi: f64) -> Option<f64> {
        if !self.apart() {
            return Some(hi);
        }
        let l = hi.min(self.copy_centre(self.last_copy(hi)) + self.half);
        if l.is_nan() {
            Some(hi)
        } else {
            (l >= lo).then_some(l)
        }
    }
}

/// The stretches of a ray near a point at rest, within static distance `reach` of it: the
/// arcs of its circle ([`Arc`], for the reach) within the λ window [lo, hi] where its height
/// p_z λ is within the reach of the point's `z`; where the height differs by Δz, only the
/// arcs within √(reach² − Δz²) (the static distance is √(d_H² + Δz²)).
#[derive(Clone, Copy, Debug)]
pub struct Stretches {
    pub arc: Arc,
    pub lo: f64,
    pub hi: f64,
    pub pz: f64,
    pub z: f64,
    pub reach: f64,
    /// The curvature scale a (the arcs' distances are in units of it).
    pub a: f64,
}

impl Stretches {
    /// The λ in [0, until] where the ray most likely passes deepest into a ball of static
    /// radius `radius` about the point, one per copy of the arc (at most `most`, earliest
    /// first), where the static distance there is less than `radius`: the least of
    /// D² ≈ d₀² + a²·S·δ² + (p_z λ − z)² (d_H² to second order in the angle δ about h from
    /// the point's direction, for a ray that passes near it: S is the law of cosines'
    /// spread), then D at that λ from the law of cosines itself (docs/physics.md, "Aimed
    /// occlusion"). A guess for a probe to verify, not a bound.
    pub fn deepest(&self, until: f64, radius: f64, most: usize) -> impl Iterator<Item = f64> {
        let arc = self.arc;
        let (lo, hi) = (self.lo.max(0.0), self.hi.min(until));
        let usable = arc.apart() && lo <= hi && arc.spread > 0.0;
        let omega = TAU * arc.per_turn;
        let k = self.a * self.a * arc.spread * omega * omega;
        let (a, pz, z) = (self.a, self.pz, self.z);
        let pz2 = pz * pz;
        let first = arc.first_copy(lo);
        let copies = if usable {
            ((arc.last_copy(hi) - first + 1.0).max(0.0) as usize).min(most)
        } else {
            0
        };
        (0..copies).filter_map(move |n| {
            let centre = arc.copy_centre(first + n as f64);
            // With p_z = 0 the height does not move the least distance off the arc's centre.
            let l = if pz2 > 0.0 {
                (k * centre + pz2 * (z / pz)) / (k + pz2)
            } else {
                centre
            };
            let l = l
                .max(centre - arc.half)
                .min(centre + arc.half)
                .max(lo)
                .min(hi);
            let cosh_d = arc.nearest - arc.spread * (omega * (l - centre)).cos();
            let dh = a * cosh_d.max(1.0).acosh();
            (dh.hypot(pz * l - z) < radius).then_some(l)
        })
    }

    /// Whether [l0, l1] (λ from the ray's start) meets a stretch (true when unsure: NaN).
    pub fn meets(&self, l0: f64, l1: f64) -> bool {
        if l1 < self.lo || l0 > self.hi {
            return false;
        }
        let (l0, l1) = (l0.max(self.lo), l1.min(self.hi));
        if !self.arc.meets(l0, l1) {
            return false;
        }
        // The least |Δz| over [l0, l1] (z is linear in λ): the disc's distance must be
        // within √(reach² − Δz²) there.
        let (z0, z1) = (self.pz * l0 - self.z, self.pz * l1 - self.z);
        let dz = if (z0 > 0.0) != (z1 > 0.0) {
            0.0
        } else {
            z0.abs().min(z1.abs())
        };
        if !(dz > 0.0) {
            return true; // the whole reach (or unsure: NaN)
        }
        let m = (self.reach * self.reach - dz * dz).max(0.0).sqrt();
        self.arc
            .within((m / self.a).cosh())
            .is_some_and(|arc| arc.meets(l0, l1))
    }
}
