// ---------------------------------------------------------------------------------------
// Surfaces (render::target::Target::surface): texture coordinates, the emitter's velocity at
// the hit point, the photon's direction in the emitter's rest frame, cos_i.

vec2 lonLat(vec3 p) {
    vec3 n = normalize(p);
    float u = (atan2s(n.y, n.x) + PI) / (2.0 * PI);
    float v = 0.5 + asinA(clamp(n.z, -1.0, 1.0)) / PI;
    return clamp(vec2(u, v), 0.0, 1.0);
}

// The rest-frame components at the worldline point p of the vector v at x, carried from x to
// the centre to first order with Γ there (render::target::rest_frame_photon), in the chart of
// local descriptions, as the ball's coordinates are.
vec4 restFrameVector(WPoint p, mat4 frame, vec4 x, vec4 v) {
    vec4 centre = localEvent(p.ev);
    vec4 vn = localVector(x, v);
    if (!minkowski()) vn -= localChristoffel(centre, centre - localEvent(x), vn);
    return components(dualFrame(localMetric(centre), localFrame(p.ev, frame)), vn);
}

// The photon's rest-frame components at the worldline point p (restFrameVector) and the
// emitter's four-velocity at x: ∂t at rest, in free fall the centre's carried to x.
void restFramePhoton(int i, WPoint p, mat4 frame, vec4 x, vec4 k, out vec4 uemit, out vec4 kl) {
    uemit = vec4(0.0); kl = vec4(0.0);
    kl = restFrameVector(p, frame, x, k);
    uemit = vec4(1.0, 0.0, 0.0, 0.0);
    if (isFree(i)) {
        vec4 centre = localEvent(p.ev);
        vec4 u = localVector(p.ev, frame[0]);
        if (!minkowski()) u -= localChristoffel(centre, localEvent(x) - centre, u);
        uemit = localVectorBack(x, u);
    }
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
    return measurePolarization(restFrameVector(p, frame, x, hp.up), restFrameVector(p, frame, x, hp.right), hp.dir);
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

