//! Gödel's rotating universe (Gödel, Rev. Mod. Phys. 21, 447 (1949)) in pseudo-Cartesian
//! coordinates x = r cos φ, y = r sin φ, smooth on the axis.
//!
//! Line element (docs/physics.md, "The Gödel metric"), written as ds² = −(dt + α)² + h with
//! α = (x dy − y dx)/(√2 a) and the static observers' spatial metric
//! h = dr²/(1+s²) + r²(1+s²) dφ² + dz², s = r/2a. In these coordinates
//!
//!   g_tt = −1,  g_tx = y/(√2 a),  g_ty = −x/(√2 a),
//!   g_ij = δ_ij − k J_i J_j − m X_i X_j   (i, j ∈ {x, y}),  g_zz = 1,
//!
//! with k = 1/4a², m = 1/(4a² + r²), X = (x, y), J = (−y, x). The inverse follows from the
//! dual frame (∂t, ∂_i − α_i ∂t): with c = 1/(1 + k r²),
//!
//!   g^tt = 1 − 2c,  g^tx = c y/(√2 a),  g^ty = −c x/(√2 a),
//!   g^ij = c δ_ij + k(1 + c) X_i X_j,  g^zz = 1,
//!
//! which is the cylindrical inverse g^tt = −(1−s²)/(1+s²), g^tφ = −1/(√2 a(1+s²)), …
//! (docs/physics.md, "The Gödel metric") rewritten. The Hamiltonian used by the integrator
//! (docs/physics.md, "Geodesics") is then
//!   2H = (1 − 2c) p_t² − (√2/a) c p_t L + c(p_x² + p_y²) + k(1 + c)(x p_x + y p_y)² + p_z²,
//! L = x p_y − y p_x = p_φ.

use crate::godel_chart::rotating_derivatives;
use crate::metric::Spacetime;
use crate::vectors::MetricTensor;
use crate::vectors::{Covector, Event, FourVector};
use std::f64::consts::SQRT_2;

/// The Gödel metric with parameter `a` > 0 (optical horizon at r = 2a).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Godel {
    pub a: f64,
    /// k = 1/4a², b = √2/a and 1/(√2 a) (the factor of g_tx and g_ty), precomputed: the
    /// integrator's right-hand side then needs a single division, the metric one.
    k: f64,
    b: f64,
    turn: f64,
}

impl Godel {
    /// The Gödel metric; `a` must be positive and finite (checked by callers that parse input).
    pub fn new(a: f64) -> Self {
        debug_assert!(a > 0.0 && a.is_finite());
        Godel {
            a,
            k: 0.25 / (a * a),
            b: SQRT_2 / a,
            turn: 1.0 / (SQRT_2 * a),
        }
    }
    /// 1/(√2 a): g_tx = y/(√2 a), g_ty = −x/(√2 a).
    pub(crate) fn turn(&self) -> f64 {
        self.turn
    }
    /// Radius of the optical horizon, r_G = 2a.
    pub fn horizon_radius(&self) -> f64 {
        2.0 * self.a
    }

    /// The shortest coordinate time in which a light ray returns to its starting axis,
    /// T_ret = 2πa(√2 − 1), for rays in the plane (Kundt 1956; Kajari et al. 2009): rays
    /// tilted out of the plane take longer, up to √2·πa along the axis. So a ray followed
    /// Δt into the past makes at most Δt/T_ret + 1 loops.
    pub fn shortest_loop_time(&self) -> f64 {
        2.0 * std::f64::consts::PI * self.a * (std::f64::consts::SQRT_2 - 1.0)
    }
}

impl Spacetime for Godel {
    fn metric(&self, e: Event) -> MetricTensor {
        let (x, y, a, k) = (e.x, e.y, self.a, self.k);
        let m = 1.0 / (4.0 * a * a + x * x + y * y);
        let gtx = y * self.turn;
        let gty = -x * self.turn;
        let gxx = 1.0 - k * y * y - m * x * x;
        let gxy = (k - m) * x * y;
        let gyy = 1.0 - k * x * x - m * y * y;
        [
            [-1.0, gtx, gty, 0.0],
            [gtx, gxx, gxy, 0.0],
            [gty, gxy, gyy, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }

    fn inverse_metric(&self, e: Event) -> MetricTensor {
        let (x, y, k) = (e.x, e.y, self.k);
        let c = 1.0 / (1.0 + k * (x * x + y * y));
        let q = k * (1.0 + c);
        let gtx = c * y * self.turn;
        let gty = -c * x * self.turn;
        [
            [1.0 - 2.0 * c, gtx, gty, 0.0],
            [gtx, c + q * x * x, q * x * y, 0.0],
            [gty, q * x * y, c + q * y * y, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }

    fn metric_derivatives(&self, e: Event) -> [MetricTensor; 4] {
        let (x, y, a, k) = (e.x, e.y, self.a, self.k);
        let m = 1.0 / (4.0 * a * a + x * x + y * y);
        // g_xx = 1 − k y² − m x², g_xy = (k − m) x y, g_yy = 1 − k x² − m y².
        rotating_derivatives(self.turn, k, m, x, y)
    }

    #[inline]
    fn hamilton(&self, e: Event, p: Covector) -> (FourVector, Covector) {
        let (x, y, k, b) = (e.x, e.y, self.k, self.b);
        let c = 1.0 / (1.0 + k * (x * x + y * y));
        let pt = p.t;
        let l = x * p.y - y * p.x;
        let rho = x * p.x + y * p.y;
        let q = k * (1.0 + c) * rho;
        let half_bcp = 0.5 * b * c * pt;
        let xdot = FourVector::new(
            (1.0 - 2.0 * c) * pt - 0.5 * b * c * l,
            half_bcp * y + c * p.x + q * x,
            -half_bcp * x + c * p.y + q * y,
            p.z,
        );
        // ṗ_i = −½ ∂_i(2H); ∂_i c = −2k c² X_i.
        let big_q = -2.0 * pt * pt - b * pt * l + (p.x * p.x + p.y * p.y) + k * rho * rho;
        let kc2q = k * c * c * big_q;
        let pdot = Covector::new(
            0.0,
            kc2q * x + half_bcp * p.y - q * p.x,
            kc2q * y - half_bcp * p.x - q * p.y,
            0.0,
        );
        (xdot, pdot)
    }
}
