//! Stereo eyes: an observer displaced along its camera's right axis, as an exact event with
//! its own frame (docs/physics.md, "Stereo eyes").
//!
//! An eye is the image of the observer under the isometry exp(d ξ), where ξ is the Killing
//! field whose value at the observer's event is the observer's unit right axis e_R (a
//! spacelike vector orthogonal to its 4-velocity, so the displacement is "at the same time
//! in its frame") and which does not rotate there (no ∂φ part once the event is moved to the
//! origin). Because exp(d ξ) is an isometry, the eye's frame is the observer's frame pushed
//! forward: the eye moves as the observer does, and its pictures are those of an observer of
//! the same kind at another event. Its orbit has proper length |d| (|ξ| is constant along
//! an orbit of a Killing field).
//!
//! - Minkowski: ξ is the constant translation e_R; the eye is x + d e_R with the same frame.
//! - Gödel: with T_P the map of the observer's event P to the origin
//!   ([`Isometry::to_origin`]) and u = (T_P)_* e_R = (u^t, u^x, u^y, u^z) there (the metric is
//!   Minkowski's at the origin), ξ = T_P^* (u^t ∂t + u^x K_x + u^y K_y + u^z ∂z). ∂t and ∂z are
//!   central, and u^x K_x + u^y K_y = ρ (R_θ)_* K_x with ρ e^{iθ} = u^x + i u^y
//!   ([∂φ, K_x] = −K_y, [∂φ, K_y] = K_x), so
//!   exp(d ξ) = T_P⁻¹ ∘ shift_t(d u^t) ∘ shift_z(d u^z) ∘ R_θ ∘ exp(d ρ K_x) ∘ R_{−θ} ∘ T_P.
//!   Checked against integrating dX/ds = ξ(X) in `tests/integration/eyes.rs`.
//! - A Gödel-type member: the same product with the member's isometries
//!   ([`TypeIsometry`]; docs/physics.md, "The Gödel-type family", "Isometries of the
//!   family"), whose K_x and K_y are ∂x and ∂y on the axis and obey the same brackets with
//!   ∂φ. On the sphere (m² < 0) two factors can fail: the flow of K_x beyond the pole
//!   (μ|d ρ| ≥ π), and T_P⁻¹, whose time shift jumps across a cut on the far side of the
//!   sphere; an eye there is not placed (`None`). Along exp(s ρ K_x) the base point runs on a
//!   straight line of the stereographic plane from 0, on which the cut's test quantity
//!   Re(1 − k ζ̄₁ ζ) is affine, so checking the eye itself checks the whole orbit. With a
//!   scene's observer (within π/μ − ρ_c of the axis, so |k ζ_P| ≤ Ω) the cut needs
//!   |ζ| ≥ 1/Ω, which the small separations of scenes reach only at speeds near light along
//!   the right axis (u, and so the flow's parameter, grows as γ).

use crate::frame::{boost, LocalVelocity};
use crate::godel_type::GodelType;
use crate::godel_type_symmetry::{base_coordinate, TypeIsometry};
use crate::isometry::{Complex, Isometry};
use crate::killing::KillingField;
use crate::metric::{Metric, Spacetime};
use crate::polarization::cross;
use crate::vectors::{Event, FourVector, Tetrad};

/// An observer as the scene describes one: its event, its velocity relative to the static
/// observer there, and its camera's forward and up axes in its own frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewpoint {
    pub event: Event,
    pub velocity: LocalVelocity,
    pub forward: [f64; 3],
    pub up: [f64; 3],
}

impl Viewpoint {
    /// The observer's frame (the static frame boosted by its velocity).
    pub fn frame(&self, metric: &Metric) -> Tetrad {
        metric.observer_frame(self.event, self.velocity)
    }

    /// The camera's axis with components `n` in the observer's spatial frame, as a vector.
    fn axis(frame: &Tetrad, n: [f64; 3]) -> FourVector {
        frame.vector([0.0, n[0], n[1], n[2]])
    }

    /// The eye at proper distance `offset` along the camera's right axis (forward × up;
    /// negative: to the left): the image of this viewpoint under exp(offset ξ) (module
    /// documentation). An offset of 0 gives this viewpoint unchanged; `None` only on the
    /// sphere of a Gödel-type member with m² < 0, where the eye would reach the pole opposite
    /// the axis or cross the cut of the map back (and for a member's event that is not
    /// finite).
    pub fn eye(&self, metric: &Metric, offset: f64) -> Option<Viewpoint> {
        if offset == 0.0 {
            return Some(*self);
        }
        let frame = self.frame(metric);
        let right = cross(self.forward, self.up);
        let e_right = Viewpoint::axis(&frame, right);
        let carried = [
            frame.e[0],
            Viewpoint::axis(&frame, self.forward),
            Viewpoint::axis(&frame, self.up),
        ];
        match metric {
            Metric::Minkowski(_) => Some(Viewpoint {
                event: Event::from_array(add(self.event.to_array(), offset, e_right)),
                ..*self
            }),
            Metric::Godel(g) => {
                let a = g.a;
                let to_origin = Isometry::to_origin(a, self.event);
                let u = to_origin.push(self.event, e_right);
                let (rho, theta) = (u.x.hypot(u.y), u.y.atan2(u.x));
                let steps = [
                    to_origin,
                    Isometry::rotation(a, -theta),
                    Isometry::flow(a, KillingField::Kx, offset * rho),
                    Isometry::rotation(a, theta),
                    Isometry::flow(a, KillingField::T, offset * u.t),
                    Isometry::flow(a, KillingField::Z, offset * u.z),
                    to_origin.inverse(),
                ];
                let (event, carried) =
                    carry(&steps, self.event, carried, Isometry::apply, Isometry::push);
                Some(Viewpoint::seen_at(metric, event, carried))
            }
            Metric::GodelType(member) => {
                let m = *member;
                let to_origin = TypeIsometry::to_origin(m, self.event)?;
                let u = to_origin.push(self.event, e_right);
                let (rho, theta) = (u.x.hypot(u.y), u.y.atan2(u.x));
                let steps = [
                    to_origin,
                    TypeIsometry::rotation(m, -theta),
                    TypeIsometry::flow(m, KillingField::Kx, offset * rho)?,
                    TypeIsometry::rotation(m, theta),
                    TypeIsometry::flow(m, KillingField::T, offset * u.t)?,
                    TypeIsometry::flow(m, KillingField::Z, offset * u.z)?,
                ];
                let (moved, at_origin) = carry(
                    &steps,
                    self.event,
                    carried,
                    TypeIsometry::apply,
                    TypeIsometry::push,
                );
                if across_the_cut(m, self.event, moved) {
                    return None;
                }
                let back = to_origin.inverse();
                let (event, carried) = carry(
                    &[back],
                    moved,
                    at_origin,
                    TypeIsometry::apply,
                    TypeIsometry::push,
                );
                Some(Viewpoint::seen_at(metric, event, carried))
            }
        }
    }

    /// The viewpoint at `event` whose 4-velocity and forward and up axes are `carried`, in
    /// the scene's terms: velocity relative to the static observer there, axes in the frame
    /// that velocity's boost gives (renormalized against rounding).
    fn seen_at(metric: &Metric, event: Event, carried: [FourVector; 3]) -> Viewpoint {
        let g = |u: FourVector, v: FourVector| metric.dot(event, u, v);
        let fixed = metric.static_frame(event);
        let gamma = -g(carried[0], fixed.e[0]);
        let along = [1, 2, 3].map(|i| g(carried[0], fixed.e[i]) / gamma);
        let speed = norm(along);
        let velocity = match LocalVelocity::new(speed, along) {
            Some(v) if speed > 0.0 => v,
            _ => LocalVelocity::REST,
        };
        let frame = boost(&fixed, velocity);
        let components = |v: FourVector| unit([1, 2, 3].map(|i| g(v, frame.e[i])));
        Viewpoint {
            event,
            velocity,
            forward: components(carried[1]),
            up: components(carried[2]),
        }
    }
}

/// `event` and the vectors `carried` there mapped by each of `steps` in turn.
fn carry<M>(
    steps: &[M],
    event: Event,
    carried: [FourVector; 3],
    apply: impl Fn(&M, Event) -> Event,
    push: impl Fn(&M, Event, FourVector) -> FourVector,
) -> (Event, [FourVector; 3]) {
    let (mut event, mut carried) = (event, carried);
    for map in steps {
        let at = event;
        event = apply(map, at);
        carried = carried.map(|v| push(map, at, v));
    }
    (event, carried)
}

/// Whether T_P⁻¹, the map back from the origin to the observer's event `p`, would take
/// `moved` across its cut: on the sphere (m² < 0), where Re(1 − k ζ̄₁ ζ) ≤ 0 with ζ₁ = −ζ_P
/// the base coordinate T_P⁻¹ sends to the origin and k = m²/4 (docs/physics.md, "Isometries
/// of the family"). Never for m² ≥ 0.
fn across_the_cut(member: GodelType, p: Event, moved: Event) -> bool {
    if member.m2 >= 0.0 {
        return false;
    }
    let zeta_p = base_coordinate(member, p.x, p.y);
    let zeta = base_coordinate(member, moved.x, moved.y);
    let one = Complex::new(1.0, 0.0);
    (one + (zeta_p.conj() * zeta).scale(0.25 * member.m2)).re <= 0.0
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = norm(v);
    v.map(|c| c / n)
}

fn add(x: [f64; 4], s: f64, v: FourVector) -> [f64; 4] {
    let v = v.to_array();
    [0, 1, 2, 3].map(|i| x[i] + s * v[i])
}
