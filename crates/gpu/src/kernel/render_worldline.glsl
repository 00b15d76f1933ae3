// ---------------------------------------------------------------------------------------
// Objects (docs/physics.md, "Local objects"; render::target, render::worldline), read from
// the table once per sample: what is the same for every sample (frames, Γ, a free fall's
// closed form and isometry) the host computed in f64 (crates/gpu/src/input.rs). GLSL inlines
// every call, so the heavy functions below each have one call site (two for `localize`), and
// the kernel stays small enough to compile in seconds.

// The chart of local descriptions (render::chart): a ball's rest-frame coordinates are normal
// coordinates to second order in it. Gödel's and Minkowski's own coordinates; a member's
// Gödel-like chart (spacetime_metric's chart*), so that the Gödel member's balls are Gödel's.
vec4 localEvent(vec4 e) {
#ifdef MEMBER
    return chartEvent(e);
#endif
    return e;
}
// The chart's differential at `at` on the plane (the identity but in a member).
mat2 localJacobian(vec4 at) {
#ifdef MEMBER
    return chartJacobian(at.yz);
#endif
    return mat2(1.0);
}
vec4 localVector(vec4 at, vec4 v) { return vec4(v.x, localJacobian(at) * v.yz, v.w); }
mat4 localFrame(vec4 at, mat4 f) {
    mat2 j = localJacobian(at);
    return mat4(vec4(f[0].x, j * f[0].yz, f[0].w), vec4(f[1].x, j * f[1].yz, f[1].w),
                vec4(f[2].x, j * f[2].yz, f[2].w), vec4(f[3].x, j * f[3].yz, f[3].w));
}
mat4 localMetric(vec4 X) {
#ifdef MEMBER
    vec3 p = chartRotating(X);
    return rotatingMetric(X.yz, p.x, p.y, p.z);
#endif
    return metricAt(X);
}
// ∂x g, ∂y g and g⁻¹ at the event X of the chart (zero and the metric's in Minkowski space,
// whose Γ vanish).
void localDerivatives(vec4 X, out mat4 dX, out mat4 dY) {
    dX = mat4(0.0); dY = mat4(0.0);
    if (minkowski()) return;
#ifdef MEMBER
    vec3 p = chartRotating(X);
    rotatingDerivatives(X.yz, p.x, p.y, p.z, dX, dY);
    return;
#endif
    metricDerivatives(X, dX, dY);
}
mat4 localInverse(vec4 X) {
#ifdef MEMBER
    return rotatingInverse(X.yz, MEMBER_OMEGA, 0.25 * MEMBER_M2);
#endif
    return inverseMetricAt(X);
}

struct Object {
    int kind;
    float radius;
    float extent;   // planes: |x|, |y| ≤ extent (≤ 0: unbounded)
    vec4 pos;       // at rest (0, x, y, z); coordinate sphere: centre; plane: height in .w
    vec4 local;     // at rest: its position in the chart of local descriptions
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
#ifdef MEMBER
    TExact tex;     // free fall in a member: the geodesic through its start (Gödel's `geo` and `back`)
#endif
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
// falling ball's first and last λ within reach in the current loop, from the loop's start, and
// a seed of its proper time at the first (fallingWindow).
bool searched[N_OBJECTS];
vec2 oCw[N_OBJECTS];
float oCz[N_OBJECTS];
// A ball at rest's ballNear for the ray (render_reject).
vec4 oNear[N_OBJECTS];
vec3 fbWindow[N_OBJECTS];

// The stores into the per-object arrays, each at the constant indices of a loop whose body
// is the store alone, which compilers unroll: never at the runtime index i (drivers have
// stored at the wrong index; docs/physics.md, "The GPU kernel").
void storeObject(int i, Object o) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) objs[j] = o;
    }
}
void storeSearched(int i, bool s, vec2 cw, float cz, vec4 near) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) {
            searched[j] = s;
            oCw[j] = cw;
            oCz[j] = cz;
            oNear[j] = near;
        }
    }
}
void storeFallingWindow(int i, vec3 window) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) fbWindow[j] = window;
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
    Object o = Object(toInt(t0.x, -1, KIND_PLANE), t0.y, t0.z, vec4(0.0, t1.xyz), vec4(0.0), mat4(0.0),
                      mat3(0.0), mat3(0.0), mat3(0.0), NO_ISO, NO_OGEO, vec4(0.0), vec4(0.0),
                      1.0, 1.0, 1.0
#ifdef MEMBER
                      , NO_TEXACT
#endif
                      );
    o.local = o.pos;
    if (restKind(o.kind)) {
#ifdef MEMBER
        o.local = vec4(0.0, tableTexel(at + 2).xyz);
#endif
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
#ifdef MEMBER
        // (E, p_z, κ, k⊥), (Λ, cos χ, sin χ), the isometry back, the sphere's (α, β).
        vec4 w = tableTexel(at + 11);
        o.tex = TExact(TIso(t2.z - o.start.x, b.xy, b.z, b.w),
                       TGeo(MB, g0.x, g0.y, g0.z, g0.w, g1.x, g1.yz, true), w.xy, w.zw, MEMBER_M2 < 0.0);
#endif
    }
    return o;
}

// Every object into objs, and the per-ray arrays cleared.
void loadObjects() {
    for (int i = 0; i < N_OBJECTS; i++) {
        searched[i] = false;
        oCw[i] = vec2(0.0);
        oCz[i] = 0.0;
        oNear[i] = vec4(0.0);
        fbWindow[i] = vec3(NO_TAU);
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
#ifdef MEMBER
    } else if (member()) {
        texAt(objs[i].tex, tau, p.ev, p.u);
#endif
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
// in closed form, in a member by surface(); at rest: the static frame). Read from the table here, at a hit, not for
// every object when a sample starts.
mat4 bodyFrame(int i, WPoint p) {
    mat4 f = tableMat(OBJECT_TEXELS * i + 3);
#ifdef MEMBER
    // A falling ball's legs as at its start: surface() transports them (memberTransports).
    if (isFree(i)) return mat4(p.u, f[1], f[2], f[3]);
#endif
    if (!isFree(i) || !godel()) return f;
    vec4 e0 = vec4(0.0), k0 = vec4(0.0);
    ogeoAt(objs[i].geo, p.tau, e0, k0);
    mat4 legs = transportLegs(objs[i].geo, p.tau, e0, mat4(f[1], f[2], f[3], vec4(0.0)), 3);
    legs = pushLegs(objs[i].back, e0, legs, 3);
    return mat4(p.u, legs[0], legs[1], legs[2]);
}

// A first guess of the proper time at which the worldline has coordinate time t.
// A free fall's: the proper time of equal coordinate time (the CPU interpolates it from its
// integration steps), by Newton steps on t(τ) from the mean rate's guess (dt/dτ = u^t).
float tauGuess(int i, float t) {
    if (!isFree(i)) return t;
    float tau = (t - objs[i].start.x) / objs[i].rate;
#ifdef MEMBER
    // In a member a worldline may hover in t where it passes near ρ_c (u^t → 0), and turn back
    // in t beyond it, where Newton's steps wander off. Each loop advances t by rate·λ_ret:
    // bracket t(τ) = t by quarter loops from the mean rate's guess, then bisect and
    // interpolate.
    float lret = memberReturn(objs[i].tex.origin);
    if (lret < INF) {
        // One worldline evaluation per pass (GLSL inlines each call site; softpipe's compiler
        // crashed on the copies): walk from τ in quarter loops until t(τ) = t is bracketed,
        // then bisect, at most 28 evaluations.
        float step_ = 0.25 * lret;
        float lo = tau, hi = tau, flo = 0.0, fhi = 0.0, x = tau;
        bool haveLo = false, haveHi = false;
        for (int k = 0; k < 28; k++) {
            float f = worldAt(i, x).ev.x - t;
            if (f <= 0.0) { lo = x; flo = f; haveLo = true; }
            else { hi = x; fhi = f; haveHi = true; }
            // Bracketed to 10⁻⁵ of a loop: a guess needs no more (and the data-dependent end
            // keeps compilers from unrolling the loop into 28 copies of the worldline).
            if (haveLo && haveHi && hi - lo <= 1e-5 * lret) break;
            x = haveLo && haveHi ? 0.5 * (lo + hi) : (haveLo ? lo + step_ : hi - step_);
        }
        if (haveLo && haveHi) return fhi > flo ? lo + (hi - lo) * (-flo) / (fhi - flo) : 0.5 * (lo + hi);
        return x;
    }
    // (A member's falling ball always returns: one that escapes a causal member is refused,
    // and in the others every orbit returns. So Newton is left out of its kernel.)
    return tau;
#else
    for (int it = 0; it < TIME_STEPS; it++) {
        WPoint p = worldAt(i, tau);
        tau += (t - p.ev.x) / max(p.u.x, 0.05);
    }
    return tau;
#endif
}

// ---------------------------------------------------------------------------------------
// Localizing a ray point in an object's rest frame (render::worldline::Worldline::localize).

// The second-order normal-coordinate displacement of x from the worldline point p, taken
// after the isometry that sends p to the origin, and p's four-velocity carried there
// (render::worldline::origin_coords). Minkowski: the displacement itself.
void originDisplacement(WPoint p, vec4 x, out vec4 xi, out vec4 u) {
    xi = vec4(0.0); u = vec4(0.0);
#ifdef MEMBER
    TIso tm = typeToOrigin(MB, p.ev);
    vec4 om = vec4(0.0);
    typeApplyPush(MB, tm, p.ev, p.u, om, u);
    // The chart's differential at the origin is the identity: u stays as it is.
    xi = normalDisplacement(vec4(0.0), chartEvent(typeApplyIso(MB, tm, x)));
    return;
#endif
    if (!godel()) { xi = x - p.ev; u = p.u; return; }
    Iso to = toOrigin(p.ev);
    vec4 o = vec4(0.0);
    applyPush(to, p.ev, p.u, o, u);
    xi = normalDisplacement(vec4(0.0), applyIso(to, x));
}

// The first-order simultaneity −g(u, Δ) of x with the worldline point p, and g(Δ, Δ), in the
// chart of local descriptions (render::worldline::first_order).
vec2 firstOrder(WPoint p, vec4 x) {
    vec4 pl = localEvent(p.ev);
    vec4 d = localEvent(x) - pl;
    mat4 g = localMetric(pl);
    return vec2(-dotg(g, localVector(p.ev, p.u), d), dotg(g, d, d));
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
        // second-order ξ⁰. In the chart of local descriptions (t is the same in it).
        vec4 xl = localEvent(x);
        vec3 c = objs[i].local.yzw;
        float t = xl.x + dot(objs[i].dual[0].yzw, xl.yzw - c);
        vec4 xi = components(objs[i].dual, xl - vec4(t, c));
        lp.exact = length(xi.yzw) <= far;
        if (lp.exact) {
            for (int it = 0; it < 2; it++) {   // a fixed count, without jumps: unrolled
                vec4 d = xl - vec4(t, c);
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
    vec2 first = firstOrder(p, x);
    float f0 = first.x;
    float len0 = sqrt(max(first.y + f0 * f0, 0.0));
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
        float f = firstOrder(p, x).x;
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
#ifdef MEMBER
    TIso tm = typeToOrigin(MB, lp.at.ev);
    frame = mat4(typePush(tm, lp.at.ev, frame[0]), typePush(tm, lp.at.ev, frame[1]),
                 typePush(tm, lp.at.ev, frame[2]), typePush(tm, lp.at.ev, frame[3]));
#endif
    if (godel()) {
        // The frame carried to the origin, where disp was taken.
        Iso to = toOrigin(lp.at.ev);
        frame = pushLegs(to, lp.at.ev, frame, 4);
    }
    return components(dualFrame(metricAt(vec4(0.0)), frame), lp.disp).yzw;
}

