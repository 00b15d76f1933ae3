//! The five Killing vector fields of Gödel's universe in pseudo-Cartesian coordinates.
//!
//! Gödel's metric is homogeneous: its isometry group is five-dimensional (Gödel, Rev. Mod.
//! Phys. 21, 447 (1949), Sec. 2; the Killing fields in cylindrical form are given by Kundt,
//! Z. Phys. 145, 611 (1956) and Novello, Soares & Tiomno, PRD 27, 779 (1983)). With
//! s = r/2a, D = √(1+s²) they are ∂t, ∂z, ∂φ and the two "translations"
//!
//!   K_x = −(r sinφ/(√2 a D)) ∂t + D cosφ ∂r − sinφ (1+2s²)/(r D) ∂φ,
//!   K_y = +(r cosφ/(√2 a D)) ∂t + D sinφ ∂r + cosφ (1+2s²)/(r D) ∂φ.
//!
//! Written in the basis (∂t, ∂x, ∂y, ∂z) with x = r cosφ, y = r sinφ (ξ^x = ξ^r cosφ −
//! r sinφ ξ^φ, ξ^y = ξ^r sinφ + r cosφ ξ^φ) the 1/r terms cancel and both are smooth on
//! the axis, where they reduce to ∂x and ∂y:
//!
//!   K_x = ( −y/(√2 a D), (1 + (x² + 2y²)/4a²)/D, −x y/(4a² D), 0 ),
//!   K_y = (  x/(√2 a D), −x y/(4a² D), (1 + (2x² + y²)/4a²)/D, 0 ).
//!
//! Their algebra: [K_x, K_y] = (√2/a) ∂t + (1/a²) ∂φ, [∂φ, K_x] = −K_y, [∂φ, K_y] = K_x,
//! ∂t and ∂z central (checked in `tests/integration/symmetry.rs`).

use crate::vectors::{Event, FourVector};
use std::f64::consts::SQRT_2;

/// One of the five independent Killing fields of the Gödel metric with parameter `a`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KillingField {
    /// ∂t: time translation (its conserved momentum is −E).
    T,
    /// ∂z: translation along the rotation axis (p_z).
    Z,
    /// ∂φ = −y ∂x + x ∂y: rotation about the axis through the origin (L).
    Phi,
    /// K_x: the "translation" that is ∂x on the axis.
    Kx,
    /// K_y: the "translation" that is ∂y on the axis.
    Ky,
}

impl KillingField {
    /// All five, in the order T, Z, Phi, Kx, Ky.
    pub const ALL: [KillingField; 5] = [
        KillingField::T,
        KillingField::Z,
        KillingField::Phi,
        KillingField::Kx,
        KillingField::Ky,
    ];

    /// The field's components (ξ^t, ξ^x, ξ^y, ξ^z) at `at`, for Gödel parameter `a`.
    pub fn at(self, a: f64, at: Event) -> FourVector {
        let (x, y) = (at.x, at.y);
        let k = 0.25 / (a * a);
        let d = (1.0 + k * (x * x + y * y)).sqrt();
        match self {
            KillingField::T => FourVector::new(1.0, 0.0, 0.0, 0.0),
            KillingField::Z => FourVector::new(0.0, 0.0, 0.0, 1.0),
            KillingField::Phi => FourVector::new(0.0, -y, x, 0.0),
            KillingField::Kx => FourVector::new(
                -y / (SQRT_2 * a * d),
                (1.0 + k * (x * x + 2.0 * y * y)) / d,
                -k * x * y / d,
                0.0,
            ),
            KillingField::Ky => FourVector::new(
                x / (SQRT_2 * a * d),
                -k * x * y / d,
                (1.0 + k * (2.0 * x * x + y * y)) / d,
                0.0,
            ),
        }
    }
}
