
// ---------------------------------------------------------------------------------------
// The Gödel-type family (docs/physics.md, "The Gödel-type family"; spacetime::godel_type_geodesic
// and spacetime::godel_type_symmetry): a member (m², Ω) as the pair `mb`, its closed-form
// geodesics through the origin and its isometries R_α ∘ T_P0 in the base coordinate
// ζ = G(m²ρ²)(x + iy), the geodesic through any event, and (in a member's kernel, MEMBER)
// parallel transport along it, integrated. Compiled only where FAMILY is defined: by the
// family's probes (crates/gpu/tests/integration/probes.rs holds each function to its Rust
// twin) and by the kernel of a member's scene.
#ifdef FAMILY

// The functions the closed forms and the base coordinate are built from, each with its
// series near 0 (where the quotient of two small floats would lose its digits) and the
// kernel's own trigonometry elsewhere. Series: asinh(s)/s = 1 − s²/6 + 3s⁴/40, the same in
// v = s² (v < 0: asin), atan(x)/x = 1 − x²/3 + x⁴/5, tanh(h)/h = 1 − h²/3 + 2h⁴/15 (tan: signs
// alternate the other way, the same in u = ±4h²), atanh(s)/s = 1 + s²/3 + s⁴/5 (v < 0: atan),
// sinh(x)/x and cosh x to x⁴: below the thresholds the first omitted term is at most 2.2e-9,
// but asinh's 5v³/112 < 5e-8, below one rounding of f32. Above them log and the quotient lose up
// to ULP/s relative (asinh_, atanh_ of a small s).
float asinhcF(float v) {
    if (abs(v) < 1e-2) return 1.0 + v * (-1.0 / 6.0 + v * (3.0 / 40.0));
    float s = sqrt(abs(v));
    return v > 0.0 ? asinh_(s) / s : asinA(s) / s;
}
float atancF(float x) {
    if (abs(x) < 1e-2) { float x2 = x * x; return 1.0 + x2 * (-1.0 / 3.0 + x2 * 0.2); }
    return atanA(x) / x;
}
// tanh(√u/2)/(√u/2) (tan for u < 0).
float halfTanhcF(float u) {
    float h = 0.5 * sqrt(abs(u));
    if (h < 0.05) { float w = 0.25 * u; return 1.0 + w * (-1.0 / 3.0 + w * (2.0 / 15.0)); }
    if (u > 0.0) { float e2 = exp(-2.0 * h); return (1.0 - e2) / ((1.0 + e2) * h); }
    vec2 cs = cis(h);
    return cs.y / (cs.x * h);
}
// atanh(√v)/√v (atan for v < 0).
float atanhcF(float v) {
    float s = sqrt(abs(v));
    if (s < 0.05) return 1.0 + v * (1.0 / 3.0 + v * 0.2);
    return v > 0.0 ? atanh_(s) / s : atanA(s) / s;
}
// sinh(x)/x and cosh x, for the escaping regime.
vec2 sinhcCoshF(float x) {
    if (abs(x) < 0.1) { float x2 = x * x; return vec2(1.0 + x2 * (1.0 / 6.0 + x2 / 120.0), 1.0 + x2 * (0.5 + x2 / 24.0)); }
    float e = exp(x), ei = 1.0 / e;
    return vec2(0.5 * (e - ei) / x, 0.5 * (e + ei));
}

// The closed form through the origin with tangent k = (E, k⊥ cos χ, k⊥ sin χ, p_z)
// (spacetime::TypeOriginGeodesic): Λ = Ω²E² − m²k⊥²/4 sets the regime (> 0 returning after
// π/√Λ; ≤ 0 escaping).
struct TGeo { vec2 mb; float e; float pz; float kappa; float kperp; float lam; vec2 cchi; bool ok; };
const TGeo NO_TGEO = TGeo(vec2(0.0), 0.0, 0.0, 0.0, 0.0, 0.0, vec2(1.0, 0.0), false);

// Ω² − m²/4: in a member's kernel the host's, made in f64 (where m² = 4Ω² f32's difference
// would be rounding, and its sign decides which rays escape).
float typeDelta(vec2 mb) {
#ifdef MEMBER
    return MEMBER_DELTA;
#else
    return mb.y * mb.y - 0.25 * mb.x;
#endif
}

// Λ = Ω²E² − m²k⊥²/4 as Ω²(κ + p_z²) + (Ω² − m²/4)k⊥² (E² = k⊥² + p_z² + κ): no
// cancellation between terms of size Ω²E² where Λ is small.
float typeBigLambda(TGeo g) {
    return g.mb.y * g.mb.y * (g.kappa + g.pz * g.pz) + typeDelta(g.mb) * g.kperp * g.kperp;
}

TGeo typeOriginGeodesic(vec2 mb, vec4 k) {
    TGeo g = NO_TGEO;
    float e = k.x;
    float kp2 = dot(k.yz, k.yz);
    float kappa = e * e - kp2 - k.w * k.w;
    g.ok = finite(e) && finite(kp2) && finite(k.w) && e != 0.0 && kappa >= -1e-4 * e * e
        && mb.y > 0.0 && finite(mb.y) && finite(mb.x);
    g.mb = mb;
    g.e = e;
    g.pz = k.w;
    g.kappa = max(kappa, 0.0);
    g.kperp = sqrt(kp2);
    g.cchi = g.kperp > 0.0 ? k.yz / g.kperp : vec2(1.0, 0.0);
    g.lam = typeBigLambda(g);
    return g;
}

// The same for a light ray: κ = 0 exactly (its rounding in f32 would shift Λ by Ω²·ε E²).
TGeo typeOriginNull(vec2 mb, vec4 k) {
    TGeo g = typeOriginGeodesic(mb, k);
    g.kappa = 0.0;
    g.lam = typeBigLambda(g);
    return g;
}

// π/√Λ, or −1 for a geodesic that escapes.
float typeReturnParameter(TGeo g) { return g.lam > 0.0 ? PI / sqrt(g.lam) : -1.0; }

// C1, S1, Φ (continuous in λ) and J = ∫ S1²/(1 + v) dλ at λ (spacetime's `parts`, with J's
// cancellation-free form where Λ > 0 and c/Λ ≤ 1).
vec4 typeParts(TGeo g, float lambda) {
    float spin = g.mb.y * abs(g.e);
    float c = 0.25 * g.mb.x * g.kperp * g.kperp;
    if (g.lam > 0.0) {
        float r = sqrt(g.lam);
        float th = r * lambda;
        vec2 cs = cis(th);
        float sn = cs.y, co = cs.x;
        float turn = th + atan2s((spin - r) * sn * co, r * co * co + spin * sn * sn);
        float eps = c / g.lam;
        float j = 0.0;
        if (eps <= 1.0) {
            float q = spin / r;
            float z = sn * co / ((1.0 + q) * (co * co + q * sn * sn));
            float bigK = (th / (1.0 + q) - z * atancF(eps * z)) / q;
            j = bigK / (g.lam * r);
        } else {
            j = (lambda - turn / spin) / c;
        }
        return vec4(co, sn / r, turn, j);
    }
    float c1 = 1.0, s1 = lambda;
    if (g.lam < 0.0) {
        float r = sqrt(-g.lam);
        vec2 sc = sinhcCoshF(r * lambda);
        c1 = sc.y;
        s1 = sc.x * lambda;
    }
    float turn = atanA(spin * s1 / c1);
    return vec4(c1, s1, turn, (lambda - turn / spin) / c);
}

// Event and tangent at λ.
void tgeoAt(TGeo g, float lambda, out vec4 ev, out vec4 tan_) {
    ev = vec4(0.0); tan_ = vec4(0.0);
    float e = g.e, w2 = g.mb.y * g.mb.y;
    float a = g.kperp * g.kperp;
    vec4 p = typeParts(g, lambda);
    float v = 0.25 * g.mb.x * a * p.y * p.y;
    float rho = g.kperp * p.y * asinhcF(v);
    vec2 cb = cis(sign(e) * p.z);
    vec2 cp = cmul(g.cchi, cb);
    ev = vec4(e * lambda - w2 * e * a * p.w, rho * cp, g.pz * lambda);
    float oneV = 1.0 + v;
    float drho = g.kperp * p.x / sqrt(oneV);
    float rhoDphi = rho * g.mb.y * e / oneV;
    tan_ = vec4(e - w2 * e * a * p.y * p.y / oneV, drho * cp + rhoDphi * vec2(-cp.y, cp.x), g.pz);
}

// The base coordinate, its inverse and their differentials (spacetime::godel_type_symmetry).
vec2 baseCoordinate(vec2 mb, vec2 xy) { return halfTanhcF(mb.x * dot(xy, xy)) * xy; }
vec2 fromBaseCoordinate(vec2 mb, vec2 zeta) { return atanhcF(0.25 * mb.x * dot(zeta, zeta)) * zeta; }
vec2 baseDifferential(vec2 mb, vec2 xy, vec2 d) {
    float r2 = dot(xy, xy);
    if (r2 == 0.0) return d;
    float g = halfTanhcF(mb.x * r2);
    float stretch = 1.0 - 0.25 * mb.x * g * g * r2;
    return g * d + (stretch - g) * dot(xy, d) / r2 * xy;
}
vec2 fromBaseDifferential(vec2 mb, vec2 zeta, vec2 dzeta) {
    float n = dot(zeta, zeta);
    if (n == 0.0) return dzeta;
    float v = 0.25 * mb.x * n;
    float f = atanhcF(v);
    return f * dzeta + (1.0 / (1.0 - v) - f) * dot(zeta, dzeta) / n * zeta;
}

// χ = (Ω/k) arg(1 − k ζ̄0 ζ), accurate as k → 0.
float typeTimeShift(vec2 mb, vec2 zeta0, vec2 zeta) {
    float k = 0.25 * mb.x;
    vec2 p = cmul(conj2(zeta0), zeta);
    float d = 1.0 - k * p.x;
    if (d > 0.0) return -mb.y * p.y / d * atancF(k * p.y / d);
    return mb.y / k * atan2s(-k * p.y, d);
}

// R_rot ∘ T_P0, P0 = (t0, ζ0, z0).
struct TIso { float t0; vec2 zeta0; float z0; float rot; };
const TIso NO_TISO = TIso(0.0, vec2(0.0), 0.0, 0.0);

TIso typeToOrigin(vec2 mb, vec4 p) { return TIso(p.x, baseCoordinate(mb, p.yz), p.w, 0.0); }
TIso typeInverseIso(TIso m) { return TIso(-m.t0, -cmul(cis(m.rot), m.zeta0), -m.z0, -m.rot); }

// The image of the event `at` and of the vector v there.
void typeApplyPush(vec2 mb, TIso m, vec4 at, vec4 v, out vec4 e, out vec4 k) {
    e = vec4(0.0); k = vec4(0.0);
    if (m.zeta0 == vec2(0.0) && m.rot == 0.0) {
        e = vec4(at.x - m.t0, at.yz, at.w - m.z0);
        k = v;
        return;
    }
    float kc = 0.25 * mb.x;
    vec2 zeta = baseCoordinate(mb, at.yz);
    vec2 den = vec2(1.0, 0.0) - kc * cmul(conj2(m.zeta0), zeta);
    vec2 rot = cis(m.rot);
    vec2 zeta1 = cmul(rot, cdiv(zeta - m.zeta0, den));
    e = vec4(at.x - m.t0 - typeTimeShift(mb, m.zeta0, zeta), fromBaseCoordinate(mb, zeta1), at.w - m.z0);
    vec2 dzeta = baseDifferential(mb, at.yz, v.yz);
    float scale = 1.0 - kc * dot(m.zeta0, m.zeta0);
    vec2 dzeta1 = cmul(rot, cdiv(dzeta * scale, cmul(den, den)));
    float dt = v.x + mb.y * cdiv(cmul(conj2(m.zeta0), dzeta), den).y;
    k = vec4(dt, fromBaseDifferential(mb, zeta1, dzeta1), v.w);
}

// The geodesic through any event (spacetime::TypeExactGeodesic): the closed form through the
// origin mapped back by T⁻¹. On the sphere (m² < 0) the map back's principal time shift jumps
// by (Ω/k)·2π where the projection crosses its cut; the geodesic follows the continuous
// arg(α + β e^{iψ}) along its circle (ψ = 2 sgn(E) Φ), β = k ζ̄1·(the circle's centre).
struct TExact { TIso back; TGeo origin; vec2 alpha; vec2 beta; bool wound; };
const TExact NO_TEXACT = TExact(NO_TISO, NO_TGEO, vec2(1.0, 0.0), vec2(0.0), false);

#ifdef MEMBER
// The image of the vector v at `at` in the kernel's member.
vec4 typePush(TIso m, vec4 at, vec4 v) {
    vec4 e = vec4(0.0), k = vec4(0.0);
    typeApplyPush(MB, m, at, v, e, k);
    return k;
}
#endif

vec4 typeApplyIso(vec2 mb, TIso m, vec4 at) {
    vec4 e = vec4(0.0), k = vec4(0.0);
    typeApplyPush(mb, m, at, vec4(0.0), e, k);
    return e;
}

// The closed form g through the origin carried back by `back` (the sphere's continuous arg
// set up for it).
TExact typeExactFromOrigin(vec2 mb, TIso back, TGeo g) {
    vec2 beta = vec2(0.0);
    if (mb.x < 0.0 && g.ok) {
        float sg = sign(g.e);
        float r = g.kperp / (2.0 * mb.y * abs(g.e));
        vec2 centre = vec2(-sg * r * g.cchi.y, sg * r * g.cchi.x);
        beta = 0.25 * mb.x * cmul(conj2(back.zeta0), centre);
    }
    return TExact(back, g, vec2(1.0, 0.0) - beta, beta, mb.x < 0.0);
}

// The geodesic through `at` with tangent k, `to` the isometry sending `at` to the origin
// (the observer's is the host's, made in f64); `light`: k is null (typeOriginNull).
TExact typeExactThrough(vec2 mb, TIso to, vec4 at, vec4 k, bool light) {
    vec4 e0 = vec4(0.0), k0 = vec4(0.0);
    typeApplyPush(mb, to, at, k, e0, k0);
    TGeo g = typeOriginGeodesic(mb, k0);
    if (light) g = typeOriginNull(mb, k0);
    return typeExactFromOrigin(mb, typeInverseIso(to), g);
}

TExact typeExactGeodesic(vec2 mb, vec4 at, vec4 k) {
    return typeExactThrough(mb, typeToOrigin(mb, at), at, k, false);
}

// arg(α + β e^{iψ}) continued in ψ from 0 at ψ = 0 (α + β = 1): the term of larger modulus
// carries the winding.
float continuousArg(vec2 alpha, vec2 beta, float psi) {
    vec2 one = vec2(1.0, 0.0);
    if (dot(beta, beta) <= dot(alpha, alpha)) {
        vec2 r = cdiv(beta, alpha);
        return carg(one + cmul(r, cis(psi))) - carg(one + r);
    }
    vec2 r = cdiv(alpha, beta);
    return psi + carg(one + cmul(r, cis(-psi))) - carg(one + r);
}

void texAt(TExact g, float lambda, out vec4 ev, out vec4 tan_) {
    ev = vec4(0.0); tan_ = vec4(0.0);
    vec2 mb = g.origin.mb;
    vec4 e0 = vec4(0.0), k0 = vec4(0.0);
    tgeoAt(g.origin, lambda, e0, k0);
    typeApplyPush(mb, g.back, e0, k0, ev, tan_);
    if (g.wound) {
        float kk = 0.25 * mb.x;
        float psi = 2.0 * sign(g.origin.e) * typeParts(g.origin, lambda).z;
        float continuous = continuousArg(g.alpha, g.beta, psi);
        vec2 den = vec2(1.0, 0.0) - kk * cmul(conj2(g.back.zeta0), baseCoordinate(mb, e0.yz));
        float turns = floor((continuous - carg(den)) / (2.0 * PI) + 0.5);
        ev.x -= mb.y / kk * 2.0 * PI * turns;
    }
}

#ifdef MEMBER
// ---------------------------------------------------------------------------------------
// Parallel transport along a member's geodesic (docs/physics.md, "Polarization" and "The GPU
// kernel in the family"; the CPU integrates it with the ray, render::polarization): the
// family has no closed-form transport, so dW/dλ = −Γ(k, W) is integrated by RK4, the event
// and tangent from the closed form. A returning geodesic's later loops are its first one
// moved in t and z, which moves no component: over whole loops W goes by the first loop's
// transport matrix M, raised to the loops' power by squaring.

// Γ(k, w) for the four columns of w, with the metric's derivatives and inverse at the event.
mat4 columnsGamma(mat4 dX, mat4 dY, mat4 gi, vec4 k, mat4 w) {
    return mat4(christoffelWith(dX, dY, gi, k, w[0]), christoffelWith(dX, dY, gi, k, w[1]),
                christoffelWith(dX, dY, gi, k, w[2]), christoffelWith(dX, dY, gi, k, w[3]));
}

// The columns of w carried from λ = l0 to l1 in `steps` RK4 steps. The points of the steps'
// starts and midpoints, at half steps, are taken one per pass, each once (GLSL inlines every
// call site: one copy of the closed form and of the metric keeps the kernel small enough
// for every driver's compiler; softpipe's crashed on more).
mat4 typeTransportStretch(TExact g, float l0, float l1, int steps, mat4 w) {
    float h = (l1 - l0) / float(steps);
    mat4 d1 = mat4(0.0), d2 = mat4(0.0), d3 = mat4(0.0);
    for (int s = 0; s < 8193; s++) {
        if (s > 2 * steps) break;
        vec4 x = vec4(0.0), k = vec4(0.0);
        texAt(g, l0 + 0.5 * h * float(s), x, k);
        mat4 dX = mat4(0.0), dY = mat4(0.0);
        metricDerivatives(x, dX, dY);
        mat4 gi = inverseMetricAt(x);
        if (s % 2 == 1) {
            d2 = columnsGamma(dX, dY, gi, k, w - 0.5 * h * d1);
            d3 = columnsGamma(dX, dY, gi, k, w - 0.5 * h * d2);
        } else {
            if (s > 0) w -= h / 6.0 * (d1 + 2.0 * d2 + 2.0 * d3 + columnsGamma(dX, dY, gi, k, w - h * d3));
            d1 = columnsGamma(dX, dY, gi, k, w);
        }
    }
    return w;
}

// Steps for a stretch of parameter length `len` of a geodesic whose segments are `seg` long:
// eight a segment (RK4's error per loop then stays below 1e-6), at most 4096.
int typeTransportSteps(float len, float seg) {
    return toInt(ceil(8.0 * abs(len) / seg), 8, 4096);
}

// The columns of w carried from λ = 0 to `loops` whole loops of parameter `lret` (INF: the
// geodesic does not return) and then `within` more, the segments `seg` long.
mat4 typeTransport(TExact g, int loops, float within, float lret, float seg, mat4 w) {
    // One call of the stretch's integration (GLSL inlines each call site): the loop's matrix
    // first where whole loops are taken, then the stretch within.
    bool whole = loops != 0 && lret < INF;
    float dir = loops > 0 ? 1.0 : -1.0;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 0 && !whole) continue;
        float len = pass == 0 ? dir * lret : within;
        mat4 moved = typeTransportStretch(g, 0.0, len, typeTransportSteps(len, seg), pass == 0 ? mat4(1.0) : w);
        if (pass == 1) return moved;
        int n = loops > 0 ? loops : -loops;
        for (int bit = 0; bit < 24; bit++) {
            if (n == 0) break;
            if (n % 2 == 1) w = moved * w;
            moved = moved * moved;
            n /= 2;
        }
    }
    return w;
}
#endif

#endif
