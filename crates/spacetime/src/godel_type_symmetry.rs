//! Symmetries of the Gödel-type family (`GodelType`): the five Killing fields and the finite
//! isometries, for every m² (docs/physics.md, "The Gödel-type family", subsections "Killing
//! fields of the family" and "Isometries of the family"). The Gödel member's versions are
//! `killing.rs` and `isometry.rs`; this file follows their conventions.
//!
//! The metric is a timelike fibre over a two-surface of constant curvature K = −m²:
//! ds² = −(dt + A)² + h + dz², A = H dφ, dA = 2Ω (area form of h). With k = m²/4 and the
//! complex base coordinate
//!
//!   ζ = G(u)(x + i y),  G(u) = tanh(√u/2)/(√u/2),  u = m²ρ²   (tan for u < 0, G(0) = 1),
//!
//! i.e. ζ = (2/m) tanh(mρ/2) e^{iφ} (the Poincaré disc |ζ| < 2/m for m² > 0; the plane for
//! m² = 0; the sphere's stereographic plane, ζ = (2/μ) tan(μρ/2) e^{iφ}, for m² = −μ² < 0),
//! one set of formulas holds for all members:
//!
//!   h = |dζ|²/(1 − k|ζ|²)²,  A = Ω Im(ζ̄ dζ)/(1 − k|ζ|²),  x + i y = F(k|ζ|²) ζ,
//!   F(v) = atanh(√v)/√v (atan for v < 0, F(0) = 1).
//!
//! The base isometry ζ ↦ (ζ − ζ0)/(1 − k ζ̄0 ζ) (disc: Möbius map, plane: translation,
//! sphere: rotation) changes A by −dχ, χ = (Ω/k) arg(1 − k ζ̄0 ζ) (→ −Ω Im(ζ̄0 ζ) as k → 0),
//! so that
//!
//!   T_{P0}:  ζ′ = (ζ − ζ0)/(1 − k ζ̄0 ζ),  t′ = t − t0 − χ(ζ),  z′ = z − z0
//!
//! is an isometry sending P0 = (t0, ζ0, z0) to the origin. For Gödel (k = 1/4a², ζ = 2a w)
//! χ = 2√2 a arg(1 − w̄0 w), as in `isometry.rs`. An isometry here is R_α ∘ T_{P0}, and
//! (R_α ∘ T_{P0})⁻¹ = R_{−α} ∘ T_{P1}, P1 = (−t0, −e^{iα} ζ0, −z0), because
//! (1 − k ζ̄0 ζ)(1 + k ζ̄0 ζ′) = 1 − k|ζ0|² > 0 makes the two time shifts opposite.
//!
//! The sphere (m² < 0): the coordinates cover it without the pole ρ = π/μ opposite the axis,
//! and t is not single-valued around that pole (the flux of dA through the sphere is
//! 8πΩ/μ² ≠ 0). With the principal arg, T_{P0} is an isometry on the chart except the arc
//! where 1 − k ζ̄0 ζ ≤ 0 (from the point T_{P0} sends to the pole, to the pole), across which
//! its time shift jumps by 8πΩ/μ². `to_origin` refuses events outside the chart (μρ ≥ π).
//! For m² ≥ 0, |k ζ̄0 ζ| < 1 keeps 1 − k ζ̄0 ζ in the right half-plane: no cut.
//!
//! The Killing fields are the generators: ∂t, ∂z, ∂φ and the translations (ζ0 = −ε, −iε)
//!
//!   K_x = −Ω G y ∂t + [(x² + P y²)/ρ²] ∂x + [(1 − P) x y/ρ²] ∂y,
//!   K_y =  Ω G x ∂t + [(1 − P) x y/ρ²] ∂x + [(y² + P x²)/ρ²] ∂y,
//!
//! P = ρ D′/D = √u coth √u (√−u cot √−u for u < 0), i.e. K_x = −(H/D) sin φ ∂t + cos φ ∂ρ
//! − (D′/D) sin φ ∂φ; on the axis they are ∂x and ∂y.

use crate::godel_type::GodelType;
use crate::isometry::Complex;
use crate::killing::KillingField;
use crate::vectors::{Event, FourVector};

/// tanh(√u/2)/(√u/2) (tan for u < 0), 1 at u = 0: ζ = G(u)(x + i y). Accurate near u = 0
/// (tanh and tan keep their relative accuracy for small arguments).
fn half_tanhc(u: f64) -> f64 {
    let h = 0.5 * u.abs().sqrt();
    if h == 0.0 {
        1.0
    } else if u > 0.0 {
        h.tanh() / h
    } else {
        h.tan() / h
    }
}

/// atanh(√v)/√v (atan(√−v)/√−v for v < 0), 1 at v = 0: x + i y = F(k|ζ|²) ζ.
fn atanhc(v: f64) -> f64 {
    let s = v.abs().sqrt();
    if s == 0.0 {
        1.0
    } else if v > 0.0 {
        s.atanh() / s
    } else {
        s.atan() / s
    }
}

/// √u coth √u (√−u cot √−u for u < 0), 1 at u = 0: ρ D′(ρ)/D(ρ).
fn xcothx(u: f64) -> f64 {
    let s = u.abs().sqrt();
    if s == 0.0 {
        1.0
    } else if u > 0.0 {
        s / s.tanh()
    } else {
        s / s.tan()
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

/// k = m²/4, the curvature scale of the base coordinate (K = −4k).
fn curvature(member: GodelType) -> f64 {
    0.25 * member.m2
}

/// The base coordinate ζ = G(m²ρ²)(x + i y) of a point (module documentation).
pub fn base_coordinate(member: GodelType, x: f64, y: f64) -> Complex {
    let g = half_tanhc(member.m2 * (x * x + y * y));
    Complex::new(g * x, g * y)
}

/// The inverse of [`base_coordinate`]: x + i y = F(k|ζ|²) ζ.
pub fn from_base_coordinate(member: GodelType, zeta: Complex) -> (f64, f64) {
    let f = atanhc(curvature(member) * zeta.norm_sqr());
    (f * zeta.re, f * zeta.im)
}

/// dζ for a displacement (dx, dy) at (x, y). From ζ = g(ρ) e^{iφ} with dg/dρ = 1 − k g²:
/// dζ = G dX + (1 − k|ζ|² − G) X (X·dX)/ρ², X = x + i y.
fn base_differential(member: GodelType, x: f64, y: f64, dx: f64, dy: f64) -> Complex {
    let r2 = x * x + y * y;
    if r2 == 0.0 {
        return Complex::new(dx, dy);
    }
    let g = half_tanhc(member.m2 * r2);
    let stretch = 1.0 - curvature(member) * g * g * r2;
    let radial = (stretch - g) * (x * dx + y * dy) / r2;
    Complex::new(g * dx + radial * x, g * dy + radial * y)
}

/// d(x + i y) for a displacement dζ at ζ: F dζ + (1/(1 − k|ζ|²) − F) ζ Re(ζ̄ dζ)/|ζ|².
fn from_base_differential(member: GodelType, zeta: Complex, dzeta: Complex) -> (f64, f64) {
    let n = zeta.norm_sqr();
    if n == 0.0 {
        return (dzeta.re, dzeta.im);
    }
    let v = curvature(member) * n;
    let f = atanhc(v);
    let radial = (1.0 / (1.0 - v) - f) * (zeta.conj() * dzeta).re / n;
    (
        f * dzeta.re + radial * zeta.re,
        f * dzeta.im + radial * zeta.im,
    )
}

/// The time shift χ = (Ω/k) arg(1 − k ζ̄0 ζ) of T_{P0} at ζ, written so that it stays
/// accurate as k → 0 (where it tends to −Ω Im(ζ̄0 ζ)): with d = Re(1 − k ζ̄0 ζ) > 0,
/// arg = −atan(k I/d), I = Im(ζ̄0 ζ), and atan(x)/x carries the 1/k.
fn time_shift(member: GodelType, zeta0: Complex, zeta: Complex) -> f64 {
    let k = curvature(member);
    let p = zeta0.conj() * zeta;
    let d = 1.0 - k * p.re;
    if d > 0.0 {
        -member.omega * p.im / d * atanc(k * p.im / d)
    } else {
        // Only on the sphere (k < 0), far from the axis: no cancellation to avoid.
        member.omega / k * (-k * p.im).atan2(d)
    }
}

/// The Killing field `field` of the member at `at`, components (ξ^t, ξ^x, ξ^y, ξ^z)
/// (module documentation; the Gödel member's are [`KillingField::at`] in Gödel's r).
pub fn killing_field(member: GodelType, field: KillingField, at: Event) -> FourVector {
    let (x, y) = (at.x, at.y);
    match field {
        KillingField::T => FourVector::new(1.0, 0.0, 0.0, 0.0),
        KillingField::Z => FourVector::new(0.0, 0.0, 0.0, 1.0),
        KillingField::Phi => FourVector::new(0.0, -y, x, 0.0),
        KillingField::Kx | KillingField::Ky => {
            let r2 = x * x + y * y;
            let kx = field == KillingField::Kx;
            if r2 == 0.0 {
                // On the axis: ∂x, ∂y.
                let (a, b) = if kx { (1.0, 0.0) } else { (0.0, 1.0) };
                return FourVector::new(0.0, a, b, 0.0);
            }
            let u = member.m2 * r2;
            let p = xcothx(u);
            let og = member.omega * half_tanhc(u);
            let (cc, ss, cs) = (x * x / r2, y * y / r2, (1.0 - p) * x * y / r2);
            if kx {
                FourVector::new(-og * y, cc + p * ss, cs, 0.0)
            } else {
                FourVector::new(og * x, cs, ss + p * cc, 0.0)
            }
        }
    }
}

/// The isometry X ↦ R_rotation(T_{P0}(X)) of a Gödel-type member, where T_{P0} sends
/// P0 = (t0, ζ0, z0) to the origin and R_α rotates by α about the axis (module
/// documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TypeIsometry {
    pub member: GodelType,
    pub t0: f64,
    /// Base coordinate of the event sent to the origin.
    pub zeta0: Complex,
    pub z0: f64,
    /// Rotation applied after the map to the origin (radians, counter-clockwise).
    pub rotation: f64,
}

impl TypeIsometry {
    /// The identity.
    pub fn identity(member: GodelType) -> Self {
        TypeIsometry {
            member,
            t0: 0.0,
            zeta0: Complex::default(),
            z0: 0.0,
            rotation: 0.0,
        }
    }

    /// T_{P0}: sends `p0` to the origin (no rotation). `None` if `p0` is not finite or, for
    /// m² < 0, lies outside the chart (μρ ≥ π, at or beyond the pole opposite the axis).
    pub fn to_origin(member: GodelType, p0: Event) -> Option<Self> {
        if !p0.is_finite() {
            return None;
        }
        if let Some(edge) = member.coordinate_radius() {
            if p0.r() >= edge {
                return None;
            }
        }
        Some(TypeIsometry {
            member,
            t0: p0.t,
            zeta0: base_coordinate(member, p0.x, p0.y),
            z0: p0.z,
            rotation: 0.0,
        })
    }

    /// The rotation by `alpha` about the axis ρ = 0.
    pub fn rotation(member: GodelType, alpha: f64) -> Self {
        TypeIsometry {
            rotation: alpha,
            ..TypeIsometry::identity(member)
        }
    }

    /// The flow of a Killing field for parameter `s`, exp(s ξ). ∂t, ∂z, ∂φ shift t, z, φ by
    /// s. On the x axis K_x = ∂x (ρ is the proper distance), so K_x carries the origin to
    /// (0, s, 0, 0), and its flow is T_P⁻¹ with P that event; likewise K_y. `None` for a
    /// translation with μ|s| ≥ π on the sphere (the image of the origin leaves the chart).
    pub fn flow(member: GodelType, field: KillingField, s: f64) -> Option<Self> {
        let id = TypeIsometry::identity(member);
        Some(match field {
            KillingField::T => TypeIsometry { t0: -s, ..id },
            KillingField::Z => TypeIsometry { z0: -s, ..id },
            KillingField::Phi => TypeIsometry::rotation(member, s),
            KillingField::Kx => {
                TypeIsometry::to_origin(member, Event::new(0.0, s, 0.0, 0.0))?.inverse()
            }
            KillingField::Ky => {
                TypeIsometry::to_origin(member, Event::new(0.0, 0.0, s, 0.0))?.inverse()
            }
        })
    }

    /// This map followed by a further rotation by `alpha`.
    pub fn then_rotate(self, alpha: f64) -> Self {
        TypeIsometry {
            rotation: self.rotation + alpha,
            ..self
        }
    }

    /// The inverse map: (R_α ∘ T_{P0})⁻¹ = R_{−α} ∘ T_{P1}, P1 = (−t0, −e^{iα} ζ0, −z0).
    pub fn inverse(&self) -> Self {
        TypeIsometry {
            member: self.member,
            t0: -self.t0,
            zeta0: (Complex::cis(self.rotation) * self.zeta0).scale(-1.0),
            z0: -self.z0,
            rotation: -self.rotation,
        }
    }

    /// Whether the map only shifts t and z: then its differential is the identity and no
    /// base-coordinate round trip is needed.
    fn is_translation(&self) -> bool {
        self.zeta0.re == 0.0 && self.zeta0.im == 0.0 && self.rotation == 0.0
    }

    /// The image of an event.
    pub fn apply(&self, e: Event) -> Event {
        if self.is_translation() {
            return Event::new(e.t - self.t0, e.x, e.y, e.z - self.z0);
        }
        self.image_event(e, &self.moved(e))
    }

    /// The differential: the image at `apply(at)` of the tangent vector `v` at `at`.
    pub fn push(&self, at: Event, v: FourVector) -> FourVector {
        let [w] = self.push_all(at, [v]);
        w
    }

    /// `push` of several vectors at one event (a tetrad): the base map of `at` made once.
    pub fn push_all<const N: usize>(&self, at: Event, vs: [FourVector; N]) -> [FourVector; N] {
        if self.is_translation() {
            return vs;
        }
        let m = self.moved(at);
        vs.map(|v| self.image_vector(at, v, &m))
    }

    /// `apply` and `push` together, the base coordinate computed once.
    pub fn apply_push(&self, at: Event, v: FourVector) -> (Event, FourVector) {
        if self.is_translation() {
            return (self.apply(at), v);
        }
        let m = self.moved(at);
        (self.image_event(at, &m), self.image_vector(at, v, &m))
    }

    /// The base map of `at`: ζ ↦ e^{iα}(ζ − ζ0)/(1 − k ζ̄0 ζ).
    fn moved(&self, at: Event) -> Moved {
        let zeta = base_coordinate(self.member, at.x, at.y);
        let k = curvature(self.member);
        let den = Complex::new(1.0, 0.0) - (self.zeta0.conj() * zeta).scale(k);
        let rot = Complex::cis(self.rotation);
        let zeta1 = rot * ((zeta - self.zeta0) / den);
        Moved {
            zeta,
            den,
            rot,
            zeta1,
        }
    }

    fn image_event(&self, at: Event, m: &Moved) -> Event {
        let (x, y) = from_base_coordinate(self.member, m.zeta1);
        Event::new(
            at.t - self.t0 - time_shift(self.member, self.zeta0, m.zeta),
            x,
            y,
            at.z - self.z0,
        )
    }

    fn image_vector(&self, at: Event, v: FourVector, m: &Moved) -> FourVector {
        let k = curvature(self.member);
        let dzeta = base_differential(self.member, at.x, at.y, v.x, v.y);
        // d[(ζ − ζ0)/(1 − k ζ̄0 ζ)] = (1 − k|ζ0|²) dζ/(1 − k ζ̄0 ζ)².
        let scale = 1.0 - k * self.zeta0.norm_sqr();
        let dzeta1 = m.rot * (dzeta.scale(scale) / (m.den * m.den));
        let (dx, dy) = from_base_differential(self.member, m.zeta1, dzeta1);
        // dt′ = dt − dχ = dt + Ω Im(ζ̄0 dζ/(1 − k ζ̄0 ζ)).
        let dt = v.t + self.member.omega * (self.zeta0.conj() * dzeta / m.den).im;
        FourVector::new(dt, dx, dy, v.z)
    }
}

/// The base coordinate of an event and its image under an isometry's base map.
struct Moved {
    zeta: Complex,
    den: Complex,
    rot: Complex,
    zeta1: Complex,
}
