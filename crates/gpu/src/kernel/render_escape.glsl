// ---------------------------------------------------------------------------------------
// Where a light ray of a causal Gödel-type member (m² ≥ 4Ω²: MEMBER_CAUSAL) is done
// (render::tracer::escape; docs/physics.md, "The exact tracer in the family" and "The GPU
// kernel in the family"): t falls along every past-directed ray, so once a ray is beyond every
// object, and will not come back before the time bound, it has escaped. Its distance from the
// observer's axis is the closed form's ρ in the observer's origin frame (the isometries move
// the base rigidly), which grows monotonically along an escaping ray and up to half its loop
// along a returning one; z = z_obs + p_z λ is monotone.
//
// The CPU bounds all objects at once, by their coordinate boxes over the trace's time window;
// the kernel bounds each object by itself, without the window, so that the page may fly the
// observer through time with the same kernel: its base distance from the observer's axis plus
// its reach (a ball at rest: REACH_PER_RADIUS radii; a falling ball: its start's distance
// plus the largest ρ of its orbit, which returns to its axis (the host refuses one that
// escapes) plus 1.25 γ radii, as render::falling; a coordinate sphere and a bounded plane by
// the chart's axis, ρ being the proper radius). A falling ball and an unbounded plane have no
// bounded z, a ball at rest and a sphere z ± their reach, a plane its height.
#if defined(MEMBER) && MEMBER_CAUSAL != 0
// farFrom: the first segment end of a returning ray's loop beyond `radius` (its loop's
// segments farFrom..nseg − farFrom lie beyond every object, as in every later loop: the CPU
// steps over them in one segment); nseg where none.
struct Escape { float radius; float zlo; float zhi; int farFrom; };
Escape esc = Escape(INF, -INF, INF, 0);

// The distance from the observer's axis of the ray r at the end of its segment k in its
// first loop (ρ in its origin frame).
float rhoAt(Ray r, int k) {
    vec4 e0 = vec4(0.0), k0 = vec4(0.0);
    tgeoAt(r.tex.origin, float(k) * r.h, e0, k0);
    return length(e0.yz);
}

// The bounds for the current sample's observer (objects loaded) and its ray r.
void escapeSetUp(Ray r) {
    TIso to = TIso(0.0, u_obs_to.xy, u_obs_to.z, u_obs_to.w);
    float rhoObs = length(u_obs_x.xy);
    // render::tracer::escape's margin, and f32's rounding of the distances.
    float margin = 1e-3 * u_a + 1e-4 * (rhoObs + u_a);
    float radius = 0.0, zlo = INF, zhi = -INF;
    for (int i = 0; i < N_OBJECTS; i++) {
        if (objs[i].kind < 0) continue;
        float reach = INF, z0 = -INF, z1 = INF;
        float r = objs[i].radius;
        vec4 c = objs[i].pos;
        if (isRest(i)) {
            float own = REACH_PER_RADIUS * r;
            reach = length(typeApplyIso(MB, to, c).yz) + own;
            z0 = c.w - own;
            z1 = c.w + own;
        } else if (isCoordSphere(i)) {
            reach = rhoObs + length(c.yz) + r;
            z0 = c.w - r;
            z1 = c.w + r;
        } else if (isPlane(i)) {
            if (objs[i].extent > 0.0) reach = rhoObs + SQRT2 * objs[i].extent;
            z0 = c.w;
            z1 = c.w;
        } else if (isFree(i)) {
            float lret = memberReturn(objs[i].tex.origin);
            if (lret < INF) {
                vec4 e = vec4(0.0), k = vec4(0.0);
                tgeoAt(objs[i].tex.origin, 0.5 * lret, e, k);
                reach = length(typeApplyIso(MB, to, objs[i].start).yz) + length(e.yz)
                      + 1.25 * objs[i].gamma * r;
            }
        }
        radius = max(radius, reach);
        zlo = min(zlo, z0);
        zhi = max(zhi, z1);
    }
    esc = Escape(radius < INF ? radius + margin : INF, zlo - margin, zhi + margin, r.nseg);
    // ρ rises up to half the loop: the first segment end beyond the radius by bisection.
    int lo = 0, hi = r.nseg / 2;
    if (r.nseg > 0 && rhoAt(r, hi) > esc.radius) {
        for (int it = 0; it < 32; it++) {
            if (hi - lo <= 1) break;
            int mid = (lo + hi) / 2;
            if (rhoAt(r, mid) > esc.radius) hi = mid; else lo = mid;
        }
        esc.farFrom = hi;
    }
}

// Whether a ray moving along z at rate pz is past the objects' z range at z, moving away.
bool beyondZ(float z, float pz) { return (pz > 0.0 && z > esc.zhi) || (pz < 0.0 && z < esc.zlo); }

// The pixel ray r at the end of its segment `done` (counted from its start), at event x: −2
// when it is done (in its first loop, or along an escaping ray:
// render::tracer::escape::EscapeStop::done); the stretch of the search to go on from where
// it is beyond every object in a loop's rising half, until that loop comes back (the CPU's
// far segment); −3 for an escaping ray that leaves the scenes' chart (mρ > MAX_M_RHO) near
// an unbounded plane it runs along: the CPU runs it to MAX_FAMILY_SEGMENTS and marks it out
// of work, f32 would overflow first; −1 otherwise.
int escapeStep(Ray r, int done, vec4 x, float tBound) {
    float pz = r.tex.origin.pz;
    int loop = r.nseg > 0 ? done / r.nseg : 0;
    int k = done - loop * r.nseg;
    if (loop == 0 || r.nseg == 0) {
        if (beyondZ(x.w, pz)) return -2;
        float rho = rhoAt(r, k);
        if (!(rho > esc.radius)) return r.nseg == 0 && sqrt(MEMBER_M2) * rho > MAX_M_RHO ? -3 : -1;
        if (r.nseg == 0) return -2;
        if (2 * k > r.nseg) return -1;
        vec4 back = vec4(0.0), kb = vec4(0.0);
        rayAt(r, 0, r.lret - float(k) * r.h, back, kb);
        if (back.x < tBound || beyondZ(back.w, pz)) return -2;
    } else if (k != esc.farFrom || 2 * k > r.nseg) {
        return -1;
    }
    int target = (loop * r.nseg + r.nseg - k) / EXACT_SEGMENTS;
    return target > done / EXACT_SEGMENTS ? target : -1;
}
#endif
