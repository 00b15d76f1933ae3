//! An observer's worldline over a stretch of its proper time: the geodesic with its
//! 4-velocity (docs/physics.md, "Frames" and "Exact geodesics"), and that 4-velocity read
//! back as a velocity relative to the static observer where it arrives. `godel explore`'s
//! flight (the page's controls and "fall freely") moves its observer with this.
//!
//! In Gödel's universe the geodesic is the closed form carried by the isometries
//! ([`ExactGeodesic`]); in Minkowski space it is the straight line; in the Gödel-type family
//! it is integrated (DOP853). The 4-velocity of an
//! observer moving with `v` relative to the static frame (e₀, e₁, e₂, e₃) is
//! u = γ(e₀ + v n·e), so back: γ = −g(u, e₀), γ v nᵢ = g(u, eᵢ).

use crate::closed_form::ExactGeodesic;
use crate::frame::LocalVelocity;
use crate::geodesic::{trace, Geodesic, GeodesicKind, StopReason, TraceLimits};
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
/// velocity there; `None` where the result is not finite.
pub fn fall(
    metric: &Metric,
    at: Event,
    velocity: LocalVelocity,
    tau: f64,
) -> Option<(Event, LocalVelocity)> {
    let u = metric.observer_frame(at, velocity).e[0];
    let (event, tangent) = match metric {
        Metric::Godel(g) => ExactGeodesic::new(g.a, at, u)?.at(tau),
        Metric::GodelType(_) => integrated_fall(metric, at, u, tau)?,
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

/// The geodesic with 4-velocity `u` at `at` after proper time `tau`, integrated (DOP853 at
/// the default tolerances; a fall into the past runs along −u); `None` unless the
/// integration reaches |tau| within its step budget.
fn integrated_fall(
    metric: &Metric,
    at: Event,
    u: FourVector,
    tau: f64,
) -> Option<(Event, FourVector)> {
    if tau == 0.0 {
        return Some((at, u));
    }
    let sign = tau.signum();
    let start = FourVector::from_array(u.to_array().map(|c| sign * c));
    let geodesic = Geodesic::from_tangent(metric, GeodesicKind::Timelike, at, start);
    let limits = TraceLimits {
        max_affine: tau.abs(),
        ..Default::default()
    };
    let traced = trace(*metric, &geodesic, &limits);
    if traced.stop != StopReason::AffineLimit {
        return None;
    }
    let end = traced.end;
    let tangent = end.tangent(metric).to_array().map(|c| sign * c);
    Some((end.x, FourVector::from_array(tangent)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Godel, Minkowski};

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
}
