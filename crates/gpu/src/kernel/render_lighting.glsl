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
int firstRoot(vec4 prev, vec4 g, vec4 cellNo, int offset, int count, bool atJoin) {
    vec4 change = vec4(lessThan(prev, vec4(0.0))) * vec4(greaterThan(g, vec4(0.0)))
                + vec4(greaterThan(prev, vec4(0.0))) * vec4(lessThan(g, vec4(0.0)));
    vec4 join = atJoin ? vec4(equal(cellNo, vec4(float(SHADOW_GRID)))) : vec4(0.0);
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

// G at four grid points u of cell numbers cellNo, and at ψ, of the current winding and branch:
// Gödel's (shadowG4, shadowG) or a member's (typeShadowExcess4, typeShadowExcess).
vec4 lightG4(vec4 u, vec4 cellNo) {
#ifdef MEMBER
    return typeShadowExcess4(MB, shadow.rho, shadow.zp, shadow.cmax, u, shadow.n, shadow.inbound);
#endif
    return shadowG4(shadow.rho, shadow.zp, u, cellNo, shadow.n, shadow.inbound);
}
float lightG(float psi) {
#ifdef MEMBER
    return typeShadowExcess(MB, shadow.rho, shadow.zp, shadow.psiMin, psi, shadow.n, shadow.inbound);
#endif
    return shadowG(psi, shadow.n, shadow.inbound);
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
        // (The hit's local description is surface()'s, made once per hit.)
        vec4 kl = restFrameVector(kLight), kv = restFrameVector(view);
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

#ifdef MEMBER
// A member's light (spacetime::godel_type_connect, render_lighting_family): the source's
// isometry back from its axis frame, and the lowest |c| of the returning-only branches. There
// shadow.rho is the hit's Gödel-like radius R_P and shadow.s unused.
TIso lightBack = NO_TISO;
float lightCesc = 0.0;

// lightGeometry's in a member (type_shadow_rays_within): no ray where σ_min = Ω|ζ_P| ≥ 1 or
// the hit lies on the source's worldline; windings up to ⌈(max_past + δ)/T_min⌉ + 1, δ the
// isometry's shift of the hit's time, T_min = π/(Ω + √max(0, Ω² − m²/4)).
bool memberLightGeometry() {
    TIso to = typeToOrigin(MB, shadow.source);
    lightBack = typeInverseIso(to);
    shadow.p = typeApplyIso(MB, to, hp.x);
    shadow.zp = shadow.p.w;
    vec4 reach = typeShadowReach(MB, shadow.p);
    if (!(reach.y < 1.0) || (reach.x == 0.0 && shadow.zp == 0.0)) return false;
    shadow.rho = reach.x;
    shadow.cmax = reach.z;
    shadow.psiMin = atan2s(reach.y, reach.z);
    lightCesc = reach.w;
    float tmin = PI / (MEMBER_OMEGA + sqrt(max(MEMBER_DELTA, 0.0)));
    int windings = toInt(ceil((shadow.p.x - hp.x.x + u_max_past) / tmin), 0, MAX_WINDINGS) + 1;
    shadow.cells = shadow.zp == 0.0 ? 1 : SHADOW_GRID;
    shadow.total = (windings + 1) * 2 * shadow.cells;
    return true;
}
#endif

// Light shadow.light's geometry for the hit: the source's isometry, the hit in the source's frame,
// the grid's size; false when no ray of it can count. A function of shadow.light and the hit alone
// (a round that resumes a light makes it again).
bool lightGeometry() {
    float a = u_a;
    vec4 lt = tableTexel(OBJECT_TEXELS * N_OBJECTS + LIGHT_TEXELS * shadow.light);
    shadow.source = vec4(0.0, lt.xyz);
    shadow.power = lt.w;
#ifdef MEMBER
    return memberLightGeometry();
#endif
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
    float clo = 0.0;   // the lowest |c| of the branch
#ifdef MEMBER
    // On the source's axis (R_P = 0) the outbound branch of winding n is the inbound one of
    // n − 1, and the straight ray along z counts no light (its D² is not defined: the CPU drops
    // it): the outbound branches are skipped. A branch whose c_lo is not below c_max has no ray.
    if (shadow.rho == 0.0 && !shadow.inbound) {
        shadow.idx += shadow.cells - cell + 1;
        return false;
    }
    if (shadow.zp != 0.0) {
        clo = shadow.n == 0 && !shadow.inbound ? 0.0 : lightCesc;
        if (clo >= shadow.cmax) {
            shadow.idx += shadow.cells - cell + 1;
            return false;
        }
    }
#endif
    if (shadow.zp == 0.0) {
        shadow.idx++;
        shadow.psi = 0.5 * PI;
        shadow.iter = -1;
        return true;
    }
    // The grid's point before the pass's first cell and G there, made again in every pass
    // (never carried from the last): a pass that a later round resumes starts from the same
    // values as one that follows its predecessor in the same round. The grid runs in |c|
    // from clo to c_max (Gödel: from 0, where G = −|z_P|).
    float span = shadow.cmax - clo;
    shadow.u0 = clo + span * float(cell - 1) / float(SHADOW_GRID);
    shadow.g0 = cell == 1 && !member()
        ? -abs(shadow.zp)
        : lightG4(vec4(shadow.u0), vec4(float(cell - 1))).x;
    // Sixteen cells per pass, in four groups written out (each pass of a loop counts
    // against llvmpipe's limit).
    int count = min(CELLS_PER_PASS, shadow.cells - cell + 1);
    vec4 base = float(cell) + vec4(0.0, 1.0, 2.0, 3.0);
    vec4 us[4] = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    vec4 gs[4] = us;
    us[0] = clo + span * base / float(SHADOW_GRID);
    us[1] = clo + span * (base + 4.0) / float(SHADOW_GRID);
    us[2] = clo + span * (base + 8.0) / float(SHADOW_GRID);
    us[3] = clo + span * (base + 12.0) / float(SHADOW_GRID);
    gs[0] = lightG4(us[0], base);
    gs[1] = lightG4(us[1], base + 4.0);
    gs[2] = lightG4(us[2], base + 8.0);
    gs[3] = lightG4(us[3], base + 12.0);
    // (A member's exact zero at the join of the branches counts once, as on the CPU, except
    // on the axis, whose outbound branches are skipped.)
    bool join = shadow.inbound && (!member() || shadow.rho > 0.0);
    int found = min(min(firstRoot(vec4(shadow.g0, gs[0].xyz), gs[0], base, 0, count, join),
                        firstRoot(vec4(gs[0].w, gs[1].xyz), gs[1], base + 4.0, 4, count, join)),
                    min(firstRoot(vec4(gs[1].w, gs[2].xyz), gs[2], base + 8.0, 8, count, join),
                        firstRoot(vec4(gs[2].w, gs[3].xyz), gs[3], base + 12.0, 12, count, join)));
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
    // (A member's G is INF where a branch's λ runs off to infinity: then bisection.)
    bool secant = shadow.fhi != shadow.flo && finite(shadow.fhi) && finite(shadow.flo);
    float m = secant ? (shadow.lo * shadow.fhi - shadow.hi * shadow.flo) / (shadow.fhi - shadow.flo) : 0.5 * (shadow.lo + shadow.hi);
    if (!finite(m) || !(m > shadow.lo && m < shadow.hi)) m = 0.5 * (shadow.lo + shadow.hi);
    shadow.psi = m;
    float fm = lightG(m);
    shadow.iter++;
    if (fm == 0.0 || shadow.hi - shadow.lo <= 4.0 * 1.1920929e-7 * max(shadow.hi, 1e-30) || shadow.iter >= REFINE_STEPS) return true;
    if ((fm > 0.0) == (shadow.fhi > 0.0)) { shadow.hi = m; shadow.fhi = fm; if (shadow.side == 1) shadow.flo *= 0.5; shadow.side = 1; }
    else { shadow.lo = m; shadow.flo = fm; if (shadow.side == -1) shadow.fhi *= 0.5; shadow.side = -1; }
    return false;
}

// The ray of root shadow.psi (spacetime::connect): 0 when it does not count, 1 when it counts
// unoccluded (shadow.weight), 2 when its occlusion must be searched (the search is set up).
#ifdef MEMBER
// shadowRaySetUp's in a member (type_shadow_rays_within, render::lighting): the root's λ (none:
// a branch without it), its ray from the source's axis frame carried back (the sphere's cut
// included), dropped where emitted before the window; incidence, D², and the occlusion search
// over equal segments of at most ClosedForm::segment_length (E = 1 in the axis frame).
int memberShadowRaySetUp() {
    float lambda = typeShadowLambda(MB, shadow.rho, shadow.psiMin, shadow.psi, shadow.n, shadow.inbound);
    if (!(lambda >= 0.0)) return 0;
    vec4 em = vec4(0.0), tg = vec4(0.0), emission = vec4(0.0), tangent = vec4(0.0);
    typeShadowRay(MB, shadow.p, shadow.psi, lambda, em, tg);
    typeShadowRayBack(MB, lightBack, hp.x, lambda, em, tg, emission, tangent);
    if (emission.x < hp.x.x - u_max_past) return 0;
    // The closed form from the source's axis frame, started at the emission's time.
    Ray r = NO_RAY;
    TGeo g = typeOriginNull(MB, tg);
    if (!g.ok) return 0;
    r.tex = typeExactFromOrigin(MB, TIso(-emission.x, lightBack.zeta0, lightBack.z0, lightBack.rot), g);
    r.geo.ok = true;
    r.lret = INF;
    vec4 xe = vec4(0.0), kEnd = vec4(0.0);
    rayAt(r, 0, lambda, xe, kEnd);
    vec2 inc = incidence(kEnd);
    if (!finite(inc.x) || !(inc.x > 0.0)) return 0;
    float d2 = typeAreaDistanceSq(MB, shadow.psi, lambda);
    if (!(d2 > 0.0 && finite(d2))) return 0;
    shadow.weight = shadow.power * inc.y * inc.y * inc.x / (4.0 * PI * d2);
    float end = lambda * (1.0 - END_CUT);
    float lret = memberReturn(g);
    float step_ = MEMBER_STEP;   // / |E|, E = 1
    float seg = lret < INF ? lret / max(float(EXACT_SEGMENTS), ceil(lret / step_)) : step_;
    int segs = toInt(ceil(end / seg), 1, MAX_SEGMENTS);
    float last = end * float(segs - 1) / float(segs);
    if (!setSearched(shadow.source, r.geo, end, hp.target, last)) return 1;
    startLongSearch(r, segs, end, -1.0, false, -INF);
    plan.skipObj = hp.target;
    plan.skipSeg = segs - 1;
    return 2;
}
#endif

int shadowRaySetUp() {
#ifdef MEMBER
    return memberShadowRaySetUp();
#endif
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
    // The falling balls' windows take the shift a return (its search, from the ray's start,
    // takes no loop copies).
    r.shift = returnShift(r.geo);
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
    startAim();
    return 2;
}

