// ---------------------------------------------------------------------------------------
// The ray: a closed form carried back from the origin by the observer's isometry (Gödel;
// "Closed forms", "Isometries"), or a straight line (Minkowski), with loop copies shifted
// in t and z (render::segment, docs/physics.md "The intersection search").

struct Ray {
    Iso back;     // from the origin frame to the scene's coordinates (times relative)
    OGeo geo;     // Gödel: the closed form in the origin frame
    vec4 x0;      // Minkowski: start event
    vec4 k0;      // Minkowski: tangent; Gödel: the tangent at the start
    float lret;   // Gödel: return parameter
    vec2 shift;   // Gödel: (Δt, Δz) per loop
};
const Ray NO_RAY = Ray(NO_ISO, NO_OGEO, vec4(0.0), vec4(0.0), 0.0, vec2(0.0));

// The ray's event and tangent at parameter l of loop j.
void rayAt(Ray r, int j, float l, out vec4 ev, out vec4 k) {
    ev = vec4(0.0); k = vec4(0.0);
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

// The ray through `at` with tangent `k` (Gödel: the exact geodesic; spacetime::ExactGeodesic),
// `to` the isometry sending `at` to the origin (Gödel only).
Ray makeRay(vec4 at, vec4 k, Iso to) {
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
        float sg = sign(r.geo.e);
        r.shift = vec2(sg * 2.0 * SQRT2 * u_a * PI - r.geo.e * r.lret, r.geo.pz * r.lret);
    }
    return r;
}


