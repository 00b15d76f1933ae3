//! What the kernel reads, made from a scene: its uniforms and the scene table, and what it
//! writes: the slots of four channels of each sample's record. The one packer of that
//! layout, shared by the offscreen host (`crate::host`) and the viewer page (which receives
//! [`KernelInput`] as JSON and sets the same uniforms).
//!
//! What is the same for every sample is computed here once, in f64, with the CPU tracer's own
//! functions (`spacetime`: frames, Christoffel symbols, isometries, closed forms), and rounded
//! to f32 once: the kernel reads it (docs/physics.md, "The GPU kernel").
//!
//! Scene table (RGBA32F texels, [`TABLE_WIDTH`] per row): per object [`OBJECT_TEXELS`],
//!
//! | texel | ball at rest | ball in free fall | coordinate sphere | plane |
//! | --- | --- | --- | --- | --- |
//! | 0 | (0, R, 0, 0) | (1, R, 0, 0) | (2, R, 0, 0) | (3, 0, extent or 0, 0) |
//! | 1 | (x, y, z, 0) | start (x, y, z, 0) | centre (x, y, z, 0) | (0, 0, height, 0) |
//! | 2 | — | start time (hi, lo), B's t₀, 0 | — | — |
//! | 3–6 | static frame e0..e3 | start frame u, e1..e3 (Gödel: e1..e3 in the origin frame) | — | — |
//! | 7–10 | dual rows c0..c3 | (γ, γ(1 + v), rate, 0); (E, p_z, κ, ω); (cos χ, sin χ, r_max, q); B's (w₀, z₀, rotation) | — | — |
//! | 11–16 | Γ^μ_αβ there, μ = t, x, y: (Γ^μ_tt, Γ^μ_tx, Γ^μ_ty, Γ^μ_xx), (Γ^μ_xy, Γ^μ_yy, 0, 0) | — | — | — |
//!
//! (a scene without objects gets one of kind −1, never searched), then per light
//! [`LIGHT_TEXELS`]: (x, y, z, power). A ball at rest has its static frame, that frame's dual
//! rows (frame components are dot products with them) and the Christoffel symbols at its
//! position (those with a z index vanish: neither metric depends on z or mixes it with t, x, y;
//! `tests/integration/table.rs` checks it). A ball in free fall has its start frame (the static frame boosted by its
//! velocity; u its four-velocity) and, in Gödel's universe, its worldline's closed form in the
//! start's origin frame (spacetime::OriginGeodesic of u carried there) and the isometry B
//! from that frame back (spacetime::Isometry), its legs e1..e3 carried into that frame (where
//! the kernel transports them); γ = −u_t, and the rate is the coordinate time per proper time
//! over whole loops. They are made for the start at time zero (a shift of t is an isometry):
//! the kernel adds the start's time relative to the observer's, so that the table does not
//! depend on the observer (the page flies many observers with one table). Times are split
//! into f32 hi + lo parts, so that the kernel subtracts the observer's time without losing
//! the digits (f32 has 24 bits; scenes allow times up to 10⁶).
//!
//! The observer's uniforms that depend on its position alone, its static frame and its
//! isometry to the origin, are made here too ([`ObserverUniforms`]), and by the same function
//! for each position of a flight (the server sends them with every position it gives the
//! page); the boost by the observer's velocity stays in the kernel, since the page changes
//! the velocity itself, every animation frame, without the server.

use render::chart::LocalChart;
use render::segment::{BOUNDARY_LAMBDA, STEP_PER_SCALE};
use scene::{Camera, Motion, Scene, Shape};
use serde::Serialize;
use spacetime::measure::DualFrame;
use spacetime::{
    Event, ExactGeodesic, FourVector, GodelType, Isometry, LocalVelocity, Metric, Spacetime,
    TypeExactGeodesic, TypeIsometry, TypeOriginGeodesic,
};
use std::f64::consts::{PI, SQRT_2};
use std::ops::Range;

/// Texels per row of the scene table.
pub const TABLE_WIDTH: usize = 256;
/// Texels per object and per light.
pub const OBJECT_TEXELS: usize = 17;
pub const LIGHT_TEXELS: usize = 1;

/// The output slots of a record, four channels each (see [`slots`]).
pub const SLOT_CHANNELS: [&str; 24] = [
    "object", "status", "u", "v", // slot 0
    "g", "t_emit", "lambda", "cos_i", // slot 1
    "x", "y", "z", "view_x", // slot 2
    "dir_x", "dir_y", "dir_z", "view_y", // slot 3
    "view_z", "pol_x", "pol_y", "pol_z", // slot 4
    "light_0", "light_1", "light_2", "light_3", // slot 5, then four lights per slot
];

/// Slots a record of a scene with `lights` lights fills: five fixed ones, then the lights
/// four channels to a slot.
pub fn slots(lights: usize) -> usize {
    5 + lights.div_ceil(4)
}

/// The slots of a sample's progress between rounds, after the record's (the kernel's
/// `Progress`: phase, budget, probes and status first).
pub const STATE_SLOTS: usize = 3;

/// The progress slot's phase of a finished sample.
pub const PHASE_DONE: f32 = 2.0;

/// The first slot a round writes where it cannot write them all: the lights' (the record's five
/// fixed slots are then made from the final progress by a finishing draw).
pub const ROUND_SLOT0: usize = 5;

/// Where light `k`'s channel is: (slot, component).
pub fn light_channel(k: usize) -> (usize, usize) {
    (5 + k / 4, k % 4)
}

/// How a host draws a tile: each round writes the slots `rounds`; where they are not all the
/// slots, a finishing draw then writes the record's, `finish`. The array textures of a tile's
/// slots have `layers` layers.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoundPlan {
    pub rounds: Range<usize>,
    pub finish: Option<Range<usize>>,
    pub layers: usize,
}

/// The kernel's uniforms (names without the `u_` prefix of the GLSL source).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Uniforms {
    /// 0 Minkowski, 1 Gödel, 2 a Gödel-type member (the defines say it to the kernel).
    pub metric: i32,
    pub a: f32,
    pub obs_t: [f32; 2],
    pub obs_x: [f32; 3],
    /// The static frame and isometry at `obs_x` (JSON: `obs_static` and `obs_to` among the
    /// others).
    #[serde(flatten)]
    pub observer: ObserverUniforms,
    pub velocity: [f32; 4],
    pub forward: [f32; 3],
    pub up: [f32; 3],
    pub camera: i32,
    pub fov: [f32; 2],
    /// The sample grid's size (the camera's size times the samples per side).
    pub size: [i32; 2],
    pub max_past: f32,
    pub max_loops: i32,
    pub lights: i32,
    /// A Gödel-type member's constants as the kernel's `u_member`
    /// ([`MemberConstants::uniform`]); zeros outside the family.
    pub member: [f32; 4],
}

/// What the kernel reads of an observer at a position (x, y, z): the same at every sample,
/// so made once in f64 with `spacetime`'s own functions and rounded to f32 once.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ObserverUniforms {
    /// The static frame there (`Spacetime::static_frame`: Gram–Schmidt of ∂t, ∂x, ∂y, ∂z; the
    /// identity in Minkowski's spacetime), column-major as a GLSL mat4: columns e0..e3. The
    /// kernel boosts it by the observer's velocity.
    pub obs_static: [f32; 16],
    /// Gödel: the isometry sending the observer's event to the origin
    /// (`spacetime::Isometry::to_origin`) as (w₀.re, w₀.im, z₀, rotation); a Gödel-type
    /// member: its own (`spacetime::TypeIsometry::to_origin`) as (ζ₀.re, ζ₀.im, z₀,
    /// rotation). Its t₀ is 0, as the kernel's times are relative to the observer's.
    /// Minkowski: zeros (a translation, which the kernel never needs: its rays are straight
    /// lines from the observer).
    pub obs_to: [f32; 4],
}

impl ObserverUniforms {
    /// The one home of the observer's position-dependent uniforms: both hosts and the page
    /// (through the server) take them from here.
    pub fn new(metric: &Metric, x: f64, y: f64, z: f64) -> ObserverUniforms {
        let at = Event::new(0.0, x, y, z);
        let frame = metric.static_frame(at);
        let mut obs_static = [0.0f32; 16];
        for (column, e) in obs_static.chunks_exact_mut(4).zip(frame.e) {
            column.copy_from_slice(&texel(e));
        }
        let obs_to = match metric {
            Metric::Godel(g) => {
                let to = Isometry::to_origin(g.a, at);
                [to.w0.re, to.w0.im, to.z0, to.rotation].map(|c| c as f32)
            }
            // A scene's observer lies in the chart (scene validation); outside it, the
            // identity (never traced from).
            Metric::GodelType(m) => TypeIsometry::to_origin(*m, at).map_or([0.0; 4], |to| {
                [to.zeta0.re, to.zeta0.im, to.z0, to.rotation].map(|c| c as f32)
            }),
            Metric::Minkowski(_) => [0.0; 4],
        };
        ObserverUniforms { obs_static, obs_to }
    }
}

/// Everything the kernel needs for one scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct KernelInput {
    pub uniforms: Uniforms,
    /// The scene table, four floats per texel, [`TABLE_WIDTH`] texels per row (padded).
    pub table: Vec<f32>,
    pub table_rows: usize,
    /// The scene's object and light counts (the kernel's N_OBJECTS and N_LIGHTS are these,
    /// at least 1).
    pub objects: usize,
    pub light_count: usize,
    /// Which kinds of object the scene has: at rest, in free fall, coordinate spheres,
    /// planes (the kernel leaves out the code of the others).
    pub kinds: [bool; 4],
    /// Samples per side of a pixel.
    pub supersample: u32,
    /// A Gödel-type member's constants (`None` for Gödel's universe and Minkowski's).
    pub member: Option<MemberConstants>,
}

/// A Gödel-type member's constants, made in f64 and rounded once (gpu_input.glsl): whether it
/// is causal as a define (the escape stop's code is left out of the others), the rest as the
/// uniform `u_member`, so that members of one scene share a compiled kernel.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MemberConstants {
    pub m2: f32,
    pub omega: f32,
    /// Ω² − m²/4: its sign decides which light rays escape (render::segment::family_return),
    /// and where m² = 4Ω² f32's own difference would be rounding.
    pub delta: f32,
    /// m² ≥ 4Ω² up to rounding (render::tracer::EscapeStop): light may escape.
    pub causal: bool,
    /// The longest segment of a ray, STEP_PER_SCALE length scales.
    pub step: f32,
}

impl MemberConstants {
    fn new(member: GodelType, length_scale: f64) -> MemberConstants {
        let w2 = member.omega * member.omega;
        MemberConstants {
            m2: member.m2 as f32,
            omega: member.omega as f32,
            delta: (w2 - 0.25 * member.m2) as f32,
            causal: member.m2 >= 4.0 * w2 * (1.0 - BOUNDARY_LAMBDA),
            step: (STEP_PER_SCALE * length_scale) as f32,
        }
    }

    /// `u_member`: (m², Ω, Ω² − m²/4, the longest segment).
    pub fn uniform(&self) -> [f32; 4] {
        [self.m2, self.omega, self.delta, self.step]
    }
}

/// A time as f32 hi + lo, hi + lo ≈ t to ~2⁻⁴⁸ relative.
pub fn split_time(t: f64) -> [f32; 2] {
    let hi = t as f32;
    [hi, (t - f64::from(hi)) as f32]
}

/// Why the kernel cannot trace `scene`, in one sentence; `None` where it can (docs/physics.md,
/// "The GPU kernel in the family"): a ball falling fast enough to escape a causal Gödel-type
/// member (the kernel's escape stop bounds each object by its orbit, and such a ball has none).
pub fn refusal(scene: &Scene) -> Option<String> {
    let member = scene.metric.godel_type()?;
    let escapes = scene.objects.iter().any(|o| match o.motion {
        Motion::Geodesic { start, velocity } => {
            let start0 = Event::new(0.0, start.x, start.y, start.z);
            let u = scene.metric.observer_frame(start0, velocity).e[0];
            TypeIsometry::to_origin(member, start0)
                .and_then(|to| TypeOriginGeodesic::new(member, to.push(start0, u)))
                .is_some_and(|g| {
                    let spin = member.omega * g.energy;
                    g.big_lambda() <= BOUNDARY_LAMBDA * spin * spin
                })
        }
        Motion::Rest { .. } => false,
    });
    escapes.then(|| {
        "a ball of this scene falls fast enough to escape the member's axis, which the GPU \
         kernel's escape stop cannot bound"
            .to_string()
    })
}

impl KernelInput {
    pub fn new(scene: &Scene) -> KernelInput {
        let obs = scene.observer;
        let (camera, fov) = match scene.camera {
            Camera::Pinhole { fov_deg, .. } => (0, [fov_deg as f32, 0.0]),
            Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                ..
            } => (1, [h_fov_deg as f32, v_fov_deg as f32]),
            Camera::Sphere { .. } => (1, [360.0, 180.0]),
            Camera::Fisheye { fov_deg, .. } => (2, [fov_deg as f32, 0.0]),
        };
        let sample = scene.sample_camera();
        let f = |v: [f64; 3]| v.map(|c| c as f32);
        let v = obs.velocity;
        let member = (scene.metric.godel_type())
            .map(|m| MemberConstants::new(m, scene.metric.length_scale()));
        let uniforms = Uniforms {
            metric: match scene.metric {
                Metric::Minkowski(_) => 0,
                Metric::Godel(_) => 1,
                Metric::GodelType(_) => 2,
            },
            a: scene.metric.length_scale() as f32,
            obs_t: split_time(obs.event.t),
            obs_x: f([obs.event.x, obs.event.y, obs.event.z]),
            observer: ObserverUniforms::new(&scene.metric, obs.event.x, obs.event.y, obs.event.z),
            velocity: [
                v.speed as f32,
                v.direction[0] as f32,
                v.direction[1] as f32,
                v.direction[2] as f32,
            ],
            forward: f(obs.forward),
            up: f(obs.up),
            camera,
            fov,
            size: [sample.width() as i32, sample.height() as i32],
            max_past: scene.trace.max_past as f32,
            max_loops: scene::MAX_RAY_LOOPS as i32,
            lights: scene.lights.len() as i32,
            member: member.as_ref().map_or([0.0; 4], MemberConstants::uniform),
        };
        let mut texels: Vec<[f32; 4]> = Vec::new();
        for o in &scene.objects {
            let mut t = [[0.0f32; 4]; OBJECT_TEXELS];
            match (o.shape, o.motion) {
                (Shape::Sphere { radius }, Motion::Rest { position }) => {
                    t[0] = [0.0, radius as f32, 0.0, 0.0];
                    t[1] = [position.x as f32, position.y as f32, position.z as f32, 0.0];
                    rest_ball(&scene.metric, position, &mut t);
                }
                (Shape::Sphere { radius }, Motion::Geodesic { start, velocity }) => {
                    t[0] = [1.0, radius as f32, 0.0, 0.0];
                    t[1] = [start.x as f32, start.y as f32, start.z as f32, 0.0];
                    if !falling_ball(&scene.metric, start, velocity, &mut t) {
                        // Never for a scene's ball (its coordinates are within 10⁶ a, its
                        // speed below 1): without a closed form it is never searched.
                        t = [[0.0; 4]; OBJECT_TEXELS];
                        t[0] = [-1.0, 0.0, 0.0, 0.0];
                    }
                }
                (Shape::CoordinateSphere { center, radius }, _) => {
                    t[0] = [2.0, radius as f32, 0.0, 0.0];
                    t[1] = [center[0] as f32, center[1] as f32, center[2] as f32, 0.0];
                }
                (Shape::Plane { height, extent }, _) => {
                    t[0] = [3.0, 0.0, extent.unwrap_or(0.0) as f32, 0.0];
                    t[1] = [0.0, 0.0, height as f32, 0.0];
                }
            }
            texels.extend(t);
        }
        if scene.objects.is_empty() {
            // The kernel's arrays hold at least one object: one that is never searched.
            texels.push([-1.0, 0.0, 0.0, 0.0]);
            texels.extend([[0.0; 4]; OBJECT_TEXELS - 1]);
        }
        for l in &scene.lights {
            let p = l.position;
            texels.push([p.x as f32, p.y as f32, p.z as f32, l.power as f32]);
        }
        let mut kinds = [false; 4];
        for o in &scene.objects {
            kinds[match (o.shape, o.motion) {
                (Shape::Sphere { .. }, Motion::Rest { .. }) => 0,
                (Shape::Sphere { .. }, Motion::Geodesic { .. }) => 1,
                (Shape::CoordinateSphere { .. }, _) => 2,
                (Shape::Plane { .. }, _) => 3,
            }] = true;
        }
        let rows = texels.len().div_ceil(TABLE_WIDTH).max(1);
        texels.resize(rows * TABLE_WIDTH, [0.0; 4]);
        KernelInput {
            uniforms,
            table: texels.into_iter().flatten().collect(),
            table_rows: rows,
            objects: scene.objects.len(),
            light_count: scene.lights.len(),
            kinds,
            supersample: scene.supersample(),
            member,
        }
    }

    /// The defines the kernel is compiled with, as a source prefix (after `#version`): the
    /// sizes of its arrays, its render targets, and what the scene has (code for what it lacks
    /// is left out: a GPU runs both sides of a branch its samples take apart).
    pub fn defines(&self, draw_buffers: usize) -> String {
        let flag = |b: bool| u8::from(b);
        format!(
            "#define N_OBJECTS {}\n#define N_LIGHTS {}\n#define DRAW_BUFFERS {}\n\
             #define GODEL {}\n#define HAS_LIGHTS {}\n#define HAS_REST {}\n#define HAS_FREE {}\n\
             #define HAS_COORD_SPHERE {}\n#define HAS_PLANE {}\n",
            self.objects.max(1),
            self.light_count.max(1),
            draw_buffers,
            i32::from(self.uniforms.metric == 1),
            flag(self.light_count > 0),
            flag(self.kinds[0]),
            flag(self.kinds[1]),
            flag(self.kinds[2]),
            flag(self.kinds[3]),
        ) + &self.member.as_ref().map_or(String::new(), |m| {
            format!(
                "#define FAMILY 1\n#define MEMBER 1\n#define MEMBER_CAUSAL {}\n",
                flag(m.causal)
            )
        })
    }

    /// The slots of this scene's records.
    pub fn slots(&self) -> usize {
        slots(self.light_count)
    }

    /// Render targets a draw of this scene's kernel uses where `available` can be bound:
    /// enough for all its slots (a round then writes them in one draw), at least 1.
    pub fn draw_buffers(&self, available: usize) -> usize {
        available.clamp(1, self.slots() + STATE_SLOTS)
    }

    /// How a host draws a tile's rounds with `buffers` render targets (docs/physics.md,
    /// "Rounds"): every draw binds `buffers` layers from its first slot, so that every draw
    /// has the same targets (drivers compile a shader again for each set of targets).
    pub fn round_plan(&self, buffers: usize) -> RoundPlan {
        let slots = self.slots();
        let all = slots + STATE_SLOTS;
        let (rounds, finish) = if all <= buffers {
            (0..all, None)
        } else {
            (ROUND_SLOT0..all, Some(0..slots))
        };
        let end = |r: &Range<usize>| r.start + r.len().div_ceil(buffers) * buffers;
        let layers = end(&rounds).max(finish.as_ref().map_or(0, end));
        RoundPlan {
            rounds,
            finish,
            layers,
        }
    }
}

/// A vector as a texel.
fn texel(v: FourVector) -> [f32; 4] {
    v.to_array().map(|c| c as f32)
}

/// Texels 2–16 of a ball at rest at `position`: its body frame (the static frame there), and
/// in the chart of local descriptions (`render::chart::LocalChart`: a member's Gödel-like
/// chart, else the metric's own) its position (texel 2, a member only), the frame's dual rows
/// and the Christoffel symbols there (as `render::worldline` makes them), those of t, x and y
/// (symmetric in the lower two).
fn rest_ball(metric: &Metric, position: Event, t: &mut [[f32; 4]; OBJECT_TEXELS]) {
    let p = Event::new(0.0, position.x, position.y, position.z);
    let frame = metric.static_frame(p);
    let chart = LocalChart::of(metric);
    let centre = chart.event(p);
    if metric.godel_type().is_some() {
        t[2] = [centre.x, centre.y, centre.z, 0.0].map(|c| c as f32);
    }
    let dual = DualFrame::new(&chart.metric(centre), &chart.frame(p, &frame));
    for a in 0..4 {
        t[3 + a] = texel(frame.e[a]);
        t[7 + a] = dual.0[a].map(|c| c as f32);
    }
    let gamma = chart.christoffel(centre);
    for (mu, g) in gamma.iter().take(3).enumerate() {
        t[11 + 2 * mu] = [g[0][0], g[0][1], g[0][2], g[1][1]].map(|c| c as f32);
        t[12 + 2 * mu] = [g[1][2], g[2][2], 0.0, 0.0].map(|c| c as f32);
    }
}

/// Texels 2–10 of a ball in free fall from `start` with `velocity` (the table above); false
/// where its worldline has no closed form.
fn falling_ball(
    metric: &Metric,
    start: Event,
    velocity: LocalVelocity,
    t: &mut [[f32; 4]; OBJECT_TEXELS],
) -> bool {
    // Everything for a start at time zero; the kernel adds the start's relative time.
    let start0 = Event::new(0.0, start.x, start.y, start.z);
    let frame = metric.observer_frame(start0, velocity);
    let u = frame.e[0];
    // γ = −u_t is conserved (∂t is Killing), γ(1 + v) = γ + √(γ² − 1)
    // (render::worldline::Worldline::speed_factor).
    let gamma = (-metric.lower(start0, u).t).max(1.0);
    let speed = gamma + (gamma * gamma - 1.0).sqrt();
    let [hi, lo] = split_time(start.t);
    t[3] = texel(u);
    let mut rate = u.t;
    if let Some(a) = metric.godel_a() {
        let Some(g) = ExactGeodesic::new(a, start0, u) else {
            return false;
        };
        let to = Isometry::to_origin(a, start0);
        for k in 1..4 {
            t[3 + k] = texel(to.push(start0, frame.e[k]));
        }
        let o = g.origin;
        let lret = o.return_parameter();
        // The time after one return to the axis over its parameter.
        rate = o.at(lret).0.t / lret;
        // ω and q of spacetime::closed_form (its fields are private): λ_ret = π/ω,
        // q = |E|/(√2 a ω).
        let omega = PI / lret;
        let q = o.energy.abs() / (SQRT_2 * a * omega);
        let (cc, sc) = o.cis_chi();
        t[8] = [o.energy, o.pz, o.kappa, omega].map(|c| c as f32);
        t[9] = [cc, sc, o.r_max(), q].map(|c| c as f32);
        let b = g.back;
        t[2] = [hi, lo, b.t0 as f32, 0.0];
        t[10] = [b.w0.re, b.w0.im, b.z0, b.rotation].map(|c| c as f32);
    } else if let Some(member) = metric.godel_type() {
        // The geodesic through the start (spacetime::TypeExactGeodesic); its legs stay in the
        // scene's coordinates, where the kernel transports them (typeTransport).
        let Some(g) = TypeExactGeodesic::new(member, start0, u) else {
            return false;
        };
        for k in 1..4 {
            t[3 + k] = texel(frame.e[k]);
        }
        let o = g.origin;
        rate = match o.return_parameter() {
            Some(lret) => g.at(lret).0.t / lret,
            None => u.t,
        };
        let (cc, sc) = o.cis_chi();
        t[8] = [o.energy, o.pz, o.kappa, o.kperp()].map(|c| c as f32);
        t[9] = [o.big_lambda(), cc, sc, 0.0].map(|c| c as f32);
        let b = g.back;
        t[2] = [hi, lo, b.t0 as f32, 0.0];
        t[10] = [b.zeta0.re, b.zeta0.im, b.z0, b.rotation].map(|c| c as f32);
        let (alpha, beta) = g.winding().unwrap_or_default();
        t[11] = [alpha.re, alpha.im, beta.re, beta.im].map(|c| c as f32);
    } else {
        for k in 1..4 {
            t[3 + k] = texel(frame.e[k]);
        }
        t[2] = [hi, lo, 0.0, 0.0];
    }
    t[7] = [gamma, speed, rate, 0.0].map(|c| c as f32);
    true
}
