//! Stereo eyes (`spacetime::eyes`, docs/physics.md "Stereo eyes"): an eye is the observer
//! moved by the flow of the Killing field that is its right axis at its event. Checked against
//! integrating that flow, against the conserved products of a Killing field with the carried
//! frame, and in flat space against a plain translation; in the Gödel-type family likewise
//! with the member's Killing fields and isometries, and on its sphere the refusals.

use crate::common::{integrate_field, max_abs, Rng};
use crate::godel_type_symmetry::to_godel;
use spacetime::*;

/// A random observer (event within r < 3a, speed below 0.9) with orthonormal camera axes.
fn viewpoint(rng: &mut Rng, a: f64) -> Viewpoint {
    viewpoint_within(rng, 3.0 * a)
}

/// A random observer within `r_max` of the axis (speed below 0.9), orthonormal camera axes.
fn viewpoint_within(rng: &mut Rng, r_max: f64) -> Viewpoint {
    let event = rng.event(r_max);
    let velocity = LocalVelocity::new(rng.uniform(0.0, 0.9), rng.direction()).unwrap();
    let forward = rng.direction();
    let d = rng.direction();
    let dot = forward[0] * d[0] + forward[1] * d[1] + forward[2] * d[2];
    let up = [0, 1, 2].map(|i| d[i] - dot * forward[i]);
    let n = (up[0] * up[0] + up[1] * up[1] + up[2] * up[2]).sqrt();
    Viewpoint {
        event,
        velocity,
        forward,
        up: up.map(|c| c / n),
    }
}

fn right(v: &Viewpoint) -> [f64; 3] {
    let (f, u) = (v.forward, v.up);
    [
        f[1] * u[2] - f[2] * u[1],
        f[2] * u[0] - f[0] * u[2],
        f[0] * u[1] - f[1] * u[0],
    ]
}

/// The observer's 4-velocity and camera axes (forward, up, right) as vectors at its event.
fn carried(metric: &Metric, v: &Viewpoint) -> [FourVector; 4] {
    let frame = v.frame(metric);
    let axis = |n: [f64; 3]| frame.vector([0.0, n[0], n[1], n[2]]);
    [frame.e[0], axis(v.forward), axis(v.up), axis(right(v))]
}

#[test]
fn an_offset_of_zero_is_the_observer_itself() {
    let mut rng = Rng::new(37);
    for metric in [Metric::Godel(Godel::new(1.0)), Metric::Minkowski(Minkowski)] {
        let v = viewpoint(&mut rng, 1.0);
        assert_eq!(v.eye(&metric, 0.0), Some(v));
    }
}

#[test]
fn in_flat_space_an_eye_is_the_event_moved_along_the_right_axis() {
    let mut rng = Rng::new(38);
    let metric = Metric::Minkowski(Minkowski);
    for _ in 0..50 {
        let v = viewpoint(&mut rng, 1.0);
        let d = rng.uniform(-0.5, 0.5);
        let eye = v.eye(&metric, d).expect("a Gödel or Minkowski eye");
        let e_r = carried(&metric, &v)[3].to_array();
        let want: [f64; 4] = std::array::from_fn(|i| v.event.to_array()[i] + d * e_r[i]);
        let moved: [f64; 4] = std::array::from_fn(|i| eye.event.to_array()[i] - want[i]);
        assert!(max_abs(moved) < 1e-14, "{moved:?}");
        // Orthogonal to the 4-velocity: the eyes are at the same time in the observer's frame.
        let u = carried(&metric, &v)[0];
        let shift = FourVector::from_array(std::array::from_fn(|i| {
            eye.event.to_array()[i] - v.event.to_array()[i]
        }));
        assert!(metric.dot(v.event, u, shift).abs() < 1e-14);
        assert_eq!(
            (eye.velocity, eye.forward, eye.up),
            (v.velocity, v.forward, v.up)
        );
    }
}

/// In Gödel's universe, with T the map of the observer's event to the origin and u the right
/// axis there: the eye is T⁻¹ of the point the flow of ξ_u = u^t ∂t + u^x K_x + u^y K_y + u^z ∂z
/// reaches from the origin in parameter d (integrated with RK4); and the isometry keeps every
/// product g(V, ξ) of a carried vector V (4-velocity, forward, up) with the field.
#[test]
fn in_godels_universe_an_eye_is_the_flow_of_the_right_axis_killing_field() {
    let mut rng = Rng::new(39);
    let (mut worst_event, mut worst_product): (f64, f64) = (0.0, 0.0);
    for a in [1.0, 0.5] {
        let metric = Metric::Godel(Godel::new(a));
        for _ in 0..40 {
            let v = viewpoint(&mut rng, a);
            let d = rng.uniform(-0.6, 0.6) * a;
            let eye = v.eye(&metric, d).expect("a Gödel or Minkowski eye");
            let to_origin = Isometry::to_origin(a, v.event);
            let before = carried(&metric, &v);
            let u = to_origin.push(v.event, before[3]).to_array();
            let fields = [
                KillingField::T,
                KillingField::Kx,
                KillingField::Ky,
                KillingField::Z,
            ];
            let xi = |e: Event| {
                let parts = fields.map(|f| f.at(a, e).to_array());
                FourVector::from_array(std::array::from_fn(|m| {
                    (0..4).map(|k| u[k] * parts[k][m]).sum()
                }))
            };
            let origin = Event::new(0.0, 0.0, 0.0, 0.0);
            let reached = integrate_field(xi, origin, d, 400);
            let want = to_origin.inverse().apply(reached).to_array();
            let off: [f64; 4] = std::array::from_fn(|i| eye.event.to_array()[i] - want[i]);
            worst_event = worst_event.max(max_abs(off) / a);
            // The products at the origin and at the reached point, in the origin's chart.
            let after = carried(&metric, &eye);
            let at_eye = to_origin.apply(eye.event);
            for k in 0..3 {
                let p0 = metric.dot(origin, to_origin.push(v.event, before[k]), xi(origin));
                let pushed = to_origin.push(eye.event, after[k]);
                let p1 = metric.dot(at_eye, pushed, xi(at_eye));
                worst_product = worst_product.max((p1 - p0).abs());
            }
            // The eye's axes are orthonormal and the eye moves no faster than light.
            assert!(eye.velocity.speed < 1.0);
            let f = eye.forward;
            let up = eye.up;
            assert!((f[0] * up[0] + f[1] * up[1] + f[2] * up[2]).abs() < 1e-12);
        }
    }
    eprintln!("eyes: worst event {worst_event:e} (units of a), worst product {worst_product:e}");
    assert!(worst_event < 1e-10, "{worst_event:e}");
    assert!(worst_product < 1e-12, "{worst_product:e}");
}

const OMEGA: f64 = 0.7;

/// Members m²/Ω² ∈ {−1, 0, 1, 3.5, 4, 6} at Ω = 0.7, each with how far from the axis its
/// observers are put: π/μ − ρ_c on the sphere (as scenes allow), else 3 length scales.
fn members() -> Vec<(GodelType, f64)> {
    [-1.0, 0.0, 1.0, 3.5, 4.0, 6.0]
        .iter()
        .map(|ratio| {
            let m = GodelType::new(ratio * OMEGA * OMEGA, OMEGA);
            let reach = match (m.coordinate_radius(), m.critical_radius()) {
                (Some(edge), Some(rho_c)) => edge - rho_c,
                _ => 3.0 * Metric::GodelType(m).length_scale(),
            };
            (m, reach)
        })
        .collect()
}

/// The member's field ξ_u = u^t ∂t + u^x K_x + u^y K_y + u^z ∂z at `e`.
fn member_field(member: GodelType, u: [f64; 4], e: Event) -> FourVector {
    let fields = [
        KillingField::T,
        KillingField::Kx,
        KillingField::Ky,
        KillingField::Z,
    ];
    let parts = fields.map(|f| killing_field(member, f, e).to_array());
    FourVector::from_array(std::array::from_fn(|m| {
        (0..4).map(|k| u[k] * parts[k][m]).sum()
    }))
}

/// In every member, as in Gödel's universe: the eye is T⁻¹ of the point the flow of ξ_u
/// reaches from the origin in parameter d (RK4), the isometry keeps every product g(V, ξ) of
/// a carried vector with the field, |ξ| = 1 along the orbit (so the eye is at proper distance
/// |d| along it), the eye's speed is the observer's (isometries keep ∂t), the eye of the eye
/// at −d is the observer again, and an offset of 0 changes nothing.
#[test]
fn in_the_godel_type_family_an_eye_is_the_flow_of_the_right_axis_killing_field() {
    let mut rng = Rng::new(40);
    let (mut worst_event, mut worst_product, mut worst_back): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for (member, reach) in members() {
        let metric = Metric::GodelType(member);
        let a = metric.length_scale();
        for _ in 0..30 {
            let v = viewpoint_within(&mut rng, reach);
            assert_eq!(v.eye(&metric, 0.0), Some(v));
            // Scenes' eyes: half a separation of at most a.
            let d = rng.uniform(-0.5, 0.5) * a;
            let eye = v
                .eye(&metric, d)
                .unwrap_or_else(|| panic!("no eye for {member:?} at {v:?}, d = {d}"));
            let to_origin = TypeIsometry::to_origin(member, v.event).unwrap();
            let before = carried(&metric, &v);
            let u = to_origin.push(v.event, before[3]).to_array();
            let xi = |e: Event| member_field(member, u, e);
            let origin = Event::new(0.0, 0.0, 0.0, 0.0);
            let reached = integrate_field(xi, origin, d, 400);
            let want = to_origin.inverse().apply(reached).to_array();
            let off: [f64; 4] = std::array::from_fn(|i| eye.event.to_array()[i] - want[i]);
            worst_event = worst_event.max(max_abs(off) / a);
            let length = metric.dot(reached, xi(reached), xi(reached));
            assert!((length - 1.0).abs() < 1e-9, "{member:?}: |ξ|² = {length}");
            let after = carried(&metric, &eye);
            let at_eye = to_origin.apply(eye.event);
            for k in 0..3 {
                let p0 = metric.dot(origin, to_origin.push(v.event, before[k]), xi(origin));
                let pushed = to_origin.push(eye.event, after[k]);
                let p1 = metric.dot(at_eye, pushed, xi(at_eye));
                worst_product = worst_product.max((p1 - p0).abs());
            }
            assert!(
                (eye.velocity.speed - v.velocity.speed).abs() < 1e-9,
                "{member:?}: {eye:?} {v:?}"
            );
            let f = eye.forward;
            let up = eye.up;
            assert!((f[0] * up[0] + f[1] * up[1] + f[2] * up[2]).abs() < 1e-12);
            let back = eye.eye(&metric, -d).unwrap();
            let moved: [f64; 4] =
                std::array::from_fn(|i| back.event.to_array()[i] - v.event.to_array()[i]);
            let turned = (0..3)
                .map(|i| {
                    (back.forward[i] - v.forward[i])
                        .abs()
                        .max((back.up[i] - v.up[i]).abs())
                })
                .fold(0.0f64, f64::max);
            worst_back = worst_back.max(max_abs(moved) / a).max(turned);
        }
    }
    eprintln!(
        "member eyes: worst event {worst_event:e} (units of a), worst product {worst_product:e}, worst round trip {worst_back:e}"
    );
    assert!(worst_event < 1e-10, "{worst_event:e}");
    assert!(worst_product < 1e-12, "{worst_product:e}");
    assert!(worst_back < 1e-9, "{worst_back:e}");
}

/// On the sphere (m² = −Ω²) an eye is refused where the isometries cannot place it: when
/// the flow along the right axis reaches the pole opposite the axis, and when the map back
/// would take it across its cut (an observer far out, moving at nearly the speed of light
/// along its right axis). Short of the cut the eye is still the flow's.
#[test]
fn on_the_sphere_eyes_the_isometries_cannot_place_are_refused() {
    let member = GodelType::new(-OMEGA * OMEGA, OMEGA);
    let metric = Metric::GodelType(member);
    let edge = member.coordinate_radius().unwrap();
    let on_axis = Viewpoint {
        event: Event::new(0.0, 0.0, 0.0, 0.0),
        velocity: LocalVelocity::REST,
        forward: [0.0, 1.0, 0.0],
        up: [0.0, 0.0, 1.0],
    };
    // Right = forward × up = +x: the eye runs along the x axis, ρ = d.
    let near = on_axis.eye(&metric, 0.99 * edge).unwrap();
    assert!((near.event.x - 0.99 * edge).abs() < 1e-9, "{near:?}");
    assert_eq!(on_axis.eye(&metric, edge), None);
    // Far out along x, moving fast along +x (its right axis): the flow's parameter is γ d.
    let rho_c = member.critical_radius().unwrap();
    let far = Viewpoint {
        event: Event::new(0.0, edge - rho_c, 0.0, 0.0),
        velocity: LocalVelocity::new(0.999, [1.0, 0.0, 0.0]).unwrap(),
        ..on_axis
    };
    // The flow integrated in the observer's own coordinates, ξ = (T_P⁻¹)_* ξ_u ∘ T_P: its
    // time is continuous where the map back's time shift jumps.
    let to_origin = TypeIsometry::to_origin(member, far.event).unwrap();
    let back = to_origin.inverse();
    let u = to_origin
        .push(far.event, carried(&metric, &far)[3])
        .to_array();
    let field = |x: Event| {
        let there = to_origin.apply(x);
        back.push(there, member_field(member, u, there))
    };
    let flow = |d: f64| integrate_field(field, far.event, d, 4000);
    // Placed from d = 0 up to some d, refused beyond (and never placed again).
    let mut placed = 0;
    for k in 1..=200 {
        let d = 0.01 * k as f64;
        if let Some(eye) = far.eye(&metric, d) {
            assert_eq!(placed, k - 1, "placed again at d = {d}");
            placed = k;
            let want = flow(d);
            let off = max_abs(std::array::from_fn(|i| {
                eye.event.to_array()[i] - want.to_array()[i]
            }));
            assert!(off < 1e-8, "d = {d}: {eye:?} vs {want:?}");
        }
    }
    eprintln!("sphere: eyes placed up to d = {}", 0.01 * placed as f64);
    assert!(placed > 0 && placed < 200, "placed up to k = {placed}");
}

/// The Gödel member (m² = 1/a², Ω = 1/(√2 a)) places its eyes where Gödel's universe does:
/// for observers on the axis (where the two static frames agree), the member's eye carried
/// through r = 2a sinh(ρ/2a) is Gödel's eye, with the same speed.
#[test]
fn the_godel_members_eyes_are_godels() {
    let mut rng = Rng::new(41);
    for a in [1.0, 0.5] {
        let godel = Metric::Godel(Godel::new(a));
        let member = Metric::GodelType(GodelType::new(1.0 / (a * a), 1.0 / (2f64.sqrt() * a)));
        for _ in 0..20 {
            let mut v = viewpoint(&mut rng, a);
            v.event = Event::new(v.event.t, 0.0, 0.0, v.event.z);
            let d = rng.uniform(-0.5, 0.5) * a;
            let (g, m) = (v.eye(&godel, d).unwrap(), v.eye(&member, d).unwrap());
            let carried = to_godel(a, m.event).to_array();
            let off: [f64; 4] = std::array::from_fn(|i| carried[i] - g.event.to_array()[i]);
            assert!(max_abs(off) < 1e-12 * a, "{off:?}: {m:?} vs {g:?}");
            assert!((m.velocity.speed - g.velocity.speed).abs() < 1e-12);
            assert!(m.event.r() > 0.1 * d.abs(), "{m:?}");
        }
    }
}
