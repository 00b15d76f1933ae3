
// ---------------------------------------------------------------------------------------
// The probe entry point (appended after the kernel, compiled with `#define PROBE PROBE_…` in
// place of the pixel kernel; docs/physics.md "The GPU kernel"): one fragment evaluates one
// group of the kernel's functions on the arguments of its texels of u_args, and writes the
// results to its first PROBE_SLOTS slots. crates/gpu/src/probe.rs is its host,
// crates/gpu/tests/integration/probes.rs holds each function to its Rust twin in f64.
#ifdef PROBE
#define PROBE_ELEMENTARY 1
#define PROBE_METRIC 2
#define PROBE_CHRISTOFFEL 3
#define PROBE_FRAME 4
#define PROBE_CAMERA 5
#define PROBE_ISOMETRY 6
#define PROBE_CLOSED_FORM 7
#define PROBE_TRANSPORT 8
#define PROBE_SHADOW 9
#define PROBE_REJECT 10
#define PROBE_SURFACE 11
#define PROBE_FAMILY 12
#define PROBE_FAMILY_EXACT 13
#define PROBE_FAMILY_SHADOW 14

uniform sampler2D u_args;   // RGBA32F: fragment (x, y) reads texels (x·ARG_TEXELS + j, y)
const int ARG_TEXELS = 4;

vec4 arg(int j) {
    ivec2 p = ivec2(gl_FragCoord.xy);
    return texelFetch(u_args, ivec2(p.x * ARG_TEXELS + j, p.y), 0);
}
float flag(bool b) { return b ? 1.0 : 0.0; }

void main() {
    for (int s = 0; s < slots.length(); s++) slots[s] = vec4(0.0);
    vec4 a0 = arg(0), a1 = arg(1), a2 = arg(2), a3 = arg(3);
#if PROBE == PROBE_ELEMENTARY
    // a0 = (x, y, x′, s) for atanA(x), atan2s(y, x′), asinA(s), acosA(s); a1.x an angle;
    // a1.yzw arguments of asinh_, acosh_ (≥ 1) and atanh_ (|·| < 1); a2 for atanA4, a3
    // (in [0, 1]) for asinA4, a1.y for halfTanh.
    slots[0] = vec4(atanA(a0.x), atan2s(a0.y, a0.z), asinA(a0.w), acosA(a0.w));
    slots[1] = vec4(cis(a1.x), sinA(a1.x), cosA(a1.x));
    slots[2] = atanA4(a2);
    slots[3] = asinA4(a3);
    slots[4] = vec4(asinh_(a1.y), acosh_(a1.z), atanh_(a1.w), halfTanh(a1.y));
#elif PROBE == PROBE_METRIC
    // g and g⁻¹ at the event a0, by columns.
    mat4 g = metricAt(a0), gi = inverseMetricAt(a0);
    slots[0] = g[0]; slots[1] = g[1]; slots[2] = g[2]; slots[3] = g[3];
    slots[4] = gi[0]; slots[5] = gi[1]; slots[6] = gi[2]; slots[7] = gi[3];
#elif PROBE == PROBE_CHRISTOFFEL
    // Γ(u, v) and Γ(u, u) at a0 for u = a1, v = a2; the normal-coordinate displacement of a1.
    slots[0] = christoffel(a0, a1, a2);
    slots[1] = christoffel(a0, a1, a1);
    slots[2] = normalDisplacement(a0, a1);
#elif PROBE == PROBE_FRAME
    // The static frame at a0, and it boosted to speed a1.x along the unit a1.yzw, by columns.
    mat4 f = staticFrame(a0);
    mat4 b = boostFrame(f, a1.x, a1.yzw);
    slots[0] = f[0]; slots[1] = f[1]; slots[2] = f[2]; slots[3] = f[3];
    slots[4] = b[0]; slots[5] = b[1]; slots[6] = b[2]; slots[7] = b[3];
#elif PROBE == PROBE_CAMERA
    // The camera direction at image position a0.xy (the camera in the uniforms), and whether
    // there is one.
    vec3 d = vec3(0.0);
    bool ok = cameraDirection(a0.xy, d);
    slots[0] = vec4(d, flag(ok));
#elif PROBE == PROBE_ISOMETRY
    // T = R_{a1.x} ∘ T_{a0}: its parameters, the image of the event a2 and the vector a3 under
    // it, its inverse's parameters and the image of (a2, a3) under the inverse.
    Iso to = toOrigin(a0);
    Iso m = Iso(to.t0, to.w0, to.z0, a1.x);
    vec4 e = vec4(0.0), k = vec4(0.0);
    applyPush(m, a2, a3, e, k);
    Iso inv = inverseIso(m);
    vec4 ie = vec4(0.0), ik = vec4(0.0);
    applyPush(inv, a2, a3, ie, ik);
    slots[0] = vec4(to.t0, to.w0, to.z0);
    slots[1] = e; slots[2] = k;
    slots[3] = vec4(inv.t0, inv.w0, inv.z0);
    slots[4] = vec4(inv.rot, 0.0, 0.0, 0.0);
    slots[5] = ie; slots[6] = ik;
#elif PROBE == PROBE_CLOSED_FORM
    // The closed form from the origin with tangent a0 at λ = a1.x: (ok, λ_ret, β(λ), the time's
    // deviation), the event and the tangent.
    OGeo g = originGeodesic(a0);
    vec4 ev = vec4(0.0), tan_ = vec4(0.0);
    ogeoAt(g, a1.x, ev, tan_);
    slots[0] = vec4(flag(g.ok), returnParameter(g), flowRotation(g, a1.x), timeDeviation(g));
    slots[1] = ev; slots[2] = tan_;
#elif PROBE == PROBE_TRANSPORT
    // The vector a2 at the origin transported along the closed form with tangent a0 to λ = a1.x
    // (as the second of two legs: its column is chosen and written back as a host's are).
    OGeo g = originGeodesic(a0);
    vec4 ev = vec4(0.0), tan_ = vec4(0.0);
    ogeoAt(g, a1.x, ev, tan_);
    slots[0] = transportLegs(g, a1.x, ev, mat4(vec4(0.0), a2, vec4(0.0), vec4(0.0)), 2)[1];
#elif PROBE == PROBE_SHADOW
    // For a target at ρ = a0.w = 2a·s (s = a1.x, the least angle reaching it ψ_min = a1.y, its
    // height z_P = a1.z; the light's set-up sets these): θ and G of the ray leaving at ψ = a0.x
    // to the z axis, winding a0.y, inbound where a0.z > ½, and G at the four |c| of a3 (the
    // last one the grid's last point, c_max); D² of the ray leaving the axis at (ψ, χ) = a2.xy,
    // ending at λ = a2.z; Φ(θ) for q = a1.w, θ = a2.w.
    shadow.s = a1.x;
    shadow.psiMin = a1.y;
    shadow.zp = a1.z;
    int n = toInt(a0.y, 0, MAX_WINDINGS);
    bool inbound = a0.z > 0.5;
    slots[0] = vec4(shadowTheta(a0.x, n, inbound), shadowG(a0.x, n, inbound),
                    areaDistanceSq(a2.x, a2.y, a2.z), bigPhi(a1.w, a2.w));
    slots[1] = shadowG4(a0.w, a1.z, a3, vec4(0.0, 1.0, 2.0, float(SHADOW_GRID)), n, inbound);
#elif PROBE == PROBE_REJECT
    // For the closed form from the origin with tangent a0 over λ ∈ [a2.x, a2.y]: whether it
    // misses the ball of centre (w, z) = (a1.xy, a1.z) and reach a1.w, and the plane z = a2.z;
    // and the ball's test without the height's part (the whole reach on the disc).
    OGeo g = originGeodesic(a0);
    vec4 near = ballNear(g, a1.xy, a1.w);
    slots[0] = vec4(flag(ballMisses(g, a1.xy, a1.z, a1.w, a2.x, a2.y)),
                    flag(planeMisses(g, a2.z, a2.x, a2.y)), flag(g.ok),
                    flag(ballMissesNear(g, vec4(near.xy, 0.0, 0.0), a1.z, a1.w, a2.x, a2.y)));
#elif PROBE == PROBE_SURFACE
    // The texture coordinates of the direction a0.xyz.
    slots[0] = vec4(lonLat(a0.xyz), 0.0, 0.0);
#elif PROBE == PROBE_FAMILY
    // In the member (m², Ω) = a1.yz (FAMILY is defined with this probe): the closed form from
    // the origin with tangent a0 at λ = a1.x: (ok, λ_ret or −1, Λ, 0), the event, the tangent;
    // T = R_{a1.w} ∘ T_{a2}: its (t0, ζ0, z0), the image of the event a3 and of the vector a0
    // there, and the same under its inverse.
    vec2 mb = a1.yz;
    TGeo g = typeOriginGeodesic(mb, a0);
    vec4 ev = vec4(0.0), tan_ = vec4(0.0);
    tgeoAt(g, a1.x, ev, tan_);
    slots[0] = vec4(flag(g.ok), typeReturnParameter(g), g.lam, 0.0);
    slots[1] = ev; slots[2] = tan_;
    TIso to = typeToOrigin(mb, a2);
    TIso m = TIso(to.t0, to.zeta0, to.z0, a1.w);
    vec4 e = vec4(0.0), k = vec4(0.0);
    typeApplyPush(mb, m, a3, a0, e, k);
    slots[3] = vec4(m.t0, m.zeta0, m.z0);
    slots[4] = e; slots[5] = k;
    vec4 ie = vec4(0.0), ik = vec4(0.0);
    typeApplyPush(mb, typeInverseIso(m), a3, a0, ie, ik);
    slots[6] = ie; slots[7] = ik;
#elif PROBE == PROBE_FAMILY_EXACT
    // In the member (m², Ω) = a1.yz: the geodesic through the event a2 with tangent a0 at
    // λ = a1.x: (ok, 0, 0, 0), the event and the tangent.
    TExact g = typeExactGeodesic(a1.yz, a2, a0);
    vec4 ev = vec4(0.0), tan_ = vec4(0.0);
    texAt(g, a1.x, ev, tan_);
    slots[0] = vec4(flag(g.origin.ok), 0.0, 0.0, 0.0);
    slots[1] = ev; slots[2] = tan_;
#elif PROBE == PROBE_FAMILY_SHADOW
    // In the member (m², Ω) = a1.xy, the shadow rays' pieces (render_lighting_family.glsl).
    vec2 mb = a1.xy;
    if (a1.z < 0.5) {
        // In the source's axis frame, for the target a0, the ray at ψ = a1.w to ±z of winding
        // a2.x, inbound where a2.y > ½: the reach (R, σ_min, c_max, c_esc); (λ, G, D² of the
        // ray at (ψ, λ) = a2.zw, ψ_min); the emission event and tangent of the ray at ψ with
        // that λ; the grid's |c| at the fractions a3 of [c_lo, c_max] (1: c_max exactly), λ and
        // G there (the ray's λ: |z_P| for the straight ray along the axis).
        vec4 reach = typeShadowReach(mb, a0);
        float psiMin = atan2s(reach.y, reach.z);
        int n = toInt(a2.x, 0, MAX_WINDINGS);
        bool inbound = a2.y > 0.5;
        float lambda = typeShadowLambda(mb, reach.x, psiMin, a1.w, n, inbound);
        // The straight ray to a target on the axis (ψ = 0) is no root of G: λ = |z_P|.
        float lambdaRay = a1.w == 0.0 && a0.yz == vec2(0.0) ? abs(a0.w) : lambda;
        slots[0] = reach;
        slots[1] = vec4(lambda, typeShadowExcess(mb, reach.x, a0.w, psiMin, a1.w, n, inbound),
                        typeAreaDistanceSq(mb, a2.z, a2.w), psiMin);
        vec4 em = vec4(0.0), k = vec4(0.0);
        typeShadowRay(mb, a0, a1.w, lambdaRay, em, k);
        slots[2] = em; slots[3] = k;
        float clo = n == 0 && !inbound ? 0.0 : reach.w;
        vec4 u = mix(clo + (reach.z - clo) * a3, vec4(reach.z), equal(a3, vec4(1.0)));
        slots[4] = u;
        slots[5] = typeShadowLambda4(mb, reach.x, reach.z, u, n, inbound);
        slots[6] = typeShadowExcess4(mb, reach.x, a0.w, reach.z, u, n, inbound);
    } else {
        // The ray of the source at a2.xyz with emission (a2.w, 0, 0, 0) and tangent a3 in its
        // axis frame, reaching the target a0 at λ = a1.w: its emission event and tangent.
        TIso back = typeInverseIso(typeToOrigin(mb, vec4(0.0, a2.xyz)));
        vec4 em = vec4(0.0), k = vec4(0.0);
        typeShadowRayBack(mb, back, a0, a1.w, vec4(a2.w, 0.0, 0.0, 0.0), a3, em, k);
        slots[0] = em; slots[1] = k;
    }
#else
#error unknown PROBE
#endif
    writeSlots();
}
#endif
