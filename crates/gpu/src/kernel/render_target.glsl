// ---------------------------------------------------------------------------------------
// Probes: signed distance f (≤ 0 inside), rate bound |df/dλ| ≤ rate, matched proper time
// (render::target::Target::probe, docs/physics.md "The intersection search").

// `xi`: a local ball's rest-frame coordinates of the ray point, where `near`, and for a ball in
// free fall the photon's energy in its frame to first order, |k·u| (for the chord exclusion;
// the CPU's Probe::xi and energy).
struct Probe { float f; float rate; float tau; vec3 xi; bool near; float energy; };
const Probe NO_PROBE = Probe(0.0, 0.0, 0.0, vec3(0.0), false, 0.0);
// Nothing known of the object here (the CPU's infinite distance).
const Probe FAR = Probe(INF, 0.0, NO_TAU, vec3(0.0), false, 0.0);

Probe probeObject(int i, vec4 x, vec4 k, float pt, float tauSeed) {
    probes_left--;
    if (isCoordSphere(i)) {
        return Probe(length(x.yzw - objs[i].pos.yzw) - objs[i].radius, RATE_MARGIN * length(k.yzw), NO_TAU, vec3(0.0), false, 0.0);
    }
    if (isPlane(i)) return Probe(x.w - objs[i].pos.w, RATE_MARGIN * abs(k.w), NO_TAU, vec3(0.0), false, 0.0);
    float scale = minkowski() ? 1.0 : u_a;
    float far = FAR_DISTANCE * scale + FAR_RADII * objs[i].radius;
    float floor_ = objs[i].radius + 0.5 * FAR_DISTANCE * scale;
    // A far probe's estimate needs a smaller margin than a near one's distance (render::target's
    // FAR_RATE_MARGIN, where it was measured).
    float rate = GLOBAL_RATE_MARGIN * abs(pt) * objs[i].speed;
    bool measured = godel() && objs[i].speed <= FAR_RATE_MAX_SPEED_FACTOR && objs[i].speed * objs[i].radius <= u_a;
    float farRate = measured ? FAR_RATE_MARGIN * abs(pt) * objs[i].speed : rate;
    // Two tries, one call of each closed form (the kernel is inlined whole: a second call
    // site would compile the worldline's search twice). The first localizes from the seed;
    // where a stale seed called a point inside a falling ball far, the second tries the point
    // of equal coordinate time and the nearer is kept.
    Probe p = FAR;
    for (int attempt = 0; attempt < 2; attempt++) {
        bool retry = attempt == 1;
        float seed = tauSeed;
        if (retry || !(tauSeed > NO_TAU)) seed = tauGuess(i, x.x);
        Local lp = localize(i, x, seed, far);
        if (!lp.ok) break;   // (p is FAR still where the first try fails)
        float slack = isRest(i) ? 1.1 + (FAR_SLACK - 1.1) * min((lp.len - far) / far, 1.0) : FAR_SLACK;
        Probe q = Probe((lp.exact ? lp.len : max(lp.len / slack, floor_)) - objs[i].radius, lp.exact ? rate : farRate, lp.exact ? lp.at.tau : NO_TAU,
                        retry ? vec3(0.0) : lp.xi, !retry && lp.exact && isRest(i), 0.0);
        // The chord's inputs, where its test can apply (chordExcludes: s ≤ 3, ends within
        // 0.4a): the body frame is the dearest part of a probe.
        if (!retry && lp.exact && isFree(i) && godel() && objs[i].speed <= CHORD_MAX_SPEED_FACTOR && lp.len <= CHORD_MAX_END * u_a) {
            q.xi = restComponents(i, lp, bodyFrame(i, lp.at));
            q.near = true;
            q.energy = abs(dotg(metricAt(x), k, lp.at.u));
        }
        if (!retry) p = q;
        else if (q.f < p.f) p = q;
        if (lp.exact || !(tauSeed > NO_TAU) || !isFree(i)) break;
    }
    return p;
}

bool crossed(float fa, float fb) { return (fa > 0.0) != (fb > 0.0); }
bool excluded(float fa, float fb, float rate, float h) {
    return !crossed(fa, fb) && (abs(fa) + abs(fb) > rate * h || rate == 0.0);
}
// The chord exclusion (render::chord, docs/physics.md "The intersection search"): a local ball
// in Gödel's universe, both ends near it and on one side; the path strays from the chord of
// its rest-frame coordinates by at most K·h²/8, K = (3.25·[at rest] + 0.75·[falling] +
// s⁴·ρ/a)·e²/a, e = E·s, a falling ball's at most twice its ends' larger k·u.
bool chordExcludes(int i, Probe pa, Probe pb, float h) {
    if (!(godel() && pa.near && pb.near)) return false;
    float na = length(pa.xi), nb = length(pb.xi);
    float ends = max(na, nb);
    float s = objs[i].speed;
    if (!(ends <= CHORD_MAX_END * u_a && s <= CHORD_MAX_SPEED_FACTOR)) return false;
    bool rest = isRest(i);
    float e = max(pa.rate, pb.rate) / GLOBAL_RATE_MARGIN;   // E·s, from the near probes' rate
    if (!rest) e = min(e, CHORD_ENERGY_MARGIN * max(pa.energy, pb.energy));
    float turn = rest ? CHORD_BEND_AT_REST : CHORD_BEND_FALLING;
    float bend = (turn + s * s * s * s * (ends + CHORD_MAX_STRAY * u_a) / u_a) * e * e / u_a;
    float stray = bend * h * h / 8.0 + CHORD_NOISE * u_a;
    if (!(stray <= CHORD_MAX_STRAY * u_a)) return false;
    float r = objs[i].radius;
    if (pa.f > 0.0 && pb.f > 0.0) {
        vec3 d = pb.xi - pa.xi;
        float dd = dot(d, d);
        float s = dd > 0.0 ? clamp(-dot(pa.xi, d) / dd, 0.0, 1.0) : 0.0;
        return length(pa.xi + s * d) - stray > r;
    }
    return pa.f <= 0.0 && pb.f <= 0.0 && ends + stray <= r;
}

// Whether every crossing of object i counts (render::target::Target::accepts_any): all but
// planes of limited extent.
bool acceptsAny(int i) { return !isPlane(i) || objs[i].extent <= 0.0; }
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

