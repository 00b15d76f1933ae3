//! Ray–object intersection for the three kinds of object (docs/physics.md, "Local objects"
//! and "The intersection search"):
//!
//! - local spheres: a ray point is expressed in the object's rest frame at the simultaneous
//!   point of its worldline (`worldline.rs`); the ball is |ξ| ≤ R there, so aberration and
//!   Lorentz contraction come out of the geometry;
//! - coordinate spheres |X − c| ≤ R and planes z = h in pseudo-Cartesian (x, y, z), static.
//!
//! Each target reports a signed distance f (negative inside) and a bound on |df/dλ| at a
//! ray state. A hit is a crossing of the surface (a change of the side of f, on the surface
//! counting as inside), so a ray that starts inside an object sees its inner surface. A
//! crossing inside a step is excluded when both ends are on one side and
//! |f(λa)| + |f(λb)| > rate·(λb − λa) (the ray cannot reach the surface and come back
//! within the step); otherwise the step's dense output is bisected. So no hit is missed
//! between integration steps, however thin.

use crate::bounds::Aabb;
use crate::chart::LocalChart;
use crate::chord;
use crate::worldline::{Located, WorldPoint, Worldline, WorldlineError};
use scene::{Motion, Object, Shape};
use spacetime::measure::{covector_components, vector_components};
use spacetime::polarization::measured;
use spacetime::{
    normal, Christoffel, Event, FourVector, GeodesicState, Metric, MetricTensor, Spacetime, Tetrad,
};
use std::f64::consts::PI;

/// Safety factor on the rate bound: covers the variation of the local photon energy and
/// of the frame within one step.
const RATE_MARGIN: f64 = 1.5;

/// Margin on the global bound E·γ(1 + v) of a local object's rate. That bound is exact for
/// the photon's energy at the ball's centre; the normal-coordinate displacement changes with
/// the momentum carried there, k + ΓΔk, which differs by up to |Γ|·|Δ| ≈ 50 % at the edge
/// of the near zone (measured: 1.6 for the reference scene's ball).
const GLOBAL_RATE_MARGIN: f64 = 2.0;

/// Margin on the same bound for a *far* probe (a first-order estimate, below): the ray's
/// rest-frame distance falls at most at its rest-frame energy, ≤ E·γ(1 + v), and the
/// estimate d₁/slack − R toward an entry at about that over the slack. Measured (rays
/// entering random balls: 6,000 once, 2,500 in `tests/integration/far.rs`) at most 1.04 of
/// the bound at rest and 0.95 in free fall; 1.5 leaves 40 % more. Used where measured:
/// Gödel's universe, balls up to 0.85 c ([`FAR_RATE_MAX_SPEED_FACTOR`]) with
/// γ(1 + v)·R ≤ a (beyond, the estimate next to a large fast ball can be far off);
/// elsewhere far probes take the global margin. A span with a near end takes the near
/// probe's rate, the larger (docs/physics.md, "Far probes").
pub const FAR_RATE_MARGIN: f64 = 1.5;

/// The fastest ball whose far probes take [`FAR_RATE_MARGIN`]: speed factor γ(1 + v) = 3.5
/// (v = 0.849; measured up to 0.85 c).
pub const FAR_RATE_MAX_SPEED_FACTOR: f64 = 3.5;

/// Beyond this first-order rest-frame distance (in units of a, plus the radius) a local
/// object is "far": its distance is the first-order estimate divided by FAR_SLACK. The
/// second-order (normal-coordinate) distance is used only nearer: it is accurate at the
/// surface, but at separations of order a the expansion fails (it overshoots by factors
/// and then changes faster than the rate bound allows).
const FAR_DISTANCE: f64 = 0.25;
const FAR_RADII: f64 = 1.0;
const FAR_SLACK: f64 = 1.3;

/// A runtime object ready for intersection.
#[derive(Clone, Debug)]
pub enum Target {
    LocalSphere { radius: f64, worldline: Worldline },
    CoordinateSphere { center: [f64; 3], radius: f64 },
    Plane { height: f64, extent: Option<f64> },
}

/// Signed distance from a target and a bound on its rate of change along the ray.
#[derive(Clone, Copy, Debug)]
pub struct Probe {
    pub f: f64,
    pub rate: f64,
    /// Matched proper time on the worldline (local objects), to seed the next match.
    pub tau: f64,
    /// The ray point's rest-frame coordinates (local objects, near them; NaN otherwise).
    pub xi: [f64; 3],
    /// |p·u|, the ray's momentum against the four-velocity of the matched centre: the
    /// photon's energy in the ball's frame to first order in the distance (balls in free
    /// fall, near them; NaN otherwise). Their chord exclusion takes it ([`crate::chord`]).
    pub energy: f64,
}

impl Probe {
    const FAR: Probe = Probe {
        f: f64::INFINITY,
        rate: 0.0,
        tau: f64::NAN,
        xi: [f64::NAN; 3],
        energy: f64::NAN,
    };
}

/// What a hit looks like on the object.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// Texture coordinates on the body, in [0, 1].
    pub u: f64,
    pub v: f64,
    /// The emitter's four-velocity at the hit point (for the frequency shift).
    pub emitter_velocity: FourVector,
    /// Unit photon direction (of propagation, toward the observer) in the object's frame.
    pub dir: [f64; 3],
    /// Cosine between the surface normal on the side the photon leaves (outward, or
    /// inward for an inner surface seen from inside) and `dir`; ≥ 0.
    pub cos_i: f64,
    /// The polarization vector measured in the object's frame: a unit vector orthogonal to
    /// `dir` (docs/physics.md, "Polarization").
    pub pol: [f64; 3],
}

impl Target {
    /// Builds the target of `object`; worldlines cover coordinate times [t_min, t_max].
    pub fn new(
        metric: Metric,
        object: &Object,
        t_min: f64,
        t_max: f64,
    ) -> Result<Target, WorldlineError> {
        Ok(match object.shape {
            Shape::Sphere { radius } => {
                // A point near a moving ball is simultaneous (in its rest frame) with a
                // worldline point up to γ·v times the near zone's size away in time: the
                // worldline must reach that far beyond the traced range.
                let pad = match object.motion {
                    Motion::Rest { .. } => 0.0,
                    Motion::Geodesic { velocity, .. } => {
                        let near = FAR_DISTANCE * metric.length_scale() + FAR_RADII * radius;
                        2.0 * velocity.gamma() * near
                    }
                };
                Target::LocalSphere {
                    radius,
                    worldline: Worldline::new(metric, &object.motion, t_min - pad, t_max + pad)?,
                }
            }
            Shape::CoordinateSphere { center, radius } => {
                Target::CoordinateSphere { center, radius }
            }
            Shape::Plane { height, extent } => Target::Plane { height, extent },
        })
    }

    /// How many integration steps the object's worldline holds (0 unless in free fall).
    pub fn integration_steps(&self) -> usize {
        match self {
            Target::LocalSphere { worldline, .. } => worldline.integration_steps(),
            _ => 0,
        }
    }

    /// A coordinate box that holds every point of the object at coordinate times in
    /// [t0, t1]. Generous on purpose: it only decides which loops of a ray to skip.
    pub fn bounds(&self, metric: &Metric, t0: f64, t1: f64) -> Aabb {
        match self {
            Target::LocalSphere { radius, worldline } => {
                // The rest frame's "now" differs from coordinate time across the ball.
                let dt = 4.0 * radius + 0.1;
                let b = worldline.bounds(t0 - dt, t1 + dt);
                // A proper length spans more in coordinates far out in Gödel's universe
                // (docs/physics.md, "The Gödel metric": g_rr = 1/(1 + s²)).
                let stretch = metric.coordinate_stretch(b.max_radius() + 2.0 * radius);
                b.grown(2.0 * radius * stretch + 0.05)
            }
            Target::CoordinateSphere { center, radius } => {
                Aabb::point(*center).grown(radius * (1.0 + 1e-9))
            }
            Target::Plane { height, extent } => {
                let e = extent.unwrap_or(f64::INFINITY);
                Aabb {
                    min: [-e, -e, *height],
                    max: [e, e, *height],
                }
            }
        }
    }

    /// Probe at ray state `s`; `tau_seed` is the previous match on this ray (NaN if none).
    pub fn probe(&self, metric: &Metric, s: &GeodesicState, tau_seed: f64) -> Probe {
        #[cfg(feature = "count-probes")]
        crate::probe_count::add();
        match self {
            Target::LocalSphere { radius, worldline } => {
                let seed = if tau_seed.is_finite() {
                    tau_seed
                } else {
                    worldline.tau_guess(s.x.t)
                };
                let far = FAR_DISTANCE * metric.length_scale() + FAR_RADII * radius;
                let at = |seed: f64| {
                    let lp = worldline.localize(metric, s.x, seed, far)?;
                    Some((
                        local_probe(metric, *radius, worldline, far, &lp, s),
                        matches!(lp, Located::Near(_)),
                    ))
                };
                match at(seed) {
                    // A previous match can be a stale seed in free fall: the first-order
                    // distance from a point far from simultaneous may call "far" (an estimate,
                    // not a bound) a ray point that lies inside the ball. Then the match from
                    // the point of equal coordinate time counts too, the nearer one kept.
                    Some((p, false))
                        if tau_seed.is_finite() && matches!(worldline, Worldline::Free(_)) =>
                    {
                        match at(worldline.tau_guess(s.x.t)) {
                            Some((q, _)) if q.f < p.f => q,
                            _ => p,
                        }
                    }
                    Some((p, _)) => p,
                    None => Probe::FAR,
                }
            }
            Target::CoordinateSphere { center, radius } => {
                let d = norm3([s.x.x - center[0], s.x.y - center[1], s.x.z - center[2]]);
                let v = metric.raise(s.x, s.p);
                Probe {
                    f: d - radius,
                    rate: RATE_MARGIN * norm3([v.x, v.y, v.z]),
                    tau: f64::NAN,
                    xi: [f64::NAN; 3],
                    energy: f64::NAN,
                }
            }
            Target::Plane { height, .. } => {
                let v = metric.raise(s.x, s.p);
                Probe {
                    f: s.x.z - height,
                    rate: RATE_MARGIN * v.z.abs(),
                    tau: f64::NAN,
                    xi: [f64::NAN; 3],
                    energy: f64::NAN,
                }
            }
        }
    }

    /// Whether the ray crosses the surface between two probes with values fa, fb: a change
    /// of side, with f ≤ 0 counting as inside (on the surface is inside). Any crossing is a
    /// hit: for a ray that starts outside the first crossing is its entry; for a ray that
    /// starts inside (or on the surface) it is the exit, so it sees the inner surface
    /// (a large coordinate sphere around the observer becomes the scene's surroundings).
    /// For planes, z ≤ height counts as the "inside" side.
    pub fn crossed(fa: f64, fb: f64) -> bool {
        (fa > 0.0) != (fb > 0.0)
    }

    /// Whether a crossing inside a span of length `h` with end values fa, fb is impossible:
    /// both ends on one side, and the ray cannot reach the surface and come back within the
    /// span, since |df/dλ| ≤ rate (`rate == 0`: f is constant, e.g. a ray lying in a plane).
    pub fn excluded(fa: f64, fb: f64, rate: f64, h: f64) -> bool {
        !Self::crossed(fa, fb) && (fa.abs() + fb.abs() > rate * h || rate == 0.0)
    }

    /// Whether a span of length `h` between the probes `pa` and `pb` (both on one side)
    /// provably holds no crossing by the chord of the ray's rest-frame path
    /// ([`crate::chord`]): local balls in Gödel's universe, both ends near the ball.
    pub fn chord_excludes(&self, metric: &Metric, pa: &Probe, pb: &Probe, h: f64) -> bool {
        let (Target::LocalSphere { radius, worldline }, Some(a)) = (self, metric.godel_a()) else {
            return false;
        };
        if !(pa.xi[0].is_finite() && pb.xi[0].is_finite()) {
            return false;
        }
        // The static energy E, from the rate bound GLOBAL_RATE_MARGIN·E·s of near probes
        // (`local_probe`).
        let s = worldline.speed_factor();
        let energy = pa.rate.max(pb.rate) / (GLOBAL_RATE_MARGIN * s);
        // |ξ| at the ends: the probes' own distances, f + R.
        let ends = pa.f.max(pb.f) + radius;
        let at_rest = matches!(worldline, Worldline::Rest { .. });
        let e = chord::photon_energy(at_rest, s, energy, (pa.energy, pb.energy));
        chord::stray(a, at_rest, s, e, ends, h)
            .is_some_and(|e| chord::excludes(*radius, (pa.xi, pa.f), (pb.xi, pb.f), e))
    }

    /// Whether a probe may vouch for a span of several steps: its distance is a lower bound
    /// of the true one and its rate bounds |df/dλ| along the whole ray. True for objects at
    /// rest (u = ∂t: the rest frame's "now" is unambiguous and the ray's energy there is
    /// exactly E). For free fall, far from the ball the looping worldline makes "now"
    /// ambiguous, so its far estimates only serve within one step.
    pub fn vouches_for_spans(&self) -> bool {
        matches!(
            self,
            Target::LocalSphere {
                worldline: Worldline::Rest { .. },
                ..
            }
        )
    }

    /// Whether the target is a coordinate plane (its f, z − height, linear in λ along a
    /// closed-form ray).
    pub fn is_plane(&self) -> bool {
        matches!(self, Target::Plane { .. })
    }

    /// Whether every crossing counts ([`Target::accepts`] always true): all but planes of
    /// limited extent.
    pub fn accepts_any(&self) -> bool {
        !matches!(
            self,
            Target::Plane {
                extent: Some(_),
                ..
            }
        )
    }

    /// Whether a plane crossing at `s` lies inside the plane's extent (always true otherwise).
    pub fn accepts(&self, s: &GeodesicState) -> bool {
        match self {
            Target::Plane {
                extent: Some(e), ..
            } => s.x.x.abs() <= *e && s.x.y.abs() <= *e,
            _ => true,
        }
    }

    /// Surface data at a hit state `s`, with the pixel's screen-up and screen-right `screen`
    /// transported there; `None` where the rest frame cannot be matched or they measure as no
    /// polarization vector.
    pub fn surface(
        &self,
        metric: &Metric,
        s: &GeodesicState,
        tau_seed: f64,
        screen: [FourVector; 2],
    ) -> Option<Surface> {
        let k = metric.raise(s.x, s.p);
        match self {
            Target::LocalSphere { worldline, .. } => {
                let seed = if tau_seed.is_finite() {
                    tau_seed
                } else {
                    worldline.tau_guess(s.x.t)
                };
                let lp = worldline
                    .localize(metric, s.x, seed, f64::INFINITY)?
                    .near()?;
                let rest = RestFrame::new(metric, &lp.at, s.x);
                let kl = rest.photon(k);
                let (u, v) = lon_lat(lp.xi);
                let dir = normalize3([-kl[1], -kl[2], -kl[3]]);
                let n = normalize3(lp.xi);
                let [fl, rl] = screen.map(|v| rest.photon(v));
                Some(Surface {
                    u,
                    v,
                    emitter_velocity: rest.emitter_velocity(worldline),
                    dir,
                    // The normal on the side the photon leaves (inward for an inner surface).
                    cos_i: dot3(n, dir).abs(),
                    pol: measured(fl, rl, dir)?,
                })
            }
            Target::CoordinateSphere { center, .. } => {
                let n = normalize3([s.x.x - center[0], s.x.y - center[1], s.x.z - center[2]]);
                let (u, v) = lon_lat(n);
                let dir = static_direction(metric, s.x, k);
                Some(Surface {
                    u,
                    v,
                    emitter_velocity: FourVector::new(1.0, 0.0, 0.0, 0.0),
                    dir,
                    cos_i: dot3(n, normalize3([-k.x, -k.y, -k.z])).abs(),
                    pol: static_polarization(metric, s.x, screen, dir)?,
                })
            }
            Target::Plane { extent, .. } => {
                let (u, v) = match extent {
                    Some(e) => (0.5 + s.x.x / (2.0 * e), 0.5 + s.x.y / (2.0 * e)),
                    None => (s.x.x.rem_euclid(1.0), s.x.y.rem_euclid(1.0)),
                };
                let dir = static_direction(metric, s.x, k);
                let kn = normalize3([-k.x, -k.y, -k.z]);
                Some(Surface {
                    u,
                    v,
                    emitter_velocity: FourVector::new(1.0, 0.0, 0.0, 0.0),
                    dir,
                    cos_i: kn[2].abs(),
                    pol: static_polarization(metric, s.x, screen, dir)?,
                })
            }
        }
    }
}

/// The probe of a local ball of radius `radius` at the ray state `s`, from its match `lp`
/// on the worldline (first-order distances beyond `far` are estimates).
fn local_probe(
    metric: &Metric,
    radius: f64,
    worldline: &Worldline,
    far: f64,
    lp: &Located,
    s: &GeodesicState,
) -> Probe {
    let s_factor = worldline.speed_factor();
    let (d, tau, xi, energy, margin) = match *lp {
        Located::Near(lp) => (
            norm3(lp.xi),
            lp.at.tau,
            lp.xi,
            match worldline {
                Worldline::Free(_) => lp.at.frame.e[0].contract(s.p).abs(),
                Worldline::Rest { .. } => f64::NAN, // E itself, which the chord takes
            },
            GLOBAL_RATE_MARGIN,
        ),
        Located::Far(d1) => {
            // Far estimates are shrunk to stay below the true distance: at the switch the
            // first-order distance exceeds the second-order one by ~5 %, further out by
            // more; the slack grows from 1.1 to FAR_SLACK. (Free fall: the estimate comes
            // from a point that is not simultaneous and is never trusted beyond one step,
            // so the full slack at once.)
            let slack = match worldline {
                Worldline::Rest { .. } => 1.1 + (FAR_SLACK - 1.1) * ((d1 - far) / far).min(1.0),
                Worldline::Free(_) => FAR_SLACK,
            };
            // A far point is outside (beyond R + FAR_DISTANCE·a to first order): however
            // large the ball, its estimate stays at least half that margin clear, never on
            // the inside (2.95/1.3 once made a false crossing). A far match is not
            // simultaneous: the next probe re-seeds from t.
            let floor = radius + 0.5 * FAR_DISTANCE * metric.length_scale();
            let measured = metric
                .godel_a()
                .is_some_and(|a| s_factor <= FAR_RATE_MAX_SPEED_FACTOR && s_factor * radius <= a);
            let margin = if measured {
                FAR_RATE_MARGIN
            } else {
                GLOBAL_RATE_MARGIN
            };
            (
                (d1 / slack).max(floor),
                f64::NAN,
                [f64::NAN; 3],
                f64::NAN,
                margin,
            )
        }
    };
    // The ray's speed in the rest frame is its energy there, −p·u, which is at most
    // E·γ(1 + v) everywhere on the ray (see Worldline::speed_factor): a bound valid over any
    // span, not just one step.
    let eps_max = s.p.t.abs() * s_factor;
    Probe {
        f: d - radius,
        rate: margin * eps_max,
        tau,
        xi,
        energy,
    }
}

/// How light arriving at a surface point meets the surface (for direct illumination).
#[derive(Clone, Copy, Debug)]
pub struct Incidence {
    /// Cosine between the normal on the viewer's side (outward, or inward where the viewer
    /// sees an inner surface from inside; for planes the side the viewer is on) and the
    /// direction the light comes from, in the object's rest frame; negative when the light
    /// arrives from behind the surface the viewer sees.
    pub cos: f64,
    /// The light's energy −k·u in the object's rest frame (for k normalized to energy 1 at
    /// a static source, the source→object frequency ratio).
    pub energy: f64,
}

impl Target {
    /// Incidence of light with future-directed tangent `k_light` at the surface point `x`
    /// (a hit found with matched proper time `tau`); `view` is the backward ray's tangent
    /// there (it decides which side of a plane the viewer sees).
    pub fn incidence(
        &self,
        metric: &Metric,
        x: Event,
        tau: f64,
        view: FourVector,
        k_light: FourVector,
    ) -> Option<Incidence> {
        match self {
            Target::LocalSphere { worldline, .. } => {
                let seed = if tau.is_finite() {
                    tau
                } else {
                    worldline.tau_guess(x.t)
                };
                let lp = worldline.localize(metric, x, seed, f64::INFINITY)?.near()?;
                let rest = RestFrame::new(metric, &lp.at, x);
                let (kl, kv) = (rest.photon(k_light), rest.photon(view));
                let n = normalize3(lp.xi);
                // The viewer's photon leaves along −view: outside when it moves outward.
                let side = viewer_side(n, [-kv[1], -kv[2], -kv[3]]);
                let d = normalize3([kl[1], kl[2], kl[3]]);
                Some(Incidence {
                    cos: -side * dot3(n, d),
                    energy: kl[0],
                })
            }
            Target::CoordinateSphere { center, .. } => {
                // Coordinate normal and direction, as for `cos_i` of these orientation aids.
                let n = normalize3([x.x - center[0], x.y - center[1], x.z - center[2]]);
                let side = viewer_side(n, [-view.x, -view.y, -view.z]);
                Some(Incidence {
                    cos: -side * dot3(n, normalize3([k_light.x, k_light.y, k_light.z])),
                    energy: -metric.lower(x, k_light).t,
                })
            }
            Target::Plane { .. } => {
                // The viewer's photon leaves along −view: its z sign picks the lit side.
                let side = if view.z < 0.0 { 1.0 } else { -1.0 };
                let d = normalize3([k_light.x, k_light.y, k_light.z]);
                Some(Incidence {
                    cos: -side * d[2],
                    energy: -metric.lower(x, k_light).t,
                })
            }
        }
    }
}

/// A ball's rest frame at a surface point: what measures photons there. Made once per point,
/// since a hit measures three vectors (the photon and the screen's two axes) and the direct
/// light two (the light's photon and the viewer's).
struct RestFrame {
    chart: LocalChart,
    /// The surface point.
    x: Event,
    /// Γ and the metric at the centre, in the chart of local descriptions.
    gam: Christoffel,
    g: MetricTensor,
    /// The body frame at the centre, in that chart.
    frame: Tetrad,
    /// The coordinate displacement from the centre to the point there.
    d: [f64; 4],
}

impl RestFrame {
    /// The rest frame of the worldline point `at` (the centre), for measurements at `x`.
    fn new(metric: &Metric, at: &WorldPoint, x: Event) -> RestFrame {
        // In the chart of local descriptions ([`LocalChart`]), as the ball's coordinates are.
        let chart = LocalChart::of(metric);
        let (centre, here) = (chart.event(at.event), chart.event(x));
        RestFrame {
            chart,
            x,
            gam: chart.christoffel(centre),
            g: chart.metric(centre),
            frame: chart.frame(at.event, &at.frame),
            d: (here - centre).to_array(),
        }
    }

    /// The photon `k` at the point, carried to the centre to first order with Γ there, then
    /// measured in the body frame: (k⁰, k¹, k², k³).
    fn photon(&self, k: FourVector) -> [f64; 4] {
        let back = self.d.map(|c| -c);
        let kn = normal::transport(&self.gam, back, self.chart.vector(self.x, k).to_array());
        vector_components(&self.g, &self.frame, FourVector::from_array(kn))
    }

    /// The emitter's velocity at the point. For objects at rest the surface point is static
    /// (u = ∂t exactly); for free fall the centre's velocity is carried to the point to first
    /// order with Γ at the centre.
    fn emitter_velocity(&self, wl: &Worldline) -> FourVector {
        match wl {
            Worldline::Rest { .. } => FourVector::new(1.0, 0.0, 0.0, 0.0),
            Worldline::Free(_) => {
                let u = normal::transport(&self.gam, self.d, self.frame.e[0].to_array());
                self.chart.vector_back(self.x, FourVector::from_array(u))
            }
        }
    }
}

/// +1 when the viewer's photon, leaving the surface along `photon`, is on the side of the
/// outward normal `n` (an outer surface), −1 for an inner surface seen from inside.
fn viewer_side(n: [f64; 3], photon: [f64; 3]) -> f64 {
    if dot3(n, photon) >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The record's `pol` from the pixel's screen-up and screen-right `screen` at `x`, measured by
/// the static observer there, for a photon travelling along `dir` in its frame (coordinate
/// objects: their body axes are the static frame's).
fn static_polarization(
    metric: &Metric,
    x: Event,
    screen: [FourVector; 2],
    dir: [f64; 3],
) -> Option<[f64; 3]> {
    let (g, frame) = (metric.metric(x), metric.static_frame(x));
    let [f, r] = screen.map(|v| vector_components(&g, &frame, v));
    measured(f, r, dir)
}

/// Unit direction of propagation of the photon (−k) in the static frame at `x`.
fn static_direction(metric: &Metric, x: Event, k: FourVector) -> [f64; 3] {
    let c = covector_components(&metric.static_frame(x), metric.lower(x, -1.0 * k));
    normalize3([c[1], c[2], c[3]])
}

/// Body longitude/latitude as texture coordinates: u = (φ + π)/2π from e1 toward e2,
/// v = ½ + asin(n·e3)/π (v = 1 at the north pole e3).
pub fn lon_lat(p: [f64; 3]) -> (f64, f64) {
    let n = normalize3(p);
    let u = (n[1].atan2(n[0]) + PI) / (2.0 * PI);
    let v = 0.5 + n[2].clamp(-1.0, 1.0).asin() / PI;
    (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0))
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn norm3(a: [f64; 3]) -> f64 {
    dot3(a, a).sqrt()
}
fn normalize3(a: [f64; 3]) -> [f64; 3] {
    let n = norm3(a);
    if n > 0.0 {
        [a[0] / n, a[1] / n, a[2] / n]
    } else {
        [0.0; 3]
    }
}
