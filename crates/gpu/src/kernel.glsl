// godel's exact tracer as one GLSL ES 3.00 fragment kernel: one fragment = one sample of
// the camera's sample grid, its outputs the data file's channels. It is the twin of the CPU
// exact tracer (crates/render: tracer.rs, intersect.rs, target.rs, worldline.rs,
// lighting.rs; crates/spacetime: closed_form.rs, isometry.rs, connect.rs, frame.rs) with the
// same camera conventions, isometry, closed forms, loop copies, search bounds and statuses;
// each block cites its section of docs/physics.md. Single precision throughout ("The GPU
// kernel" in docs/physics.md says what that costs).
//
// The host prepends `#version 300 es` and its defines (crates/gpu/src/input.rs,
// `KernelInput::defines`): N_OBJECTS and N_LIGHTS (the scene's counts, at least 1 for the
// array sizes), DRAW_BUFFERS (render targets per pass), GODEL (1 for Gödel's metric, 0 for
// Minkowski's), HAS_LIGHTS and HAS_REST, HAS_FREE, HAS_COORD_SPHERE, HAS_PLANE (whether the
// scene has lights and objects of each kind); benchmarks may add COUNT_PROBES (each sample's
// probe count in place of view_x).
//
// Rules, so that no conforming driver can run it two ways (docs/physics.md, "The GPU kernel";
// crates/gpu/tests/kernel_rules.rs checks them on this text): arrays, matrices and vectors
// are stored into only at constant indices (constants, or the index of a loop with constant
// bounds whose body is a few stores: a store at a runtime index i is such a loop storing where
// j == i); no NaN is tested (finite() reads the bits) or made on purpose; floats become ints
// only through toInt; every variable gets a value where it is declared, every out parameter
// first thing in its function.
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

uniform float u_a;           // Gödel parameter a
uniform vec2 u_obs_t;        // observer time as hi + lo (times of objects are made relative to it)
uniform vec3 u_obs_x;        // observer position (x, y, z)
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

// The intersection search's bounds (render::intersect, docs/physics.md "The intersection
// search"): halvings of a span, probes per object and span, conservative advancement cap.
const int SEARCH_DEPTH = 30;
const int SEARCH_PROBES = 131072;
const float MAX_SKIP = 1.0;
// Segments per loop of a closed-form ray (render::segment::EXACT_SEGMENTS).
const int EXACT_SEGMENTS = 16;
// GPU only: segments of a Minkowski ray or a shadow ray at most.
const int MAX_SEGMENTS = 100000;
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
// render::target: rate margins and the near zone of local objects.
const float RATE_MARGIN = 1.5;
const float GLOBAL_RATE_MARGIN = 2.0;
const float FAR_DISTANCE = 0.25;
const float FAR_RADII = 1.0;
const float FAR_SLACK = 1.3;
// render::lighting: the occlusion test stops this fraction of the ray short of the lit point.
const float END_CUT = 1e-6;
// spacetime::connect: grid cells per winding and branch bracketing the shadow-ray roots.
const int SHADOW_GRID = 256;
// Cells of a falling ball's worldline per loop of a pixel ray (fallingLast).
const int FALL_CELLS = 16;
const int CELLS_PER_PASS = 16;
const int MAX_WINDINGS = 10000;
// render::reject: reach of a ball at rest per radius and per a.
const float REACH_PER_RADIUS = 1.25;
const float REACH_PER_A = 1e-6;

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


// ---------------------------------------------------------------------------------------
// Complex numbers (vec2) and small helpers.

// Finite, and below 1e38 (INF, 3e38, counts as infinite), told by the bits: the magnitude's
// bit pattern orders as the value does, and NaN's and infinity's lie above 1e38's. No isnan:
// a compiler that assumes no NaN may fold it away.
bool finite(float v) { return (floatBitsToUint(v) & 0x7fffffffu) < 0x7e967699u; }
// A float made an int in [lo, hi] (a count, an index): GLSL leaves the conversion of values
// outside int's range undefined, so v is clamped first, and a v that is not finite gives lo.
int toInt(float v, int lo, int hi) { return finite(v) ? int(clamp(v, float(lo), float(hi))) : lo; }

// Arctangents and arcsines of our own: GLSL leaves their precision to the implementation,
// and Mesa's are approximations (measured on llvmpipe: asin off by 4e-4, atan by 3e-6).
// Cephes' atanf (S. L. Moshier): range reduction to |t| ≤ tan(π/8) and a minimax
// polynomial, relative error ~2e-7.
float atanA(float x) {
    float ax = abs(x);
    float y = 0.0, t = ax;
    if (ax > 2.414213562373095) { y = 0.5 * PI; t = -1.0 / ax; }
    else if (ax > 0.4142135623730950) { y = 0.25 * PI; t = (ax - 1.0) / (ax + 1.0); }
    float z = t * t;
    y += (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z - 3.33329491539e-1) * z * t + t;
    return x < 0.0 ? -y : y;
}
float atan2s(float y, float x) {
    if (x == 0.0 && y == 0.0) return 0.0;
    float ax = abs(x), ay = abs(y);
    float r = ay <= ax ? atanA(ay / ax) : 0.5 * PI - atanA(ax / ay);
    if (x < 0.0) r = PI - r;
    return y < 0.0 ? -r : r;
}
float asinA(float x) { return atan2s(x, sqrt(max((1.0 - x) * (1.0 + x), 0.0))); }
// The same, four at a time (the shadow rays' grid).
vec4 atanA4(vec4 x) {
    vec4 ax = abs(x);
    bvec4 big = greaterThan(ax, vec4(2.414213562373095));
    bvec4 mid = greaterThan(ax, vec4(0.4142135623730950));
    vec4 t = mix(mix(ax, (ax - 1.0) / (ax + 1.0), mid), -1.0 / max(ax, 1e-30), big);
    vec4 y = mix(mix(vec4(0.0), vec4(0.25 * PI), mid), vec4(0.5 * PI), big);
    vec4 z = t * t;
    y += (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z - 3.33329491539e-1) * z * t + t;
    return mix(y, -y, lessThan(x, vec4(0.0)));
}
// asin of x ∈ [0, 1].
vec4 asinA4(vec4 x) {
    vec4 c = sqrt(max((1.0 - x) * (1.0 + x), 0.0));
    bvec4 low = lessThanEqual(x, c);
    return mix(0.5 * PI - atanA4(c / max(x, 1e-30)), atanA4(x / max(c, 1e-30)), low);
}
float acosA(float x) { return atan2s(sqrt(max((1.0 - x) * (1.0 + x), 0.0)), x); }

vec2 cmul(vec2 p, vec2 q) { return vec2(p.x * q.x - p.y * q.y, p.x * q.y + p.y * q.x); }
vec2 cdiv(vec2 p, vec2 q) { return vec2(p.x * q.x + p.y * q.y, p.y * q.x - p.x * q.y) / dot(q, q); }
vec2 conj2(vec2 p) { return vec2(p.x, -p.y); }
// Cosine and sine of our own, for the same reason: Chromium's software WebGL (SwiftShader)
// computes sin and cos to within 2e-4 only (Vulkan's bound is 2^-11). Cephes' sinf/cosf
// (S. L. Moshier): reduction by π/4 in three parts (exact for |a| < 8192) to an even octant,
// minimax polynomials on [−π/4, π/4], error ~1 ulp.
vec2 cis(float a) {
    float j = floor(abs(a) * 1.27323954473516);   // 4/π
    j += mod(j, 2.0);
    float x = ((abs(a) - j * 0.78515625) - j * 2.4187564849853515625e-4) - j * 3.77489497744594108e-8;
    float z = x * x;
    float s = ((-1.9515295891e-4 * z + 8.3321608736e-3) * z - 1.6666654611e-1) * z * x + x;
    float c = ((2.443315711809948e-5 * z - 1.388731625493765e-3) * z + 4.166664568298827e-2) * z * z - 0.5 * z + 1.0;
    // The quarter turn q: (c, s) rotated by q·π/2, chosen by comparing floats (no conversion
    // to int, no branch: cis is inlined at every call, and SwiftShader took minutes to compile
    // the kernel with a toInt here).
    float q = mod(j * 0.5, 4.0);
    vec2 r = q < 0.5 ? vec2(c, s) : (q < 1.5 ? vec2(-s, c) : (q < 2.5 ? vec2(-c, -s) : vec2(s, -c)));
    return vec2(r.x, a < 0.0 ? -r.y : r.y);
}
float sinA(float a) { return cis(a).y; }
float cosA(float a) { return cis(a).x; }
float carg(vec2 p) { return atan2s(p.y, p.x); }
float asinh_(float x) { return sign(x) * log(abs(x) + sqrt(x * x + 1.0)); }
// tanh(asinh(x)/2) = x/(1 + √(1 + x²)): the disc radius |h| of a ray's circle centre.
float halfTanh(float x) { return x / (1.0 + sqrt(1.0 + x * x)); }
float acosh_(float x) { return log(x + sqrt(max(x * x - 1.0, 0.0))); }
float atanh_(float x) { return 0.5 * log((1.0 + x) / (1.0 - x)); }

vec4 tableTexel(int i) { return texelFetch(u_table, ivec2(i % TABLE_WIDTH, i / TABLE_WIDTH), 0); }

// ---------------------------------------------------------------------------------------
// The metric (docs/physics.md, "The Gödel metric"; spacetime::godel, spacetime::minkowski).

bool godel() { return GODEL != 0; }

mat4 metricAt(vec4 e) {
    if (!godel()) return mat4(-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    float a = u_a, x = e.y, y = e.z;
    float k = 0.25 / (a * a);
    float m = 1.0 / (4.0 * a * a + x * x + y * y);
    float gtx = y / (SQRT2 * a), gty = -x / (SQRT2 * a);
    float gxx = 1.0 - k * y * y - m * x * x;
    float gxy = (k - m) * x * y;
    float gyy = 1.0 - k * x * x - m * y * y;
    return mat4(-1.0, gtx, gty, 0.0,
                gtx, gxx, gxy, 0.0,
                gty, gxy, gyy, 0.0,
                0.0, 0.0, 0.0, 1.0);
}

mat4 inverseMetricAt(vec4 e) {
    if (!godel()) return mat4(-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    float a = u_a, x = e.y, y = e.z;
    float k = 0.25 / (a * a);
    float c = 1.0 / (1.0 + k * (x * x + y * y));
    float q = k * (1.0 + c);
    float gtx = c * y / (SQRT2 * a), gty = -c * x / (SQRT2 * a);
    return mat4(1.0 - 2.0 * c, gtx, gty, 0.0,
                gtx, c + q * x * x, q * x * y, 0.0,
                gty, q * x * y, c + q * y * y, 0.0,
                0.0, 0.0, 0.0, 1.0);
}

float dotg(mat4 g, vec4 u, vec4 v) { return dot(u, g * v); }

// The metric's derivatives ∂x g and ∂y g (the others vanish; spacetime::godel,
// metric_derivatives).
void metricDerivatives(vec4 e, out mat4 dX, out mat4 dY) {
    dX = mat4(0.0); dY = mat4(0.0);
    float a = u_a, x = e.y, y = e.z;
    float k = 0.25 / (a * a);
    float m = 1.0 / (4.0 * a * a + x * x + y * y);
    float m2 = m * m;
    float w = 1.0 / (SQRT2 * a);
    float dx_xx = 2.0 * m2 * x * x * x - 2.0 * m * x;
    float dy_xx = -2.0 * k * y + 2.0 * m2 * y * x * x;
    float dx_xy = (k - m) * y + 2.0 * m2 * x * x * y;
    float dy_xy = (k - m) * x + 2.0 * m2 * x * y * y;
    float dx_yy = -2.0 * k * x + 2.0 * m2 * x * y * y;
    float dy_yy = 2.0 * m2 * y * y * y - 2.0 * m * y;
    dX = mat4(0.0, 0.0, -w, 0.0,
              0.0, dx_xx, dx_xy, 0.0,
              -w, dx_xy, dx_yy, 0.0,
              0.0, 0.0, 0.0, 0.0);
    dY = mat4(0.0, w, 0.0, 0.0,
              w, dy_xx, dy_xy, 0.0,
              0.0, dy_xy, dy_yy, 0.0,
              0.0, 0.0, 0.0, 0.0);
}

// Γ^μ_αβ u^α v^β = ½ g^μν (∂_α g_νβ u^α v^β + ∂_β g_να u^α v^β − ∂_ν g_αβ u^α v^β), from the
// derivatives and the inverse metric at the point (Minkowski: all zero).
vec4 christoffelWith(mat4 dX, mat4 dY, mat4 ginv, vec4 u, vec4 v) {
    mat4 du = u.y * dX + u.z * dY;
    mat4 dv = v.y * dX + v.z * dY;
    vec4 low = du * v + dv * u - vec4(0.0, dot(u, dX * v), dot(u, dY * v), 0.0);
    return 0.5 * (ginv * low);
}

vec4 christoffel(vec4 e, vec4 u, vec4 v) {
    if (!godel()) return vec4(0.0);
    mat4 dX = mat4(0.0), dY = mat4(0.0);
    metricDerivatives(e, dX, dY);
    return christoffelWith(dX, dY, inverseMetricAt(e), u, v);
}

// Riemann normal coordinates to second order (docs/physics.md, "Local objects";
// spacetime::normal; the first-order transport is written out in restFramePhoton).
vec4 normalDisplacement(vec4 at, vec4 d) { return d + 0.5 * christoffel(at, d, d); }

// ---------------------------------------------------------------------------------------
// Frames (docs/physics.md, "Frames"; spacetime::frame): the static frame by Gram–Schmidt of
// (∂t, ∂x, ∂y, ∂z), boosts. A frame is a mat4 whose columns are e0..e3.

mat4 staticFrame(vec4 at) {
    mat4 g = metricAt(at);
    vec4 e0 = vec4(1.0, 0.0, 0.0, 0.0);
    e0 = e0 / sqrt(-dotg(g, e0, e0));
    vec4 v = vec4(0.0, 1.0, 0.0, 0.0);
    v += dotg(g, v, e0) * e0;
    vec4 e1 = v / sqrt(dotg(g, v, v));
    v = vec4(0.0, 0.0, 1.0, 0.0);
    v += dotg(g, v, e0) * e0;
    v -= dotg(g, v, e1) * e1;
    vec4 e2 = v / sqrt(dotg(g, v, v));
    v = vec4(0.0, 0.0, 0.0, 1.0);
    v += dotg(g, v, e0) * e0;
    v -= dotg(g, v, e1) * e1;
    v -= dotg(g, v, e2) * e2;
    return mat4(e0, e1, e2, v / sqrt(dotg(g, v, v)));
}

// The standard boost: Λ⁰₀ = γ, Λ⁰ᵢ = Λⁱ₀ = γ v nᵢ, Λⁱⱼ = δᵢⱼ + (γ − 1) nᵢ nⱼ.
mat4 boostFrame(mat4 f, float speed, vec3 n) {
    float gam = 1.0 / sqrt(1.0 - speed * speed);
    mat4 out_ = mat4(0.0);
    out_[0] = f * vec4(gam, gam * speed * n);
    for (int i = 0; i < 3; i++) {
        vec3 row = (gam - 1.0) * n[i] * n;
        row[i] += 1.0;
        out_[i + 1] = f * vec4(gam * speed * n[i], row);
    }
    return out_;
}

// The dual rows c_a = η_aa g(e_a, ·): frame components of a vector v are dot(c_a, v).
mat4 dualFrame(mat4 g, mat4 f) {
    mat4 d = mat4(0.0);
    for (int a = 0; a < 4; a++) d[a] = (a == 0 ? -1.0 : 1.0) * (g * f[a]);
    return d;
}
vec4 components(mat4 dual, vec4 v) { return vec4(dot(dual[0], v), dot(dual[1], v), dot(dual[2], v), dot(dual[3], v)); }

// ---------------------------------------------------------------------------------------
// Cameras (docs/physics.md, "Pixels and cameras"; scene::camera): the unit direction in the
// camera basis (forward, right, up) at image position (x, y) of the sample grid; false for
// a fisheye pixel outside its circle.

bool cameraDirection(vec2 p, out vec3 d) {
    d = vec3(0.0);
    float w = float(u_size.x), h = float(u_size.y);
    if (u_camera == 0) {
        vec2 halfFov = cis(radians(0.5 * u_fov.x));
        float t = halfFov.y / halfFov.x;
        float x = t * (2.0 * p.x / w - 1.0);
        float y = t * (h / w) * (1.0 - 2.0 * p.y / h);
        d = vec3(1.0, x, y) / sqrt(1.0 + x * x + y * y);
        return true;
    }
    if (u_camera == 1) {
        float alpha = radians(u_fov.x) * (p.x / w - 0.5);
        float beta = radians(u_fov.y) * (0.5 - p.y / h);
        d = vec3(cosA(beta) * cosA(alpha), cosA(beta) * sinA(alpha), sinA(beta));
        return true;
    }
    float dx = 2.0 * p.x / w - 1.0, dy = 1.0 - 2.0 * p.y / h;
    float rho = length(vec2(dx, dy));
    if (rho > 1.0) return false;
    float theta = rho * radians(0.5 * u_fov.x);
    vec2 sc = rho > 0.0 ? vec2(dx, dy) / rho : vec2(0.0, 1.0);
    d = vec3(cosA(theta), sinA(theta) * sc.x, sinA(theta) * sc.y);
    return true;
}

// ---------------------------------------------------------------------------------------
// Isometries (docs/physics.md, "Isometries"; spacetime::isometry): X ↦ R_rot(T_{P0}(X)) in
// the disc coordinate w = (x + iy)/√(x² + y² + 4a²).

struct Iso { float t0; vec2 w0; float z0; float rot; };
// The identity, and the value of every Iso before it is set (no variable is read unset).
const Iso NO_ISO = Iso(0.0, vec2(0.0), 0.0, 0.0);

vec2 disc(vec2 xy) { return xy / sqrt(dot(xy, xy) + 4.0 * u_a * u_a); }
vec2 fromDisc(vec2 w) { return 2.0 * u_a * w / sqrt(1.0 - dot(w, w)); }

Iso toOrigin(vec4 p) { return Iso(p.x, disc(p.yz), p.w, 0.0); }
Iso inverseIso(Iso m) { return Iso(-m.t0, -cmul(cis(m.rot), m.w0), -m.z0, -m.rot); }
bool isTranslation(Iso m) { return m.w0 == vec2(0.0) && m.rot == 0.0; }

// The image of an event and of the tangent vector v there (spacetime::Isometry::apply_push).
void applyPush(Iso m, vec4 at, vec4 v, out vec4 e, out vec4 k) {
    e = vec4(0.0); k = vec4(0.0);
    if (isTranslation(m)) {
        e = vec4(at.x - m.t0, at.y, at.z, at.w - m.z0);
        k = v;
        return;
    }
    float a = u_a;
    vec2 w = disc(at.yz);
    vec2 den = vec2(1.0, 0.0) - cmul(conj2(m.w0), w);
    vec2 rot = cis(m.rot);
    vec2 w1 = cmul(rot, cdiv(w - m.w0, den));
    e = vec4(at.x - m.t0 - 2.0 * SQRT2 * a * carg(den), fromDisc(w1), at.w - m.z0);
    // dw = (dx + i dy)/S − (x + i y)(x dx + y dy)/S³.
    float s2 = dot(at.yz, at.yz) + 4.0 * a * a;
    float s = sqrt(s2);
    float rad = dot(at.yz, v.yz) / (s2 * s);
    vec2 dw = v.yz / s - at.yz * rad;
    vec2 dw1 = cmul(rot, cdiv(dw * (1.0 - dot(m.w0, m.w0)), cmul(den, den)));
    // d(x + iy) = 2a dw/√(1 − |w|²) + 2a w Re(w̄ dw)/(1 − |w|²)^{3/2}.
    float n = 1.0 - dot(w1, w1);
    float f = 2.0 * a / sqrt(n);
    float g = f * dot(w1, dw1) / n;
    k = vec4(v.x + 2.0 * SQRT2 * a * cdiv(cmul(conj2(m.w0), dw), den).y, f * dw1 + g * w1, v.w);
}

vec4 applyIso(Iso m, vec4 at) { vec4 e = vec4(0.0), k = vec4(0.0); applyPush(m, at, vec4(0.0), e, k); return e; }
vec4 pushIso(Iso m, vec4 at, vec4 v) { vec4 e = vec4(0.0), k = vec4(0.0); applyPush(m, at, v, e, k); return k; }

// ---------------------------------------------------------------------------------------
// Closed-form geodesics through the origin (docs/physics.md, "Closed forms";
// spacetime::closed_form): x + iy = r_max sin θ e^{i(χ + sgn(E) Φ(θ))},
// t = sgn(E) 2√2 a Φ(θ) − E λ, z = p_z λ, θ = ωλ, Φ = arctan(q tan θ) continued.

struct OGeo { float e; float pz; float kappa; vec2 cchi; float omega; float rmax; float q; bool ok; };
const OGeo NO_OGEO = OGeo(0.0, 0.0, 0.0, vec2(0.0), 0.0, 0.0, 0.0, false);

OGeo originGeodesic(vec4 k) {
    OGeo g = NO_OGEO;
    float e = k.x;
    float kp2 = dot(k.yz, k.yz);
    float kappa = e * e - kp2 - k.w * k.w;
    g.ok = finite(e) && finite(kp2) && finite(k.w) && e != 0.0 && kappa >= -1e-4 * e * e;
    kappa = max(kappa, 0.0);
    g.e = e;
    g.pz = k.w;
    g.kappa = kappa;
    g.omega = sqrt(e * e + kappa + k.w * k.w) / (2.0 * u_a);
    float kp = sqrt(kp2);
    g.cchi = kp > 0.0 ? k.yz / kp : vec2(1.0, 0.0);
    g.rmax = kp / g.omega;
    g.q = abs(e) / (SQRT2 * u_a * g.omega);
    return g;
}

float returnParameter(OGeo g) { return PI / g.omega; }

void ogeoAt(OGeo g, float lambda, out vec4 ev, out vec4 tan_) {
    ev = vec4(0.0); tan_ = vec4(0.0);
    float a = u_a, e = g.e, w = g.omega, q = g.q;
    float sg = sign(e);
    float th = w * lambda;
    float s = sinA(th), c = cosA(th);
    float den = c * c + q * s * s;
    float b = (q - 1.0) * s * c;
    float big = th + atan2s(b, den);
    float dbig = q / (c * c + q * q * s * s);
    float n = sqrt(den * den + b * b);
    float cb = (c * den - s * b) / n, sb = sg * (s * den + c * b) / n;
    float cp = g.cchi.x * cb - g.cchi.y * sb, sp = g.cchi.y * cb + g.cchi.x * sb;
    float r = g.rmax * s;
    ev = vec4(sg * 2.0 * SQRT2 * a * big - e * lambda, r * cp, r * sp, g.pz * lambda);
    float u = w * g.rmax * c, v = w * g.rmax * sg * dbig * s;
    tan_ = vec4(sg * 2.0 * SQRT2 * a * w * dbig - e, u * cp - v * sp, u * sp + v * cp, g.pz);
}

// Parallel transport along the closed form (docs/physics.md, "Parallel transport along closed
// forms"; spacetime::transport): W(λ) = F_λ* exp(−λA) W with A = ∇ξ at the origin and
// F_λ = T_{γ(λ)}⁻¹ ∘ R_β(λ).
vec4 nablaXi(OGeo g, vec4 w) {
    vec2 kxy = g.omega * g.rmax * g.cchi;
    float s = 1.0 / (SQRT2 * u_a);
    float e = g.e * s;
    kxy *= s;
    return vec4(w.y * kxy.y - w.z * kxy.x, w.x * kxy.y - w.z * e, -w.x * kxy.x + w.y * e, 0.0);
}

float flowRotation(OGeo g, float lambda) {
    float alpha = sign(g.e) * 2.0 * g.omega * lambda;
    float h = halfTanh(g.rmax / (2.0 * u_a));
    float h2 = h * h;
    return alpha - 2.0 * atan2s(-h2 * sinA(alpha), 1.0 - h2 * cosA(alpha));
}

vec4 transportFromOrigin(OGeo g, float lambda, vec4 at, vec4 w) {
    vec4 aw = nablaXi(g, w);
    vec4 aaw = nablaXi(g, aw);
    float om = sqrt(g.kappa + g.pz * g.pz) / (SQRT2 * u_a);
    float x = om * lambda;
    float c1 = 0.0, c2 = 0.0;
    if (abs(x) < 1e-2) {
        c1 = lambda * (1.0 - x * x / 6.0);
        c2 = 0.5 * lambda * lambda * (1.0 - x * x / 12.0);
    } else {
        c1 = sinA(x) / om;
        c2 = (1.0 - cosA(x)) / (om * om);
    }
    vec4 v = w - c1 * aw + c2 * aaw;
    float beta = flowRotation(g, lambda);
    float cb = cosA(beta), sb = sinA(beta);
    v = vec4(v.x, cb * v.y - sb * v.z, sb * v.y + cb * v.z, v.w);
    return pushIso(inverseIso(toOrigin(at)), vec4(0.0), v);
}

// ---------------------------------------------------------------------------------------
// The ray: a closed form carried back from the origin by the observer's isometry (Gödel;
// "Closed forms", "Isometries"), or a straight line (Minkowski), with loop copies shifted
// in t and z (render::segment, docs/physics.md "The intersection search").

struct Ray {
    Iso back;     // from the origin frame to the scene's coordinates (times relative)
    OGeo geo;     // Gödel: the closed form in the origin frame
    vec4 x0;      // Minkowski: start event
    vec4 k0;      // Minkowski: tangent; Gödel: the tangent at the start
    float lret;   // Gödel: return parameter
    vec2 shift;   // Gödel: (Δt, Δz) per loop
};
const Ray NO_RAY = Ray(NO_ISO, NO_OGEO, vec4(0.0), vec4(0.0), 0.0, vec2(0.0));

// The ray's event and tangent at parameter l of loop j.
void rayAt(Ray r, int j, float l, out vec4 ev, out vec4 k) {
    ev = vec4(0.0); k = vec4(0.0);
    if (!godel()) {
        ev = r.x0 + l * r.k0;
        k = r.k0;
        return;
    }
    vec4 e0 = vec4(0.0), k0 = vec4(0.0);
    ogeoAt(r.geo, l, e0, k0);
    applyPush(r.back, e0, k0, ev, k);
    ev.x += float(j) * r.shift.x;
    ev.w += float(j) * r.shift.y;
}

// The ray through `at` with tangent `k` (Gödel: the exact geodesic; spacetime::ExactGeodesic).
Ray makeRay(vec4 at, vec4 k) {
    Ray r = NO_RAY;
    r.x0 = at;
    r.k0 = k;
    r.back = Iso(0.0, vec2(0.0), 0.0, 0.0);
    r.geo.ok = true;
    r.lret = INF;
    r.shift = vec2(0.0);
    if (godel()) {
        Iso to = toOrigin(at);
        r.geo = originGeodesic(pushIso(to, at, k));
        r.back = inverseIso(to);
        r.lret = returnParameter(r.geo);
        float sg = sign(r.geo.e);
        r.shift = vec2(sg * 2.0 * SQRT2 * u_a * PI - r.geo.e * r.lret, r.geo.pz * r.lret);
    }
    return r;
}


// ---------------------------------------------------------------------------------------
// Objects (docs/physics.md, "Local objects"; render::target, render::worldline), read from
// the table once per sample: what is the same for every sample (frames, Γ, a free fall's
// closed form and isometry) the host computed in f64 (crates/gpu/src/input.rs). GLSL inlines
// every call, so the heavy functions below each have one call site (two for `localize`), and
// the kernel stays small enough to compile in seconds.

struct Object {
    int kind;
    float radius;
    float extent;   // planes: |x|, |y| ≤ extent (≤ 0: unbounded)
    vec4 pos;       // at rest (0, x, y, z); coordinate sphere: centre; plane: height in .w
    mat4 dual;      // at rest: dual rows of the static frame
    mat3 chrT;      // at rest: Γ^μ_αβ at the position for μ = t, x, y and α, β = t, x, y
    mat3 chrX;      // (those with a z index vanish)
    mat3 chrY;
    Iso back;       // free fall: from the start's origin frame back
    OGeo geo;       // free fall: the closed form in that frame
    vec4 start;     // free fall: start event; Minkowski: and its velocity below
    vec4 u0;
    float speed;    // γ(1 + v) relative to the static observers
    float rate;     // free fall: coordinate time per proper time over whole loops
    float gamma;    // free fall: γ = −u_t, conserved
};
Object objs[N_OBJECTS];

// The kinds of object, each false at compile time where the scene has none of it (the host's
// HAS_* defines): GPUs and llvmpipe run both sides of a branch their samples take apart, so
// code for kinds a scene lacks would cost every sample.
bool restKind(int kind) { return HAS_REST != 0 && kind == KIND_REST; }
bool freeKind(int kind) { return HAS_FREE != 0 && kind == KIND_FREE; }
bool isRest(int i) { return restKind(objs[i].kind); }
bool isFree(int i) { return freeKind(objs[i].kind); }
bool isCoordSphere(int i) { return HAS_COORD_SPHERE != 0 && objs[i].kind == KIND_COORD_SPHERE; }
bool isPlane(int i) { return HAS_PLANE != 0 && objs[i].kind == KIND_PLANE; }

// Per object, for the ray being searched: whether it is searched at all (setSearched), a
// ball's centre (disc coordinate, z) and a plane's height in the ray's origin frame, and a
// falling ball's last λ within reach in the current loop, from the loop's start (fallingLast).
bool searched[N_OBJECTS];
vec2 oCw[N_OBJECTS];
float oCz[N_OBJECTS];
float fbLast[N_OBJECTS];

// The stores into the per-object arrays, each at the constant indices of a loop whose body
// is the store alone, which compilers unroll: never at the runtime index i (drivers have
// stored at the wrong index; docs/physics.md, "The GPU kernel").
void storeObject(int i, Object o) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) objs[j] = o;
    }
}
void storeSearched(int i, bool s, vec2 cw, float cz) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) {
            searched[j] = s;
            oCw[j] = cw;
            oCz[j] = cz;
        }
    }
}
void storeFallingLast(int i, float last) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) fbLast[j] = last;
    }
}

// Four texels from `at` on, as the columns of a matrix.
mat4 tableMat(int at) { return mat4(tableTexel(at), tableTexel(at + 1), tableTexel(at + 2), tableTexel(at + 3)); }

// The symmetric matrix of the two texels from `at` on: (m00, m01, m02, m11), (m12, m22, −, −).
mat3 tableSymmetric(int at) {
    vec4 p = tableTexel(at), q = tableTexel(at + 1);
    return mat3(p.x, p.y, p.z, p.y, p.w, q.x, p.z, q.x, q.y);
}

// Γ^μ_αβ d^α d^β at the position of the ball at rest i.
vec4 restChristoffel(int i, vec4 d) {
    vec3 v = d.xyz;
    return vec4(dot(v, objs[i].chrT * v), dot(v, objs[i].chrX * v), dot(v, objs[i].chrY * v), 0.0);
}

// Object i, read from the table (zero where its kind has no use for a field; the layout is
// input.rs's).
Object loadObject(int i) {
    int at = OBJECT_TEXELS * i;
    vec4 t0 = tableTexel(at);
    vec4 t1 = tableTexel(at + 1);
    Object o = Object(toInt(t0.x, -1, KIND_PLANE), t0.y, t0.z, vec4(0.0, t1.xyz), mat4(0.0),
                      mat3(0.0), mat3(0.0), mat3(0.0), NO_ISO, NO_OGEO, vec4(0.0), vec4(0.0),
                      1.0, 1.0, 1.0);
    if (restKind(o.kind)) {
        o.dual = tableMat(at + 7);
        o.chrT = tableSymmetric(at + 11);
        o.chrX = tableSymmetric(at + 13);
        o.chrY = tableSymmetric(at + 15);
    } else if (freeKind(o.kind)) {
        vec4 t2 = tableTexel(at + 2);
        // Start time relative to the observer's: (hi − hi) + (lo − lo) keeps the digits.
        o.start = vec4((t2.x - u_obs_t.x) + (t2.y - u_obs_t.y), t1.xyz);
        o.u0 = tableTexel(at + 3);
        vec4 s = tableTexel(at + 7);
        o.gamma = s.x;
        o.speed = s.y;
        o.rate = s.z;
        vec4 g0 = tableTexel(at + 8), g1 = tableTexel(at + 9), b = tableTexel(at + 10);
        o.geo = OGeo(g0.x, g0.y, g0.z, g1.xy, g0.w, g1.z, g1.w, true);
        // The table's isometry is that of a start at time zero: shifted by the start's time.
        o.back = Iso(t2.z - o.start.x, b.xy, b.z, b.w);
    }
    return o;
}

// Every object into objs, and the per-ray arrays cleared.
void loadObjects() {
    for (int i = 0; i < N_OBJECTS; i++) {
        searched[i] = false;
        oCw[i] = vec2(0.0);
        oCz[i] = 0.0;
        fbLast[i] = NO_TAU;
    }
    for (int i = 0; i < N_OBJECTS; i++) storeObject(i, loadObject(i));
}

struct WPoint { float tau; vec4 ev; vec4 u; };
const WPoint NO_WPOINT = WPoint(0.0, vec4(0.0), vec4(0.0));

// The worldline point at proper time τ: event and four-velocity (free fall: the closed form
// carried back from the start's origin frame; Minkowski: a straight line).
WPoint worldAt(int i, float tau) {
    WPoint p = NO_WPOINT;
    p.tau = tau;
    if (!isFree(i)) {
        p.ev = vec4(tau, objs[i].pos.yzw);
        p.u = vec4(1.0, 0.0, 0.0, 0.0);
    } else if (!godel()) {
        p.ev = objs[i].start + tau * objs[i].u0;
        p.u = objs[i].u0;
    } else {
        vec4 e0 = vec4(0.0), k0 = vec4(0.0);
        ogeoAt(objs[i].geo, tau, e0, k0);
        applyPush(objs[i].back, e0, k0, p.ev, p.u);
    }
    return p;
}

// The body frame at the worldline point p (free fall: the start frame parallel-transported
// in closed form; at rest: the static frame). Read from the table here, at a hit, not for
// every object when a sample starts.
mat4 bodyFrame(int i, WPoint p) {
    mat4 f = tableMat(OBJECT_TEXELS * i + 3);
    if (!isFree(i) || !godel()) return f;
    vec4 e0 = vec4(0.0), k0 = vec4(0.0);
    ogeoAt(objs[i].geo, p.tau, e0, k0);
    vec4 w1 = transportFromOrigin(objs[i].geo, p.tau, e0, f[1]);
    vec4 w2 = transportFromOrigin(objs[i].geo, p.tau, e0, f[2]);
    vec4 w3 = transportFromOrigin(objs[i].geo, p.tau, e0, f[3]);
    return mat4(p.u, pushIso(objs[i].back, e0, w1), pushIso(objs[i].back, e0, w2), pushIso(objs[i].back, e0, w3));
}

// A first guess of the proper time at which the worldline has coordinate time t.
// A free fall's: the proper time of equal coordinate time (the CPU interpolates it from its
// integration steps), by Newton steps on t(τ) from the mean rate's guess (dt/dτ = u^t).
float tauGuess(int i, float t) {
    if (!isFree(i)) return t;
    float tau = (t - objs[i].start.x) / objs[i].rate;
    for (int it = 0; it < TIME_STEPS; it++) {
        WPoint p = worldAt(i, tau);
        tau += (t - p.ev.x) / max(p.u.x, 0.05);
    }
    return tau;
}

// ---------------------------------------------------------------------------------------
// Localizing a ray point in an object's rest frame (render::worldline::Worldline::localize).

// The second-order normal-coordinate displacement of x from the worldline point p, taken
// after the isometry that sends p to the origin, and p's four-velocity carried there
// (render::worldline::origin_coords). Minkowski: the displacement itself.
void originDisplacement(WPoint p, vec4 x, out vec4 xi, out vec4 u) {
    xi = vec4(0.0); u = vec4(0.0);
    if (!godel()) { xi = x - p.ev; u = p.u; return; }
    Iso to = toOrigin(p.ev);
    vec4 o = vec4(0.0);
    applyPush(to, p.ev, p.u, o, u);
    xi = normalDisplacement(vec4(0.0), applyIso(to, x));
}

// xi: spatial rest-frame components (at rest); len: their length; disp: the second-order
// normal-coordinate displacement (free fall: taken at the origin, whose components need the
// body frame carried there).
struct Local { WPoint at; vec3 xi; float len; vec4 disp; bool exact; bool ok; };
const Local NO_LOCAL = Local(NO_WPOINT, vec3(0.0), 0.0, vec4(0.0), false, false);

Local localize(int i, vec4 x, float seed, float far) {
    Local lp = NO_LOCAL;
    lp.ok = true;
    lp.disp = vec4(0.0);
    if (isRest(i)) {
        // u = ∂t: g(u, Δ) = 0 fixes Δt = g_ti Δxⁱ at first order; then two steps with the
        // second-order ξ⁰.
        vec3 dx = x.yzw - objs[i].pos.yzw;
        float t = x.x + dot(objs[i].dual[0].yzw, dx);
        vec4 xi = components(objs[i].dual, x - vec4(t, objs[i].pos.yzw));
        lp.exact = length(xi.yzw) <= far;
        if (lp.exact) {
            for (int it = 0; it < 2; it++) {   // a fixed count, without jumps: unrolled
                vec4 d = x - vec4(t, objs[i].pos.yzw);
                xi = components(objs[i].dual, d + 0.5 * restChristoffel(i, d));
                t += xi.x;
            }
        }
        lp.at = WPoint(t, vec4(t, objs[i].pos.yzw), vec4(1.0, 0.0, 0.0, 0.0));
        lp.xi = xi.yzw;
        lp.len = length(xi.yzw);
        return lp;
    }
    // Free fall: the first-order simultaneity ξ⁰ = −g(u, Δ) = 0 by the secant method from
    // the seed, then one Newton step on the second-order ξ⁰ taken at the origin (as on the
    // CPU). One worldline evaluation per pass of the loop.
    // The seed's point first (a far point needs no more, and no loop pass).
    WPoint p = worldAt(i, seed);
    mat4 g = metricAt(p.ev);
    float f0 = -dotg(g, p.u, x - p.ev);
    float len0 = sqrt(max(dotg(g, x - p.ev, x - p.ev) + f0 * f0, 0.0));
    if (len0 > far) {
        lp.at = p;
        lp.len = len0;
        lp.exact = false;
        return lp;
    }
    float ta = seed, fa = f0, tau = seed + f0;
    int stage = 1;   // 1 secant, 2 after the Newton step
    mat4 g0 = metricAt(vec4(0.0));
    vec4 xi = vec4(0.0), uo = vec4(0.0);
    for (int it = 1; it < SIMULTANEITY_STEPS + 3; it++) {
        p = worldAt(i, tau);
        if (stage == 2) break;
        g = metricAt(p.ev);
        float f = -dotg(g, p.u, x - p.ev);
        bool done = abs(f) < 1e-7 * u_a || tau == ta || it > SIMULTANEITY_STEPS;
        if (done) {
            originDisplacement(p, x, xi, uo);
            tau += -dotg(g0, uo, xi);
            stage = 2;
            continue;
        }
        float slope = (f - fa) / (tau - ta);
        float step_ = (slope < 0.0 && finite(slope)) ? -f / slope : f;
        ta = tau; fa = f;
        tau = tau + step_;
    }
    originDisplacement(p, x, xi, uo);
    float x0 = -dotg(g0, uo, xi);
    lp.at = p;
    lp.disp = xi;
    lp.len = sqrt(max(dotg(g0, xi, xi) + x0 * x0, 0.0));
    lp.exact = true;
    lp.ok = finite(lp.len) && finite(tau);
    return lp;
}

// The rest-frame spatial components of a localized ray point, given the body frame there.
vec3 restComponents(int i, Local lp, mat4 frame) {
    if (isRest(i)) return lp.xi;
    if (godel()) {
        // The frame carried to the origin, where disp was taken.
        Iso to = toOrigin(lp.at.ev);
        frame = mat4(pushIso(to, lp.at.ev, frame[0]), pushIso(to, lp.at.ev, frame[1]),
                     pushIso(to, lp.at.ev, frame[2]), pushIso(to, lp.at.ev, frame[3]));
    }
    return components(dualFrame(metricAt(vec4(0.0)), frame), lp.disp).yzw;
}

// ---------------------------------------------------------------------------------------
// Probes: signed distance f (≤ 0 inside), rate bound |df/dλ| ≤ rate, matched proper time
// (render::target::Target::probe, docs/physics.md "The intersection search").

struct Probe { float f; float rate; float tau; };
const Probe NO_PROBE = Probe(0.0, 0.0, 0.0);
// Nothing known of the object here (the CPU's infinite distance).
const Probe FAR = Probe(INF, 0.0, NO_TAU);

Probe probeObject(int i, vec4 x, vec4 k, float pt, float tauSeed) {
    probes_left--;
    if (isCoordSphere(i)) {
        return Probe(length(x.yzw - objs[i].pos.yzw) - objs[i].radius, RATE_MARGIN * length(k.yzw), NO_TAU);
    }
    if (isPlane(i)) return Probe(x.w - objs[i].pos.w, RATE_MARGIN * abs(k.w), NO_TAU);
    float scale = godel() ? u_a : 1.0;
    float far = FAR_DISTANCE * scale + FAR_RADII * objs[i].radius;
    float floor_ = objs[i].radius + 0.5 * FAR_DISTANCE * scale;
    float rate = GLOBAL_RATE_MARGIN * abs(pt) * objs[i].speed;
    float seed = tauSeed > NO_TAU ? tauSeed : tauGuess(i, x.x);
    Local lp = localize(i, x, seed, far);
    if (!lp.ok) return FAR;
    float slack = isRest(i) ? 1.1 + (FAR_SLACK - 1.1) * min((lp.len - far) / far, 1.0) : FAR_SLACK;
    Probe p = Probe((lp.exact ? lp.len : max(lp.len / slack, floor_)) - objs[i].radius, rate, lp.exact ? lp.at.tau : NO_TAU);
    // A stale seed may call a point inside a falling ball far: then the point of equal
    // coordinate time is tried too and the nearer kept.
    if (!lp.exact && tauSeed > NO_TAU && isFree(i)) {
        Local lq = localize(i, x, tauGuess(i, x.x), far);
        if (lq.ok) {
            float dq = lq.exact ? lq.len : max(lq.len / FAR_SLACK, floor_);
            if (dq - objs[i].radius < p.f) p = Probe(dq - objs[i].radius, rate, lq.exact ? lq.at.tau : NO_TAU);
        }
    }
    return p;
}

bool crossed(float fa, float fb) { return (fa > 0.0) != (fb > 0.0); }
bool excluded(float fa, float fb, float rate, float h) {
    return !crossed(fa, fb) && (abs(fa) + abs(fb) > rate * h || rate == 0.0);
}
bool accepts(int i, vec4 x) {
    return !isPlane(i) || objs[i].extent <= 0.0 || (abs(x.y) <= objs[i].extent && abs(x.z) <= objs[i].extent);
}

// A coordinate box around object i (render::target::Target::bounds); false when there is
// none (free fall: every loop is searched).
bool objectBox(int i, out vec3 lo, out vec3 hi) {
    lo = vec3(0.0); hi = vec3(0.0);
    vec3 c = objs[i].pos.yzw;
    float grow = 0.0;
    if (isRest(i)) {
        float r = length(c.xy) + 2.0 * objs[i].radius;
        float s2 = godel() ? pow(r / (2.0 * u_a), 2.0) : 0.0;
        grow = 2.0 * objs[i].radius * sqrt(1.0 + s2) + 0.05;
    } else if (isCoordSphere(i)) {
        grow = objs[i].radius * (1.0 + 1e-6);
    } else if (isPlane(i)) {
        float e = objs[i].extent > 0.0 ? objs[i].extent : INF;
        lo = vec3(-e, -e, c.z);
        hi = vec3(e, e, c.z);
        return true;
    } else {
        return false;
    }
    lo = c - grow;
    hi = c + grow;
    return true;
}

// ---------------------------------------------------------------------------------------
// Whole-ray rejection of balls at rest and planes (render::reject, docs/physics.md
// "Whole-ray rejection"): it only drops searches that could not find a crossing.

// Whether the closed-form ray g from the origin, over λ ∈ [from, until], stays farther than
// the reach from the static ball whose centre is (wc, zc) in the origin frame.
bool ballMisses(OGeo g, vec2 wc, float zc, float reach, float from, float until) {
    float a = u_a;
    float lo = 0.0, hi = 0.0;
    if (g.pz == 0.0) {
        if (abs(zc) > reach) return true;
        lo = from; hi = until;
    } else {
        float l1 = (zc - reach) / g.pz, l2 = (zc + reach) / g.pz;
        lo = max(min(l1, l2), from);
        hi = min(max(l1, l2), until);
    }
    if (hi < lo) return true;
    float sg = sign(g.e);
    vec2 dir = vec2(-sg * g.cchi.y, sg * g.cchi.x);
    float big = asinh_(g.rmax / (2.0 * a));
    float rho = a * big;
    vec2 h = dir * halfTanh(g.rmax / (2.0 * a));
    vec2 mc = cdiv(wc - h, vec2(1.0, 0.0) - cmul(conj2(h), wc));
    float dhc = 2.0 * a * atanh_(min(length(mc), 0.9999999));
    if (abs(dhc - rho) > reach) return true;
    float lret = returnParameter(g);
    if (!finite(hi - lo) || !(hi - lo < lret)) return false;
    float alpha0 = carg(-h);
    float d1 = alpha0 + sg * 2.0 * PI * lo / lret - carg(mc);
    float d2 = alpha0 + sg * 2.0 * PI * hi / lret - carg(mc);
    float dmin = min(d1, d2), dmax = max(d1, d2);
    if (ceil(dmin / (2.0 * PI)) * 2.0 * PI <= dmax) return false;
    float c1 = cosA(d1 - 2.0 * PI * floor(d1 / (2.0 * PI) + 0.5));
    float c2 = cosA(d2 - 2.0 * PI * floor(d2 / (2.0 * PI) + 0.5));
    float cosd = max(c1, c2);
    float x = dhc / a, y = rho / a;
    float coshd = cosh(x) * cosh(y) - sinh(x) * sinh(y) * cosd;
    return a * acosh_(max(coshd, 1.0)) > reach;
}

bool planeMisses(OGeo g, float z, float from, float until) {
    float f0 = g.pz * from - z;
    float f1 = g.pz * until - z, span = abs(g.pz * until);
    if (!(until < INF)) {
        f1 = g.pz == 0.0 ? f0 : (g.pz > 0.0 ? INF : -INF);
        span = 0.0;
    }
    float clear = 1e-6 * (1.0 + abs(z) + span);
    return abs(f0) > clear && abs(f1) > clear && (f0 > 0.0) == (f1 > 0.0);
}

// The reach of a ball at rest (render::reject), widened by the rounding of f32 coordinates
// in the origin frame.
float reachOf(int i) { return REACH_PER_RADIUS * objs[i].radius + REACH_PER_A * u_a + 1e-4 * u_a; }

// Whether the searched ray g stays clear of object i (a ball at rest or a plane, Gödel's
// universe) over λ ∈ [from, until]; false when unsure or for other objects.
// cw, cz: the ball's centre or the plane's height in the ray's origin frame (oCw, oCz).
bool missesAt(int i, OGeo g, vec2 cw, float cz, float from, float until) {
    if (!godel()) return false;
    if (isRest(i)) return ballMisses(g, cw, cz, reachOf(i), from, until);
    if (isPlane(i)) return planeMisses(g, cz, from, until);
    return false;
}
bool objectMisses(int i, OGeo g, float from, float until) { return missesAt(i, g, oCw[i], oCz[i], from, until); }

// Which objects a ray from the place of `from` (whose origin-frame closed form is g),
// searched over λ ∈ [0, until], may meet: sets searched (object `skip`: only if it may also
// over [0, skipUntil]), oCw and oCz; whether any.
bool setSearched(vec4 from, OGeo g, float until, int skip, float skipUntil) {
    bool any = false;
    for (int i = 0; i < N_OBJECTS; i++) {
        vec2 cw = vec2(0.0);
        float cz = 0.0;
        if (isRest(i)) {
            vec4 c = applyIso(toOrigin(vec4(0.0, from.yzw)), objs[i].pos);
            cw = disc(c.yz);
            cz = c.w;
        } else if (isPlane(i)) {
            cz = objs[i].pos.w - from.w;
        }
        bool s = objs[i].kind >= 0 && !missesAt(i, g, cw, cz, 0.0, until)
            && (i != skip || !missesAt(i, g, cw, cz, 0.0, skipUntil));
        storeSearched(i, s, cw, cz);
        any = any || s;
    }
    return any;
}

// ---------------------------------------------------------------------------------------
// Loop by loop, balls in free fall (render::falling, render::circle; docs/physics.md "Balls
// in free fall"). In the pixel ray's origin frame the ray's loop j runs along a circle of the
// disc at times between (j + 1)Δt and jΔt; a ball point lies within static distance reach of
// its simultaneous centre, and within the time slack S of it. The centre's worldline is cut
// into cells of proper time (here per loop, at most FALL_CELLS, over the proper times whose
// time may fall in the loop's window; the CPU cuts the whole worldline once per render):
// each cell lies within m of its middle point. The last λ of the loop within M = reach + m of
// a cell whose time lies in the window (its z window and the arc of the ray's circle near the
// cell, by the hyperbolic law of cosines) is the last λ where the loop must search the ball.

// The largest λ in [lo, hi] at which the closed-form ray g (from the origin) may lie within
// hyperbolic distance m of the disc point w (cosh(m/a) given); NO_TAU when none; hi when
// unsure (render::circle::RayCircle::last_within).
float lastWithin(OGeo g, vec2 w, float coshM, float lo, float hi) {
    if (!finite(lo) || !finite(hi) || !(lo <= hi)) return NO_TAU;
    float a = u_a;
    float sg = sign(g.e);
    float big = asinh_(g.rmax / (2.0 * a));
    vec2 h = vec2(-sg * g.cchi.y, sg * g.cchi.x) * halfTanh(g.rmax / (2.0 * a));
    float nh = 1.0 - dot(h, h), nw = 1.0 - dot(w, w);
    float ch = 1.0 + 2.0 * dot(w - h, w - h) / (nh * nw);
    float sh = sqrt(max(ch * ch - 1.0, 0.0));
    float num = ch * cosh(big) - coshM;
    float den = sh * sinh(big);
    if (!finite(num) || !finite(den)) return hi;
    if (num <= -den) return hi;     // within m all round the circle
    if (num > den) return NO_TAU;   // beyond m all round
    // Single precision: the arc widened by 1e-4 rad (the CPU's 1e-9).
    float halfArc = acosA(clamp(num / den, -1.0, 1.0)) + 1e-4;
    float beta = carg(cdiv(w - h, vec2(1.0, 0.0) - cmul(conj2(h), w)));
    float lret = returnParameter(g);
    float psiHi = sg * carg(-h) - sg * beta + 2.0 * PI * hi / lret;
    float r = psiHi - 2.0 * PI * floor(psiHi / (2.0 * PI) + 0.5);
    float back = abs(r) <= halfArc ? 0.0 : (r > halfArc ? r - halfArc : r + 2.0 * PI - halfArc);
    float l = hi - back * lret / (2.0 * PI);
    return l >= lo ? l : NO_TAU;
}

// The proper time of the falling ball i at which its own origin frame's time is t (its
// closed form's time rises at least at (1 + p_z²)/γ per proper time), and how far off it
// may be.
vec2 ballTimeToTau(int i, float t) {
    OGeo b = objs[i].geo;
    float low = (1.0 + b.pz * b.pz) / b.e;
    float tau = t / objs[i].rate;
    float off = 0.0;
    for (int it = 0; it < TIME_STEPS + 1; it++) {
        vec4 e = vec4(0.0), k = vec4(0.0);
        ogeoAt(b, tau, e, k);
        off = t - e.x;
        tau += off / max(k.x, low);
    }
    return vec2(tau, abs(off) / low);
}

// The falling ball i's last λ within reach in loop j of the pixel ray `ray`, from the loop's
// start (NO_TAU: the loop needs no search of the ball), or INF where the test does not apply
// (Minkowski).
float fallingLast(int i, int j, Ray ray) {
    if (!godel()) return INF;
    float a = u_a;
    float gam = objs[i].gamma;
    float sv = sqrt(max(gam * gam - 1.0, 0.0));
    float r = objs[i].radius;
    // Reach and time slack (render::falling), widened for single precision.
    float reach = 1.25 * gam * r + 1e-4 * a;
    float slack = 1.25 * gam * r * (sv / gam + SQRT2) + 1e-4 * a;
    float up = gam + SQRT2 * sv;
    Iso toO = inverseIso(ray.back);
    vec4 start = applyIso(toO, objs[i].start);
    // The loop's window of times, and the ball's own time there: the isometry from the
    // ball's origin frame to the ray's shifts times by at most A (docs/physics.md, "Isometries").
    float tLo = float(j + 1) * ray.shift.x - slack, tHi = float(j) * ray.shift.x + slack;
    float wmax = objs[i].geo.rmax / sqrt(objs[i].geo.rmax * objs[i].geo.rmax + 4.0 * a * a);
    float shiftA = 2.0 * SQRT2 * a * asinA(min(length(disc(start.yz)) * wmax, 1.0));
    vec2 t1 = ballTimeToTau(i, tLo - start.x - shiftA), t2 = ballTimeToTau(i, tHi - start.x + shiftA);
    float tau1 = t1.x - t1.y, tau2 = t2.x + t2.y;
    // z is linear along both: no cell can be near when the ball's z range over [τ1, τ2] is
    // farther than the reach (plus the cells' extent) from the loop's.
    float zb1 = start.w + objs[i].u0.w * tau1, zb2 = start.w + objs[i].u0.w * tau2;
    float zr1 = float(j) * ray.shift.y, zr2 = float(j + 1) * ray.shift.y;
    float zGap = max(max(min(zb1, zb2) - max(zr1, zr2), min(zr1, zr2) - max(zb1, zb2)), 0.0);
    if (zGap > reach + 0.5 * sv * max(max(r, 1e-3), (tau2 - tau1) / float(FALL_CELLS))) {
        return NO_TAU;
    }
    int cells = toInt(ceil((tau2 - tau1) / max(r, 1e-3)), 1, FALL_CELLS);
    float dtau = (tau2 - tau1) / float(cells);
    float near = reach + 0.5 * sv * dtau;
    float coshM = cosh(near / a);
    float sl = slack + 0.5 * up * dtau;
    float l0 = float(j) * ray.lret, l1 = l0 + ray.lret;
    float last = NO_TAU;
    for (int c = 0; c < FALL_CELLS; c++) {
        if (c >= cells || last >= l1) break;
        vec4 p = applyIso(toO, worldAt(i, tau1 + (float(c) + 0.5) * dtau).ev);
        if (p.x < tLo + slack - sl || p.x > tHi - slack + sl) continue;
        float lo = l0, hi = l1;
        if (ray.geo.pz == 0.0) {
            if (abs(p.w) > near) continue;
        } else {
            float za = (p.w - near) / ray.geo.pz, zb = (p.w + near) / ray.geo.pz;
            lo = max(min(za, zb), l0);
            hi = min(max(za, zb), l1);
        }
        float l = lastWithin(ray.geo, disc(p.yz), coshM, max(lo, last), hi);
        if (l > NO_TAU) last = l;
    }
    return last > NO_TAU ? last - l0 : NO_TAU;
}

// ---------------------------------------------------------------------------------------
// The intersection search (render::intersect, render::tracer; docs/physics.md "The
// intersection search") as one state machine with one probe call: a ray is searched loop by
// loop (later loops are the first one's copies) and segment by segment; per segment and
// object, conservative advancement from the last probe, else a depth-first bisection that
// drops spans excluded by the rate bound (at most SEARCH_DEPTH halvings and SEARCH_PROBES
// probes), and the Illinois refinement of a crossing. The bisection is stackless: spans are
// dyadic pieces of the searched stretch, so the span after a finished one follows from its
// depth and index (its start probe is the finished span's end probe; its end is probed
// again, which the CPU keeps on a stack).

const int M_LOOP = 0;      // at the start of loop mach.loop_
const int M_START = 1;     // the loop's start probes, object by object
const int M_SEGMENT = 2;   // at the start of segment mach.seg
const int M_SCAN = 3;      // the next object of the segment
const int M_BISECT = 4;    // the span [bis.a, bis.b] of object mach.obj, both end probes known
const int M_REFINE = 5;    // Illinois steps on a crossing
const int M_DONE = 6;

// What a requested probe is for.
const int Q_NONE = 0;
const int Q_START = 1;     // the loop's start probe of object mach.obj
const int Q_END = 2;       // the segment's end probe of object mach.obj
const int Q_SPAN = 3;      // the end probe of the span [bis.a, bis.b]
const int Q_REFINE = 4;    // a refinement step at req.lambda
const int Q_ROOT = 5;      // the crossing's own probe (its τ; the plane's extent)

struct Found { int status; int target; int loop_; float lambda; float tau; };
const Found NO_FOUND = Found(0, -1, 0, 0.0, 0.0);

// The search plan (startSearch): `loops` copies of a stretch of length `span` cut into `segs`
// segments (a Gödel pixel ray's loops), or, where `cont`, `loops` stretches one after the other
// of the ray's `total` segments (a straight ray, a shadow ray: cut so that each stretch's start
// is a checkpoint of the rounds, main); pixel rays stop at the time bound. Shadow rays: the lit
// object `skipObj` is not searched from segment `skipSeg` on (its last). The first loop's box.
struct Plan {
    Ray ray;
    int loops; int segs; int total; bool cont;
    float span; float pt; float tBound; bool pixel;
    int skipObj; int skipSeg;
    vec3 boxLo; vec3 boxHi;
};
Plan plan = Plan(NO_RAY, 0, 0, 0, false, 0.0, 0.0, 0.0, false, -1, 0, vec3(0.0), vec3(0.0));

// The machine's place: its mode, loop, segment [lo, hi] and object, the segment's earliest
// crossing so far, and the search's result.
struct Machine { int mode; int loop_; int seg; int obj; float lo; float hi; Found best; Found result; };
Machine mach = Machine(0, 0, 0, 0, 0.0, 0.0, NO_FOUND, NO_FOUND);
// The probes at the start and the end of the segment, per object, and the λ where each was
// taken. Two arrays, written only at constant indices (setEndProbe; the end probes become
// the next segment's start probes by a copy): drivers that store at a runtime index into
// one buffer of both went wrong (docs/physics.md, "The GPU kernel").
Probe startProbe[N_OBJECTS], endProbe[N_OBJECTS];
float startAt[N_OBJECTS], endAt[N_OBJECTS];
// Bisection of one object's stretch [start, start + len]: the span [a, b] at depth `depth` and
// index `index`, with its end probes pa, pb; the probes it took.
struct Bisection { float start; float len; float a; float b; int depth; int index; int probes; Probe pa; Probe pb; };
Bisection bis = Bisection(0.0, 0.0, 0.0, 0.0, 0, 0, 0, NO_PROBE, NO_PROBE);
// Refinement of a crossing: the bracket [lo, hi], f there, the Illinois side, the steps.
struct Refinement { float lo; float hi; float flo; float fhi; int side; int iter; };
Refinement ill = Refinement(0.0, 0.0, 0.0, 0.0, 0, 0);
// The probe requested by a step (for what, of which object, where), and its answer.
struct Request { int tag; int obj; int loop_; float lambda; float seed; Probe answer; vec4 x; };
Request req = Request(Q_NONE, 0, 0, 0.0, 0.0, NO_PROBE, vec4(0.0));

// Whether the current loop searches object i on a segment starting at λ0 (from the loop's
// start): a ball in free fall of a pixel ray up to its last λ within reach (fbLast).
bool loopSearches(int i, float lambda0) {
    return !(isFree(i) && plan.pixel) || lambda0 <= fbLast[i];
}

// Object i's probe at the segment's start, or at its end, taken at λ = at: stored at the
// loop's constant indices, never at the runtime index i.
void setStartProbe(int i, Probe p, float at) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) {
            startProbe[j] = p;
            startAt[j] = at;
        }
    }
}
void setEndProbe(int i, Probe p, float at) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) {
            endProbe[j] = p;
            endAt[j] = at;
        }
    }
}

void request(int tag, float lambda, float seed) {
    req.tag = tag;
    req.obj = mach.obj;
    req.loop_ = mach.loop_;
    req.lambda = lambda;
    req.seed = seed;
}

float loopOffset() { return float(mach.loop_) * plan.span; }

// The searched ray's event and tangent at parameter l of loop (or stretch) j.
void searchRayAt(int j, float l, out vec4 ev, out vec4 k) {
    ev = vec4(0.0); k = vec4(0.0);
    if (plan.cont) rayAt(plan.ray, 0, l + float(j) * plan.span, ev, k);
    else rayAt(plan.ray, j, l, ev, k);
}

void finish(int status) {
    mach.result = Found(status, -1, 0, 0.0, NO_TAU);
    mach.mode = M_DONE;
}

// The loop's box, for skipping loops that come near no object (render::segment::loop_bounds):
// segment ends, grown by a quarter of the longest chord.
void loopBox() {
    vec4 x = vec4(0.0), k = vec4(0.0), prev = vec4(0.0);
    float grow = 0.0;
    for (int s = 0; s <= plan.segs; s++) {
        rayAt(plan.ray, 0, plan.span * float(s) / float(plan.segs), x, k);
        if (s == 0) { plan.boxLo = x.yzw; plan.boxHi = x.yzw; prev = x; }
        plan.boxLo = min(plan.boxLo, x.yzw);
        plan.boxHi = max(plan.boxHi, x.yzw);
        grow = max(grow, 0.25 * length(x.yzw - prev.yzw));
        prev = x;
    }
    plan.boxLo -= grow;
    plan.boxHi += grow;
}

void startSearch(Ray r, int loops, int segs, float span, float pt, bool pixel, float tBound) {
    plan.ray = r;
    plan.loops = loops;
    plan.segs = segs;
    plan.span = span;
    plan.pt = pt;
    plan.pixel = pixel;
    plan.tBound = tBound;
    plan.cont = false;
    plan.total = loops * segs;
    mach.loop_ = 0;
    mach.mode = M_LOOP;
    plan.skipObj = -1;
    plan.skipSeg = MAX_SEGMENTS + 1;
    req.tag = Q_NONE;
    for (int i = 0; i < N_OBJECTS; i++) {
        startProbe[i] = NO_PROBE;
        endProbe[i] = NO_PROBE;
        startAt[i] = 0.0;
        endAt[i] = 0.0;
    }
    plan.boxLo = vec3(0.0);
    plan.boxHi = vec3(0.0);
    if (loops > 1) loopBox();
}

// A search of the ray r over λ ∈ [0, length] in `total` segments, as stretches of
// EXACT_SEGMENTS segments one after the other (searchRayAt).
void startLongSearch(Ray r, int total, float length, float pt, bool pixel, float tBound) {
    int loops = (total + EXACT_SEGMENTS - 1) / EXACT_SEGMENTS;
    startSearch(r, 1, EXACT_SEGMENTS, length * float(EXACT_SEGMENTS) / float(total), pt, pixel, tBound);
    plan.loops = loops;
    plan.cont = true;
    plan.total = total;
}

// The span after the finished span [bis.a, bis.b] of the current bisection: climb while it is a
// right half, then take the right sibling, whose start probe is bis.b's and whose end is probed.
void nextSpan() {
    // The trailing ones of the index are the levels to climb: 2^k = (i + 1) & −(i + 1).
    int up = toInt(log2(float((bis.index + 1) & -(bis.index + 1))) + 0.5, 0, SEARCH_DEPTH);
    bis.depth -= up;
    bis.index >>= up;
    if (bis.depth <= 0) {
        mach.mode = M_SCAN;   // no crossing of this object in the segment
        return;
    }
    if (bis.probes == SEARCH_PROBES) { finish(WORK_LIMIT); return; }
    bis.probes++;
    bis.index++;
    bis.pa = bis.pb;
    bis.a = bis.b;
    bis.b = bis.start + bis.len * float(bis.index + 1) / exp2(float(bis.depth));
    request(Q_SPAN, bis.b, bis.pa.tau);
}

// One step of the machine: takes the answer to its last request, then either requests a
// probe or moves on.
void machineStep() {
    int tag = req.tag;
    req.tag = Q_NONE;
    if (tag == Q_START) {
        setStartProbe(mach.obj, req.answer, loopOffset());
    } else if (tag == Q_END) {
        setEndProbe(mach.obj, req.answer, mach.hi + loopOffset());
        bis.pb = req.answer;
        float limit = mach.best.status == HIT ? mach.best.lambda : mach.hi;
        bis.start = mach.lo;
        bis.len = min(limit, mach.hi) - mach.lo;
        bis.a = bis.start;
        bis.b = bis.start + bis.len;
        bis.depth = 0;
        bis.index = 0;
        bis.probes = 0;
        mach.mode = M_BISECT;
    } else if (tag == Q_SPAN) {
        bis.pb = req.answer;
    } else if (tag == Q_ROOT) {
        if (accepts(mach.obj, req.x)) {
            if (mach.best.status != HIT || req.lambda < mach.best.lambda) {
                mach.best = Found(HIT, mach.obj, mach.loop_, req.lambda, req.answer.tau);
            }
            mach.mode = M_SCAN;
        } else {
            mach.mode = M_BISECT;   // a plane crossed beyond its extent: on with the next span
            nextSpan();
            if (mach.mode != M_SCAN) return;
        }
    } else if (tag == Q_REFINE) {
        float fm = req.answer.f, m = req.lambda;
        if (fm == 0.0 || ill.hi - ill.lo <= 4.0 * 1.1920929e-7 * max(max(abs(ill.hi), abs(ill.lo)), 1e-30)) {
            request(Q_ROOT, m, bis.pa.tau);
            return;
        }
        if ((fm > 0.0) == (ill.fhi > 0.0)) {
            ill.hi = m; ill.fhi = fm;
            if (ill.side == 1) ill.flo *= 0.5;
            ill.side = 1;
        } else {
            ill.lo = m; ill.flo = fm;
            if (ill.side == -1) ill.fhi *= 0.5;
            ill.side = -1;
        }
    }

    if (mach.mode == M_LOOP) {
        // Skip a loop whose box meets no searched object's box, one loop a pass (each loop's
        // start is a checkpoint of the sample's rounds: main); stop at the time bound.
        if (mach.loop_ >= plan.loops) {
            finish(plan.pixel && godel() ? WORK_LIMIT : ESCAPED);
            return;
        }
        float dz = float(mach.loop_) * plan.ray.shift.y;
        if (plan.pixel && float(mach.loop_) * plan.ray.shift.x < plan.tBound) { finish(ESCAPED); return; }
        vec3 lo = plan.boxLo + vec3(0.0, 0.0, dz), hi = plan.boxHi + vec3(0.0, 0.0, dz);
        bool near = mach.loop_ == 0 || plan.cont;   // the box is of copies of the first loop
        for (int i = 0; i < N_OBJECTS; i++) {
            vec3 olo = vec3(0.0), ohi = vec3(0.0);
            if (!searched[i]) continue;
            if (isFree(i) && plan.pixel) {
                // Balls in free fall: searched up to the loop's last λ within their reach.
                float last = fallingLast(i, mach.loop_, plan.ray);
                storeFallingLast(i, last);
                near = near || last > NO_TAU;
            } else {
                near = near || !objectBox(i, olo, ohi) || (all(lessThanEqual(olo, hi)) && all(lessThanEqual(lo, ohi)));
            }
        }
        if (!near) {
            mach.loop_++;
            return;
        }
        mach.obj = -1;
        mach.mode = M_START;
    }
    if (mach.mode == M_START) {
        mach.obj++;
        while (mach.obj < N_OBJECTS && !(searched[mach.obj] && loopSearches(mach.obj, 0.0))) mach.obj++;
        if (mach.obj < N_OBJECTS) { request(Q_START, 0.0, NO_TAU); return; }
        mach.seg = 0;
        mach.mode = M_SEGMENT;
    }
    if (mach.mode == M_SEGMENT) {
        if (mach.loop_ * plan.segs + mach.seg >= plan.total) { finish(ESCAPED); return; }   // a long search's end
        mach.lo = plan.span * float(mach.seg) / float(plan.segs);
        mach.hi = plan.span * float(mach.seg + 1) / float(plan.segs);
        mach.best = Found(ESCAPED, -1, 0, 0.0, NO_TAU);
        mach.obj = -1;
        mach.mode = M_SCAN;
    }
    if (mach.mode == M_BISECT) {
        bool finiteBoth = finite(bis.pa.f) && finite(bis.pb.f);
        if (bis.b > bis.a && (finite(bis.pa.f) || finite(bis.pb.f))) {
            if (finiteBoth && crossed(bis.pa.f, bis.pb.f)) {
                ill.lo = bis.a; ill.hi = bis.b; ill.flo = bis.pa.f; ill.fhi = bis.pb.f;
                ill.side = 0; ill.iter = 0;
                mach.mode = M_REFINE;
            } else {
                float rate = max(bis.pa.rate, bis.pb.rate);
                if (!((finiteBoth && excluded(bis.pa.f, bis.pb.f, rate, bis.b - bis.a)) || bis.depth >= SEARCH_DEPTH)) {
                    // Halve: the earlier half first.
                    if (bis.probes == SEARCH_PROBES) { finish(WORK_LIMIT); return; }
                    bis.probes++;
                    bis.b = 0.5 * (bis.a + bis.b);
                    bis.depth++;
                    bis.index *= 2;
                    request(Q_SPAN, bis.b, bis.pa.tau);
                    return;
                }
                nextSpan();
                if (mach.mode != M_SCAN) return;
            }
        } else {
            nextSpan();
            if (mach.mode != M_SCAN) return;
        }
    }
    if (mach.mode == M_REFINE) {
        if (ill.iter == REFINE_STEPS) {
            request(Q_ROOT, 0.5 * (ill.lo + ill.hi), bis.pa.tau);
            return;
        }
        float m = ill.fhi != ill.flo ? (ill.lo * ill.fhi - ill.hi * ill.flo) / (ill.fhi - ill.flo) : 0.5 * (ill.lo + ill.hi);
        if (!finite(m) || !(m > ill.lo && m < ill.hi)) m = 0.5 * (ill.lo + ill.hi);
        ill.iter++;
        request(Q_REFINE, m, bis.pa.tau);
        return;
    }
    if (mach.mode == M_SCAN) {
        float off = loopOffset();
        for (mach.obj++; mach.obj < N_OBJECTS; mach.obj++) {
            if (!searched[mach.obj]) continue;
            Probe p = startProbe[mach.obj];
            float at = startAt[mach.obj];
            if (!loopSearches(mach.obj, mach.lo)) {
                // Past the ball's last λ within reach in this loop (a later loop probes afresh).
                setEndProbe(mach.obj, p, at);
                continue;
            }
            if (mach.obj == plan.skipObj && mach.loop_ * plan.segs + mach.seg >= plan.skipSeg) {
                setEndProbe(mach.obj, p, at);
                continue;
            }
            // GPU only: a segment that provably stays clear of a ball at rest or a plane is
            // not searched ("Whole-ray rejection", applied per segment); its end probe is a
            // lower bound of the distance there (the ball's |ξ| ≥ D/1.05 > reach/1.05; the
            // plane's height, linear in λ), from which the next segment goes on.
            if (objectMisses(mach.obj, plan.ray.geo, mach.lo + off, mach.hi + off)) {
                float fEnd = isRest(mach.obj)
                    ? REACH_PER_RADIUS * objs[mach.obj].radius / 1.05 - objs[mach.obj].radius
                    : plan.ray.geo.pz * (mach.hi + off) - oCz[mach.obj];
                setEndProbe(mach.obj, Probe(fEnd, p.rate, NO_TAU), mach.hi + off);
                continue;
            }
            float clear = abs(p.f);
            if (isRest(mach.obj) && finite(clear) && p.rate > 0.0 && mach.hi + off < at + min(clear / p.rate, MAX_SKIP)) {
                setEndProbe(mach.obj, p, at);   // provably no crossing of this object within the segment
                continue;
            }
            // A probe taken before lo still bounds |f| at lo from below (same side).
            bis.pa = Probe(p.f - sign(p.f) * p.rate * (mach.lo + off - at), p.rate, p.tau);
            request(Q_END, mach.hi, bis.pa.tau);
            return;
        }
        // Every object scanned: the segment's earliest crossing ends the search.
        if (mach.best.status == HIT) {
            mach.result = mach.best;
            // A long search's hit as a parameter from the ray's start.
            if (plan.cont) mach.result = Found(HIT, mach.best.target, 0, mach.best.lambda + loopOffset(), mach.best.tau);
            mach.mode = M_DONE;
            return;
        }
        if (plan.pixel) {
            vec4 x = vec4(0.0), k = vec4(0.0);
            searchRayAt(mach.loop_, mach.hi, x, k);
            if (x.x < plan.tBound) { finish(ESCAPED); return; }
        }
        for (int i = 0; i < N_OBJECTS; i++) {   // the end probes start the next segment
            startProbe[i] = endProbe[i];
            startAt[i] = endAt[i];
        }
        mach.seg++;
        if (mach.seg < plan.segs) {
            mach.mode = M_SEGMENT;
        } else {
            mach.loop_++;
            mach.mode = M_LOOP;
        }
    }
}

// One pass of the machine: the probe it asked for, if any (the kernel's one call of
// probeObject), then its next step.
void searchPass() {
    if (req.tag != Q_NONE) {
        if (probes_left <= 0) { finish(WORK_LIMIT); return; }
        vec4 k = vec4(0.0);
        searchRayAt(req.loop_, req.lambda, req.x, k);
        req.answer = probeObject(req.obj, req.x, k, plan.pt, req.seed);
        // A probe answers a finite distance or FAR (INF, the CPU's infinity: nothing known);
        // anything else (a driver's NaN) ends the search, and the sample is marked failed:
        // no search goes on from a value it cannot order.
        if (!(finite(req.answer.f) || req.answer.f == INF) || !finite(req.answer.rate)) {
            finish(FAILED);
            return;
        }
    }
    machineStep();
}

// ---------------------------------------------------------------------------------------
// Surfaces (render::target::Target::surface): texture coordinates, the emitter's velocity at
// the hit point, the photon's direction in the emitter's rest frame, cos_i.

vec2 lonLat(vec3 p) {
    vec3 n = normalize(p);
    float u = (atan2s(n.y, n.x) + PI) / (2.0 * PI);
    float v = 0.5 + asinA(clamp(n.z, -1.0, 1.0)) / PI;
    return clamp(vec2(u, v), 0.0, 1.0);
}

// The photon's rest-frame components at the worldline point p, k carried from x to the
// centre to first order, and the emitter's four-velocity at x
// (render::target::rest_frame_photon).
void restFramePhoton(int i, WPoint p, mat4 frame, vec4 x, vec4 k, out vec4 uemit, out vec4 kl) {
    uemit = vec4(0.0); kl = vec4(0.0);
    mat4 dX = mat4(0.0), dY = mat4(0.0);
    metricDerivatives(p.ev, dX, dY);
    mat4 ginv = inverseMetricAt(p.ev);
    if (!godel()) { dX = mat4(0.0); dY = mat4(0.0); }
    vec4 kn = k - christoffelWith(dX, dY, ginv, p.ev - x, k);
    kl = components(dualFrame(metricAt(p.ev), frame), kn);
    uemit = isFree(i) ? frame[0] - christoffelWith(dX, dY, ginv, x - p.ev, frame[0]) : vec4(1.0, 0.0, 0.0, 0.0);
}

// The hit: what the record and the lights need of it: the object, the event and the photon's
// tangent there, the worldline point and body frame, the rest-frame position, the emitter's
// velocity, texture coordinates, the photon's direction in the emitter's frame, cos_i, the
// pixel's screen-up and screen-right transported to the hit, the measured polarization.
struct HitPoint {
    int target; vec4 x; vec4 k; WPoint at; mat4 frame; vec3 xi; vec4 uemit; vec2 uv; vec3 dir;
    float cosI; vec4 up; vec4 right; vec3 pol;
};
HitPoint hp = HitPoint(0, vec4(0.0), vec4(0.0), NO_WPOINT, mat4(0.0), vec3(0.0), vec4(0.0),
                       vec2(0.0), vec3(0.0), 0.0, vec4(0.0), vec4(0.0), vec3(0.0));

// The record's `pol` from the frame components of the transported screen-up f and
// screen-right r, for a photon travelling along dir in that frame (docs/physics.md,
// "Polarization", "What an observer measures" and "The data file's channels";
// spacetime::polarization::measured): each measured as its spatial part less its part along
// dir (a, b), pol the rotation part a + dir × b made orthogonal to dir and unit; false where
// that vanishes.
bool measurePolarization(vec4 f, vec4 r, vec3 dir) {
    vec3 a = f.yzw - dot(f.yzw, dir) * dir;
    vec3 b = r.yzw - dot(r.yzw, dir) * dir;
    vec3 v = a + cross(dir, b);
    v -= dot(v, dir) * dir;
    float len = length(v);
    hp.pol = v / max(len, 1e-30);
    return len > 1e-6 && finite(len);
}

// The screen vectors at x carried to the worldline point p to first order and measured in
// its body frame, as the photon in restFramePhoton (render::target::Target::surface).
bool restFramePolarization(WPoint p, mat4 frame, vec4 x) {
    mat4 dX = mat4(0.0), dY = mat4(0.0);
    metricDerivatives(p.ev, dX, dY);
    mat4 ginv = inverseMetricAt(p.ev);
    if (!godel()) { dX = mat4(0.0); dY = mat4(0.0); }
    mat4 dual = dualFrame(metricAt(p.ev), frame);
    vec4 up = components(dual, hp.up - christoffelWith(dX, dY, ginv, p.ev - x, hp.up));
    vec4 right = components(dual, hp.right - christoffelWith(dX, dY, ginv, p.ev - x, hp.right));
    return measurePolarization(up, right, hp.dir);
}

bool surface() {
    int i = hp.target;
    vec4 x = hp.x, k = hp.k;
    hp.uemit = vec4(1.0, 0.0, 0.0, 0.0);
    float seed = hp.at.tau > NO_TAU ? hp.at.tau : tauGuess(i, x.x);
    hp.at = WPoint(x.x, x, hp.uemit);
    hp.frame = mat4(1.0);
    if (isRest(i) || isFree(i)) {
        Local lp = localize(i, x, seed, INF);
        if (!lp.ok) return false;
        hp.at = lp.at;
        hp.frame = bodyFrame(i, hp.at);
        hp.xi = restComponents(i, lp, hp.frame);
        vec4 kl = vec4(0.0);
        restFramePhoton(i, hp.at, hp.frame, x, k, hp.uemit, kl);
        hp.uv = lonLat(hp.xi);
        hp.dir = normalize(-kl.yzw);
        hp.cosI = abs(dot(normalize(hp.xi), hp.dir));
        return restFramePolarization(hp.at, hp.frame, x);
    }
    // Coordinate objects: static emitters; the photon's direction in the static frame.
    mat4 f = staticFrame(x);
    vec4 p = metricAt(x) * (-k);
    hp.dir = normalize(vec3(dot(f[1], p), dot(f[2], p), dot(f[3], p)));
    if (isCoordSphere(i)) {
        vec3 n = normalize(x.yzw - objs[i].pos.yzw);
        hp.uv = lonLat(n);
        hp.cosI = abs(dot(n, normalize(-k.yzw)));
    } else {
        hp.uv = objs[i].extent > 0.0 ? 0.5 + x.yz / (2.0 * objs[i].extent) : fract(x.yz);
        hp.cosI = abs(normalize(-k.yzw).z);
    }
    // Their body axes are the static frame's.
    mat4 dual = dualFrame(metricAt(x), f);
    return measurePolarization(components(dual, hp.up), components(dual, hp.right), hp.dir);
}

// ---------------------------------------------------------------------------------------
// Direct light by shadow rays (render::lighting, spacetime::connect; docs/physics.md "Light
// rays between a source and an event", "Area distance and irradiance", "Occlusion").

// The shadow rays, light by light: every root of G on a grid of SHADOW_GRID cells per
// winding and branch (z_P = 0: the in-plane ray only), refined by Illinois steps; a ray is
// counted unless emitted more than max_past before the hit, arriving from behind, at a
// caustic, or occluded. The enumeration runs in passes of the kernel's one loop (`main`):
// a light's set-up, sixteen cells of the grid, one refinement step, or one ray's set-up.
struct ShadowRays {
    int light; int idx; int total; int cells;   // the light, the grid index, its cells
    int n; bool inbound; int side; int iter;    // the winding and branch; the refinement's side, steps
    float rho; float cmax; float zp; float power; float sum; float weight;
    float u0; float g0;                         // the grid point before a pass's first and G there
    // The root's bracket in ψ = arccos |c| and G there, and the root's ψ; the hit's distance
    // from the source's axis over 2a, and the least ψ that reaches it.
    float lo; float hi; float flo; float fhi; float psi; float s; float psiMin;
    vec4 p; vec4 source; Iso back;              // the hit in the source's frame; the source; its isometry
    bool failed;                                // an occlusion search ran out of work
};
ShadowRays shadow = ShadowRays(0, 0, 0, 0, 0, false, 0, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
                               0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
                               vec4(0.0), vec4(0.0), NO_ISO, false);

// Φ(θ) = arctan(q tan θ), continuous.
float bigPhi(float q, float th) {
    float s = sinA(th), c = cosA(th);
    return th + atan2s((q - 1.0) * s * c, c * c + q * s * s);
}

// θ of a winding and branch for the ray leaving at angle ψ to the z axis, for the target at
// ρ = 2a s (shadow.s) whose reach ψ_min (shadow.psiMin, where r_max = ρ) the light's set-up made: sin θ₀ =
// ρ/r_max = s√(1 + c²)/sin ψ, and cos θ₀ from σ² − s²(1 + c²) = (1 + s²) sin(ψ − ψ_min)
// sin(ψ + ψ_min), without the cancellation of r_max − ρ near the reach, where asin's slope
// would turn f32's rounding of ρ/r_max into an error of θ near √ε (spacetime::connect refines
// in ψ for the same reason in f64).
float shadowTheta(float psi, int n, bool inbound) {
    float c = cosA(psi);
    float d = (1.0 + shadow.s * shadow.s) * sinA(psi - shadow.psiMin) * sinA(psi + shadow.psiMin);
    float th0 = atan2s(shadow.s * sqrt(1.0 + c * c), sqrt(max(d, 0.0)));
    return float(n) * PI + (inbound ? PI - th0 : th0);
}

// G(ψ) = 2a c θ/√(1 + c²) − |z_P|, c = cos ψ: its roots are the rays of a winding and branch.
float shadowG(float psi, int n, bool inbound) {
    float c = cosA(psi);
    return 2.0 * u_a * c * shadowTheta(psi, n, inbound) / sqrt(1.0 + c * c) - abs(shadow.zp);
}

// The first cell of a group of four (pass indices offset..offset+3, cell numbers `cellNo`)
// whose value g changes sign from `prev` or is an exact zero (except at the join of the
// branches, which only the outbound branch counts); CELLS_PER_PASS if none. Only the pass's
// first `count` cells count.
int firstRoot(vec4 prev, vec4 g, vec4 cellNo, int offset, int count, bool inbound) {
    vec4 change = vec4(lessThan(prev, vec4(0.0))) * vec4(greaterThan(g, vec4(0.0)))
                + vec4(greaterThan(prev, vec4(0.0))) * vec4(lessThan(g, vec4(0.0)));
    vec4 join = inbound ? vec4(equal(cellNo, vec4(float(SHADOW_GRID)))) : vec4(0.0);
    vec4 zero = vec4(equal(g, vec4(0.0))) * (1.0 - join);
    vec4 inPass = vec4(lessThan(float(offset) + vec4(0.0, 1.0, 2.0, 3.0), vec4(float(count))));
    vec4 root = min(change + zero, 1.0) * inPass;
    if (root.x > 0.0) return offset;
    if (root.y > 0.0) return offset + 1;
    if (root.z > 0.0) return offset + 2;
    if (root.w > 0.0) return offset + 3;
    return CELLS_PER_PASS;
}

// G at four grid points u of cell numbers cellNo (the last one, u = c_max, reaches ρ exactly:
// θ₀ = π/2 there, as the CPU has it, not asin of a rounded ratio near 1).
vec4 shadowG4(float rho, float zp, vec4 u, vec4 cellNo, int n, bool inbound) {
    vec4 rmax = 2.0 * u_a * sqrt((1.0 - u * u) / (1.0 + u * u));
    vec4 th0 = mix(asinA4(min(rho / rmax, vec4(1.0))), vec4(0.5 * PI),
                   equal(cellNo, vec4(float(SHADOW_GRID))));
    vec4 th = float(n) * PI + (inbound ? PI - th0 : th0);
    return 2.0 * u_a * u * th / sqrt(1.0 + u * u) - abs(zp);
}

// D² = dA/dΩ of the ray with emission direction (ψ, χ) in the source's axis frame, ending at
// parameter λ (spacetime::source_area_distance_sq): the Jacobi field J_ψ = ∂γ/∂ψ of the
// closed form, here analytic (a central difference would lose its digits in f32), and
// J_χ = ∂φ (docs/physics.md, "Area distance and irradiance").
float areaDistanceSq(float psi, float chi, float lambda) {
    float a = u_a;
    float c = cosA(psi), s = sinA(psi);
    float w1 = 1.0 + c * c;
    float omega = sqrt(w1) / (2.0 * a);
    float rmax = s / omega;
    float q = sqrt(2.0 / w1);
    float th = omega * lambda;
    float st = sinA(th), ct = cosA(th);
    float den2 = ct * ct + q * q * st * st;
    float big = bigPhi(q, th);
    float domega = -c * s / (4.0 * a * a * omega);
    float dth = lambda * domega;
    float drmax = (c * omega - s * domega) / (omega * omega);
    float dq = -q / omega * domega;
    float dbig = (q * dth + st * ct * dq) / den2;
    float phi = chi + big;
    vec2 e = vec2(cosA(phi), sinA(phi));
    float r = rmax * st;
    float dr = drmax * st + rmax * ct * dth;
    vec4 x = vec4(2.0 * SQRT2 * a * big - lambda, r * e, c * lambda);
    vec4 jpsi = vec4(2.0 * SQRT2 * a * dbig, dr * e + r * dbig * vec2(-e.y, e.x), -s * lambda);
    vec4 jchi = vec4(0.0, -x.z, x.y, 0.0);
    mat4 g = metricAt(x);
    float pp = dotg(g, jpsi, jpsi), cc = dotg(g, jchi, jchi), pc = dotg(g, jpsi, jchi);
    return sqrt(max(pp * cc - pc * pc, 0.0)) / s;
}

// Incidence of light with future tangent kLight at the hit (render::target::Target::incidence):
// (cos, energy in the object's frame).
vec2 incidence(vec4 kLight) {
    int i = hp.target;
    vec4 x = hp.x, view = hp.k;
    if (isRest(i) || isFree(i)) {
        vec4 ue = vec4(0.0), kl = vec4(0.0), kv = vec4(0.0);
        restFramePhoton(i, hp.at, hp.frame, x, kLight, ue, kl);
        restFramePhoton(i, hp.at, hp.frame, x, view, ue, kv);
        vec3 n = normalize(hp.xi);
        float side = dot(n, -kv.yzw) >= 0.0 ? 1.0 : -1.0;
        return vec2(-side * dot(n, normalize(kl.yzw)), kl.x);
    }
    float energy = -(metricAt(x) * kLight).x;
    if (isCoordSphere(i)) {
        vec3 n = normalize(x.yzw - objs[i].pos.yzw);
        float side = dot(n, -view.yzw) >= 0.0 ? 1.0 : -1.0;
        return vec2(-side * dot(n, normalize(kLight.yzw)), energy);
    }
    float side = view.w < 0.0 ? 1.0 : -1.0;
    return vec2(-side * normalize(kLight.yzw).z, energy);
}


// Light li's channel (slot 5 + li / 4, component li % 4): stored at the loop's constant
// indices, never at the runtime index li.
void setLight(int li, float v) {
    for (int k = 0; k < N_LIGHTS; k++) {
        if (k == li) slots[5 + k / 4][k % 4] = v;
    }
}

// Ends the current light: its irradiance (negative: unknown) into its channel.
void endLight() {
    setLight(shadow.light, shadow.failed ? -1.0 : shadow.sum);
    shadow.light++;
    shadow.idx = -1;
}

// Light shadow.light's geometry for the hit: the source's isometry, the hit in the source's frame,
// the grid's size; false when no ray of it can count. A function of shadow.light and the hit alone
// (a round that resumes a light makes it again).
bool lightGeometry() {
    float a = u_a;
    vec4 lt = tableTexel(OBJECT_TEXELS * N_OBJECTS + LIGHT_TEXELS * shadow.light);
    shadow.source = vec4(0.0, lt.xyz);
    shadow.power = lt.w;
    Iso to = toOrigin(shadow.source);
    shadow.back = inverseIso(to);
    shadow.p = applyIso(to, hp.x);
    shadow.rho = length(shadow.p.yz);
    shadow.zp = shadow.p.w;
    shadow.s = shadow.rho / (2.0 * a);
    float s2 = shadow.s * shadow.s;
    if (s2 >= 1.0) return false;   // beyond the source's horizon: no ray
    shadow.cmax = sqrt((1.0 - s2) / (1.0 + s2));
    shadow.psiMin = atan2s(shadow.s * SQRT2, sqrt(1.0 - s2));   // sin²ψ_min = 2s²/(1 + s²)
    // Rays of winding n take at least n·T_ret (the shortest loop time) in the source's
    // frame, where emission events keep their scene time (the source is on its axis):
    // windings emitted before the window are not enumerated (the CPU drops their rays).
    float tret = 2.0 * PI * a * (SQRT2 - 1.0);
    int windings = toInt(floor((shadow.p.x - hp.x.x + u_max_past) / tret), -1, MAX_WINDINGS);
    if (windings < 0) return false;
    shadow.cells = shadow.zp == 0.0 ? 1 : SHADOW_GRID;
    shadow.total = (windings + 1) * 2 * shadow.cells;
    return true;
}

// Sets up light shadow.light for the hit; false when no ray of it can count.
bool startLight() {
    shadow.sum = 0.0;
    shadow.failed = false;
    if (!lightGeometry()) return false;
    shadow.idx = 0;
    return true;
}

// One pass over up to sixteen cells of the current light's grid: true when it stopped at a
// root (its bracket [shadow.lo, shadow.hi] in ψ set up for refinement, or shadow.psi set when exact).
bool gridPass() {
    shadow.n = shadow.idx / (2 * shadow.cells);
    shadow.inbound = (shadow.idx / shadow.cells) % 2 == 1;
    int cell = shadow.idx % shadow.cells + 1;
    if (shadow.zp == 0.0) {
        shadow.idx++;
        shadow.psi = 0.5 * PI;
        shadow.iter = -1;
        return true;
    }
    // The grid's point before the pass's first cell and G there, made again in every pass
    // (never carried from the last): a pass that a later round resumes starts from the same
    // values as one that follows its predecessor in the same round.
    shadow.u0 = shadow.cmax * float(cell - 1) / float(SHADOW_GRID);
    shadow.g0 = cell == 1
        ? -abs(shadow.zp)
        : shadowG4(shadow.rho, shadow.zp, vec4(shadow.u0), vec4(float(cell - 1)), shadow.n, shadow.inbound).x;
    // Sixteen cells per pass, in four groups written out (each pass of a loop counts
    // against llvmpipe's limit).
    int count = min(CELLS_PER_PASS, shadow.cells - cell + 1);
    vec4 base = float(cell) + vec4(0.0, 1.0, 2.0, 3.0);
    vec4 us[4] = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    vec4 gs[4] = us;
    us[0] = shadow.cmax * base / float(SHADOW_GRID);
    us[1] = shadow.cmax * (base + 4.0) / float(SHADOW_GRID);
    us[2] = shadow.cmax * (base + 8.0) / float(SHADOW_GRID);
    us[3] = shadow.cmax * (base + 12.0) / float(SHADOW_GRID);
    gs[0] = shadowG4(shadow.rho, shadow.zp, us[0], base, shadow.n, shadow.inbound);
    gs[1] = shadowG4(shadow.rho, shadow.zp, us[1], base + 4.0, shadow.n, shadow.inbound);
    gs[2] = shadowG4(shadow.rho, shadow.zp, us[2], base + 8.0, shadow.n, shadow.inbound);
    gs[3] = shadowG4(shadow.rho, shadow.zp, us[3], base + 12.0, shadow.n, shadow.inbound);
    int found = min(min(firstRoot(vec4(shadow.g0, gs[0].xyz), gs[0], base, 0, count, shadow.inbound),
                        firstRoot(vec4(gs[0].w, gs[1].xyz), gs[1], base + 4.0, 4, count, shadow.inbound)),
                    min(firstRoot(vec4(gs[1].w, gs[2].xyz), gs[2], base + 8.0, 8, count, shadow.inbound),
                        firstRoot(vec4(gs[2].w, gs[3].xyz), gs[3], base + 12.0, 12, count, shadow.inbound)));
    if (found >= CELLS_PER_PASS) {
        shadow.idx += count;
        return false;
    }
    // The cell [u0, u1] of the root, as the bracket [ψ(u1), ψ(u0)] in ψ = arccos u (ψ falls
    // as u grows; the grid's last point is ψ_min exactly, as on the CPU).
    int prev = max(found - 1, 0);
    float u0 = found == 0 ? shadow.u0 : us[prev / 4][prev % 4];
    float g0 = found == 0 ? shadow.g0 : gs[prev / 4][prev % 4];
    float u1 = us[found / 4][found % 4];
    float g1 = gs[found / 4][found % 4];
    bool last = cell + found == SHADOW_GRID;
    shadow.lo = last ? shadow.psiMin : acosA(u1);
    shadow.flo = g1;
    shadow.hi = acosA(u0);
    shadow.fhi = g0;
    shadow.idx += found + 1;
    shadow.side = 0;
    shadow.iter = 0;
    shadow.psi = shadow.lo;
    if (g1 == 0.0) shadow.iter = -1;   // an exact root: no refinement
    return true;
}

// One Illinois step on the bracketed root of G (spacetime::refine_root); true when done.
bool rootStep() {
    float m = shadow.fhi != shadow.flo ? (shadow.lo * shadow.fhi - shadow.hi * shadow.flo) / (shadow.fhi - shadow.flo) : 0.5 * (shadow.lo + shadow.hi);
    if (!finite(m) || !(m > shadow.lo && m < shadow.hi)) m = 0.5 * (shadow.lo + shadow.hi);
    shadow.psi = m;
    float fm = shadowG(m, shadow.n, shadow.inbound);
    shadow.iter++;
    if (fm == 0.0 || shadow.hi - shadow.lo <= 4.0 * 1.1920929e-7 * max(shadow.hi, 1e-30) || shadow.iter >= REFINE_STEPS) return true;
    if ((fm > 0.0) == (shadow.fhi > 0.0)) { shadow.hi = m; shadow.fhi = fm; if (shadow.side == 1) shadow.flo *= 0.5; shadow.side = 1; }
    else { shadow.lo = m; shadow.flo = fm; if (shadow.side == -1) shadow.fhi *= 0.5; shadow.side = -1; }
    return false;
}

// The ray of root shadow.psi (spacetime::connect): 0 when it does not count, 1 when it counts
// unoccluded (shadow.weight), 2 when its occlusion must be searched (the search is set up).
int shadowRaySetUp() {
    float a = u_a;
    float c = sign(shadow.zp) * cosA(shadow.psi);
    int n = shadow.n;
    float th = shadowTheta(shadow.psi, n, shadow.inbound);
    float w1 = 1.0 + c * c;
    float omega = sqrt(w1) / (2.0 * a);
    float big = bigPhi(sqrt(2.0 / w1), th);
    float lambda = th / omega;
    float chi = carg(shadow.p.yz) - big + float(n) * PI;
    float sinpsi = sinA(shadow.psi);
    vec4 em = vec4(shadow.p.x - (2.0 * SQRT2 * a * big - lambda), 0.0, 0.0, 0.0);
    vec4 tg = vec4(1.0, sinpsi * cosA(chi), sinpsi * sinA(chi), c);
    vec4 emission = applyIso(shadow.back, em);
    if (emission.x < hp.x.x - u_max_past) return 0;
    // The ray in the source's axis frame: the closed form from the origin, moved by the
    // emission time, carried back by the source's isometry (its end then lies on the hit
    // point to the rounding of one map, not of two).
    Ray r = NO_RAY;
    r.geo = originGeodesic(tg);
    if (!r.geo.ok) return 0;
    r.back = shadow.back;
    r.back.t0 -= em.x;
    r.lret = returnParameter(r.geo);
    r.shift = vec2(0.0);
    vec4 xe = vec4(0.0), kEnd = vec4(0.0);
    rayAt(r, 0, lambda, xe, kEnd);
    vec2 inc = incidence(kEnd);
    if (!finite(inc.x) || !(inc.x > 0.0)) return 0;
    float d2 = areaDistanceSq(c < 0.0 ? PI - shadow.psi : shadow.psi, chi, lambda);
    if (!(d2 > 0.0 && finite(d2))) return 0;
    shadow.weight = shadow.power * inc.y * inc.y * inc.x / (4.0 * PI * d2);
    // Occlusion: the ray from its emission to just before the lit point (END_CUT),
    // searched for every object it may come near; the lit object up to the last segment
    // only (render::lighting: that stretch is nearly a circle arc, which meets a sphere in
    // two points at most, so light arriving at the lit point from outside has not crossed
    // the ball there); its whole-ray test over that stretch may drop it (a lit plane always:
    // z is linear, and the ray meets it at its end).
    float end = lambda * (1.0 - END_CUT);
    int segs = toInt(ceil(end / (r.lret / float(EXACT_SEGMENTS))), 1, MAX_SEGMENTS);
    float last = end * float(segs - 1) / float(segs);
    bool any = setSearched(shadow.source, r.geo, end, hp.target, last);
    if (!any) return 1;
    startLongSearch(r, segs, end, -1.0, false, -INF);   // p_t = −1: E = 1, ∂t carried to ∂t
    plan.skipObj = hp.target;
    plan.skipSeg = segs - 1;
    return 2;
}

// ---------------------------------------------------------------------------------------
// The record of one sample: slots of four channels (crates/gpu/src/input.rs lists them):
// 0 (object, status, u, v), 1 (g, t_emit, lambda, cos_i), 2 (x, y, z, view_x),
// 3 (dir_x, dir_y, dir_z, view_y), 4 (view_z, pol_x, pol_y, pol_z), then four lights each from 5.

// The pixel's screen-up and screen-right (docs/physics.md, "Polarization", "The pixel's
// screen"; render::polarization::screen): the camera's up projected orthogonal to the
// pixel's direction n (forward where n is along up), and n × that, as vectors of the
// observer's frame.
void pixelScreen(mat4 frame, vec3 n) {
    vec3 s = u_up - dot(u_up, n) * n;
    if (dot(s, s) < 1e-12) s = u_forward - dot(u_forward, n) * n;
    s = normalize(s);
    hp.up = frame * vec4(0.0, s);
    hp.right = frame * vec4(0.0, cross(n, s));
}

// The screen vectors parallel-transported along the pixel's ray r from the observer `obs` to
// the hit at `within` into a loop, `lambda` in all (render::polarization::exact): pushed to
// the origin by the observer's isometry, transported there in closed form over the whole
// parameter ("Parallel transport along closed forms") and pushed back. The ray's event in
// its origin frame is taken at `within`: later loops retrace the first shifted in t and z,
// which moves no vector. Minkowski: components are kept (Cartesian coordinates, no Γ).
void transportScreen(Ray r, vec4 obs, float within, float lambda) {
    if (!godel()) return;
    vec4 e0 = vec4(0.0), k0 = vec4(0.0);
    ogeoAt(r.geo, within, e0, k0);
    Iso to = toOrigin(obs);
    vec4 up = transportFromOrigin(r.geo, lambda, e0, pushIso(to, obs, hp.up));
    vec4 right = transportFromOrigin(r.geo, lambda, e0, pushIso(to, obs, hp.right));
    hp.up = pushIso(r.back, e0, up);
    hp.right = pushIso(r.back, e0, right);
}

// The outputs: slots [u_slot0, u_slot0 + DRAW_BUFFERS) of `slots`.
// Whether main's round was cut short by llvmpipe's loop limit: it then writes the previous
// round's slots (zeros in a first round) and its progress.
bool roundCut = false;

vec4 slotOut(int layer) {
    if (!roundCut || layer >= STATE) return slots[layer];
    ivec2 frag = ivec2(gl_FragCoord.xy);
    return u_round > 0 ? texelFetch(u_prev, ivec3(frag, layer), 0) : vec4(0.0);
}

void writeSlots() {
    o0 = slotOut(u_slot0);
#if DRAW_BUFFERS > 1
    o1 = slotOut(u_slot0 + 1);
#endif
#if DRAW_BUFFERS > 2
    o2 = slotOut(u_slot0 + 2);
#endif
#if DRAW_BUFFERS > 3
    o3 = slotOut(u_slot0 + 3);
#endif
#if DRAW_BUFFERS > 4
    o4 = slotOut(u_slot0 + 4);
#endif
#if DRAW_BUFFERS > 5
    o5 = slotOut(u_slot0 + 5);
#endif
#if DRAW_BUFFERS > 6
    o6 = slotOut(u_slot0 + 6);
#endif
#if DRAW_BUFFERS > 7
    o7 = slotOut(u_slot0 + 7);
#endif
}

// ---------------------------------------------------------------------------------------
// Rounds (docs/physics.md, "The GPU kernel", "Rounds"). A sample is traced in rounds of draws
// (crates/gpu/src/host.rs; the page's trace.js): each round goes on from where the previous
// one left the sample, for at most its budget of passes, and keeps what it finished up to the
// last checkpoint it reached: the start of each loop of the pixel's search, the search's end,
// and each step of the shadow rays' enumeration. At a checkpoint the sample's state is a few
// numbers (Progress), written into its state slots; the next round makes everything else
// again from them, and the searches are memoryless there (a loop probes its objects afresh).
// So a record does not depend on how its work was cut into rounds: not on draw sizes, the
// driver's grouping of samples, timing or load. llvmpipe ends every loop of a shader once its
// loops have run 65535 passes in all, per group of samples and silently: a round cut short
// so is told by a last loop that must run twice, and dropped (the sample runs it again with
// half the budget).

const int PH_PIXEL = 0;    // the pixel's search, at the start of loop `counter`
const int PH_LIGHTS = 1;   // the shadow rays: light `counter`, grid index `idx`; `sub` ≥ 0: in
                           // the occlusion search of the step's ray, at the start of stretch `sub`
const int PH_DONE = 2;     // finished with `status`
// Ints kept in f32 between rounds: exact up to 2^24.
const int MAX_COUNT = 16777215;

struct Progress {
    int phase; int budget; int probes; int status;
    int counter; int idx; int sub;
    float sum;   // the current light's sum so far (−1: unknown, one of its searches ran out of work)
    Found hit;   // the pixel's hit (PH_LIGHTS; PH_DONE with status HIT)
};

Progress readProgress() {
    vec4 s0 = slots[STATE], s1 = slots[STATE + 1], s2 = slots[STATE + 2];
    return Progress(toInt(s0.x, PH_PIXEL, PH_DONE), toInt(s0.y, MIN_BUDGET, MAX_BUDGET),
                    toInt(s0.z, 0, PIXEL_PROBES), toInt(s0.w, HIT, WORK_LIMIT),
                    toInt(s1.x, 0, MAX_COUNT), toInt(s1.y, -1, MAX_COUNT), toInt(s2.w, -1, MAX_COUNT), s1.z,
                    Found(HIT, toInt(s1.w, -1, N_OBJECTS), toInt(s2.x, 0, MAX_COUNT), s2.y, s2.z));
}

void writeProgress(Progress p) {
    slots[STATE] = vec4(float(p.phase), float(p.budget), float(p.probes), float(p.status));
    slots[STATE + 1] = vec4(float(p.counter), float(p.idx), p.sum, float(p.hit.target));
    slots[STATE + 2] = vec4(float(p.hit.loop_), p.hit.lambda, p.hit.tau, float(p.sub));
}

// Whether the checkpoint p lies after q (the order of the work: phase, loop or light, grid
// index, stretch).
bool after(Progress p, Progress q) {
    if (p.phase != q.phase) return p.phase > q.phase;
    if (p.counter != q.counter) return p.counter > q.counter;
    if (p.idx != q.idx) return p.idx > q.idx;
    return p.sub > q.sub;
}

// Checkpoints: the start of loop `loop` of the pixel's search; a step of the shadow rays
// (the enumeration's state); the end.
Progress atLoop(Progress p, int loop) {
    p.phase = PH_PIXEL;
    p.counter = loop;
    p.probes = probes_left;
    return p;
}
Progress atStretch(Progress step, int stretch) {
    step.sub = stretch;
    step.probes = probes_left;
    return step;
}
Progress atLightStep(Progress p, Found hit) {
    p.phase = PH_LIGHTS;
    p.counter = shadow.light;
    p.idx = shadow.idx;
    p.sub = -1;
    p.sum = shadow.failed ? -1.0 : shadow.sum;
    p.hit = hit;
    p.probes = probes_left;
    return p;
}
Progress atEnd(Progress p, int status, Found hit) {
    p.phase = PH_DONE;
    p.status = status;
    p.hit = hit;
    p.probes = probes_left;
    return p;
}

// Starts the pixel's search along r; -1, or the sample's status where no search is needed.
int startPixel(Ray r, vec4 obs, float pt, float tBound) {
    bool any = setSearched(obs, r.geo, INF, -1, INF);
    if (!r.geo.ok) return FAILED;
    if (godel()) {
        if (!finite(r.shift.x) || !(r.shift.x < 0.0)) return FAILED;
        // A ray near no object escapes (if it reaches the time bound within the loops).
        if (!any) return float(u_max_loops) * r.shift.x < tBound ? ESCAPED : WORK_LIMIT;
        startSearch(r, u_max_loops + 1, EXACT_SEGMENTS, r.lret, pt, true, tBound);
    } else {
        float lmax = u_max_past / max(abs(r.k0.x), 1e-30);
        startLongSearch(r, toInt(ceil(lmax), 1, MAX_SEGMENTS), lmax, pt, true, tBound);
    }
    return -1;
}

// The pixel's hit f: its event, body frame, surface and shift (h*, which the lights use) and
// the record's slots; its status (escaped where the hit lies before the time bound, failed
// where it has no surface or shift).
int takeHit(Found f, Ray r, mat4 frame, vec3 n, vec4 obs, vec4 k, float tBound) {
    rayAt(r, f.loop_, f.lambda, hp.x, hp.k);
    float lambda = f.lambda + float(f.loop_) * r.lret;
    pixelScreen(frame, n);
    transportScreen(r, obs, f.lambda, lambda);
    hp.target = f.target;
    hp.at.tau = f.tau;
    bool ok = surface();
    // g = (p·u_obs)/(p·u_emit), the backward ray's momentum at both ends.
    float g = dot(frame[0], metricAt(obs) * k) / dot(hp.uemit, metricAt(hp.x) * hp.k);
    if (hp.x.x < tBound) return ESCAPED;
    if (!ok || !(g > 0.0 && finite(g))) return FAILED;
    slots[0] = vec4(float(hp.target), 0.0, hp.uv);
    slots[1] = vec4(g, hp.x.x, lambda, hp.cosI);
    slots[2].xyz = hp.x.yzw;
    slots[3].xyz = hp.dir;
    slots[4].yzw = hp.pol;
    return HIT;
}

// The record's status slot, for a sample finished with `status` after its probes (the hit's
// other slots are takeHit's).
void finishRecord(int status, int probes) {
    if (status != HIT) slots[0] = vec4(-1.0, float(status), 0.0, 0.0);
#ifdef COUNT_PROBES
    slots[2].w = float(PIXEL_PROBES - probes);   // benchmarks: the probes in view_x
#endif
}

#if !defined(RAY_PATH) && !defined(PROBE)
// One round of one sample (u_finish 0: its progress, its lights', and its record once it is
// finished), or its record from its final progress (u_finish 1: where the host's render
// targets cannot take every slot in one draw, its rounds write only the lights' and the
// progress's slots, and this draw the record's).
void main() {
    ivec2 frag = ivec2(gl_FragCoord.xy);
    ivec2 pix = u_origin + frag;
    for (int s = 0; s < ALL_SLOTS + 8; s++) slots[s] = vec4(0.0);
    // The previous round's slots: the record (of a sample finished before), the lights and
    // the progress.
    if (u_round > 0) {
        for (int layer = 0; layer < ALL_SLOTS; layer++) slots[layer] = texelFetch(u_prev, ivec3(frag, layer), 0);
    }
    // (No ?: between structures: WebGL forbids it.)
    Progress at = Progress(PH_PIXEL, clamp(u_budget, MIN_BUDGET, MAX_BUDGET), PIXEL_PROBES,
                           NOT_TRACED, 0, -1, -1, 0.0, NO_FOUND);
    if (u_round > 0) at = readProgress();
    if (u_finish == 0 && at.phase == PH_DONE) {   // finished in an earlier round: kept as it is
        writeSlots();
        return;
    }
    probes_left = at.probes;
    Progress cp = at;   // the last checkpoint reached
    bool moved = false; // whether it lies past the round's start

    vec3 d = vec3(0.0);
    bool traced = cameraDirection(vec2(pix) + 0.5, d);
    vec3 right = cross(u_forward, u_up);
    vec3 n = d.x * u_forward + d.y * right + d.z * u_up;
    slots[2].w = n.x;
    slots[3].w = n.y;
    slots[4].x = n.z;
    loadObjects();
    vec4 obs = vec4(0.0, u_obs_x);
    mat4 frame = boostFrame(staticFrame(obs), u_velocity.x, u_velocity.yzw);
    vec4 k = frame * vec4(-1.0, n);                 // the past-directed photon
    float pt = (metricAt(obs) * k).x;               // p_t, conserved
    Ray r = makeRay(obs, k);
    float tBound = -u_max_past;

    // The finishing draw's status (a hit's slots are made again by takeHit below).
    int finished = !traced ? NOT_TRACED : at.phase == PH_DONE ? at.status : WORK_LIMIT;
    bool searching = false;
    bool pixelSearch = false;
    int resume = -1;   // the stretch at which the restored step's occlusion search goes on
    Found hit = at.hit;
    Progress step = at;   // the current step of the shadow rays, as a checkpoint
    if (!traced) {
        cp = atEnd(at, NOT_TRACED, NO_FOUND);
    } else if (at.phase == PH_PIXEL) {
        int decided = startPixel(r, obs, pt, tBound);
        if (decided >= 0) {
            cp = atEnd(at, decided, NO_FOUND);
        } else {
            mach.loop_ = at.counter;
            searching = true;
            pixelSearch = true;
        }
    } else if (at.phase == PH_LIGHTS) {
        shadow.light = at.counter;
        shadow.idx = at.idx;
        shadow.failed = at.sum < 0.0;
        shadow.sum = max(at.sum, 0.0);
        resume = at.sub;
    }
    if (cp.phase == PH_DONE) moved = true;
    // The hit is taken (takeHit: its event, surface, shift and record slots) at the top of the
    // loop below, its one call site (GLSL inlines every call: one copy of the surface's code
    // keeps the kernel's compilation short): for the finishing draw, for a round that resumes
    // the lights, and once the pixel's search has found it (`fresh`).
    bool take = u_finish != 0 ? finished == HIT : traced && at.phase == PH_LIGHTS;
    bool fresh = false;

    // The passes: the pixel's search, then the shadow rays light by light, each step of their
    // enumeration a checkpoint, the search of one ray's occlusion between two steps. A
    // search's passes run in a loop of their own: llvmpipe runs every statement of a loop's
    // body on each pass, masked, so the enumeration's code stays out of the search's loop.
    int spent = 0;
    for (int job = 0; job < MAX_BUDGET && (take || (u_finish == 0 && cp.phase != PH_DONE && spent < at.budget)); job++) {
        if (take) {
            take = false;
            int status = takeHit(hit, r, frame, n, obs, k, tBound);
            if (u_finish != 0) {
                finished = status;
                break;
            }
            if (fresh) {
                fresh = false;
                moved = true;
                if (status != HIT || !godel() || HAS_LIGHTS == 0 || u_lights == 0) {
                    cp = atEnd(cp, status, hit);
                    break;
                }
                shadow.light = 0;
                shadow.idx = -1;
                shadow.sum = 0.0;
                shadow.failed = false;
                cp = atLightStep(cp, hit);
            } else if (shadow.idx >= 0 && shadow.light < u_lights) {
                lightGeometry();   // a resumed light's, from the hit just taken
            }
            continue;
        }
        if (searching) {
            for (int pass = 0; pass < MAX_BUDGET && mach.mode != M_DONE && spent < at.budget; pass++) {
                spent++;
                if (mach.mode == M_LOOP && req.tag == Q_NONE) {
                    // A loop's or a stretch's start: a checkpoint (none before the round's start).
                    Progress p = atStretch(step, mach.loop_);   // (no ?: of structures in WebGL)
                    if (pixelSearch) p = atLoop(cp, mach.loop_);
                    if (!after(at, p)) {
                        moved = moved || after(p, at);
                        cp = p;
                    }
                }
                searchPass();
            }
            if (mach.mode != M_DONE) break;   // the round's budget is spent
            searching = false;
            Found f = mach.result;
            if (pixelSearch) {
                pixelSearch = false;
                if (f.status != HIT) {
                    moved = true;
                    cp = atEnd(cp, f.status, f);
                    break;
                }
                hit = f;
                take = true;
                fresh = true;
                continue;
            }
            if (f.status == WORK_LIMIT || f.status == FAILED) {   // occlusion unknown
                shadow.failed = true;
            } else if (f.status != HIT) {
                shadow.sum += shadow.weight;
            }
            continue;
        }
#if HAS_LIGHTS != 0
        // Steps of the shadow rays' enumeration, in a loop of their own until one needs an
        // occlusion search: a light's set-up or end, sixteen cells of its grid, or a root's
        // refinement and its ray's set-up.
        for (int pass = 0; pass < MAX_BUDGET && !searching && spent < at.budget; pass++) {
            spent++;
            step = atLightStep(cp, hit);
            if (!after(at, step)) {
                moved = moved || after(step, at);
                cp = step;
            }
            if (shadow.light >= u_lights) {
                cp = atEnd(cp, HIT, hit);
                break;
            }
            if (shadow.idx < 0) {
                if (!startLight()) endLight();
            } else if (shadow.idx >= shadow.total || shadow.failed) {
                endLight();
            } else if (gridPass()) {
                for (int it = 0; it < REFINE_STEPS && shadow.iter >= 0; it++) {
                    spent++;
                    if (rootStep()) break;
                }
                int use = shadowRaySetUp();
                if (use == 1) shadow.sum += shadow.weight;
                if (use == 2) {
                    searching = true;
                    if (resume >= 0) mach.loop_ = resume;   // the restored step's search, where it was
                    resume = -1;
                }
            }
        }
        if (!searching && cp.phase != PH_DONE) break;   // the round's budget is spent
#endif
    }

    if (u_finish != 0) {
        finishRecord(finished, at.probes);
        writeSlots();
        return;
    }

    // llvmpipe's loop limit: a loop that must run twice tells whether this round was cut.
    int passes = 0;
    for (int i = 0; i < u_two; i++) passes++;
    Progress next = cp;
    next.budget = at.budget;
    if (passes != 2) {
        // Cut short: nothing of this round is kept; again with half the budget.
        roundCut = true;
        next = at;
        next.budget = max(at.budget / 2, MIN_BUDGET);
    } else if (!moved) {
        // No checkpoint reached: more passes next round, up to MAX_BUDGET; beyond that the
        // pixel's search is out of work, or the light's occlusion unknown.
        if (at.budget < MAX_BUDGET) next.budget = min(at.budget * 2, MAX_BUDGET);
        else if (at.phase == PH_LIGHTS) next.sum = -1.0;
        else next = atEnd(at, WORK_LIMIT, NO_FOUND);
    }
    // A sample finished in this round: its record (a hit's slots are the hit's, made by
    // takeHit in this round).
    if (passes == 2 && next.phase == PH_DONE) finishRecord(next.status, next.probes);
    writeProgress(next);
    writeSlots();
}
#endif

// ---------------------------------------------------------------------------------------
// The explore map's light ray of one sample (compiled with RAY_PATH in place of the pixel
// kernel; render::map::light_ray, docs/physics.md "The explore map"): the page reads a
// sample's record from a frame it traced and draws the sample's path on the map with the
// closed forms above, without the server. The exact geodesic from the observer with the
// tangent the pixel kernel launched along the record's direction, sampled from the observer
// to the record's parameter at the hit, or to the trace's past limit for a ray that hit
// nothing. Draw 1 (u_points = 0, one fragment) gives that end parameter, the number of
// points and the emission event's distance from the observer's axis; draw 2 gives the
// points, one a fragment.
#ifdef RAY_PATH
uniform vec4 u_ray;        // the record's direction in the observer's frame; λ at the hit (< 0: none)
uniform vec3 u_emission;   // the emission event's x, y, z (a hit)
uniform int u_points;      // draw 1: 0; draw 2: the points after the observer's event
uniform int u_row;         // draw 2: points per row of the target

// render::map: points per loop of a ray (a loop returns to the observer's axis), the most
// points, doublings and halvings of the search for the parameter where a ray reaches a time.
const float POINTS_PER_LOOP = 96.0;
const int MAX_RAY_POINTS = 4096;
const int MAP_SEARCH_STEPS = 200;

vec4 rayEvent(Ray r, float l) { vec4 ev = vec4(0.0), k = vec4(0.0); rayAt(r, 0, l, ev, k); return ev; }

// The parameter at which the past-directed ray reaches relative time t (t decreases along
// it): doubling, then bisection, each bounded.
float parameterAtTime(Ray r, float t) {
    float hi = 1.0;
    for (int i = 0; i < MAP_SEARCH_STEPS; i++) {
        if (rayEvent(r, hi).x <= t) break;
        hi *= 2.0;
    }
    float lo = 0.0;
    for (int i = 0; i < MAP_SEARCH_STEPS; i++) {
        float mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        if (rayEvent(r, mid).x > t) lo = mid; else hi = mid;
    }
    return hi;
}

void main() {
    for (int s = 0; s < ALL_SLOTS + 8; s++) slots[s] = vec4(0.0);
    vec4 obs = vec4(0.0, u_obs_x);
    mat4 frame = boostFrame(staticFrame(obs), u_velocity.x, u_velocity.yzw);
    Ray r = makeRay(obs, frame * vec4(-1.0, normalize(u_ray.xyz)));
    if (!r.geo.ok || (godel() && (!finite(r.shift.x) || !(r.shift.x < 0.0)))) {
        slots[0] = vec4(-1.0);   // no closed form: no path
    } else if (u_points == 0) {
        float end = u_ray.w >= 0.0 ? u_ray.w : parameterAtTime(r, -u_max_past);
        float loops = godel() ? max(end / r.lret, 1.0) : 1.0;
        float points = min(max(ceil(loops * POINTS_PER_LOOP), 2.0), float(MAX_RAY_POINTS - 1));
        vec4 e = vec4(0.0, u_emission);
        float rEmit = godel() ? length(applyIso(toOrigin(obs), e).yz) : length(e.yz - obs.yz);
        slots[0] = vec4(end, points, rEmit, 1.0);
    } else {
        ivec2 p = ivec2(gl_FragCoord.xy);
        int i = 1 + p.x + u_row * p.y;
        float l = u_ray.w * float(i) / float(u_points);
        if (godel()) {
            // In the origin frame the distance from the observer's axis is the cylindrical r.
            vec4 e0 = vec4(0.0), k0 = vec4(0.0);
            ogeoAt(r.geo, l, e0, k0);
            slots[0] = applyIso(r.back, e0);
            slots[1] = vec4(length(e0.yz), 0.0, 0.0, 0.0);
        } else {
            slots[0] = obs + l * r.k0;
            slots[1] = vec4(length(slots[0].yz - obs.yz), 0.0, 0.0, 0.0);
        }
    }
    writeSlots();
}
#endif
