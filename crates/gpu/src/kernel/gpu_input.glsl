// godel's exact tracer as one GLSL ES 3.00 fragment kernel: one fragment = one sample of
// the camera's sample grid, its outputs the data file's channels. It is the twin of the CPU
// exact tracer (crates/render: tracer.rs, intersect.rs, target.rs, worldline.rs,
// lighting.rs; crates/spacetime: closed_form.rs, isometry.rs, connect.rs, frame.rs) with the
// same camera conventions, isometry, closed forms, loop copies, search bounds and statuses;
// each block cites its section of docs/physics.md. Single precision throughout ("The GPU
// kernel" in docs/physics.md says what that costs).
//
// The kernel is the chunks of crates/gpu/src/kernel/, each named after the Rust module it
// mirrors, one after the other in the order crates/gpu/src/lib.rs lists (`KERNEL`); this one
// holds the conventions, the inputs, the constants and the record's slots.
//
// The host prepends `#version 300 es` and its defines (crates/gpu/src/input.rs,
// `KernelInput::defines`): N_OBJECTS and N_LIGHTS (the scene's counts, at least 1 for the
// array sizes), DRAW_BUFFERS (render targets per pass), GODEL (1 for Gödel's metric, 0 for
// Minkowski's and the family's), for a Gödel-type member MEMBER with FAMILY and
// MEMBER_CAUSAL (1 where m² ≥ 4Ω² up to rounding: light may escape; the member's other
// constants are the uniform u_member, so that members share a compiled kernel), HAS_LIGHTS
// and HAS_REST, HAS_FREE, HAS_COORD_SPHERE, HAS_PLANE (whether the scene has lights and
// objects of each kind); benchmarks may add COUNT_PROBES (each sample's
// probe count in place of view_x), and the family's probe FAMILY (the Gödel-type family's
// functions, spacetime_godel_type.glsl).
//
// Rules, so that no conforming driver can run it two ways (docs/physics.md, "The GPU kernel";
// crates/gpu/tests/integration/kernel_rules.rs checks them on this text): arrays, matrices and vectors
// are stored into only at constant indices (constants, or the index of a loop with constant
// bounds whose body is a few stores: a store at a runtime index i is such a loop storing where
// j == i); no NaN is tested (finite() reads the bits) or made on purpose; floats become ints
// only through toInt; every variable gets a value where it is declared, every out parameter
// first thing in its function; no `?:` between structures (WebGL refuses it).
//
// Conventions (docs/physics.md, "Conventions"): c = 1, signature (−,+,+,+), events and
// vectors as vec4 (t, x, y, z) in pseudo-Cartesian coordinates, times relative to the
// observer's (the metric does not depend on t: a shift of t is an isometry), complex numbers
// as vec2 (re, im).

precision highp float;
precision highp int;
precision highp sampler2D;

// ---------------------------------------------------------------------------------------
// Inputs. The scene table holds per object OBJECT_TEXELS texels and per light LIGHT_TEXELS
// (layout written by crates/gpu/src/input.rs, the one packer).

uniform float u_a;           // Gödel parameter a; a member's length scale (Metric::length_scale)
uniform vec2 u_obs_t;        // observer time as hi + lo (times of objects are made relative to it)
uniform vec3 u_obs_x;        // observer position (x, y, z)
uniform mat4 u_obs_static;   // the static frame there, columns e0..e3 (made by the host in f64)
uniform vec4 u_obs_to;       // the isometry sending the observer to the origin, (w0, z0, rot)
                             // (a member: its base coordinate ζ0 in place of w0)
uniform vec4 u_velocity;     // observer speed and unit direction in the static frame
uniform vec3 u_forward;      // camera axes in the observer's frame
uniform vec3 u_up;
uniform int u_camera;        // 0 pinhole, 1 panorama (sphere too), 2 fisheye
uniform vec2 u_fov;          // degrees: pinhole (fov, −), panorama (h, v), fisheye (fov, −)
uniform ivec2 u_size;        // the sample grid's width and height
uniform ivec2 u_origin;      // this draw's first column and row of the sample grid
uniform float u_max_past;    // follow rays this far into the past
uniform int u_max_loops;     // loop copies at most (MAX_RAY_LOOPS)
uniform int u_slot0;         // the first output slot this pass writes
uniform int u_lights;        // the scene's lights (N_LIGHTS is at least 1)
uniform int u_two;           // 2: the bound of the loop that detects llvmpipe's loop limit
uniform sampler2D u_table;   // the scene table, RGBA32F
// Rounds (main): 0 in a tile's first round (nothing to read), then 1; u_finish 1 in the draw
// that writes the records; u_budget: passes per sample in the first round; u_prev: the
// previous round's slots of this tile, one layer per slot.
uniform int u_round;
uniform int u_finish;
uniform int u_budget;
uniform highp sampler2DArray u_prev;

layout(location = 0) out vec4 o0;
#if DRAW_BUFFERS > 1
layout(location = 1) out vec4 o1;
#endif
#if DRAW_BUFFERS > 2
layout(location = 2) out vec4 o2;
#endif
#if DRAW_BUFFERS > 3
layout(location = 3) out vec4 o3;
#endif
#if DRAW_BUFFERS > 4
layout(location = 4) out vec4 o4;
#endif
#if DRAW_BUFFERS > 5
layout(location = 5) out vec4 o5;
#endif
#if DRAW_BUFFERS > 6
layout(location = 6) out vec4 o6;
#endif
#if DRAW_BUFFERS > 7
layout(location = 7) out vec4 o7;
#endif

const int TABLE_WIDTH = 256;
const int OBJECT_TEXELS = 17;
const int LIGHT_TEXELS = 1;

const int KIND_REST = 0;
const int KIND_FREE = 1;
const int KIND_COORD_SPHERE = 2;
const int KIND_PLANE = 3;   // (−1: the placeholder of a scene without objects)

const int HIT = 0;
const int ESCAPED = 1;
const int FAILED = 3;
const int NOT_TRACED = 4;
const int WORK_LIMIT = 5;

const float PI = 3.14159265358979;
const float SQRT2 = 1.41421356237310;
const float NO_TAU = -3.0e38;      // "no matched proper time" (the CPU's NaN)
const float INF = 3.0e38;

#ifdef MEMBER
// A Gödel-type member's constants (gpu::input::MemberConstants): m², Ω, Ω² − m²/4 (made in
// f64: its sign decides which rays escape, and f32's Ω² − m²/4 would be rounding where
// m² = 4Ω²) and the longest segment of a ray (render::segment::STEP_PER_SCALE length scales).
uniform vec4 u_member;
#define MEMBER_M2 u_member.x
#define MEMBER_OMEGA u_member.y
#define MEMBER_DELTA u_member.z
#define MEMBER_STEP u_member.w
#define MB u_member.xy   // the member as the family's functions take it
// render::tracer::MAX_FAMILY_SEGMENTS: segments of an escaping ray at most.
const int MAX_FAMILY_SEGMENTS = 16384;
// render::segment::BOUNDARY_LAMBDA: below this fraction of Ω²E², Λ counts as 0 (escaping).
const float BOUNDARY_LAMBDA = 1e-12;
// scene::ranges: positions of a member with m² > 0 end at mρ = 30 (beyond, f64 loses its
// digits; here an escaping ray's e^{mρ} would near f32's range).
const float MAX_M_RHO = 30.0;
#endif

// The intersection search's bounds (render::intersect, docs/physics.md "The intersection
// search"): halvings of a span, probes per object and span, conservative advancement cap.
const int SEARCH_DEPTH = 30;
const int SEARCH_PROBES = 131072;
const float MAX_SKIP = 1.0;
// Segments per loop of a closed-form ray (render::segment::EXACT_SEGMENTS).
const int EXACT_SEGMENTS = 16;
// GPU only: segments of a Minkowski ray or a shadow ray at most.
const int MAX_SEGMENTS = 100000;
// Segment and loop counts kept as ints (below 2^30: their products with EXACT_SEGMENTS stay ints).
const int MAX_COUNT_SEGMENTS = 1 << 24;
// Probes per sample, all its searches together: a count kept exactly in f32 between rounds,
// far above what the other bounds allow (the CPU has no such bound; the search's own bounds
// end a search first).
const int PIXEL_PROBES = 16777215;
// Root refinement steps (spacetime::refine_root) and simultaneity steps
// (render::worldline::SIMULTANEITY_STEPS).
const int REFINE_STEPS = 100;
const int SIMULTANEITY_STEPS = 12;
// Newton steps of a falling ball's proper time at a coordinate time (tauGuess).
const int TIME_STEPS = 3;
// render::target: rate margins (near and far probes) and the near zone of local objects.
const float RATE_MARGIN = 1.5;
const float GLOBAL_RATE_MARGIN = 2.0;
const float FAR_RATE_MARGIN = 1.5;
const float FAR_RATE_MAX_SPEED_FACTOR = 3.5;
const float FAR_DISTANCE = 0.25;
const float FAR_RADII = 1.0;
const float FAR_SLACK = 1.3;
// render::chord: the chord exclusion's domain (speed factor, units of a), its bend at rest and
// in free fall (units of e²/a) and a falling ball's energy margin; its noise allowance here
// covers f32's rest-frame coordinates (~1e-6 a; the CPU's is 1e-8 a).
const float CHORD_MAX_SPEED_FACTOR = 3.0;
const float CHORD_MAX_END = 0.4;
const float CHORD_MAX_STRAY = 0.05;
const float CHORD_BEND_AT_REST = 3.25;
const float CHORD_BEND_FALLING = 0.75;
const float CHORD_ENERGY_MARGIN = 2.0;
const float CHORD_NOISE = 1e-4;
// render::lighting: the occlusion test stops this fraction of the ray short of the lit point.
const float END_CUT = 1e-6;
// spacetime::connect: grid cells per winding and branch bracketing the shadow-ray roots.
const int SHADOW_GRID = 256;
// A falling ball's window per loop of a pixel ray (fallingWindow; render::falling): its reach
// per radius (REACH_PER_RADIUS there, f32's rounding far below its margin), the proper time a
// cell spans per radius, and at most FALL_CELLS cells a loop (longer cells beyond).
const float FALL_REACH_PER_RADIUS = 1.08;
const float FALL_CELL_PER_RADIUS = 0.5;
const int FALL_CELLS = 64;
const int CELLS_PER_PASS = 16;
const int MAX_WINDINGS = 10000;
// Copies of a ball's arc aimed at per shadow ray (render::lighting::MAX_AIMS).
const int MAX_AIMS = 4;
// Reach of a ball at rest (render::reject::reach): R·(1 + REST_REACH_CURVATURE·(R/a)²) +
// REACH_PER_A·a, widened for f32 (reachOf). A Gödel-type member's escape test takes
// REACH_PER_RADIUS radii.
const float REST_REACH_CURVATURE = 0.25;
const float REACH_PER_A = 1e-6;
const float REACH_PER_RADIUS = 1.25;

// GPU only: passes of one round of a sample (main): the first round's u_budget, halved
// after a round that llvmpipe's loop limit cut short, doubled after one that reached no
// checkpoint; a sample whose work between two checkpoints takes more than MAX_BUDGET passes
// is marked "work limit".
const int MIN_BUDGET = 8;
const int MAX_BUDGET = 1048576;

int probes_left = 0;   // the pixel's probe budget (PIXEL_PROBES)

// The sample's slots of four channels (see `main`): the record's five fixed ones, its lights
// four to a slot (none without lights, as the host counts them: crates/gpu/src/input.rs), then
// the sample's progress (STATE_SLOTS, carried from round to round).
const int RECORD_SLOTS = 5 + (HAS_LIGHTS != 0 ? (N_LIGHTS + 3) / 4 : 0);
const int STATE = RECORD_SLOTS;
const int STATE_SLOTS = 3;
const int ALL_SLOTS = RECORD_SLOTS + STATE_SLOTS;
vec4 slots[ALL_SLOTS + 8];


