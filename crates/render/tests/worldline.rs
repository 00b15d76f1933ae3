//! Worldlines: transported frames stay orthonormal, and a ray point whose simultaneous
//! worldline point lies outside the integrated range still gets a finite distance.

use render::worldline::Worldline;
use scene::Motion;
use spacetime::{Event, Godel, LocalVelocity, Metric, Minkowski, Spacetime};

#[test]
fn free_fall_frames_stay_orthonormal_along_the_worldline() {
    let m = Metric::Godel(Godel::new(1.0));
    let motion = Motion::Geodesic {
        start: Event::new(0.0, -1.0, 0.3, 0.0),
        velocity: LocalVelocity::new(0.7, [1.0, 0.2, 0.1]).unwrap(),
    };
    let wl = Worldline::new(m, &motion, -12.0, 1.0).unwrap();
    for i in 0..=100 {
        let tau = -5.0 + 0.05 * i as f64;
        let p = wl.at(&m, tau).expect("inside the integrated range");
        for a in 0..4 {
            for b in 0..4 {
                let want = if a != b {
                    0.0
                } else if a == 0 {
                    -1.0
                } else {
                    1.0
                };
                let got = m.dot(p.event, p.frame.e[a], p.frame.e[b]);
                assert!(
                    (got - want).abs() < 1e-9,
                    "τ = {tau}: g(e{a}, e{b}) = {got}"
                );
            }
        }
    }
}

#[test]
fn regression_far_point_beyond_the_integrated_range_is_not_skipped() {
    // A fast sphere in flat spacetime: a ray point whose rest-frame "now" lies beyond the
    // worldline's integrated range used to give no distance at all (an infinite probe), and
    // the tracer then skipped the whole step holding the hit.
    let m = Metric::Minkowski(Minkowski);
    let motion = Motion::Geodesic {
        start: Event::new(0.0, -2.0, 3.0, 0.0),
        velocity: LocalVelocity::new(0.9, [1.0, 0.0, 0.0]).unwrap(),
    };
    let wl = Worldline::new(m, &motion, -2.0, 0.5).unwrap();
    let x = Event::new(-1.9, 30.0, 3.0, 0.0);
    // The previous match on the ray (the seed) lies far beyond the integrated range.
    let far = wl
        .localize(&m, x, 100.0, 1.0)
        .expect("a distance, not None");
    let d = (far.xi[0].powi(2) + far.xi[1].powi(2) + far.xi[2].powi(2)).sqrt();
    assert!(d.is_finite() && d > 1.0, "distance {d}");
}
