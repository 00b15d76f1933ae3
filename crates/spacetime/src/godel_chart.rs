//! A Gödel-type member in its Gödel-like chart (docs/physics.md, "The Gödel-type family",
//! "The Gödel-like chart"): the radius r = (2/m) sinh(mρ/2) (sin for m² < 0, r = ρ for
//! m² = 0) in place of the proper radius ρ, t, φ and z unchanged. With κ = m²/4 the line
//! element becomes rational,
//!
//!   ds² = −(dt + Ω r² dφ)² + dr²/(1 + κr²) + r²(1 + κr²) dφ² + dz²,
//!
//! in pseudo-Cartesian x = r cos φ, y = r sin φ, with J = (−y, x), X = (x, y):
//!
//!   g_tt = −1,  g_tx = Ω y,  g_ty = −Ω x,  g_ij = δ_ij − K J_i J_j − M X_i X_j,
//!   K = Ω² − κ,  M = κ/(1 + κr²),
//!
//! and with c = 1/(1 + κr²) the inverse (from the dual frame, as in `godel.rs`)
//!
//!   g^tt = −1 + Ω²r² c,  g^tx = Ω c y,  g^ty = −Ω c x,  g^ij = δ_ij + κ X_i X_j − κ c J_i J_j.
//!
//! For the Gödel member (κ = 1/4a², Ω = 1/(√2 a)) these are Gödel's own formulas: K = 1/4a²,
//! M = 1/(4a² + r²). The renderer describes local objects of a member in this chart, so
//! that the Gödel member's objects are Gödel's to rounding.
//!
//! The map from the member's coordinates is X = σ(u) x with u = m²ρ² and the entire
//! function σ(u) = sinh(√u/2)/(√u/2) = Σ (u/4)^k/(2k + 1)! (sin for u < 0); its
//! differential dX = σ dx + 2m² σ'(u) x (x·dx) on the spatial part.

use crate::godel_type::{SERIES_BELOW, SERIES_TERMS};
use crate::metric::Spacetime;
use crate::vectors::{Covector, Event, FourVector, MetricTensor};
use crate::GodelType;

/// A member of the Gödel-type family in its Gödel-like chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GodelChart {
    pub member: GodelType,
}

/// σ(u) and σ'(u) (module documentation).
fn sigma(u: f64) -> (f64, f64) {
    if u.abs() < SERIES_BELOW {
        // σ = Σ_k u^k/(4^k (2k+1)!), σ' = Σ_k k u^{k−1}/(4^k (2k+1)!).
        let (mut s, mut ds) = (1.0, 0.0);
        let mut coefficient = 1.0; // 1/(4^k (2k+1)!)
        for k in 1..=SERIES_TERMS {
            let kf = k as f64;
            coefficient *= 0.25 / ((2.0 * kf) * (2.0 * kf + 1.0));
            s += coefficient * u.powi(k as i32);
            ds += kf * coefficient * u.powi(k as i32 - 1);
        }
        return (s, ds);
    }
    // h = √u/2: σ = sinh h/h, dσ/du = (h cosh h − sinh h)/h² · 1/(8h) (sin, cos for u < 0).
    let (h, sh, ch) = if u > 0.0 {
        let h = 0.5 * u.sqrt();
        (h, h.sinh(), h.cosh())
    } else {
        let h = 0.5 * (-u).sqrt();
        (h, h.sin(), h.cos())
    };
    let s = sh / h;
    let ds = (ch - s) / (2.0 * u);
    (s, ds)
}

impl GodelChart {
    pub fn new(member: GodelType) -> GodelChart {
        GodelChart { member }
    }

    fn kappa(&self) -> f64 {
        0.25 * self.member.m2
    }

    /// The event `e` of the member's coordinates in this chart.
    pub fn event(&self, e: Event) -> Event {
        let (s, _) = sigma(self.member.m2 * (e.x * e.x + e.y * e.y));
        Event::new(e.t, s * e.x, s * e.y, e.z)
    }

    /// The spatial differential of [`GodelChart::event`] at (x, y): [[∂X/∂x, ∂X/∂y], [∂Y/∂x, ∂Y/∂y]].
    fn jacobian(&self, x: f64, y: f64) -> [[f64; 2]; 2] {
        let m2 = self.member.m2;
        let (s, ds) = sigma(m2 * (x * x + y * y));
        let c = 2.0 * m2 * ds;
        [[s + c * x * x, c * x * y], [c * x * y, s + c * y * y]]
    }

    /// The vector `v` at `at` (member's coordinates) in this chart.
    pub fn vector(&self, at: Event, v: FourVector) -> FourVector {
        let j = self.jacobian(at.x, at.y);
        FourVector::new(
            v.t,
            j[0][0] * v.x + j[0][1] * v.y,
            j[1][0] * v.x + j[1][1] * v.y,
            v.z,
        )
    }

    /// The vector `v` of this chart at the member's event `at`, in the member's coordinates
    /// (the inverse of [`GodelChart::vector`]).
    pub fn vector_back(&self, at: Event, v: FourVector) -> FourVector {
        let j = self.jacobian(at.x, at.y);
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        FourVector::new(
            v.t,
            (j[1][1] * v.x - j[0][1] * v.y) / det,
            (-j[1][0] * v.x + j[0][0] * v.y) / det,
            v.z,
        )
    }
}

/// ∂_x g and ∂_y g (the others vanish) of g_tt = −1, g_tx = w y, g_ty = −w x,
/// g_ij = δ_ij − k J_i J_j − m X_i X_j where m's only dependence is ∂_l m = −2 m² X_l: the
/// form of Gödel's metric (`godel.rs`) and of every member in this chart, so the one home of
/// these derivatives.
pub(crate) fn rotating_derivatives(w: f64, k: f64, m: f64, x: f64, y: f64) -> [MetricTensor; 4] {
    let m2 = m * m;
    let dx_xx = 2.0 * m2 * x * x * x - 2.0 * m * x;
    let dy_xx = -2.0 * k * y + 2.0 * m2 * y * x * x;
    let dx_xy = (k - m) * y + 2.0 * m2 * x * x * y;
    let dy_xy = (k - m) * x + 2.0 * m2 * x * y * y;
    let dx_yy = -2.0 * k * x + 2.0 * m2 * x * y * y;
    let dy_yy = 2.0 * m2 * y * y * y - 2.0 * m * y;
    let zero = [[0.0; 4]; 4];
    let dx = [
        [0.0, 0.0, -w, 0.0],
        [0.0, dx_xx, dx_xy, 0.0],
        [-w, dx_xy, dx_yy, 0.0],
        [0.0; 4],
    ];
    let dy = [
        [0.0, w, 0.0, 0.0],
        [w, dy_xx, dy_xy, 0.0],
        [0.0, dy_xy, dy_yy, 0.0],
        [0.0; 4],
    ];
    [zero, dx, dy, zero]
}

impl Spacetime for GodelChart {
    fn metric(&self, e: Event) -> MetricTensor {
        let (x, y, w, kappa) = (e.x, e.y, self.member.omega, self.kappa());
        let big_k = w * w - kappa;
        let big_m = kappa / (1.0 + kappa * (x * x + y * y));
        [
            [-1.0, w * y, -w * x, 0.0],
            [
                w * y,
                1.0 - big_k * y * y - big_m * x * x,
                (big_k - big_m) * x * y,
                0.0,
            ],
            [
                -w * x,
                (big_k - big_m) * x * y,
                1.0 - big_k * x * x - big_m * y * y,
                0.0,
            ],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }

    fn inverse_metric(&self, e: Event) -> MetricTensor {
        let (x, y, w, kappa) = (e.x, e.y, self.member.omega, self.kappa());
        let r2 = x * x + y * y;
        let c = 1.0 / (1.0 + kappa * r2);
        let kc = kappa * c;
        [
            [-1.0 + w * w * r2 * c, w * c * y, -w * c * x, 0.0],
            [
                w * c * y,
                1.0 + kappa * x * x - kc * y * y,
                (kappa + kc) * x * y,
                0.0,
            ],
            [
                -w * c * x,
                (kappa + kc) * x * y,
                1.0 + kappa * y * y - kc * x * x,
                0.0,
            ],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }

    fn metric_derivatives(&self, e: Event) -> [MetricTensor; 4] {
        let (x, y, w, kappa) = (e.x, e.y, self.member.omega, self.kappa());
        let m = kappa / (1.0 + kappa * (x * x + y * y));
        rotating_derivatives(w, w * w - kappa, m, x, y)
    }

    /// ẋ^μ = g^{μν} p_ν, ṗ_μ = ½ (g^{-1} p)^α ∂_μ g_{αβ} (g^{-1} p)^β (the chart serves local
    /// descriptions; rays are traced in the member's own coordinates).
    fn hamilton(&self, e: Event, p: Covector) -> (FourVector, Covector) {
        let xdot = self.raise(e, p);
        let v = xdot.to_array();
        let dg = self.metric_derivatives(e);
        let mut pdot = [0.0; 4];
        for (mu, d) in dg.iter().enumerate() {
            let mut s = 0.0;
            for a in 0..4 {
                for b in 0..4 {
                    s += v[a] * d[a][b] * v[b];
                }
            }
            pdot[mu] = 0.5 * s;
        }
        (xdot, Covector::from_array(pdot))
    }
}
