//! An observer's worldline over a stretch of its proper time: the geodesic with its
//! 4-velocity (docs/physics.md, "Frames" and "Exact geodesics"), and that 4-velocity read
//! back as a velocity relative to the static observer where it arrives. `godel explore`'s
//! flight (the page's controls and "fall freely") moves its observer with this.
//!
//! In Gödel's universe the geodesic is the closed form carried by the isometries
//! ([`ExactGeodesic`]); in a Gödel-type member it is the family's closed form
//! ([`TypeExactGeodesic`], "The Gödel-type family", "Closed-form geodesics of the family"),
//! which covers every event of the member's chart, so nothing is integrated; in Minkowski
//! space it is the straight line. The 4-velocity of an
//! observer moving with `v` relative to the static frame (e₀, e₁, e₂, e₃) is
//! u = γ(e₀ + v n·e), so back: γ = −g(u, e₀), γ v nᵢ = g(u, eᵢ).

use crate::closed_form::ExactGeodesic;
use crate::frame::LocalVelocity;
use crate::godel_type_geodesic::TypeExactGeodesic;
use crate::metric::{Metric, Spacetime};
use crate::vectors::{Event, FourVector};

/// The velocity relative to the static observer at `at` of an observer with 4-velocity `u`
/// (future-directed, timelike); `None` where `u` is not.
pub fn local_velocity(metric: &Metric, at: Event, u: FourVector) -> Option<LocalVelocity> {
    let e = metric.static_frame(at).e;
    let gamma = -metric.dot(at, u, e[0]);
    let p = [1, 2, 3].map(|i| metric.dot(at, u, e[i]) / gamma);
    let speed = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    if gamma.is_nan() || gamma < 1.0 - 1e-9 || !speed.is_finite() || speed >= 1.0 {
        return None;
    }
    if speed == 0.0 {
        return Some(LocalVelocity::REST);
    }
    LocalVelocity::new(speed, p)
}

/// Where an observer at `at` moving with `velocity` (relative to the static observer there)
/// is after `tau` of its proper time (negative: before) when it falls freely, and its
/// velocity there; `None` where the result is not finite (or, on a member's sphere, where
/// `at` is outside the chart).
pub fn fall(
    metric: &Metric,
    at: Event,
    velocity: LocalVelocity,
    tau: f64,
) -> Option<(Event, LocalVelocity)> {
    let u = metric.observer_frame(at, velocity).e[0];
    let (event, tangent) = match metric {
        Metric::Godel(g) => ExactGeodesic::new(g.a, at, u)?.at(tau),
        Metric::GodelType(member) => TypeExactGeodesic::new(*member, at, u)?.at(tau),
        Metric::Minkowski(_) => (
            Event::new(
                at.t + tau * u.t,
                at.x + tau * u.x,
                at.y + tau * u.y,
                at.z + tau * u.z,
            ),
            u,
        ),
    };
    if !event.is_finite() {
        return None;
    }
    Some((event, local_velocity(metric, event, tangent)?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::{trace, Geodesic, GeodesicKind, StopReason, TraceLimits};
    use crate::{Godel, GodelType, Minkowski, Tolerances};

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
    }

    #[test]
    fn the_velocity_read_back_is_the_velocity_boosted_to() {
        let metric = Metric::Godel(Godel::new(1.0));
        let at = Event::new(0.3, 0.4, -0.7, 0.2);
        let v = LocalVelocity::new(0.8, [0.3, -1.0, 0.5]).unwrap();
        let u = metric.observer_frame(at, v).e[0];
        let back = local_velocity(&metric, at, u).unwrap();
        assert!(close(back.speed, 0.8, 1e-12), "{back:?}");
        for i in 0..3 {
            assert!(close(back.direction[i], v.direction[i], 1e-12), "{back:?}");
        }
        let rest = local_velocity(&metric, at, metric.static_frame(at).e[0]).unwrap();
        assert!(rest.speed < 1e-12);
    }

    #[test]
    fn along_z_the_observer_moves_gamma_v_tau_in_gamma_tau() {
        // Gödel's universe is a product with the z line: along z, t = γτ and z = γvτ exactly,
        // from any event, and the velocity stays.
        let metric = Metric::Godel(Godel::new(1.0));
        let at = Event::new(1.0, 0.5, 0.2, -0.3);
        let v = LocalVelocity::new(0.6, [0.0, 0.0, 1.0]).unwrap();
        let (e, w) = fall(&metric, at, v, 2.0).unwrap();
        let gamma = 1.25;
        assert!(close(e.z, at.z + gamma * 0.6 * 2.0, 1e-12), "{e:?}");
        assert!(close(e.t, at.t + gamma * 2.0, 1e-12), "{e:?}");
        assert!(close(e.x, at.x, 1e-12) && close(e.y, at.y, 1e-12), "{e:?}");
        assert!(close(w.speed, 0.6, 1e-9), "{w:?}");
        // The static observers (the dust) fall freely: t = τ.
        let (e, w) = fall(&metric, at, LocalVelocity::REST, 3.0).unwrap();
        assert!(
            close(e.t, at.t + 3.0, 1e-12) && close(e.x, at.x, 1e-12),
            "{e:?}"
        );
        assert!(w.speed < 1e-9);
    }

    #[test]
    fn a_falling_observer_keeps_unit_four_velocity_and_comes_back_when_reversed() {
        let metric = Metric::Godel(Godel::new(1.0));
        let at = Event::new(0.0, 0.3, 0.1, 0.0);
        let v = LocalVelocity::new(0.5, [1.0, 1.0, 0.0]).unwrap();
        let (e, w) = fall(&metric, at, v, 1.5).unwrap();
        let u = metric.observer_frame(e, w).e[0];
        assert!(close(metric.dot(e, u, u), -1.0, 1e-9));
        let (back, w0) = fall(&metric, e, w, -1.5).unwrap();
        for (a, b) in [
            (back.t, at.t),
            (back.x, at.x),
            (back.y, at.y),
            (back.z, at.z),
        ] {
            assert!(close(a, b, 1e-9), "{back:?}");
        }
        assert!(close(w0.speed, 0.5, 1e-9), "{w0:?}");
        // Minkowski: the straight line.
        let flat = Metric::Minkowski(Minkowski);
        let (e, _) = fall(&flat, at, v, 2.0).unwrap();
        let gv = 2.0 * 0.5 / 0.75f64.sqrt() / 2f64.sqrt();
        assert!(
            close(e.x, 0.3 + gv, 1e-12) && close(e.y, 0.1 + gv, 1e-12),
            "{e:?}"
        );
    }

    /// The geodesic with 4-velocity `u` at `at` after proper time `tau` (negative: along −u
    /// into the past), integrated by DOP853 at tight tolerances.
    fn integrated(metric: &Metric, at: Event, u: FourVector, tau: f64) -> (Event, FourVector) {
        let sign = tau.signum();
        let start = FourVector::from_array(u.to_array().map(|c| sign * c));
        let geodesic = Geodesic::from_tangent(metric, GeodesicKind::Timelike, at, start);
        let limits = TraceLimits {
            max_affine: tau.abs(),
            tolerances: Tolerances {
                rtol: 1e-13,
                atol: 1e-13,
                h_max: f64::INFINITY,
                h_min: 1e-14,
            },
            ..Default::default()
        };
        let traced = trace(*metric, &geodesic, &limits);
        assert_eq!(traced.stop, StopReason::AffineLimit, "{metric:?} {at:?}");
        let end = traced.end;
        let tangent = end.tangent(metric).to_array().map(|c| sign * c);
        (end.x, FourVector::from_array(tangent))
    }

    /// In the Gödel-type family the fall is the closed form: it equals the integrated
    /// geodesic for members m²/Ω² ∈ {−1, 0, 1, 2, 3.5, 4, 6}, from events on and off the axis
    /// (on the sphere within π/μ − ρ_c of the axis, as scenes keep them), forward and
    /// backward in proper time, and the velocity read back agrees too.
    #[test]
    fn in_the_family_the_fall_is_the_integrated_geodesic() {
        let omega = 0.7;
        let mut worst: f64 = 0.0;
        for ratio in [-1.0, 0.0, 1.0, 2.0, 3.5, 4.0, 6.0] {
            let member = GodelType::new(ratio * omega * omega, omega);
            let metric = Metric::GodelType(member);
            let reach = match (member.coordinate_radius(), member.critical_radius()) {
                (Some(edge), Some(rc)) => edge - rc,
                _ => 3.0,
            };
            let starts = [
                (Event::new(0.0, 0.0, 0.0, 0.0), LocalVelocity::REST),
                (
                    Event::new(0.3, 0.0, 0.0, -0.2),
                    LocalVelocity::new(0.7, [1.0, 0.2, 0.3]).unwrap(),
                ),
                (
                    Event::new(-1.0, 0.6 * reach, -0.3 * reach, 0.5),
                    LocalVelocity::new(0.5, [-0.3, 1.0, -0.4]).unwrap(),
                ),
                (
                    Event::new(2.0, -0.9 * reach, 0.2 * reach, 0.0),
                    LocalVelocity::new(0.9, [0.1, -1.0, 0.0]).unwrap(),
                ),
            ];
            for (at, v) in starts {
                let u = metric.observer_frame(at, v).e[0];
                for tau in [2.5, -2.5, 0.4, -0.4] {
                    let (e, w) = fall(&metric, at, v, tau).unwrap();
                    let (e2, u2) = integrated(&metric, at, u, tau);
                    let w2 = local_velocity(&metric, e2, u2).unwrap();
                    let tangent = metric.observer_frame(e, w).e[0];
                    let off = [
                        e.t - e2.t,
                        e.x - e2.x,
                        e.y - e2.y,
                        e.z - e2.z,
                        tangent.t - u2.t,
                        tangent.x - u2.x,
                        tangent.y - u2.y,
                        tangent.z - u2.z,
                        w.speed - w2.speed,
                    ]
                    .iter()
                    .fold(0.0f64, |m, d| m.max(d.abs()));
                    worst = worst.max(off);
                    assert!(
                        off < 1e-8,
                        "m²/Ω² = {ratio}, from {at:?} at {v:?}, τ = {tau}: closed {e:?} {w:?}, integrated {e2:?} {w2:?}"
                    );
                }
            }
        }
        eprintln!("family fall: worst difference from the integration {worst:e}");
    }
}
