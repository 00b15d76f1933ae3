//! The Gödel-type spacetimes of Rebouças and Tiomno (Phys. Rev. D 28, 1251 (1983)), a
//! family with two constants, the vorticity Ω and m² (Gödel's universe is m² = 2Ω²), in
//! pseudo-Cartesian coordinates x = ρ cos φ, y = ρ sin φ with ρ the proper radial distance
//! (docs/physics.md, "The Gödel-type family"):
//!
//!   ds² = −[dt + H(ρ) dφ]² + dρ² + D(ρ)² dφ² + dz²,
//!   H = (4Ω/m²) sinh²(mρ/2),  D = sinh(mρ)/m   (m² < 0: sinh → sin with μ² = −m²; m² = 0:
//!   H = Ωρ², D = ρ).
//!
//! With L = x dy − y dx = ρ² dφ and u = m²ρ², both H/ρ² = 2Ω C(u) and D²/ρ² = S(u) are entire
//! functions of u, C(u) = (cosh √u − 1)/u and S(u) = sinh²√u / u (cos and sin for u < 0), so
//! one set of formulas covers every member and is smooth on the axis:
//!
//!   ds² = −(dt + f L)² + dx² + dy² + q L² + dz²,   f = 2Ω C(u),  q = m² T(u),
//!   T(u) = (S(u) − 1)/u,
//!
//!   g_tt = −1,  g_tx = f y,  g_ty = −f x,  g_ij = δ_ij + (q − f²) J_i J_j,  J = (−y, x).
//!
//! As in `godel.rs` the inverse follows from the dual frame (∂t, ∂_i − A_i ∂t), A = f J, and
//! the spatial metric h = δ + q J J, whose inverse is δ − κ J J with κ = q/(1 + q ρ²)
//! (Sherman–Morrison; 1 + q ρ² = S(u) = D²/ρ²). The Hamiltonian is, with ℓ = x p_y − y p_x,
//!
//!   2H = −p_t² + p_x² + p_y² + p_z² − 2 p_t f ℓ + p_t² f² ρ² − κ (ℓ − p_t f ρ²)².
//!
//! For m² < 0 the coordinates hold where D > 0, μρ < π.

use crate::metric::Spacetime;
use crate::vectors::{Covector, Event, FourVector, MetricTensor};

/// A member of the Gödel-type family: `m2` = m² (any sign) and the vorticity `omega` = Ω > 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GodelType {
    pub m2: f64,
    pub omega: f64,
}

/// Where the closed forms of C, S and T lose digits to cancellation, their series take over.
pub(crate) const SERIES_BELOW: f64 = 0.5;
/// Terms of the series: the last, |u|^11/24!, is below 1e-24 for |u| < 0.5.
pub(crate) const SERIES_TERMS: usize = 12;

/// C(u), C'(u), T(u) = (S(u) − 1)/u and T'(u) (module documentation).
fn functions(u: f64) -> [f64; 4] {
    if u.abs() < SERIES_BELOW {
        // C = Σ_{k≥1} u^{k−1}/(2k)!, S = Σ_{k≥1} 2^{2k−1} u^{k−1}/(2k)!, so
        // T = Σ_{k≥2} 2^{2k−1} u^{k−2}/(2k)!.
        let (mut c, mut dc, mut t, mut dt) = (0.0, 0.0, 0.0, 0.0);
        let mut factorial = 1.0; // (2k)!
        let mut power = 1.0; // 2^{2k−1}
        for k in 1..=SERIES_TERMS {
            let kf = k as f64;
            factorial *= (2.0 * kf - 1.0) * (2.0 * kf);
            power *= if k == 1 { 2.0 } else { 4.0 };
            c += u.powi(k as i32 - 1) / factorial;
            if k >= 2 {
                dc += (kf - 1.0) * u.powi(k as i32 - 2) / factorial;
                t += power * u.powi(k as i32 - 2) / factorial;
            }
            if k >= 3 {
                dt += (kf - 2.0) * power * u.powi(k as i32 - 3) / factorial;
            }
        }
        return [c, dc, t, dt];
    }
    // ch = cosh √u, sh = sinh √u / √u (cos t and sin t / t, t = √−u, for u < 0).
    let (ch, sh) = if u > 0.0 {
        let r = u.sqrt();
        (r.cosh(), r.sinh() / r)
    } else {
        let r = (-u).sqrt();
        (r.cos(), r.sin() / r)
    };
    let c = (ch - 1.0) / u;
    let dc = 0.5 * sh / u - (ch - 1.0) / (u * u);
    let s = sh * sh;
    let ds = sh * (ch - sh) / u;
    let t = (s - 1.0) / u;
    let dt = ds / u - (s - 1.0) / (u * u);
    [c, dc, t, dt]
}

impl GodelType {
    pub fn new(m2: f64, omega: f64) -> GodelType {
        GodelType { m2, omega }
    }

    /// Gödel's parameter a of the same vorticity, 1/(√2 Ω): the member m² = 2Ω² is Gödel's
    /// universe with this a (docs/physics.md, "The Gödel-type family").
    pub fn godel_a(&self) -> f64 {
        1.0 / (std::f64::consts::SQRT_2 * self.omega)
    }

    /// ρ_c, beyond which the circles about the axis are closed timelike curves and where the
    /// light rays from the axis in the plane z = 0 turn back: tanh(mρ_c/2) = m/(2Ω), ρ_c = 1/Ω
    /// for m² = 0, tan(μρ_c/2) = μ/(2Ω) for m² = −μ² < 0 (the first of its shells). None for
    /// m² ≥ 4Ω², which is causal everywhere.
    pub fn critical_radius(&self) -> Option<f64> {
        let two_omega = 2.0 * self.omega;
        if self.m2 > 0.0 {
            let m = self.m2.sqrt();
            (m < two_omega).then(|| 2.0 * (m / two_omega).atanh() / m)
        } else if self.m2 == 0.0 {
            Some(1.0 / self.omega)
        } else {
            let mu = (-self.m2).sqrt();
            Some(2.0 * (mu / two_omega).atan() / mu)
        }
    }

    /// The shortest coordinate time in which a light ray from the axis comes back to it
    /// (docs/physics.md, "Direct light in the family"): a ray with E = 1 leaving at angle ψ
    /// to the axis, σ = sin ψ, s = √Λ = √(Ω² − m²σ²/4) > 0, returns after
    /// t_loop = (π/s)(1 − Ωσ²/(Ω + s)), whose least value is π/(Ω + s₁) in the plane,
    /// s₁ = √(Ω² − m²/4), for m² < 4Ω², and π/Ω (rays along the axis) for m² ≥ 4Ω². The
    /// Gödel member gives Gödel's 2πa(√2 − 1). Along these rays t never falls (they stay
    /// within ρ_c, where ∂φ is spacelike), so a ray back on the axis n times has taken at
    /// least n times this.
    pub fn shortest_loop_time(&self) -> f64 {
        let s1 = (self.omega * self.omega - 0.25 * self.m2).max(0.0).sqrt();
        std::f64::consts::PI / (self.omega + s1)
    }

    /// Where the coordinates end: ρ = π/μ for m² = −μ² < 0 (the base is a sphere and ρ = π/μ
    /// its pole opposite the axis); None for m² ≥ 0.
    pub fn coordinate_radius(&self) -> Option<f64> {
        (self.m2 < 0.0).then(|| std::f64::consts::PI / (-self.m2).sqrt())
    }

    /// f = H/ρ², q = (D²/ρ² − 1)/ρ² and their derivatives with respect to s = ρ², at s.
    fn profile(&self, s: f64) -> Profile {
        let [c, dc, t, dt] = functions(self.m2 * s);
        let m2 = self.m2;
        Profile {
            f: 2.0 * self.omega * c,
            df: 2.0 * self.omega * m2 * dc,
            q: m2 * t,
            dq: m2 * m2 * dt,
        }
    }
}

struct Profile {
    f: f64,
    df: f64,
    q: f64,
    dq: f64,
}

impl Spacetime for GodelType {
    fn metric(&self, e: Event) -> MetricTensor {
        let (x, y) = (e.x, e.y);
        let p = self.profile(x * x + y * y);
        let c = p.q - p.f * p.f;
        [
            [-1.0, p.f * y, -p.f * x, 0.0],
            [p.f * y, 1.0 + c * y * y, -c * x * y, 0.0],
            [-p.f * x, -c * x * y, 1.0 + c * x * x, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }

    fn inverse_metric(&self, e: Event) -> MetricTensor {
        let (x, y) = (e.x, e.y);
        let s = x * x + y * y;
        let p = self.profile(s);
        let kappa = p.q / (1.0 + p.q * s);
        // h⁻¹ = δ − κ J J; A = f J; g^tt = −1 + A·h⁻¹·A, g^ti = −(h⁻¹ A)_i.
        let hi = [
            [1.0 - kappa * y * y, kappa * x * y],
            [kappa * x * y, 1.0 - kappa * x * x],
        ];
        let a = [-p.f * y, p.f * x];
        let ha = [
            hi[0][0] * a[0] + hi[0][1] * a[1],
            hi[1][0] * a[0] + hi[1][1] * a[1],
        ];
        let tt = -1.0 + a[0] * ha[0] + a[1] * ha[1];
        [
            [tt, -ha[0], -ha[1], 0.0],
            [-ha[0], hi[0][0], hi[0][1], 0.0],
            [-ha[1], hi[1][0], hi[1][1], 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }

    fn metric_derivatives(&self, e: Event) -> [MetricTensor; 4] {
        let (x, y) = (e.x, e.y);
        let p = self.profile(x * x + y * y);
        let c = p.q - p.f * p.f;
        let dc = p.dq - 2.0 * p.f * p.df;
        // ∂_x g(s) = 2x g'(s), ∂_y g(s) = 2y g'(s).
        let (fx, fy, cx, cy) = (2.0 * x * p.df, 2.0 * y * p.df, 2.0 * x * dc, 2.0 * y * dc);
        let dx = [
            [0.0, fx * y, -p.f - fx * x, 0.0],
            [fx * y, cx * y * y, -cx * x * y - c * y, 0.0],
            [
                -p.f - fx * x,
                -cx * x * y - c * y,
                cx * x * x + 2.0 * c * x,
                0.0,
            ],
            [0.0; 4],
        ];
        let dy = [
            [0.0, p.f + fy * y, -fy * x, 0.0],
            [
                p.f + fy * y,
                cy * y * y + 2.0 * c * y,
                -cy * x * y - c * x,
                0.0,
            ],
            [-fy * x, -cy * x * y - c * x, cy * x * x, 0.0],
            [0.0; 4],
        ];
        [[[0.0; 4]; 4], dx, dy, [[0.0; 4]; 4]]
    }

    fn hamilton(&self, e: Event, p: Covector) -> (FourVector, Covector) {
        let (x, y) = (e.x, e.y);
        let s = x * x + y * y;
        let pr = self.profile(s);
        let (f, df) = (pr.f, pr.df);
        let big_s = 1.0 + pr.q * s;
        let kappa = pr.q / big_s;
        let dkappa = (pr.dq * big_s - pr.q * (pr.q + pr.dq * s)) / (big_s * big_s);
        let pt = p.t;
        let l = x * p.y - y * p.x;
        let w = l - pt * f * s; // ℓ − p_t f ρ²
                                // 2H = −p_t² + |p|² + G(s, ℓ, p_t), G = −2 p_t f ℓ + p_t² f² s − κ w².
        let g_l = -2.0 * pt * f - 2.0 * kappa * w;
        let g_s = -2.0 * pt * df * l + pt * pt * (2.0 * f * df * s + f * f) - dkappa * w * w
            + 2.0 * kappa * w * pt * (df * s + f);
        let g_pt = -2.0 * f * l + 2.0 * pt * f * f * s + 2.0 * kappa * w * f * s;
        let xdot = FourVector::new(
            -pt + 0.5 * g_pt,
            p.x - 0.5 * g_l * y,
            p.y + 0.5 * g_l * x,
            p.z,
        );
        // ṗ_i = −½ ∂_i(2H): ∂_x s = 2x, ∂_x ℓ = p_y; ∂_y s = 2y, ∂_y ℓ = −p_x.
        let pdot = Covector::new(
            0.0,
            -(g_s * x + 0.5 * g_l * p.y),
            -(g_s * y - 0.5 * g_l * p.x),
            0.0,
        );
        (xdot, pdot)
    }
}
