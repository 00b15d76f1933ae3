//! Direct illumination by point lights at rest ("shadow rays", Grave et al., PRD 80,
//! 103002 (2009), Sec. IV): for a surface point hit by a pixel's ray, every future-directed
//! light ray from each light's worldline to that event, each tested for occlusion by every
//! object along it in space and time, and summed with a Lambert law in the object's rest
//! frame.
//!
//! The connecting rays are the closed forms of [`spacetime::connect`] (docs/physics.md,
//! "Light rays between a source and an event"): a source at rest is carried to the axis by
//! an isometry, where the rays are solved for in one variable. There can be several, emitted
//! at different times (two per winding around the source's axis, and infinitely many
//! windings when the target is off the source's plane); rays emitted more than `max_past`
//! before the hit are not counted, the same window as the pixel rays. In a Gödel-type
//! member they are [`spacetime::type_shadow_rays_within`], which counts the windings the
//! window can hold with the member's shortest loop time (docs/physics.md, "Direct light in
//! the family").
//!
//! Intensity law (irradiance on the surface, in the object's rest frame; docs/physics.md,
//! "Area distance and irradiance"), per ray:
//!
//!   E = P · g² · cos θ / (4π D²)
//!
//! - P: the light's `power` (isotropic in its rest frame);
//! - g = (−k·u_object)/(−k·u_source): the frequency ratio source → object; one factor for
//!   each photon's energy, one for their arrival rate (for objects at rest g = 1 exactly);
//! - cos θ: between the outward surface normal and the direction the light comes from, in
//!   the object's rest frame (no light when cos θ ≤ 0);
//! - D² = dA/dΩ: the source's area distance of the ray (the bundle's cross-section per unit
//!   solid angle at emission), exact from the Jacobi fields of the closed forms
//!   ([`spacetime::source_area_distance_sq`]); it vanishes at caustics (the focus on the
//!   source's axis), where E grows without bound, as it physically does for a point source.
//!
//! The window matters: the rays of winding n have D² growing about linearly in n (e.g.
//! 1.1, 4.7, 6.9, 10.6 for the first four rays from (1, 1, 0) to (1, 0, 0), a = 1), so
//! unoccluded windings add terms falling like 1/n and the sum grows slowly with the window.
//! Read `max_past` as how long the light has been shining before each hit.
//!
//! E is bolometric: the spectral change of the light by g is not modelled (colour is the
//! light's `color`, applied by the shaders). Occlusion: the ray is tested with the tracer's
//! own intersection search (bracketing with rate bounds, so thin occluders are not missed)
//! on the closed-form curve from emission to just before the hit ([`END_CUT`]): the lit
//! surface itself is not counted at its end point, but it does block a ray that passes
//! through the object earlier (self-shadowing, e.g. of later windings). In Gödel's universe
//! objects at rest that a connecting ray provably never comes near (`crate::reject`) are
//! left out of its search, and a ball in free fall from the ray's last λ within its reach on
//! (docs/physics.md, "Occlusion"); a Gödel-type member has no such tests, and searches
//! every object along the whole ray. A ray that passes deep into a ball at rest is found
//! blocked by one probe where it most likely passes deepest (docs/physics.md, "Aimed
//! occlusion").

use crate::intersect::{HitPoint, Intersector, OutOfWork, Probes, Want};
use crate::reject::{set_ray, Rejection};
use crate::segment::{ClosedForm, Segment, Shift};
use crate::target::Target;
use spacetime::{
    shadow_rays_within, source_area_distance_sq, type_shadow_rays_within,
    type_source_area_distance_sq, Event, GeodesicState, GeodesicSystem, Metric, ShadowRay,
    Spacetime,
};
use std::f64::consts::{PI, SQRT_2};
use std::sync::OnceLock;

/// The occlusion test stops this fraction of the affine length before the lit point, so
/// that the surface being lit does not count as its own occluder (the point lies on it to
/// root-finding precision, ~1e-12; the shadow ray ends on it to ~1e-10). Light grazing the
/// surface at cos θ below ~1e-4 may be wrongly counted as self-shadowed; its weight is that
/// small.
pub const END_CUT: f64 = 1e-6;

/// A point light at rest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSource {
    /// Its position (t ignored).
    pub position: Event,
    /// Isotropic power in its rest frame.
    pub power: f64,
}

impl LightSource {
    pub fn from_scene(l: &scene::Light) -> LightSource {
        LightSource {
            position: l.position,
            power: l.power,
        }
    }
}

/// The scene's lights and the window of emission times that counts.
pub struct Lighting {
    pub lights: Vec<LightSource>,
    /// Light emitted more than this (coordinate time) before a hit is not counted.
    window: f64,
    /// Per light, per object: its whole-ray rejection test seen from the light (built on
    /// first use, for the objects of the first call: a renderer's lighting serves one scene).
    rejections: OnceLock<Vec<Vec<Option<Rejection>>>>,
}

impl Lighting {
    pub fn new(lights: Vec<LightSource>, window: f64) -> Lighting {
        Lighting {
            lights,
            window,
            rejections: OnceLock::new(),
        }
    }

    /// The same lighting without whole-ray rejection: every connecting ray searches every
    /// object (for tests and benchmarks that compare the two).
    pub fn without_rejection(self) -> Lighting {
        let rejections = OnceLock::from(vec![Vec::new(); self.lights.len()]);
        Lighting { rejections, ..self }
    }

    /// Direct light from each source at a pixel ray's hit (see the module documentation)
    /// into `out[k]` for light k: zeros where the ray hit nothing (`hit` is `None`) or in flat
    /// spacetime, NaN where a connecting ray's occlusion search ran out of work (unknown
    /// light).
    pub fn illuminate(
        &self,
        objects: &Intersector,
        hit: Option<&HitPoint>,
        probes: &mut Probes,
        out: &mut [f32],
    ) {
        out.fill(0.0);
        let metric = &objects.metric;
        let Some(hit) = hit.filter(|_| !matches!(metric, Metric::Minkowski(_))) else {
            return;
        };
        let rejections = self.rejections.get_or_init(|| {
            self.lights
                .iter()
                .map(|l| match metric.godel_a() {
                    // Whole-ray rejection has Gödel's closed forms only.
                    Some(a) => objects
                        .targets
                        .iter()
                        .map(|t| Rejection::new(a, l.position, t))
                        .collect(),
                    None => Vec::new(),
                })
                .collect()
        });
        for ((o, light), rejections) in out.iter_mut().zip(&self.lights).zip(rejections) {
            *o = self
                .irradiance(objects, (light, rejections), hit, probes)
                .map_or(f32::NAN, |e| e as f32);
        }
    }

    /// The irradiance E = Σ P g² cos θ/(4π D²) over the unoccluded connecting rays of
    /// `light` (with its objects' rejection tests); `None` when the occlusion search of one
    /// of them ran out of work.
    fn irradiance(
        &self,
        objects: &Intersector,
        (light, rejections): (&LightSource, &[Option<Rejection>]),
        hit: &HitPoint,
        probes: &mut Probes,
    ) -> Option<f64> {
        let metric = &objects.metric;
        let x = hit.state.x;
        let view = metric.raise(x, hit.state.p);
        let target = &objects.targets[hit.target];
        let mut sum = 0.0;
        for ray in self.connecting_rays(metric, light, x) {
            let Some(geo) = ClosedForm::new(metric, ray.emission, ray.tangent) else {
                continue;
            };
            let (_, k_end) = geo.at(ray.lambda);
            let Some(inc) = target.incidence(metric, x, hit.tau, view, k_end) else {
                continue;
            };
            if !(inc.cos > 0.0) {
                continue;
            }
            let d2 = area_distance_sq(metric, light.position, &ray);
            if !(d2 > 0.0 && d2.is_finite()) {
                continue;
            }
            let from = (ray.emission.t - light.position.t, rejections);
            if occluded(objects, geo, &ray, from, hit.target, probes).ok()? {
                continue;
            }
            sum += light.power * inc.energy * inc.energy * inc.cos / (4.0 * PI * d2);
        }
        Some(sum)
    }

    /// The light rays from `light` to `x` emitted at most the window before it (none in flat
    /// spacetime, which has no lights).
    pub fn connecting_rays(
        &self,
        metric: &Metric,
        light: &LightSource,
        x: Event,
    ) -> Vec<ShadowRay> {
        match metric {
            Metric::Godel(g) => {
                // Each winding takes at least the shortest loop time of the source's clock;
                // the isometry to the source's axis shifts the target's time by at most
                // 2√2 a·π.
                let travel = self.window + 2.0 * SQRT_2 * PI * g.a;
                let n = (travel / g.shortest_loop_time())
                    .ceil()
                    .min(MAX_WINDINGS as f64) as u32
                    + 1;
                shadow_rays_within(g.a, light.position, x, self.window, n)
            }
            Metric::GodelType(m) => {
                type_shadow_rays_within(*m, light.position, x, self.window, MAX_WINDINGS)
            }
            Metric::Minkowski(_) => Vec::new(),
        }
    }
}

/// Most copies of a ball's arc at rest that [`aimed`] probes on one ray.
const MAX_AIMS: usize = 4;

/// Whether a ball at rest provably blocks the shadow ray `geo`, from one probe at each of
/// its deepest points ([`crate::circle::Stretches::deepest`], up to the last λ where the ray
/// searches it: `last` for the lit object, else `end`): a ray that starts outside the ball
/// (its probe at λ = 0, just taken by [`Intersector::probe_all`]) and is inside it there
/// has crossed its surface before, which the search would find too (docs/physics.md,
/// "Aimed occlusion"). False leaves the answer to the search.
fn aimed(
    objects: &Intersector,
    geo: ClosedForm,
    (lit, last, end): (usize, f64, f64),
    probes: &Probes,
) -> bool {
    let metric = objects.metric;
    objects.targets.iter().enumerate().any(|(i, t)| {
        let (Some(near), Target::LocalSphere { radius, .. }) = (&probes.near[i], t) else {
            return false;
        };
        let outside = probes.start_at(i, 0.0).is_some_and(|p| p.f > 0.0);
        let until = if i == lit { last } else { end };
        outside
            && near.deepest(until, *radius, MAX_AIMS).any(|l| {
                let (x, k) = geo.at(l);
                let s = GeodesicState {
                    x,
                    p: metric.lower(x, k),
                };
                t.probe(&metric, &s, f64::NAN).f <= 0.0
            })
    })
}

/// Most windings of the connecting rays searched per light and hit.
const MAX_WINDINGS: u32 = 10_000;

/// The source's area distance squared along `ray` from a source at rest at `source`.
fn area_distance_sq(metric: &Metric, source: Event, ray: &ShadowRay) -> f64 {
    match metric {
        Metric::Godel(g) => source_area_distance_sq(g.a, source, ray),
        Metric::GodelType(m) => type_source_area_distance_sq(*m, source, ray),
        Metric::Minkowski(_) => f64::NAN,
    }
}

/// Whether any object blocks `ray` (future-directed from its emission) before it reaches
/// its end, cut short by [`END_CUT`]. A surface crossing blocks, so a light inside a ball
/// reaches only the ball's inner surface. The lit object (`lit`) is not searched on the last
/// segment (at most 1/16 of a loop, and in a member half a length scale, before the lit
/// point): over so short a stretch the ray is
/// nearly a circle arc, which meets a sphere in two points at most, so light that arrives at
/// the lit point from outside (cos θ > 0) has not crossed the ball there; searching it would
/// only bisect the ray's approach to its own end point, at great cost for grazing light,
/// whose side the first-order incidence cannot tell anyway (docs/physics.md, "Occlusion"). Objects whose `rejections` test rejects the ray over
/// that stretch are not searched (nothing to search: not occluded); a ball in free fall is
/// searched only up to the last λ where the ray may be within its reach (docs/physics.md,
/// "Occlusion"). `t_start`: the emission's time after the light's event of the tests.
fn occluded(
    objects: &Intersector,
    geo: ClosedForm,
    ray: &ShadowRay,
    (t_start, rejections): (f64, &[Option<Rejection>]),
    lit: usize,
    probes: &mut Probes,
) -> Result<bool, OutOfWork> {
    let metric = objects.metric;
    let end = ray.lambda * (1.0 - END_CUT);
    let origin = geo.godel().map(|g| &g.origin);
    set_ray(rejections, origin, t_start, end, true, probes);
    let per_segment = geo.segment_length(metric.length_scale());
    let n = (end / per_segment).ceil().clamp(1.0, 1e5) as usize;
    // The lit object is searched up to the last segment only: its whole-ray test over that
    // stretch may drop it (a lit plane always: z is linear, and the ray meets it at its end).
    let last = end * (n - 1) as f64 / n as f64;
    if let (Some(r), Some(origin)) = (rejections.get(lit).and_then(Option::as_ref), origin) {
        if r.misses(origin, last) {
            probes.on_ray[lit] = false;
        }
    }
    // One chain of segments over λ from the emission, each searching what its loops search
    // (`set_ray`; only Gödel's rays, which return, are searched by loop), from a fresh probe
    // where an object's search resumes.
    if !probes.activate(0, 0.0, 0.0, end) {
        return Ok(false);
    }
    let start = GeodesicState {
        x: ray.emission,
        p: metric.lower(ray.emission, ray.tangent),
    };
    let (sys, s0) = GeodesicSystem::new(metric, &start);
    objects.probe_all(&start, 0.0, probes);
    if aimed(objects, geo, (lit, last, end), probes) {
        return Ok(true);
    }
    // The start of the next segment where the one before was made (None: skipped).
    let mut y0 = Some(s0);
    // Outside [first, last] no object is searched: those segments need no activation each.
    let (first, last) = probes.reach();
    for i in 0..n {
        let (l0, l1) = (end * i as f64 / n as f64, end * (i + 1) as f64 / n as f64);
        if l1 < first || l0 > last {
            probes.active.fill(false);
            y0 = None;
            continue;
        }
        probes.activate(0, 0.0, l0, l1);
        if i + 1 == n {
            probes.active[lit] = false;
        }
        if !probes.active.iter().any(|&on| on) {
            // Nothing to search here: the segment is not made (a closed form less).
            y0 = None;
            continue;
        }
        let d = match y0 {
            Some(y0) => Segment::exact(geo, sys, l0, y0, l1),
            None => Segment::exact_between(geo, sys, l0, l1),
        };
        if objects
            .scan(&d, Shift::default(), (l0, l1), Want::Any, probes)?
            .is_some()
        {
            return Ok(true);
        }
        y0 = Some(d.y1);
        probes.advance();
    }
    Ok(false)
}
