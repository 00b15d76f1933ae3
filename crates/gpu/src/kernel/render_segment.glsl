// ---------------------------------------------------------------------------------------
// The ray: a closed form carried back from the origin by the observer's isometry (Gödel and
// the Gödel-type family; "Closed forms", "Isometries", "The exact tracer in the family"), or
// a straight line (Minkowski), with loop copies shifted in t and z (render::segment,
// docs/physics.md "The intersection search").

struct Ray {
    Iso back;     // from the origin frame to the scene's coordinates (times relative)
    OGeo geo;     // Gödel: the closed form in the origin frame (a member: only .ok is set)
    vec4 x0;      // Minkowski: start event
    vec4 k0;      // Minkowski: tangent; Gödel: the tangent at the start
    float lret;   // Gödel and a member's returning ray: return parameter (else INF)
    vec2 shift;   // (Δt, Δz) per loop
#ifdef MEMBER
    TExact tex;   // a member: the geodesic through the observer
    float h;      // a member: its segments' λ length (render::segment::ClosedForm::segment_length)
    int nseg;     // a member's returning ray: segments per loop (0: the ray escapes)
#endif
};
#ifdef MEMBER
const Ray NO_RAY = Ray(NO_ISO, NO_OGEO, vec4(0.0), vec4(0.0), 0.0, vec2(0.0), NO_TEXACT, 0.0, 0);
#else
const Ray NO_RAY = Ray(NO_ISO, NO_OGEO, vec4(0.0), vec4(0.0), 0.0, vec2(0.0));
#endif

// The ray's event and tangent at parameter l of loop j.
void rayAt(Ray r, int j, float l, out vec4 ev, out vec4 k) {
    ev = vec4(0.0); k = vec4(0.0);
#ifdef MEMBER
    texAt(r.tex, l, ev, k);
    ev += float(j) * vec4(r.shift.x, 0.0, 0.0, r.shift.y);
    return;
#endif
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

#ifdef MEMBER
// A member's return parameter π/√Λ, or INF where the ray escapes: Λ ≤ BOUNDARY_LAMBDA·Ω²E²
// counts as the boundary Λ = 0 (render::segment::family_return).
float memberReturn(TGeo g) {
    float spin = MEMBER_OMEGA * g.e;
    return g.lam > BOUNDARY_LAMBDA * spin * spin ? PI / sqrt(g.lam) : INF;
}

// A member's light ray through `at` with tangent k, `to` sending `at` to the origin: segments
// of at most MEMBER_STEP/|E| (light moves through the base and z at the proper speed |E|), at
// least EXACT_SEGMENTS a loop and a whole number of them to the return
// (render::segment::ClosedForm::segment_length); the shift of a loop from the geodesic at
// its return.
Ray memberRay(vec4 at, vec4 k, TIso to) {
    Ray r = NO_RAY;
    r.x0 = at;
    r.k0 = k;
    r.tex = typeExactThrough(MB, to, at, k, true);
    r.geo.ok = r.tex.origin.ok;
    r.lret = memberReturn(r.tex.origin);
    float step_ = MEMBER_STEP / abs(r.tex.origin.e);
    r.h = step_;
    r.nseg = 0;
    r.shift = vec2(0.0);
    if (r.lret < INF) {
        r.nseg = toInt(ceil(r.lret / step_), EXACT_SEGMENTS, MAX_COUNT_SEGMENTS);
        r.h = r.lret / float(r.nseg);
        // From the geodesic through the observer: on the sphere a loop may wind about the
        // pole's image, and its time then takes the cut's period too (texAt).
        vec4 e1 = vec4(0.0), k1 = vec4(0.0);
        texAt(r.tex, r.lret, e1, k1);
        r.shift = vec2(e1.x - at.x, e1.w - at.w);
    }
    return r;
}

// A member's ray at parameter λ from its start (λ ≥ 0): whole loops as copies.
void memberRayAt(Ray r, float lambda, out vec4 ev, out vec4 k) {
    ev = vec4(0.0); k = vec4(0.0);
    int j = r.lret < INF ? toInt(floor(lambda / r.lret), 0, MAX_COUNT_SEGMENTS) : 0;
    rayAt(r, j, lambda - float(j) * r.lret, ev, k);
}
#endif

// The ray through `at` with tangent `k` (Gödel: the exact geodesic; spacetime::ExactGeodesic;
// a member's: memberRay), `to` the isometry sending `at` to the origin (not Minkowski's; a
// member's has the base coordinate ζ0 in place of w0).
Ray makeRay(vec4 at, vec4 k, Iso to) {
#ifdef MEMBER
    return memberRay(at, k, TIso(to.t0, to.w0, to.z0, to.rot));
#endif
    Ray r = NO_RAY;
    r.x0 = at;
    r.k0 = k;
    r.back = Iso(0.0, vec2(0.0), 0.0, 0.0);
    r.geo.ok = true;
    r.lret = INF;
    r.shift = vec2(0.0);
    if (godel()) {
        r.geo = originGeodesic(pushIso(to, at, k));
        r.back = inverseIso(to);
        r.lret = returnParameter(r.geo);
        r.shift = returnShift(r.geo);
    }
    return r;
}


