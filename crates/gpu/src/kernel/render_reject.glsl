// ---------------------------------------------------------------------------------------
// Whole-ray rejection of balls at rest and planes (render::reject, docs/physics.md
// "Whole-ray rejection"): it only drops searches that could not find a crossing.

// The hyperbolic distance of the disc point w from the disc's centre (|w| kept below 1).
float discDistance(vec2 w) { return 2.0 * u_a * atanh_(min(length(w), 0.9999999)); }

// The ray's circle about a ball at rest whose centre has the disc coordinate wc in the origin
// frame of the closed-form ray g: the angle offset α₀ − arg(m_C) of δ(λ) (below), the distance
// d_hC from the circle's centre to the ball's and the circle's radius ρ.
vec3 ballCircle(OGeo g, vec2 wc) {
    float a = u_a;
    float sg = sign(g.e);
    vec2 dir = vec2(-sg * g.cchi.y, sg * g.cchi.x);
    float big = asinh_(g.rmax / (2.0 * a));
    vec2 h = dir * halfTanh(g.rmax / (2.0 * a));
    vec2 mc = cdiv(wc - h, vec2(1.0, 0.0) - cmul(conj2(h), wc));
    return vec3(carg(-h) - carg(mc), discDistance(mc), a * big);
}

// The part of a static ball's test that depends on the ray alone, made once per ray: x, the
// angle offset α₀ − arg(m_C) of δ(λ) = α₀ + sgn(E)·2πλ/λ_ret − arg(m_C); y, the least cos δ at
// which the ray's circle comes within the reach (above 1: it never does; below −1: all round),
// from the law of cosines cosh(d_H/a) = cosh(d_hC/a)·cosh(ρ/a) − sinh(d_hC/a)·sinh(ρ/a)·cos δ;
// z and w, that law's two terms cosh(d_hC/a)·cosh(ρ/a) and sinh(d_hC/a)·sinh(ρ/a) (w = 0 where
// the circle's far side is beyond the reach: unused).
vec4 ballNear(OGeo g, vec2 wc, float reach) {
    float a = u_a;
    vec3 circle = ballCircle(g, wc);
    float offset = circle.x, dhc = circle.y, rho = circle.z;
    if (abs(dhc - rho) > reach) return vec4(offset, 2.0, 0.0, 0.0);
    float x = dhc / a, y = rho / a;
    float ss = sinh(x) * sinh(y);
    float cc = cosh(x) * cosh(y);
    float c = cc - cosh(reach / a);
    // ss = 0: d_H does not depend on δ (the centre on the circle's centre, or a ray along z).
    float cosMin = ss > 0.0 ? c / ss : (c > 0.0 ? 2.0 : -2.0);
    return vec4(offset, cosMin, cc, ss);
}

// Whether the closed-form ray g from the origin, over λ ∈ [from, until], stays farther than
// the reach from the static ball whose centre is at height zc in the origin frame, with `near`
// = ballNear(g, its disc coordinate, reach) (render::circle::Stretches::meets): where the
// height differs by at least Δz over the window, the circle must come within √(reach² − Δz²)
// on the disc (the static distance is √(d_H² + Δz²)).
bool ballMissesNear(OGeo g, vec4 near, float zc, float reach, float from, float until) {
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
    // The least |Δz| over [lo, hi] (z is linear in λ), and the least cos δ for the disc
    // distance √(reach² − Δz²) (f32: reach is widened far beyond Δz's rounding).
    float z0 = g.pz * lo - zc, z1 = g.pz * hi - zc;
    float dz = (z0 > 0.0) != (z1 > 0.0) ? 0.0 : min(abs(z0), abs(z1));
    float cosMin = near.y;
    if (dz > 0.0 && near.w > 0.0) {
        float m = sqrt(max(reach * reach - dz * dz, 0.0));
        cosMin = max(cosMin, (near.z - cosh(m / u_a)) / near.w);
        if (cosMin > 1.0) return true;
    }
    float sg = sign(g.e);
    float d1 = near.x + sg * 2.0 * PI * lo / lret;
    float d2 = near.x + sg * 2.0 * PI * hi / lret;
    float dmin = min(d1, d2), dmax = max(d1, d2);
    if (ceil(dmin / (2.0 * PI)) * 2.0 * PI <= dmax) return false;
    float c1 = cosA(d1 - 2.0 * PI * floor(d1 / (2.0 * PI) + 0.5));
    float c2 = cosA(d2 - 2.0 * PI * floor(d2 / (2.0 * PI) + 0.5));
    return max(c1, c2) < cosMin;
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

// The reach of a ball at rest whose centre has the disc coordinate cw in the ray's origin
// frame (render::reject::reach, R·(1 + 0.25·(R/a)²) + 10⁻⁶·a), widened by the rounding of f32
// coordinates there: 10⁻⁴·a, and the disc's own, whose distances 2a·atanh|w| lose
// ~2a·ε/(1 − |w|²) far out.
float reachOf(int i, vec2 cw) {
    float r = objs[i].radius;
    float nw = max(1.0 - dot(cw, cw), 1e-30);
    return r * (1.0 + REST_REACH_CURVATURE * (r / u_a) * (r / u_a)) + REACH_PER_A * u_a + 1e-4 * u_a + 1e-6 * u_a / nw;
}

// Whether the searched ray g stays clear of object i (a ball at rest or a plane, Gödel's
// universe) over λ ∈ [from, until]; false when unsure or for other objects.
// cw, cz: the ball's centre or the plane's height in the ray's origin frame (oCw, oCz);
// near: a ball's ballNear for the ray (oNear).
bool missesAt(int i, OGeo g, vec2 cw, float cz, vec4 near, float from, float until) {
    if (!godel()) return false;
    if (isRest(i)) return ballMissesNear(g, near, cz, reachOf(i, cw), from, until);
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
        vec2 cw = vec2(0.0);
        vec4 near = vec4(0.0);
        float cz = 0.0;
        if (isRest(i)) {
            vec4 c = applyIso(toOrigin(vec4(0.0, from.yzw)), objs[i].pos);
            cw = disc(c.yz);
            cz = c.w;
            if (godel()) near = ballNear(g, cw, reachOf(i, cw));
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

// Aimed occlusion (render::circle::Stretches::deepest, render::lighting::aimed; docs/physics.md
// "Aimed occlusion"): where a shadow ray most likely passes deepest into a ball at rest, on each
// copy of its arc about the ball (at most MAX_AIMS, earliest first), one probe tells whether it
// is inside there; a ray that starts outside has then crossed the surface before: blocked.
// A ball's arc for that: the first copy's centre c0 (λ from the ray's start), the arc's half
// width in λ, the law of cosines' nearest and spread terms, the λ window [lo, hi] of its
// heights, and the copies to aim at (none where the ray starts within the reach, or where the
// arc is not apart from the rest of the circle).
struct AimBall { float c0; float halfWidth; float nearest; float spread; float lo; float hi; int copies; };
const AimBall NO_AIM_BALL = AimBall(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0);

// Ball i at rest (centre wc, zc in the origin frame of g, `near` its ballNear for g), for the
// ray over λ ∈ [0, until].
AimBall aimBall(int i, OGeo g, vec2 wc, vec4 near, float zc, float until) {
    AimBall b = NO_AIM_BALL;
    float reach = reachOf(i, wc);
    // The ray starts outside: its start, the origin, lies beyond the reach.
    float d0 = length(vec2(discDistance(wc), zc));
    if (!(d0 > reach)) return b;
    b.nearest = near.z;
    b.spread = near.w;
    float cosMin = near.y;
    if (!(b.spread > 0.0 && cosMin > -1.0 && cosMin < 1.0)) return b;
    float lret = returnParameter(g), w = 2.0 * PI / lret;
    b.halfWidth = acosA(cosMin) / w;
    b.lo = 0.0;
    b.hi = until;
    if (g.pz == 0.0) {
        if (abs(zc) > reach) return b;
    } else {
        float l1 = (zc - reach) / g.pz, l2 = (zc + reach) / g.pz;
        b.lo = max(min(l1, l2), 0.0);
        b.hi = min(max(l1, l2), until);
    }
    // δ(λ) = offset + sgn(E)·ωλ vanishes at the copies' centres base + kλ_ret.
    float base = -sign(g.e) * near.x / w;
    float k0 = ceil((b.lo - b.halfWidth - base) / lret), k1 = floor((b.hi + b.halfWidth - base) / lret);
    if (!(b.lo <= b.hi && finite(k0) && finite(k1) && k1 >= k0)) return b;
    b.c0 = base + k0 * lret;
    b.copies = toInt(k1 - k0 + 1.0, 0, MAX_AIMS);
    return b;
}

// The λ where the ray most likely passes deepest into the ball on copy k of its arc: the least
// of D² ≈ d₀² + a²·S·ω²·(λ − λ_c)² + (p_z λ − z_C)², kept within the arc and [lo, hi]; −1 where
// the law of cosines puts it no deeper than the radius there.
float aimAt(AimBall b, OGeo g, float zc, float radius, int k) {
    float lret = returnParameter(g), w = 2.0 * PI / lret;
    float centre = b.c0 + float(k) * lret;
    float l = centre;
    float pz2 = g.pz * g.pz, ks = u_a * u_a * b.spread * w * w;
    if (pz2 > 0.0) l = (ks * centre + pz2 * (zc / g.pz)) / (ks + pz2);
    l = min(max(min(max(l, centre - b.halfWidth), centre + b.halfWidth), b.lo), b.hi);
    float dh = u_a * acosh_(max(b.nearest - b.spread * cosA(w * (l - centre)), 1.0));
    return length(vec2(dh, g.pz * l - zc)) < radius ? l : -1.0;
}
