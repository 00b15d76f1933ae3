//! Exact geodesics of Gödel's universe: closed forms through the origin, carried to any
//! event by the isometries of [`crate::isometry`].
//!
//! Geodesics through the axis have L = 0; their first integrals (from the Killing fields
//! ∂t, ∂φ, ∂z; Chandrasekhar & Wright, PNAS 47, 341 (1961); Novello, Soares & Tiomno,
//! PRD 27, 779 (1983), Sec. III; Grave et al., PRD 80, 103002 (2009), Sec. III) integrate
//! to elementary functions. With initial tangent k = (E, k⊥ cos χ, k⊥ sin χ, p_z) at the
//! origin (where the metric is Minkowski), κ = −g(k, k) (0 light, 1 particle with proper
//! time), ω = √(E² + κ + p_z²)/(2a), r_max = k⊥/ω, q = |E|/(√2 a ω), θ = ωλ and the
//! continuous branch Φ(θ) = arctan(q tan θ):
//!
//!   x + i y = r_max sin θ · e^{i(χ + sgn(E) Φ(θ))},
//!   t = sgn(E) 2√2 a Φ(θ) − E λ,  z = p_z λ.
//!
//! The tangent is their λ-derivative, with Φ'(θ) = q/(cos²θ + q² sin²θ):
//!
//!   d(x + i y)/dλ = ω r_max (cos θ + i sgn(E) Φ' sin θ) e^{iφ},
//!   dt/dλ = sgn(E) 2√2 a ω Φ' − E,  dz/dλ = p_z
//!
//! (at λ = 0 this gives back k, since 2√2 a ω q = 2|E|). A geodesic from any event X with
//! tangent k is T⁻¹(γ₀(λ)) with T = T_X the isometry sending X to the origin and γ₀ the
//! closed form with initial tangent T_* k; the tangent is pushed back with (T⁻¹)_*.
//! The parameter is the same affine parameter (proper time for particles).

use crate::isometry::{Complex, Isometry};
use crate::vectors::{Event, FourVector};
use std::f64::consts::{PI, SQRT_2};

/// The closed-form geodesic through the origin event with a given initial tangent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OriginGeodesic {
    pub a: f64,
    /// E = k^t (future-directed ⇔ E > 0).
    pub energy: f64,
    pub pz: f64,
    /// κ = −g(k, k): 0 for light, 1 for a particle parametrized by proper time.
    pub kappa: f64,
    /// (cos χ, sin χ) of the initial direction χ, so that e^{iφ} needs no sincos per
    /// evaluation.
    cis_chi: (f64, f64),
    omega: f64,
    r_max: f64,
    q: f64,
}

impl OriginGeodesic {
    /// The geodesic leaving the origin with tangent `k`. `k` must be causal (null up to
    /// rounding, or timelike with any normalization) and not zero; otherwise `None`.
    pub fn new(a: f64, k: FourVector) -> Option<Self> {
        let e = k.t;
        let kperp2 = k.x * k.x + k.y * k.y;
        let kappa = e * e - kperp2 - k.z * k.z;
        if !(k.is_finite() && e != 0.0 && kappa >= -1e-12 * e * e && a > 0.0) {
            return None;
        }
        let kappa = kappa.max(0.0);
        let omega = (e * e + kappa + k.z * k.z).sqrt() / (2.0 * a);
        let kperp = kperp2.sqrt();
        Some(OriginGeodesic {
            a,
            energy: e,
            pz: k.z,
            kappa,
            // (kˣ, kʸ)/k⊥, and χ = 0 along the axis (k⊥ = 0).
            cis_chi: if kperp > 0.0 {
                (k.x / kperp, k.y / kperp)
            } else {
                (1.0, 0.0)
            },
            omega,
            r_max: kperp / omega,
            q: e.abs() / (SQRT_2 * a * omega),
            // ω r_max = k⊥ and q ≥ 1 for causal k.
        })
    }

    /// Largest distance from the axis, r_max = k⊥/ω.
    pub fn r_max(&self) -> f64 {
        self.r_max
    }

    /// (cos χ, sin χ) of the initial direction χ of the spatial projection.
    pub fn cis_chi(&self) -> (f64, f64) {
        self.cis_chi
    }

    /// The initial tangent's transverse components (kˣ, kʸ) = k⊥ (cos χ, sin χ).
    pub fn initial_transverse(&self) -> (f64, f64) {
        let kperp = self.omega * self.r_max;
        (kperp * self.cis_chi.0, kperp * self.cis_chi.1)
    }

    /// The spatial projection's hyperbolic circle (docs/physics.md, "Whole-ray rejection"):
    /// radius ρ = a·asinh(r_max/2a), centre h halfway to the farthest point. Returns
    /// (sinh(ρ/a), cosh(ρ/a), |h|) = (r_max/2a, √(1 + sinh²), sinh/(1 + cosh)), the last being
    /// tanh(ρ/2a): one square root, no hyperbolic function.
    pub fn circle(&self) -> (f64, f64, f64) {
        let sinh_rho = self.r_max / (2.0 * self.a);
        let cosh_rho = (1.0 + sinh_rho * sinh_rho).sqrt();
        (sinh_rho, cosh_rho, sinh_rho / (1.0 + cosh_rho))
    }

    /// The rotation about the axis, after the isometry back from the origin, of the flow
    /// that moves the origin to the point at parameter `lambda` along this geodesic
    /// (`crate::transport`): β = α − 2 arg(1 − |h|² e^{iα}), α = sgn(E)·2ωλ the angle turned
    /// about the centre h of the projection's circle.
    pub fn flow_rotation(&self, lambda: f64) -> f64 {
        let alpha = self.energy.signum() * 2.0 * self.omega * lambda;
        let (_, _, h) = self.circle();
        let h2 = h * h;
        let (s, c) = alpha.sin_cos();
        alpha - 2.0 * Complex::new(1.0 - h2 * c, -h2 * s).arg_right()
    }

    /// The parameter after which the spatial projection is back on the axis: λ = π/ω.
    pub fn return_parameter(&self) -> f64 {
        PI / self.omega
    }

    /// Φ(θ) = arctan(q tan θ), continued through θ = π/2 + nπ, Φ'(θ) and (cos Φ, sin Φ),
    /// given (sin θ, cos θ) (computed once by the caller: libm's sincos and atan2 are a
    /// large share of an evaluation). With A = cos²θ + q sin²θ > 0 and B = (q − 1) sin θ
    /// cos θ, Φ = θ + arg(A + iB) (an atan, A > 0), so e^{iΦ} = e^{iθ} (A + iB)/|A + iB|
    /// without a sincos.
    fn big_phi(&self, th: f64, s: f64, c: f64) -> (f64, f64, (f64, f64)) {
        let q = self.q;
        let den = c * c + q * s * s;
        let b = (q - 1.0) * s * c;
        let phi = th + Complex::new(den, b).arg_right();
        let dphi = q / (c * c + q * q * s * s);
        let n = (den * den + b * b).sqrt();
        let cis = ((c * den - s * b) / n, (s * den + c * b) / n);
        (phi, dphi, cis)
    }

    /// The coordinate time t = sgn(E)·2√2·a·Φ(θ) − Eλ alone at parameter `lambda` (as
    /// [`OriginGeodesic::at`]'s event, without the position). Monotone in λ for light, with
    /// |dt/dλ| ≤ |E| (dt/dλ = E(2Φ′/q − 1), Φ′/q between 1/q² and 1, q ≤ √2).
    pub fn time(&self, lambda: f64) -> f64 {
        let th = self.omega * lambda;
        let (s, c) = th.sin_cos();
        let (big, _, _) = self.big_phi(th, s, c);
        self.energy.signum() * 2.0 * SQRT_2 * self.a * big - self.energy * lambda
    }

    /// How far the time strays from its mean rate: |t(λ) − Δt·λ/λ_ret| ≤ 2√2·a·δ, tan δ =
    /// (q − 1)/(2√q) (docs/physics.md, "Closed forms"). t(λ) − (sgn(E)·2√2·a·ω − E)·λ is
    /// sgn(E)·2√2·a·(Φ(θ) − θ), whose λ_ret-periodic part (Φ(π) = π) has tan(Φ − θ) =
    /// (q − 1)·tan θ/(1 + q·tan² θ), largest at tan² θ = 1/q. The GPU kernel bounds the λ
    /// where a ray's time lies in a band with it.
    pub fn time_deviation(&self) -> f64 {
        let q = self.q.max(1.0);
        2.0 * SQRT_2 * self.a * ((q - 1.0) / (2.0 * q.sqrt())).atan()
    }

    /// Event and tangent at parameter `lambda`.
    pub fn at(&self, lambda: f64) -> (Event, FourVector) {
        let (a, e, w) = (self.a, self.energy, self.omega);
        let sg = e.signum();
        let th = w * lambda;
        let (s, c) = th.sin_cos();
        let (big, dbig, (cb, sb)) = self.big_phi(th, s, c);
        // e^{iφ} = e^{iχ} e^{i sgn(E) Φ}, φ = χ + sgn(E) Φ.
        let (cc, sc) = self.cis_chi;
        let sb = sg * sb;
        let (cp, sp) = (cc * cb - sc * sb, sc * cb + cc * sb);
        let r = self.r_max * s;
        let event = Event::new(
            sg * 2.0 * SQRT_2 * a * big - e * lambda,
            r * cp,
            r * sp,
            self.pz * lambda,
        );
        // d(x+iy)/dλ = ω r_max (cos θ + i sgn(E) Φ' sin θ) e^{iφ}.
        let (u, v) = (w * self.r_max * c, w * self.r_max * sg * dbig * s);
        let tangent = FourVector::new(
            sg * 2.0 * SQRT_2 * a * w * dbig - e,
            u * cp - v * sp,
            u * sp + v * cp,
            self.pz,
        );
        (event, tangent)
    }
}

/// The exact geodesic through any event: the closed form through the origin mapped by
/// the isometry that sends the origin back to the starting event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactGeodesic {
    /// T⁻¹: from the origin frame back to the starting event.
    pub back: Isometry,
    pub origin: OriginGeodesic,
}

impl ExactGeodesic {
    /// The geodesic through `at` with tangent `k` (causal, non-zero; else `None`).
    pub fn new(a: f64, at: Event, k: FourVector) -> Option<Self> {
        let to = Isometry::to_origin(a, at);
        let origin = OriginGeodesic::new(a, to.push(at, k))?;
        Some(ExactGeodesic {
            back: to.inverse(),
            origin,
        })
    }

    /// Event and tangent at parameter `lambda` (λ = 0 at the starting event).
    pub fn at(&self, lambda: f64) -> (Event, FourVector) {
        let (e, k) = self.origin.at(lambda);
        self.back.apply_push(e, k)
    }
}
