// ---------------------------------------------------------------------------------------
// Closed-form geodesics through the origin (docs/physics.md, "Closed forms";
// spacetime::closed_form): x + iy = r_max sin θ e^{i(χ + sgn(E) Φ(θ))},
// t = sgn(E) 2√2 a Φ(θ) − E λ, z = p_z λ, θ = ωλ, Φ = arctan(q tan θ) continued.

struct OGeo { float e; float pz; float kappa; vec2 cchi; float omega; float rmax; float q; bool ok; };
const OGeo NO_OGEO = OGeo(0.0, 0.0, 0.0, vec2(0.0), 0.0, 0.0, 0.0, false);

OGeo originGeodesic(vec4 k) {
    OGeo g = NO_OGEO;
    float e = k.x;
    float kp2 = dot(k.yz, k.yz);
    float kappa = e * e - kp2 - k.w * k.w;
    g.ok = finite(e) && finite(kp2) && finite(k.w) && e != 0.0 && kappa >= -1e-4 * e * e;
    kappa = max(kappa, 0.0);
    g.e = e;
    g.pz = k.w;
    g.kappa = kappa;
    g.omega = sqrt(e * e + kappa + k.w * k.w) / (2.0 * u_a);
    float kp = sqrt(kp2);
    g.cchi = kp > 0.0 ? k.yz / kp : vec2(1.0, 0.0);
    g.rmax = kp / g.omega;
    g.q = abs(e) / (SQRT2 * u_a * g.omega);
    return g;
}

float returnParameter(OGeo g) { return PI / g.omega; }

// (Δt, Δz) over one return: Φ(π) = π, so t(λ_ret) = sgn(E)·2√2·a·π − E·λ_ret.
vec2 returnShift(OGeo g) {
    float lret = returnParameter(g);
    return vec2(sign(g.e) * 2.0 * SQRT2 * u_a * PI - g.e * lret, g.pz * lret);
}

// How far the time t(λ) strays from its mean rate, |t(λ) − Δt·λ/λ_ret| ≤ 2√2·a·δ with
// tan δ = (q − 1)/(2√q): the largest of |Φ(θ) − θ| (spacetime::OriginGeodesic::time_deviation).
float timeDeviation(OGeo g) {
    float q = max(g.q, 1.0);
    return 2.0 * SQRT2 * u_a * atanA((q - 1.0) / (2.0 * sqrt(q)));
}

void ogeoAt(OGeo g, float lambda, out vec4 ev, out vec4 tan_) {
    ev = vec4(0.0); tan_ = vec4(0.0);
    float a = u_a, e = g.e, w = g.omega, q = g.q;
    float sg = sign(e);
    float th = w * lambda;
    float s = sinA(th), c = cosA(th);
    float den = c * c + q * s * s;
    float b = (q - 1.0) * s * c;
    float big = th + atan2s(b, den);
    float dbig = q / (c * c + q * q * s * s);
    float n = sqrt(den * den + b * b);
    float cb = (c * den - s * b) / n, sb = sg * (s * den + c * b) / n;
    float cp = g.cchi.x * cb - g.cchi.y * sb, sp = g.cchi.y * cb + g.cchi.x * sb;
    float r = g.rmax * s;
    ev = vec4(sg * 2.0 * SQRT2 * a * big - e * lambda, r * cp, r * sp, g.pz * lambda);
    float u = w * g.rmax * c, v = w * g.rmax * sg * dbig * s;
    tan_ = vec4(sg * 2.0 * SQRT2 * a * w * dbig - e, u * cp - v * sp, u * sp + v * cp, g.pz);
}

// Parallel transport along the closed form (docs/physics.md, "Parallel transport along closed
// forms"; spacetime::transport): W(λ) = F_λ* exp(−λA) W with A = ∇ξ at the origin and
// F_λ = T_{γ(λ)}⁻¹ ∘ R_β(λ).
vec4 nablaXi(OGeo g, vec4 w) {
    vec2 kxy = g.omega * g.rmax * g.cchi;
    float s = 1.0 / (SQRT2 * u_a);
    float e = g.e * s;
    kxy *= s;
    return vec4(w.y * kxy.y - w.z * kxy.x, w.x * kxy.y - w.z * e, -w.x * kxy.x + w.y * e, 0.0);
}

float flowRotation(OGeo g, float lambda) {
    float alpha = sign(g.e) * 2.0 * g.omega * lambda;
    float h = halfTanh(g.rmax / (2.0 * u_a));
    float h2 = h * h;
    return alpha - 2.0 * atan2s(-h2 * sinA(alpha), 1.0 - h2 * cosA(alpha));
}

// The first n columns of w (n ≤ 4; the others as they are) transported: the flow's
// coefficients and the isometry once for all, one call site of the push (as pushLegs).
mat4 transportLegs(OGeo g, float lambda, vec4 at, mat4 w, int n) {
    float om = sqrt(g.kappa + g.pz * g.pz) / (SQRT2 * u_a);
    float x = om * lambda;
    float c1 = 0.0, c2 = 0.0;
    if (abs(x) < 1e-2) {
        c1 = lambda * (1.0 - x * x / 6.0);
        c2 = 0.5 * lambda * lambda * (1.0 - x * x / 12.0);
    } else {
        c1 = sinA(x) / om;
        c2 = (1.0 - cosA(x)) / (om * om);
    }
    float beta = flowRotation(g, lambda);
    float cb = cosA(beta), sb = sinA(beta);
    Iso back = inverseIso(toOrigin(at));
    mat4 out_ = w;
    for (int c = 0; c < 4; c++) {
        if (c >= n) break;
        vec4 wc = column(w, c);
        vec4 aw = nablaXi(g, wc);
        vec4 aaw = nablaXi(g, aw);
        vec4 v = wc - c1 * aw + c2 * aaw;
        v = vec4(v.x, cb * v.y - sb * v.z, sb * v.y + cb * v.z, v.w);
        out_ = withColumn(out_, c, pushIso(back, vec4(0.0), v));
    }
    return out_;
}

