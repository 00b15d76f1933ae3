//! Exact geodesics of the Gödel-type family (`GodelType`): closed forms through the origin
//! for every m² and every causal tangent, carried to any event by the isometries of
//! [`crate::godel_type_symmetry`] (docs/physics.md, "The Gödel-type family", subsection
//! "Closed-form geodesics of the family"). The Gödel member's version is `closed_form.rs`,
//! whose conventions this file follows.
//!
//! From the origin, with tangent k = (E, k⊥ cos χ, k⊥ sin χ, p_z) (the metric is Minkowski
//! there), L = 0 and the first integrals E = ṫ + H φ̇, 0 = −H E + D² φ̇, p_z = ż give, with
//! A = k⊥² = E² − κ − p_z² (κ = −g(k, k)), c = m² A/4 and
//!
//!   Λ = Ω² E² − c   (Λ > 0 returning, Λ = 0 the boundary B = A, Λ < 0 escaping; m² ≤ 0 always
//!   returns),  C1 = cos √Λ λ,  S1 = sin(√Λ λ)/√Λ   (cosh, sinh for Λ < 0; 1, λ at Λ = 0),
//!
//! the closed forms (v = c S1² = sinh²(mρ/2), or −sin²(μρ/2) for m² = −μ²):
//!
//!   ρ = k⊥ S1 F(v),  F(v) = asinh(√v)/√v   (asin for v < 0; ρ is signed, as in closed_form.rs),
//!   φ = χ + sgn(E) Φ,  Φ = arg(C1 + i Ω|E| S1)   continued in λ,
//!   t = E λ − Ω² E A J,  J = ∫ S1²/(1 + v) dλ = (λ − Φ/(Ω|E|))/c,
//!   z = p_z λ,
//!
//! and the tangent ρ̇ = k⊥ C1/√(1 + v), φ̇ = Ω E/(1 + v), ṫ = E − Ω² E A S1²/(1 + v).
//! (Derivation: φ̇ = HE/D² = ΩE/(1 + v) and ρ̇² = A − H²E²/D² give d²w/dλ² = −Λ w for
//! w = sinh(mρ/2), so w = (m/2) k⊥ S1.) For Gödel (m² = 1/a², Ω = 1/(√2 a)) Λ = ω² and these
//! are closed_form.rs's formulas with r = 2a sinh(ρ/2a).
//!
//! J's form (λ − Φ/(Ω|E|))/c loses digits as c → 0 (m² → 0). Where Λ > 0 and ε = c/Λ ≤ 1,
//! J = K/Λ^{3/2} with θ = √Λ λ, q = √(1 + ε) = Ω|E|/√Λ and
//!
//!   K = ∫₀^θ sin²/(1 + ε sin²) = [θ/(1 + q) − atan(ε z)/ε]/q,
//!   z = sin θ cos θ/((1 + q)(cos²θ + q sin²θ)),
//!
//! which has no cancellation as ε → 0 (K → θ/2 − sin θ cos θ/2). Elsewhere c > Ω²E²/2 and the
//! plain form loses at most a factor 2.
//!
//! In the base coordinate ζ of [`crate::godel_type_symmetry`] the projection is the circle
//! ζ = sgn(E) i R e^{iχ} (1 − e^{iψ}), R = k⊥/(2Ω|E|), ψ = 2 sgn(E) Φ, for every m² (of
//! geodesic curvature 2Ω|E|/k⊥: a circle, horocycle or hypercycle of the base). On the
//! sphere this circle gives the continuous branch of the time shift of the map back from
//! the origin (its principal arg jumps across a cut; see [`TypeExactGeodesic`]).
//!
//! For escaping rays the formulas hold until cosh(√−Λ λ)² overflows, at mρ ≈ 700, where the
//! metric's own sinh(mρ) overflows too.

use crate::godel_type::GodelType;
use crate::godel_type_symmetry::{base_coordinate, TypeIsometry};
use crate::isometry::Complex;
use crate::vectors::{Event, FourVector};
use std::f64::consts::PI;

/// How the distance from the axis of a geodesic from the axis behaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeodesicRegime {
    /// Λ > 0: it returns to the axis after π/√Λ (always for m² ≤ 0).
    Returning,
    /// Λ = 0: it escapes, w = sinh(mρ/2) growing linearly.
    Boundary,
    /// Λ < 0: it escapes, w growing exponentially.
    Escaping,
}

/// asinh(√v)/√v (asin(√−v)/√−v for v < 0), 1 at v = 0.
fn asinhc(v: f64) -> f64 {
    let s = v.abs().sqrt();
    if s == 0.0 {
        1.0
    } else if v > 0.0 {
        s.asinh() / s
    } else {
        s.asin() / s
    }
}

/// atan(x)/x, 1 at x = 0.
fn atanc(x: f64) -> f64 {
    if x == 0.0 {
        1.0
    } else {
        x.atan() / x
    }
}

/// The closed-form geodesic of a Gödel-type member through the origin event with a given
/// initial tangent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TypeOriginGeodesic {
    pub member: GodelType,
    /// E = k^t (future-directed ⇔ E > 0).
    pub energy: f64,
    pub pz: f64,
    /// κ = −g(k, k): 0 for light, 1 for a particle parametrized by proper time.
    pub kappa: f64,
    /// k⊥ = √A.
    kperp: f64,
    /// Λ = Ω²E² − m²A/4.
    big_lambda: f64,
    /// (cos χ, sin χ) of the initial direction.
    cis_chi: (f64, f64),
}

/// The functions of λ every quantity is built from.
struct Parts {
    c1: f64,
    s1: f64,
    /// Φ, continuous in λ.
    turn: f64,
    j: f64,
}

impl TypeOriginGeodesic {
    /// The geodesic leaving the origin with tangent `k`. `k` must be causal (null up to
    /// rounding, or timelike with any normalization) and not zero, and Ω > 0; else `None`.
    pub fn new(member: GodelType, k: FourVector) -> Option<Self> {
        let e = k.t;
        let kperp2 = k.x * k.x + k.y * k.y;
        let kappa = e * e - kperp2 - k.z * k.z;
        let ok = k.is_finite()
            && e != 0.0
            && kappa >= -1e-12 * e * e
            && member.omega > 0.0
            && member.omega.is_finite()
            && member.m2.is_finite();
        if !ok {
            return None;
        }
        let spin = member.omega * e.abs();
        Some(TypeOriginGeodesic {
            member,
            energy: e,
            pz: k.z,
            kappa: kappa.max(0.0),
            kperp: kperp2.sqrt(),
            big_lambda: spin * spin - 0.25 * member.m2 * kperp2,
            cis_chi: {
                let (s, c) = k.y.atan2(k.x).sin_cos();
                (c, s)
            },
        })
    }

    /// Ω|E|: the rate at which the projection turns on the axis.
    fn spin(&self) -> f64 {
        self.member.omega * self.energy.abs()
    }

    /// k⊥ = √A, the tangent's part in the base.
    pub fn kperp(&self) -> f64 {
        self.kperp
    }

    /// Λ = Ω²E² − m²A/4, whose sign sets the regime.
    pub fn big_lambda(&self) -> f64 {
        self.big_lambda
    }

    pub fn regime(&self) -> GeodesicRegime {
        if self.big_lambda > 0.0 {
            GeodesicRegime::Returning
        } else if self.big_lambda == 0.0 {
            GeodesicRegime::Boundary
        } else {
            GeodesicRegime::Escaping
        }
    }

    /// The parameter after which the projection is back on the axis, π/√Λ; `None` for a
    /// geodesic that escapes.
    pub fn return_parameter(&self) -> Option<f64> {
        (self.big_lambda > 0.0).then(|| PI / self.big_lambda.sqrt())
    }

    /// The largest distance from the axis, reached at half the return parameter:
    /// ρ_max = k⊥ F(c/Λ)/√Λ; `None` for a geodesic that escapes.
    pub fn rho_max(&self) -> Option<f64> {
        let lam = self.big_lambda;
        let c = 0.25 * self.member.m2 * self.kperp * self.kperp;
        (lam > 0.0).then(|| self.kperp * asinhc(c / lam) / lam.sqrt())
    }

    /// (cos χ, sin χ) of the initial direction χ of the projection.
    pub fn cis_chi(&self) -> (f64, f64) {
        self.cis_chi
    }

    /// The radius R = k⊥/(2Ω|E|) of the projection's circle in the base coordinate ζ.
    pub fn circle_radius(&self) -> f64 {
        self.kperp / (2.0 * self.spin())
    }

    /// Φ(λ): the angle the projection has turned about the axis, times sgn(E).
    pub fn turn(&self, lambda: f64) -> f64 {
        self.parts(lambda).turn
    }

    fn parts(&self, lambda: f64) -> Parts {
        let spin = self.spin();
        let lam = self.big_lambda;
        let c = 0.25 * self.member.m2 * self.kperp * self.kperp;
        if lam > 0.0 {
            let r = lam.sqrt();
            let th = r * lambda;
            let (sn, cs) = th.sin_cos();
            // Φ = θ + arg(cos θ + i q sin θ) e^{−iθ}, both scaled by √Λ (finite as Λ → 0).
            let turn = th + ((spin - r) * sn * cs).atan2(r * cs * cs + spin * sn * sn);
            let eps = c / lam;
            let j = if eps <= 1.0 {
                let q = spin / r;
                let z = sn * cs / ((1.0 + q) * (cs * cs + q * sn * sn));
                let big_k = (th / (1.0 + q) - z * atanc(eps * z)) / q;
                big_k / (lam * r)
            } else {
                (lambda - turn / spin) / c
            };
            Parts {
                c1: cs,
                s1: sn / r,
                turn,
                j,
            }
        } else {
            let (c1, s1) = if lam < 0.0 {
                let r = (-lam).sqrt();
                ((r * lambda).cosh(), (r * lambda).sinh() / r)
            } else {
                (1.0, lambda)
            };
            // Λ ≤ 0 needs c ≥ Ω²E² > 0, and C1 ≥ 1 keeps the principal arctan continuous.
            let turn = (spin * s1 / c1).atan();
            Parts {
                c1,
                s1,
                turn,
                j: (lambda - turn / spin) / c,
            }
        }
    }

    /// Event and tangent at parameter `lambda`.
    pub fn at(&self, lambda: f64) -> (Event, FourVector) {
        let m = self.member;
        let e = self.energy;
        let a = self.kperp * self.kperp;
        let p = self.parts(lambda);
        let v = 0.25 * m.m2 * a * p.s1 * p.s1;
        let rho = self.kperp * p.s1 * asinhc(v);
        let (sb, cb) = (e.signum() * p.turn).sin_cos();
        let (cc, sc) = self.cis_chi;
        let (cp, sp) = (cc * cb - sc * sb, sc * cb + cc * sb);
        let w2 = m.omega * m.omega;
        let event = Event::new(
            e * lambda - w2 * e * a * p.j,
            rho * cp,
            rho * sp,
            self.pz * lambda,
        );
        // d(x + i y)/dλ = (ρ̇ + i ρ φ̇) e^{iφ}.
        let one_v = 1.0 + v;
        let drho = self.kperp * p.c1 / one_v.sqrt();
        let rho_dphi = rho * m.omega * e / one_v;
        let tangent = FourVector::new(
            e - w2 * e * a * p.s1 * p.s1 / one_v,
            drho * cp - rho_dphi * sp,
            drho * sp + rho_dphi * cp,
            self.pz,
        );
        (event, tangent)
    }
}

/// The exact geodesic through any event: the closed form through the origin mapped by the
/// isometry that sends the origin back to the starting event.
///
/// On the sphere (m² < 0) the map back has a time shift −(Ω/k) arg(1 − k ζ̄1 ζ′) whose
/// principal arg jumps by 2π where the projection crosses the map's cut; the geodesic is
/// smooth there, so its t is the principal one plus the multiple of (Ω/k)·2π that follows
/// the continuous arg along the circle ζ′(ψ): 1 − k ζ̄1 ζ′ = α + β e^{iψ}. The geodesic is
/// singular only where its projection passes through the pole opposite the axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TypeExactGeodesic {
    /// T⁻¹: from the origin frame back to the starting event.
    pub back: TypeIsometry,
    pub origin: TypeOriginGeodesic,
    /// (α, β) on the sphere; `None` for m² ≥ 0 (no cut).
    winding: Option<(Complex, Complex)>,
}

impl TypeExactGeodesic {
    /// The geodesic through `at` with tangent `k` (causal, non-zero; `at` in the chart;
    /// else `None`).
    pub fn new(member: GodelType, at: Event, k: FourVector) -> Option<Self> {
        let to = TypeIsometry::to_origin(member, at)?;
        let origin = TypeOriginGeodesic::new(member, to.push(at, k))?;
        let back = to.inverse();
        let winding = (member.m2 < 0.0).then(|| {
            let sg = origin.energy.signum();
            let (cc, sc) = origin.cis_chi;
            let r = origin.circle_radius();
            // The circle's centre sgn(E) i R e^{iχ}.
            let centre = Complex::new(-sg * r * sc, sg * r * cc);
            let beta = (back.zeta0.conj() * centre).scale(0.25 * member.m2);
            (Complex::new(1.0, 0.0) - beta, beta)
        });
        Some(TypeExactGeodesic {
            back,
            origin,
            winding,
        })
    }

    /// (α, β) of the continuous arg on the sphere; `None` for m² ≥ 0.
    pub fn winding(&self) -> Option<(Complex, Complex)> {
        self.winding
    }

    /// Event and tangent at parameter `lambda` (λ = 0 at the starting event).
    pub fn at(&self, lambda: f64) -> (Event, FourVector) {
        let (e0, k0) = self.origin.at(lambda);
        let (mut e, k) = self.back.apply_push(e0, k0);
        if let Some((alpha, beta)) = self.winding {
            let member = self.origin.member;
            let kk = 0.25 * member.m2;
            let psi = 2.0 * self.origin.energy.signum() * self.origin.turn(lambda);
            let continuous = continuous_arg(alpha, beta, psi);
            let zeta = base_coordinate(member, e0.x, e0.y);
            let den = Complex::new(1.0, 0.0) - (self.back.zeta0.conj() * zeta).scale(kk);
            let turns = ((continuous - den.arg()) / (2.0 * PI)).round();
            e.t -= member.omega / kk * 2.0 * PI * turns;
        }
        (e, k)
    }
}

/// arg(α + β e^{iψ}) continued in ψ from 0 at ψ = 0 (α + β = 1): the inner term, the one of
/// larger modulus, carries the winding.
fn continuous_arg(alpha: Complex, beta: Complex, psi: f64) -> f64 {
    let one = Complex::new(1.0, 0.0);
    if beta.norm_sqr() <= alpha.norm_sqr() {
        let r = beta / alpha;
        (one + r * Complex::cis(psi)).arg() - (one + r).arg()
    } else {
        let r = alpha / beta;
        psi + (one + r * Complex::cis(-psi)).arg() - (one + r).arg()
    }
}
