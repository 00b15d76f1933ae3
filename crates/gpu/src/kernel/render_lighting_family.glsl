
// ---------------------------------------------------------------------------------------
// Direct light in the Gödel-type family (docs/physics.md, "The Gödel-type family", "Shadow
// rays in the family" and "Direct light in the family"; spacetime::godel_type_connect): the
// pieces of the shadow rays from a source at rest, as pure functions of the member
// mb = (m², Ω). Frame: the source's axis frame, where the source's isometry (typeToOrigin of
// the source at t = 0) has put the source on the axis at z = 0 and kept its worldline's t;
// there a ray leaves with E = 1 at angle ψ to ±z, (|c|, σ) = (cos ψ, sin ψ), and the target p
// is reached on winding n and branch (outbound: θ = nπ + θ₀, inbound: nπ + π − θ₀) where
// its λ solves σ S1(λ) = R_P, R the Gödel-like radius. Compiled only where FAMILY is defined:
// by the family's shadow probe (crates/gpu/tests/integration/probes.rs holds each function to
// spacetime::godel_type_connect) and by a member's kernel, whose lights render_lighting.glsl
// enumerates with them.
#ifdef FAMILY

// The Gödel-like radius R = (2/m) sinh(mρ/2) = ρ sinh(h)/h, h = mρ/2 (sin for m² < 0, ρ for
// m² = 0) of the point xy (GodelChart's radius), with its series where h is small.
float typeGodelRadius(vec2 mb, vec2 xy) {
    float r2 = dot(xy, xy);
    float u = mb.x * r2;
    float f = 1.0;
    if (u >= 0.0) {
        f = sinhcCoshF(0.5 * sqrt(u)).x;
    } else {
        float h = 0.5 * sqrt(-u), w = 0.25 * u;
        f = h < 0.1 ? 1.0 + w * (1.0 / 6.0 + w / 120.0) : sinA(h) / h;
    }
    return sqrt(r2) * f;
}

// A light's reach for the target p in the source's axis frame (type_shadow_rays_from_axis's
// set-up): (R_P, σ_min, c_max, c_esc) with σ_min = Ω|ζ_P| (the base coordinate's modulus;
// σ_min ≥ 1: no ray reaches p, as at and beyond ρ_c for m² < 4Ω², and set to 2 at and beyond
// the sphere's pole μρ = π), c_max = cos ψ_min = √(1 − σ_min²), and the lowest |c| of the
// returning-only branches, c_esc = √(1 − 4Ω²/m²) for m² > 4Ω² (0 otherwise), where Λ = 0.
// The grid of a (winding, branch) runs in |c| from c_lo (0 for the outbound branch of winding
// 0, c_esc for the others) to c_max; ψ_min = atan2s(σ_min, c_max).
vec4 typeShadowReach(vec2 mb, vec4 p) {
    float r = typeGodelRadius(mb, p.yz);
    float smin = mb.y * length(baseCoordinate(mb, p.yz));
    if (mb.x < 0.0 && -mb.x * dot(p.yz, p.yz) >= PI * PI) smin = 2.0;
    float cmax = sqrt(max((1.0 - smin) * (1.0 + smin), 0.0));
    // 1 − 4Ω²/m² = −4(Ω² − m²/4)/m², its sign the host's where m² = 4Ω² (typeDelta).
    float delta = typeDelta(mb);
    float cesc = delta < 0.0 && mb.x > 0.0 ? sqrt(-4.0 * delta / mb.x) : 0.0;
    return vec4(r, smin, cmax, cesc);
}

// Λ = Ω²c² + (Ω² − m²/4)σ² of the ray leaving at (c, σ) (big_lambda): Ω² − m²σ²/4 without the
// cancellation near c = 0 for m² ≈ 4Ω² (c² + σ² = 1), Ω² − m²/4 the host's in a member's kernel
// (typeDelta).
float typeShadowBigLambda(vec2 mb, float c, float sigma) {
    return mb.y * mb.y * c * c + typeDelta(mb) * sigma * sigma;
}

// λ at the Gödel-like radius r on winding n and branch (lambda_at) for the ray leaving at
// (c, σ), c ≥ 0, given d = σ² − σ_min² without cancellation (the callers below); negative
// where the branch does not exist (Λ ≤ 0 leaves only the escaping outbound ray of winding 0;
// σ = 0 reaches only r = 0). sin θ₀ = √Λ r/σ, and cos θ₀ from σ² − Λr² = (1 + κr²)(σ² − σ_min²)
// (κ = m²/4, σ_min² = Ω²r²/(1 + κr²)): near the reach, where asin's slope would turn the
// rounding of √Λ r/σ into an error of θ near √ε, θ₀ keeps its digits (as shadowTheta does).
float typeShadowLambdaCS(vec2 mb, float r, float c, float sigma, float d, int n, bool inbound) {
    if (sigma == 0.0 && r > 0.0) return -1.0;
    float lam = typeShadowBigLambda(mb, c, sigma);
    if (lam > 0.0) {
        float root = sqrt(lam);
        float th0 = atan2s(root * r, sqrt(max((1.0 + 0.25 * mb.x * r * r) * d, 0.0)));
        return (float(n) * PI + (inbound ? PI - th0 : th0)) / root;
    }
    // Escaping: λ = asinh(√−Λ x)/√−Λ, x = r/σ (x at Λ = 0).
    if (n != 0 || inbound) return -1.0;
    float x = r / sigma;
    return x * asinhcF(-lam * x * x);
}

// The same for the ray at angle ψ ∈ [0, π/2] to ±z (|c| = cos ψ; ψ = PI/2 in f32, which lies
// above π/2, is the plane c = 0 exactly), d = sin(ψ − ψ_min) sin(ψ + ψ_min): the refinement's
// form, exact at ψ = ψ_min.
float typeShadowLambda(vec2 mb, float r, float psiMin, float psi, int n, bool inbound) {
    float c = max(cosA(psi), 0.0), s = sinA(psi);
    float d = sinA(psi - psiMin) * sinA(psi + psiMin);
    return typeShadowLambdaCS(mb, r, c, s, d, n, inbound);
}

// The same at four |c| = u of the grid, d = (c_max − u)(c_max + u): exact at u = c_max (the
// grid's last point, θ₀ = π/2, as the CPU has it).
vec4 typeShadowLambda4(vec2 mb, float r, float cmax, vec4 u, int n, bool inbound) {
    vec4 s = sqrt(max((1.0 - u) * (1.0 + u), vec4(0.0)));
    vec4 d = (cmax - u) * (cmax + u);
    return vec4(typeShadowLambdaCS(mb, r, u.x, s.x, d.x, n, inbound),
                typeShadowLambdaCS(mb, r, u.y, s.y, d.y, n, inbound),
                typeShadowLambdaCS(mb, r, u.z, s.z, d.z, n, inbound),
                typeShadowLambdaCS(mb, r, u.w, s.w, d.w, n, inbound));
}

// G = |c|λ − |z_P| on a branch (excess) from its λ, with its limits where Λ ≤ 0 leaves a
// returning branch no λ (λ → ∞ as Λ → 0⁺): INF for c > 0, and θ/Ω − |z_P| at c = 0 (only for
// m² = 4Ω², where cλ = θ/Ω; θ = nπ outbound, (n + 1)π inbound).
float typeShadowExcessOf(vec2 mb, float lambda, float c, float zp, int n, bool inbound) {
    if (lambda >= 0.0) return c * lambda - abs(zp);
    if (c > 0.0) return INF;
    return (float(n) + (inbound ? 1.0 : 0.0)) * PI / mb.y - abs(zp);
}
float typeShadowExcess(vec2 mb, float r, float zp, float psiMin, float psi, int n, bool inbound) {
    float lambda = typeShadowLambda(mb, r, psiMin, psi, n, inbound);
    return typeShadowExcessOf(mb, lambda, max(cosA(psi), 0.0), zp, n, inbound);
}
vec4 typeShadowExcess4(vec2 mb, float r, float zp, float cmax, vec4 u, int n, bool inbound) {
    vec4 l = typeShadowLambda4(mb, r, cmax, u, n, inbound);
    return vec4(typeShadowExcessOf(mb, l.x, u.x, zp, n, inbound),
                typeShadowExcessOf(mb, l.y, u.y, zp, n, inbound),
                typeShadowExcessOf(mb, l.z, u.z, zp, n, inbound),
                typeShadowExcessOf(mb, l.w, u.w, zp, n, inbound));
}

// The ray of a root (ray): for the target p in the source's axis frame, reached at λ by the
// ray leaving at angle ψ ∈ [0, π/2] to the z axis on p's side (c = sign(z_P) cos ψ; the
// plane's ray (c, σ) = (0, 1) where z_P = 0), its emission event in that frame, (p.t − t(λ),
// 0, 0, 0), and its future tangent there, (1, σ cos α, σ sin α, c): the closed form from
// azimuth 0 turned by α, p's azimuth minus its end's, so that it ends at p (α = 0 for p on
// the axis: the cone's ray at azimuth 0).
void typeShadowRay(vec2 mb, vec4 p, float psi, float lambda, out vec4 emission, out vec4 tangent) {
    emission = vec4(0.0); tangent = vec4(0.0);
    bool plane = p.w == 0.0;
    float c = plane ? 0.0 : sign(p.w) * max(cosA(psi), 0.0);
    float s = plane ? 1.0 : sinA(psi);
    TGeo g = typeOriginGeodesic(mb, vec4(1.0, s, 0.0, c));
    vec4 ev = vec4(0.0), k = vec4(0.0);
    tgeoAt(g, lambda, ev, k);
    float alpha = p.yz == vec2(0.0) ? 0.0 : carg(p.yz) - carg(ev.yz);
    emission = vec4(p.x - ev.x, 0.0, 0.0, 0.0);
    tangent = vec4(1.0, s * cis(alpha), c);
}

// The ray of typeShadowRay in the scene's coordinates (rays_through): its emission event
// `em` and tangent `k` carried back by `back` (typeInverseIso of the source's typeToOrigin),
// and on the sphere (m² < 0) the emission time moved by the whole periods 8πΩ/μ² that make
// the geodesic from it end at the target's t (the cut of the map back's time shift,
// "Shadow rays in the family").
void typeShadowRayBack(vec2 mb, TIso back, vec4 target, float lambda, vec4 em, vec4 k,
                       out vec4 emission, out vec4 tangent) {
    emission = vec4(0.0); tangent = vec4(0.0);
    typeApplyPush(mb, back, em, k, emission, tangent);
    if (mb.x < 0.0) {
        vec4 end = vec4(0.0), kEnd = vec4(0.0);
        texAt(typeExactGeodesic(mb, emission, tangent), lambda, end, kEnd);
        float period = 8.0 * PI * mb.y / -mb.x;
        emission.x += floor((target.x - end.x) / period + 0.5) * period;
    }
}

// D² = dA/dΩ (type_source_area_distance_sq) of the ray leaving the source's axis at angle
// ψ ∈ (0, π) to +z with E = 1, ending at parameter λ (the azimuth does not matter: rotations
// about the axis are isometries). J_χ = ∂φ, and J_ψ = ∂γ/∂ψ at fixed λ analytic (a central
// difference would lose its digits in f32): ψ enters through σ and Λ = Ω² − κσ²
// (dΛ/dψ = −2κσc), with ∂S1/∂Λ = (C1λ − S1)/(2Λ), ∂C1/∂Λ = −λS1/2, and
// N = C1 ∂S1/∂Λ − S1 ∂C1/∂Λ = (λ − C1S1)/(2Λ) (both regimes), their series in x = Λλ² for
// |x| < 1 (where the quotients cancel). Then with R = σS1 (the Gödel-like radius, signed),
// v = κR²: dρ = dR/√(1 + v), dφ = ∂Φ/∂Λ dΛ with ∂Φ/∂Λ = ΩN/(C1² + Ω²S1²), dt = −2Ωσc ∂Φ/∂Λ
// (from κAJ = λ − Φ/Ω, A = σ²), dz = −σλ; and in (t, ρ, φ, z) the metric
// −(dt + H dφ)² + dρ² + D² dφ² + dz², H = ΩR², D² = R²(1 + v). D² = √det g(J_i, J_j)/σ.
float typeAreaDistanceSq(vec2 mb, float psi, float lambda) {
    float c = cosA(psi), s = sinA(psi);
    float w = mb.y, kap = 0.25 * mb.x;
    float lam = typeShadowBigLambda(mb, c, s);
    float x = lam * lambda * lambda;
    float c1 = 1.0, s1 = lambda;
    if (lam > 0.0) {
        float r = sqrt(lam);
        vec2 cs = cis(r * lambda);
        c1 = cs.x;
        s1 = cs.y / r;
    } else if (lam < 0.0) {
        vec2 sc = sinhcCoshF(sqrt(-lam) * lambda);
        c1 = sc.y;
        s1 = sc.x * lambda;
    }
    float l3 = lambda * lambda * lambda;
    // Σ_{k≥1} (−1)^k k x^{k−1}/(2k+1)! and Σ_{k≥1} (−1)^{k+1} 2^{2k−1} x^{k−1}/(2k+1)!, to k = 6.
    float ds1 = 0.0, nn = 0.0;
    if (abs(x) < 1.0) {
        ds1 = l3 * (-1.0 / 6.0 + x * (1.0 / 60.0 + x * (-1.0 / 1680.0 + x * (1.0 / 90720.0
              + x * (-1.0 / 7983360.0 + x * (1.0 / 1037836800.0))))));
        nn = l3 * (1.0 / 3.0 + x * (-1.0 / 15.0 + x * (2.0 / 315.0 + x * (-1.0 / 2835.0
             + x * (2.0 / 155925.0 + x * (-2.0 / 6081075.0))))));
    } else {
        ds1 = (c1 * lambda - s1) / (2.0 * lam);
        nn = (lambda - c1 * s1) / (2.0 * lam);
    }
    float dPhiDLam = w * nn / (c1 * c1 + w * w * s1 * s1);
    float dLam = -2.0 * kap * s * c;
    float bigR = s * s1;
    float v = kap * bigR * bigR;
    float dRho = (c * s1 + s * ds1 * dLam) / sqrt(1.0 + v);
    float dPhi = dPhiDLam * dLam;
    float dt = -2.0 * w * s * c * dPhiDLam;
    float dz = -s * lambda;
    float h = w * bigR * bigR;
    float d2 = bigR * bigR * (1.0 + v);
    float a = dt + h * dPhi;
    float pp = -a * a + dRho * dRho + d2 * dPhi * dPhi + dz * dz;
    float cc = d2 - h * h;
    float pc = -a * h + d2 * dPhi;
    return sqrt(max(pp * cc - pc * pc, 0.0)) / s;
}

#endif
