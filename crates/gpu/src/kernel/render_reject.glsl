// ---------------------------------------------------------------------------------------
// Whole-ray rejection of balls at rest and planes (render::reject, docs/physics.md
// "Whole-ray rejection"): it only drops searches that could not find a crossing.

// The part of a static ball's test that depends on the ray alone, made once per ray: x, the
// angle offset α₀ − arg(m_C) of δ(λ) = α₀ + sgn(E)·2πλ/λ_ret − arg(m_C); y, the least cos δ at
// which the ray's circle comes within the reach (above 1: it never does; below −1: all round),
// from the law of cosines cosh(d_H/a) = cosh(d_hC/a)·cosh(ρ/a) − sinh(d_hC/a)·sinh(ρ/a)·cos δ.
vec2 ballNear(OGeo g, vec2 wc, float reach) {
    float a = u_a;
    float sg = sign(g.e);
    vec2 dir = vec2(-sg * g.cchi.y, sg * g.cchi.x);
    float big = asinh_(g.rmax / (2.0 * a));
    float rho = a * big;
    vec2 h = dir * halfTanh(g.rmax / (2.0 * a));
    vec2 mc = cdiv(wc - h, vec2(1.0, 0.0) - cmul(conj2(h), wc));
    float dhc = 2.0 * a * atanh_(min(length(mc), 0.9999999));
    float offset = carg(-h) - carg(mc);
    if (abs(dhc - rho) > reach) return vec2(offset, 2.0);
    float x = dhc / a, y = rho / a;
    float ss = sinh(x) * sinh(y);
    float c = cosh(x) * cosh(y) - cosh(reach / a);
    // ss = 0: d_H does not depend on δ (the centre on the circle's centre, or a ray along z).
    float cosMin = ss > 0.0 ? c / ss : (c > 0.0 ? 2.0 : -2.0);
    return vec2(offset, cosMin);
}

// Whether the closed-form ray g from the origin, over λ ∈ [from, until], stays farther than
// the reach from the static ball whose centre is at height zc in the origin frame, with `near`
// = ballNear(g, its disc coordinate, reach).
bool ballMissesNear(OGeo g, vec2 near, float zc, float reach, float from, float until) {
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
    if (near.y > 1.0) return true;
    float lret = returnParameter(g);
    if (!finite(hi - lo) || !(hi - lo < lret)) return false;
    float sg = sign(g.e);
    float d1 = near.x + sg * 2.0 * PI * lo / lret;
    float d2 = near.x + sg * 2.0 * PI * hi / lret;
    float dmin = min(d1, d2), dmax = max(d1, d2);
    if (ceil(dmin / (2.0 * PI)) * 2.0 * PI <= dmax) return false;
    float c1 = cosA(d1 - 2.0 * PI * floor(d1 / (2.0 * PI) + 0.5));
    float c2 = cosA(d2 - 2.0 * PI * floor(d2 / (2.0 * PI) + 0.5));
    return max(c1, c2) < near.y;
}

// Whether the closed-form ray g from the origin, over λ ∈ [from, until], stays farther than
// the reach from the static ball whose centre is (wc, zc) in the origin frame.
bool ballMisses(OGeo g, vec2 wc, float zc, float reach, float from, float until) {
    return ballMissesNear(g, ballNear(g, wc, reach), zc, reach, from, until);
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
// cw, cz: the ball's centre or the plane's height in the ray's origin frame (oCw, oCz);
// near: a ball's ballNear for the ray (oNear).
bool missesAt(int i, OGeo g, vec2 cw, float cz, vec2 near, float from, float until) {
    if (!godel()) return false;
    if (isRest(i)) return ballMissesNear(g, near, cz, reachOf(i), from, until);
    if (isPlane(i)) return planeMisses(g, cz, from, until);
    return false;
}
bool objectMisses(int i, OGeo g, float from, float until) { return missesAt(i, g, oCw[i], oCz[i], oNear[i], from, until); }

// Which objects a ray from the place of `from` (whose origin-frame closed form is g),
// searched over λ ∈ [0, until], may meet: sets searched (object `skip`: only if it may also
// over [0, skipUntil]), oCw, oCz and oNear; whether any.
bool setSearched(vec4 from, OGeo g, float until, int skip, float skipUntil) {
    bool any = false;
    for (int i = 0; i < N_OBJECTS; i++) {
        vec2 cw = vec2(0.0), near = vec2(0.0);
        float cz = 0.0;
        if (isRest(i)) {
            vec4 c = applyIso(toOrigin(vec4(0.0, from.yzw)), objs[i].pos);
            cw = disc(c.yz);
            cz = c.w;
            if (godel()) near = ballNear(g, cw, reachOf(i));
        } else if (isPlane(i)) {
            cz = objs[i].pos.w - from.w;
        }
        bool s = objs[i].kind >= 0 && !missesAt(i, g, cw, cz, near, 0.0, until)
            && (i != skip || !missesAt(i, g, cw, cz, near, 0.0, skipUntil));
        storeSearched(i, s, cw, cz, near);
        any = any || s;
    }
    return any;
}
