// ---------------------------------------------------------------------------------------
// Surfaces (render::target::Target::surface): texture coordinates, the emitter's velocity at
// the hit point, the photon's direction in the emitter's rest frame, cos_i.

vec2 lonLat(vec3 p) {
    vec3 n = normalize(p);
    float u = (atan2s(n.y, n.x) + PI) / (2.0 * PI);
    float v = 0.5 + asinA(clamp(n.z, -1.0, 1.0)) / PI;
    return clamp(vec2(u, v), 0.0, 1.0);
}

// The hit's local description (render::target::rest_frame_photon), the same for every vector
// carried from the hit to the body's centre and measured there: in the chart of local
// descriptions the centre and the hit, the chart's differential at the hit, Γ's pieces at the
// centre, the body frame's dual rows and four-velocity there. Made once per hit
// (setLocalAt, surface()); the photon, the screen vectors and the lights' photons use it (GLSL
// inlines every call site: one copy of the chart and of Γ).
struct LocalAt { vec4 centre; vec4 here; mat2 jx; mat4 dX; mat4 dY; mat4 gi; mat4 dual; vec4 u; };
LocalAt hl = LocalAt(vec4(0.0), vec4(0.0), mat2(1.0), mat4(0.0), mat4(0.0), mat4(0.0), mat4(0.0), vec4(0.0));

void setLocalAt(WPoint p, mat4 frame, vec4 x) {
    hl.centre = localEvent(p.ev);
    hl.here = localEvent(x);
    hl.jx = localJacobian(x);
    localDerivatives(hl.centre, hl.dX, hl.dY);
    hl.gi = localInverse(hl.centre);
    mat4 f = localFrame(p.ev, frame);
    hl.dual = dualFrame(localMetric(hl.centre), f);
    hl.u = f[0];
}

// The rest-frame components of the vector v at the hit, carried to the centre to first order
// with Γ there.
vec4 restFrameVector(vec4 v) {
    vec4 vn = vec4(v.x, hl.jx * v.yz, v.w);
    vn -= christoffelWith(hl.dX, hl.dY, hl.gi, hl.centre - hl.here, vn);
    return components(hl.dual, vn);
}

// The emitter's four-velocity at the hit: ∂t at rest, in free fall the centre's carried there.
vec4 emitterVelocity(int i) {
    if (!isFree(i)) return vec4(1.0, 0.0, 0.0, 0.0);
    vec4 u = hl.u - christoffelWith(hl.dX, hl.dY, hl.gi, hl.here - hl.centre, hl.u);
    return vec4(u.x, inverse(hl.jx) * u.yz, u.w);
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

// The screen vectors at the hit carried to the body's centre to first order and measured in
// its body frame, as the photon (render::target::Target::surface).
bool restFramePolarization() {
    return measurePolarization(restFrameVector(hp.up), restFrameVector(hp.right), hp.dir);
}

#ifdef MEMBER
// A member's pixel ray at the hit (transportScreen): the ray, its loop and the parameter within.
Ray hitRay = NO_RAY;
int hitLoop = 0;
float hitWithin = 0.0;

// The parallel transports at a member's hit (typeTransport): the pixel's screen vectors along
// its ray, and a falling ball's legs along its worldline from its start, with one call of
// typeTransport (GLSL inlines every call site: two copies crashed softpipe's compiler).
void memberTransports(int i) {
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1 && !isFree(i)) break;
        TExact g = hitRay.tex;
        int loops = hitLoop;
        float within = hitWithin, lret = hitRay.lret, seg = hitRay.h;
        mat4 w = mat4(hp.up, hp.right, vec4(0.0), vec4(0.0));
        if (pass == 1) {
            // Segments as a light ray's of the same energy.
            g = objs[i].tex;
            lret = memberReturn(g.origin);
            seg = MEMBER_STEP / max(abs(g.origin.e), 1.0);
            float tau = hp.at.tau;
            loops = lret < INF ? toInt(trunc(tau / lret), -MAX_COUNT_SEGMENTS, MAX_COUNT_SEGMENTS) : 0;
            within = lret < INF ? tau - float(loops) * lret : tau;
            w = mat4(vec4(0.0), hp.frame[1], hp.frame[2], hp.frame[3]);
        }
        mat4 moved = typeTransport(g, loops, within, lret, seg, w);
        if (pass == 0) {
            hp.up = moved[0];
            hp.right = moved[1];
        } else {
            hp.frame = mat4(hp.frame[0], moved[1], moved[2], moved[3]);
        }
    }
}
#endif

bool surface() {
    int i = hp.target;
    vec4 x = hp.x, k = hp.k;
    hp.uemit = vec4(1.0, 0.0, 0.0, 0.0);
    float seed = hp.at.tau > NO_TAU ? hp.at.tau : tauGuess(i, x.x);
    hp.at = WPoint(x.x, x, hp.uemit);
    hp.frame = mat4(1.0);
    bool local = isRest(i) || isFree(i);
    Local lp = NO_LOCAL;
    if (local) {
        lp = localize(i, x, seed, INF);
        if (!lp.ok) return false;
        hp.at = lp.at;
        hp.frame = bodyFrame(i, hp.at);
    }
#ifdef MEMBER
    memberTransports(i);
#endif
    if (local) {
        hp.xi = restComponents(i, lp, hp.frame);
        setLocalAt(hp.at, hp.frame, x);
        vec4 kl = restFrameVector(k);
        hp.uemit = emitterVelocity(i);
        hp.uv = lonLat(hp.xi);
        hp.dir = normalize(-kl.yzw);
        hp.cosI = abs(dot(normalize(hp.xi), hp.dir));
        return restFramePolarization();
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
