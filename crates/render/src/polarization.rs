//! A pixel's polarization vector, carried from the observer to the emission event
//! (docs/physics.md, "Polarization"): the observer's screen-up at the pixel as a four-vector,
//! parallel-transported back along the pixel's ray, and with it the screen-right. The record
//! measures them in the emitter's rest frame (`crate::target`, `Surface::pol`;
//! [`spacetime::polarization::measured`]).
//!
//! - exact tracer: the closed-form transport along the closed-form ray ("Parallel transport
//!   along closed forms"): the vector pushed to the origin by the observer's isometry,
//!   transported there over the whole parameter (the closed form holds for every loop), and
//!   pushed back;
//! - numeric tracer: the propagator P integrated with the ray ([`spacetime::propagator`]).
//!   Later loops retrace the first one shifted in t and z, which leaves components alone, so
//!   one loop turns the screen by the same angle θ each time
//!   ([`spacetime::propagator::screen_turn`]): a hit in loop n is reached by
//!   P(λ)(cos nθ s + sin nθ r), (s, r) the pixel's screen-up and screen-right, modulo k.

use spacetime::polarization::{screen_right, screen_up};
use spacetime::propagator::{apply, propagators, screen_turn};
use spacetime::transport::transport_from_origin;
use spacetime::{
    Event, ExactGeodesic, FourVector, GeodesicState, Metric, Spacetime, Tetrad, Tolerances,
};

/// The screen-up and screen-right of the pixel looking along `n` (the camera's `up`
/// projected orthogonal to it, `forward` where `n` is along `up`; then n × up) as
/// four-vectors of the observer's `frame`.
pub fn screen(frame: &Tetrad, up: [f64; 3], forward: [f64; 3], n: [f64; 3]) -> [FourVector; 2] {
    let s = screen_up(up, forward, n);
    let r = screen_right(n, s);
    [
        frame.vector([0.0, s[0], s[1], s[2]]),
        frame.vector([0.0, r[0], r[1], r[2]]),
    ]
}

/// The vectors `screen` at `observer`, transported along the exact geodesic `geo` that starts
/// there to its point at parameter `lambda` (any number of loops).
pub fn exact(
    geo: &ExactGeodesic,
    observer: Event,
    screen: [FourVector; 2],
    lambda: f64,
) -> [FourVector; 2] {
    let to = geo.back.inverse();
    screen.map(|f| {
        let (at, w) = transport_from_origin(&geo.origin, lambda, to.push(observer, f));
        geo.back.push(at, w)
    })
}

/// Where a hit lies on a numeric ray: at `lambda` into loop `loops` (0: the first), each loop
/// `period` long.
#[derive(Clone, Copy, Debug)]
pub struct RayPlace {
    pub lambda: f64,
    pub loops: u64,
    pub period: f64,
}

/// The screen-up and screen-right `[f, g]` of the ray `start`, transported by integration to
/// `place`, modulo the tangent; `None` when the integration fails or needs more than
/// `max_steps` steps.
pub fn integrated(
    metric: Metric,
    start: &GeodesicState,
    [f, g]: [FourVector; 2],
    place: RayPlace,
    tol: Tolerances,
    max_steps: u64,
) -> Option<[FourVector; 2]> {
    let carry = |p, v: FourVector| FourVector::from_array(apply(p, v.to_array()));
    if place.loops == 0 {
        let p = propagators(metric, start, &[place.lambda], tol, max_steps)?;
        Some([carry(&p[0], f), carry(&p[0], g)])
    } else {
        let (a, b) = (
            place.lambda.min(place.period),
            place.lambda.max(place.period),
        );
        let p = propagators(metric, start, &[a, b], tol, max_steps)?;
        let (within, whole) = if place.lambda <= place.period {
            (&p[0], &p[1])
        } else {
            (&p[1], &p[0])
        };
        let turn = screen_turn(whole, &metric.metric(start.x), f, g) * place.loops as f64;
        let (s, c) = turn.sin_cos();
        Some([carry(within, c * f + s * g), carry(within, c * g - s * f)])
    }
}
