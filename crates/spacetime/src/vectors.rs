//! Typed points, vectors and frames in pseudo-Cartesian coordinates (t, x, y, z).
//!
//! Components are stored in the coordinate basis (∂t, ∂x, ∂y, ∂z) (vectors) or
//! (dt, dx, dy, dz) (covectors). Cylindrical coordinates (t, r, φ, z) are only a
//! user-facing view: x = r cos φ, y = r sin φ.

use std::ops::{Add, Mul, Neg, Sub};

/// Components g_μν (or g^μν) in the pseudo-Cartesian coordinate basis.
pub type MetricTensor = [[f64; 4]; 4];
/// Components Γ^μ_αβ, indexed `[mu][alpha][beta]`.
pub type Christoffel = [[[f64; 4]; 4]; 4];

/// A spacetime event in pseudo-Cartesian coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Event {
    pub t: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// An event in cylindrical coordinates (t, r, φ, z), φ in radians.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Cylindrical {
    pub t: f64,
    pub r: f64,
    pub phi: f64,
    pub z: f64,
}

/// Contravariant components v^μ of a tangent vector in the basis (∂t, ∂x, ∂y, ∂z).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct FourVector {
    pub t: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// Covariant components p_μ of a one-form (e.g. a momentum) in the basis (dt, dx, dy, dz).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Covector {
    pub t: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// An orthonormal frame: `e[0]` timelike (the observer's four-velocity), `e[1..4]` spatial.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tetrad {
    pub e: [FourVector; 4],
}

macro_rules! four_components {
    ($T:ident) => {
        impl $T {
            pub const fn new(t: f64, x: f64, y: f64, z: f64) -> Self {
                Self { t, x, y, z }
            }
            pub fn from_array(a: [f64; 4]) -> Self {
                Self::new(a[0], a[1], a[2], a[3])
            }
            pub fn to_array(self) -> [f64; 4] {
                [self.t, self.x, self.y, self.z]
            }
            /// True when every component is finite.
            pub fn is_finite(self) -> bool {
                self.t.is_finite() && self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
            }
        }
        impl Add for $T {
            type Output = $T;
            fn add(self, o: $T) -> $T {
                $T::new(self.t + o.t, self.x + o.x, self.y + o.y, self.z + o.z)
            }
        }
        impl Sub for $T {
            type Output = $T;
            fn sub(self, o: $T) -> $T {
                $T::new(self.t - o.t, self.x - o.x, self.y - o.y, self.z - o.z)
            }
        }
        impl Mul<$T> for f64 {
            type Output = $T;
            fn mul(self, v: $T) -> $T {
                $T::new(self * v.t, self * v.x, self * v.y, self * v.z)
            }
        }
        impl Neg for $T {
            type Output = $T;
            fn neg(self) -> $T {
                $T::new(-self.t, -self.x, -self.y, -self.z)
            }
        }
    };
}
four_components!(Event);
four_components!(FourVector);
four_components!(Covector);

impl Event {
    /// The event displaced by `s·v` in coordinates (used for finite differences and sampling).
    pub fn offset(self, v: FourVector, s: f64) -> Event {
        Event::new(
            self.t + s * v.t,
            self.x + s * v.x,
            self.y + s * v.y,
            self.z + s * v.z,
        )
    }
    /// Distance from the rotation axis, r = √(x² + y²).
    pub fn r(self) -> f64 {
        self.x.hypot(self.y)
    }
    /// Azimuth φ = atan2(y, x) in (−π, π].
    pub fn phi(self) -> f64 {
        self.y.atan2(self.x)
    }
    pub fn to_cylindrical(self) -> Cylindrical {
        Cylindrical {
            t: self.t,
            r: self.r(),
            phi: self.phi(),
            z: self.z,
        }
    }
}

impl Cylindrical {
    pub fn to_event(self) -> Event {
        let (s, c) = self.phi.sin_cos();
        Event::new(self.t, self.r * c, self.r * s, self.z)
    }
}

impl From<Cylindrical> for Event {
    fn from(c: Cylindrical) -> Event {
        c.to_event()
    }
}

impl FourVector {
    /// Contraction v^μ p_μ with a covector.
    pub fn contract(self, p: Covector) -> f64 {
        self.t * p.t + self.x * p.x + self.y * p.y + self.z * p.z
    }
    /// The cylindrical components (v^t, v^r, v^φ, v^z) at `at` (undefined on the axis).
    pub fn to_cylindrical(self, at: Event) -> [f64; 4] {
        let r2 = at.x * at.x + at.y * at.y;
        let r = r2.sqrt();
        [
            self.t,
            (at.x * self.x + at.y * self.y) / r,
            (at.x * self.y - at.y * self.x) / r2,
            self.z,
        ]
    }
}

impl Tetrad {
    /// The coordinate vector with local components `n` (n[0] along e0, n[1..4] spatial).
    pub fn vector(&self, n: [f64; 4]) -> FourVector {
        let mut v = FourVector::default();
        for (a, e) in self.e.iter().enumerate() {
            v = v + n[a] * *e;
        }
        v
    }
    /// The coordinate vector with spatial local components `n` (no e0 part).
    pub fn spatial(&self, n: [f64; 3]) -> FourVector {
        self.vector([0.0, n[0], n[1], n[2]])
    }
}
