// ---------------------------------------------------------------------------------------
// The metric (docs/physics.md, "The Gödel metric" and "The Gödel-type family";
// spacetime::godel, spacetime::godel_type, spacetime::minkowski).

bool godel() { return GODEL != 0; }
#ifdef MEMBER
bool member() { return true; }
#else
bool member() { return false; }
#endif
// Minkowski's spacetime: straight rays, no Γ.
bool minkowski() { return !godel() && !member(); }

#ifdef MEMBER
// A Gödel-type member (spacetime::godel_type): with u = m²ρ², f = H/ρ² = 2Ω C(u) and
// q = (D²/ρ² − 1)/ρ² = m² T(u), C = (cosh √u − 1)/u, T = (sinh²√u/u − 1)/u (cos and sin for
// u < 0): g_tt = −1, g_tx = f y, g_ty = −f x, g_ij = δ_ij + (q − f²) J_i J_j, J = (−y, x).
// (C, C′, T, T′) at u: below |u| < 1/2 their series (terms to u⁶/16!, the first omitted below
// 1e-10), where the closed forms would lose their digits to cancellation.
vec4 memberFunctions(float u) {
    if (abs(u) < 0.5) {
        // C = Σ_{k≥1} u^{k−1}/(2k)!, T = Σ_{k≥2} 2^{2k−1} u^{k−2}/(2k)!, and their
        // derivatives, with the powers u^{k−1}, u^{k−2}, u^{k−3} carried (0 where the
        // exponent is negative: their terms vanish).
        float c = 0.0, dc = 0.0, t = 0.0, dt = 0.0;
        float fact = 1.0, power = 0.5;   // (2k)!, 2^{2k−1}
        float p1 = 1.0, p2 = 0.0, p3 = 0.0;
        for (int k = 1; k <= 8; k++) {
            float kf = float(k);
            fact *= (2.0 * kf - 1.0) * (2.0 * kf);
            power *= 4.0;
            c += p1 / fact;
            dc += (kf - 1.0) * p2 / fact;
            t += power * p2 / fact;
            dt += (kf - 2.0) * power * p3 / fact;
            p3 = p2;
            p2 = p1;
            p1 *= u;
        }
        return vec4(c, dc, t, dt);
    }
    float ch = 1.0, sh = 1.0;   // cosh √u, sinh √u/√u (cos, sin for u < 0)
    if (u > 0.0) {
        float r = sqrt(u);
        float e = exp(r);
        ch = 0.5 * (e + 1.0 / e);
        sh = 0.5 * (e - 1.0 / e) / r;
    } else {
        float r = sqrt(-u);
        vec2 cs = cis(r);
        ch = cs.x;
        sh = cs.y / r;
    }
    float c = (ch - 1.0) / u;
    float dc = 0.5 * sh / u - (ch - 1.0) / (u * u);
    float s = sh * sh;
    float ds = sh * (ch - sh) / u;
    return vec4(c, dc, (s - 1.0) / u, ds / u - (s - 1.0) / (u * u));
}

// f, f′, q, q′ (′: d/dρ²) at ρ² = s.
vec4 memberProfile(float s) {
    vec4 fn = memberFunctions(MEMBER_M2 * s);
    return vec4(2.0 * MEMBER_OMEGA * fn.x, 2.0 * MEMBER_OMEGA * MEMBER_M2 * fn.y, MEMBER_M2 * fn.z,
                MEMBER_M2 * MEMBER_M2 * fn.w);
}

mat4 memberMetric(vec4 e) {
    float x = e.y, y = e.z;
    vec4 p = memberProfile(x * x + y * y);
    float c = p.z - p.x * p.x;
    return mat4(-1.0, p.x * y, -p.x * x, 0.0,
                p.x * y, 1.0 + c * y * y, -c * x * y, 0.0,
                -p.x * x, -c * x * y, 1.0 + c * x * x, 0.0,
                0.0, 0.0, 0.0, 1.0);
}

// From the dual frame (∂t, ∂_i − A_i ∂t), A = f J, and h⁻¹ = δ − κ J J, κ = q/(1 + qρ²).
mat4 memberInverseMetric(vec4 e) {
    float x = e.y, y = e.z;
    float s = x * x + y * y;
    vec4 p = memberProfile(s);
    float kappa = p.z / (1.0 + p.z * s);
    mat2 hi = mat2(1.0 - kappa * y * y, kappa * x * y, kappa * x * y, 1.0 - kappa * x * x);
    vec2 ha = hi * vec2(-p.x * y, p.x * x);
    float tt = -1.0 + dot(vec2(-p.x * y, p.x * x), ha);
    return mat4(tt, -ha.x, -ha.y, 0.0,
                -ha.x, hi[0][0], hi[0][1], 0.0,
                -ha.y, hi[1][0], hi[1][1], 0.0,
                0.0, 0.0, 0.0, 1.0);
}

void memberDerivatives(vec4 e, out mat4 dX, out mat4 dY) {
    dX = mat4(0.0); dY = mat4(0.0);
    float x = e.y, y = e.z;
    vec4 p = memberProfile(x * x + y * y);
    float f = p.x, c = p.z - p.x * p.x;
    float dc = p.w - 2.0 * p.x * p.y;
    // ∂_x g(ρ²) = 2x g′, ∂_y g(ρ²) = 2y g′.
    float fx = 2.0 * x * p.y, fy = 2.0 * y * p.y, cx = 2.0 * x * dc, cy = 2.0 * y * dc;
    dX = mat4(0.0, fx * y, -f - fx * x, 0.0,
              fx * y, cx * y * y, -cx * x * y - c * y, 0.0,
              -f - fx * x, -cx * x * y - c * y, cx * x * x + 2.0 * c * x, 0.0,
              0.0, 0.0, 0.0, 0.0);
    dY = mat4(0.0, f + fy * y, -fy * x, 0.0,
              f + fy * y, cy * y * y + 2.0 * c * y, -cy * x * y - c * x, 0.0,
              -fy * x, -cy * x * y - c * x, cy * x * x, 0.0,
              0.0, 0.0, 0.0, 0.0);
}
#endif

// The rotating form g_tt = −1, g_tx = w y, g_ty = −w x, g_ij = δ_ij − k J_i J_j − m X_i X_j
// (J = (−y, x), X = (x, y)): Gödel's metric (w = 1/(√2 a), k = 1/4a², m = 1/(4a² + r²)), and
// every member's in its Gödel-like chart (spacetime::godel_chart: w = Ω, k = Ω² − κ,
// m = κ/(1 + κr²), κ = m²/4). Its inverse, with c = 1/(1 + κr²): g^tt = −1 + w²r²c,
// g^tx = w c y, g^ty = −w c x, g^ij = δ_ij + κ X_i X_j − κ c J_i J_j; and its derivatives
// (spacetime::godel_chart::rotating_derivatives), where m depends on X alone, ∂_l m = −2m² X_l.
mat4 rotatingMetric(vec2 xy, float w, float k, float m) {
    float x = xy.x, y = xy.y;
    float gtx = w * y, gty = -w * x;
    float gxx = 1.0 - k * y * y - m * x * x;
    float gxy = (k - m) * x * y;
    float gyy = 1.0 - k * x * x - m * y * y;
    return mat4(-1.0, gtx, gty, 0.0,
                gtx, gxx, gxy, 0.0,
                gty, gxy, gyy, 0.0,
                0.0, 0.0, 0.0, 1.0);
}

mat4 rotatingInverse(vec2 xy, float w, float kappa) {
    float x = xy.x, y = xy.y;
    float r2 = dot(xy, xy);
    float c = 1.0 / (1.0 + kappa * r2);
    float q = kappa * (1.0 + c);   // κ X X − κ c J J = κ(1 + c) X X − κ c r² δ on the plane
    float gtx = w * c * y, gty = -w * c * x;
    return mat4(-1.0 + w * w * r2 * c, gtx, gty, 0.0,
                gtx, c + q * x * x, q * x * y, 0.0,
                gty, q * x * y, c + q * y * y, 0.0,
                0.0, 0.0, 0.0, 1.0);
}

void rotatingDerivatives(vec2 xy, float w, float k, float m, out mat4 dX, out mat4 dY) {
    dX = mat4(0.0); dY = mat4(0.0);
    float x = xy.x, y = xy.y;
    float m2 = m * m;
    float dx_xx = 2.0 * m2 * x * x * x - 2.0 * m * x;
    float dy_xx = -2.0 * k * y + 2.0 * m2 * y * x * x;
    float dx_xy = (k - m) * y + 2.0 * m2 * x * x * y;
    float dy_xy = (k - m) * x + 2.0 * m2 * x * y * y;
    float dx_yy = -2.0 * k * x + 2.0 * m2 * x * y * y;
    float dy_yy = 2.0 * m2 * y * y * y - 2.0 * m * y;
    dX = mat4(0.0, 0.0, -w, 0.0,
              0.0, dx_xx, dx_xy, 0.0,
              -w, dx_xy, dx_yy, 0.0,
              0.0, 0.0, 0.0, 0.0);
    dY = mat4(0.0, w, 0.0, 0.0,
              w, dy_xx, dy_xy, 0.0,
              0.0, dy_xy, dy_yy, 0.0,
              0.0, 0.0, 0.0, 0.0);
}

// Gödel's (w, k, m) at the event e.
vec3 godelRotating(vec4 e) {
    float a = u_a;
    return vec3(1.0 / (SQRT2 * a), 0.25 / (a * a), 1.0 / (4.0 * a * a + dot(e.yz, e.yz)));
}

mat4 metricAt(vec4 e) {
#ifdef MEMBER
    return memberMetric(e);
#endif
    if (!godel()) return mat4(-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    vec3 p = godelRotating(e);
    return rotatingMetric(e.yz, p.x, p.y, p.z);
}

mat4 inverseMetricAt(vec4 e) {
#ifdef MEMBER
    return memberInverseMetric(e);
#endif
    if (!godel()) return mat4(-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    return rotatingInverse(e.yz, 1.0 / (SQRT2 * u_a), 0.25 / (u_a * u_a));
}

float dotg(mat4 g, vec4 u, vec4 v) { return dot(u, g * v); }

// The metric's derivatives ∂x g and ∂y g (the others vanish; spacetime::godel,
// metric_derivatives).
void metricDerivatives(vec4 e, out mat4 dX, out mat4 dY) {
    dX = mat4(0.0); dY = mat4(0.0);
#ifdef MEMBER
    memberDerivatives(e, dX, dY);
    return;
#endif
    vec3 p = godelRotating(e);
    rotatingDerivatives(e.yz, p.x, p.y, p.z, dX, dY);
}

#ifdef MEMBER
// A member's Gödel-like chart (spacetime::godel_chart), in which local objects are described
// (render::chart): X = σ(u) x, u = m²ρ², σ = sinh(√u/2)/(√u/2) (sin for u < 0), and its
// differential dX = σ dx + 2m²σ′ x (x·dx); the metric there is the rotating form with w = Ω,
// κ = m²/4. σ and σ′ by their series Σ (u/4)^k/(2k + 1)! below |u| < 1/2.
vec2 chartSigma(float u) {
    if (abs(u) < 0.5) {
        float s = 1.0, ds = 0.0, coefficient = 1.0, p = 1.0;   // 1/(4^k (2k+1)!), u^{k−1}
        for (int k = 1; k <= 7; k++) {
            float kf = float(k);
            coefficient *= 0.25 / ((2.0 * kf) * (2.0 * kf + 1.0));
            ds += kf * coefficient * p;
            p *= u;
            s += coefficient * p;
        }
        return vec2(s, ds);
    }
    float h = 0.5 * sqrt(abs(u));
    float sh = 0.0, ch = 1.0;
    if (u > 0.0) {
        float e = exp(h);
        sh = 0.5 * (e - 1.0 / e);
        ch = 0.5 * (e + 1.0 / e);
    } else {
        vec2 cs = cis(h);
        sh = cs.y;
        ch = cs.x;
    }
    float s = sh / h;
    return vec2(s, (ch - s) / (2.0 * u));
}

vec4 chartEvent(vec4 e) { return vec4(e.x, chartSigma(MEMBER_M2 * dot(e.yz, e.yz)).x * e.yz, e.w); }

mat2 chartJacobian(vec2 xy) {
    vec2 s = chartSigma(MEMBER_M2 * dot(xy, xy));
    float c = 2.0 * MEMBER_M2 * s.y;
    return mat2(s.x + c * xy.x * xy.x, c * xy.x * xy.y, c * xy.x * xy.y, s.x + c * xy.y * xy.y);
}

// The chart's (w, k, m) at its event X.
vec3 chartRotating(vec4 X) {
    float kappa = 0.25 * MEMBER_M2;
    return vec3(MEMBER_OMEGA, MEMBER_OMEGA * MEMBER_OMEGA - kappa, kappa / (1.0 + kappa * dot(X.yz, X.yz)));
}
#endif

// Γ^μ_αβ u^α v^β = ½ g^μν (∂_α g_νβ u^α v^β + ∂_β g_να u^α v^β − ∂_ν g_αβ u^α v^β), from the
// derivatives and the inverse metric at the point (Minkowski: all zero).
vec4 christoffelWith(mat4 dX, mat4 dY, mat4 ginv, vec4 u, vec4 v) {
    mat4 du = u.y * dX + u.z * dY;
    mat4 dv = v.y * dX + v.z * dY;
    vec4 low = du * v + dv * u - vec4(0.0, dot(u, dX * v), dot(u, dY * v), 0.0);
    return 0.5 * (ginv * low);
}

vec4 christoffel(vec4 e, vec4 u, vec4 v) {
    if (minkowski()) return vec4(0.0);
    mat4 dX = mat4(0.0), dY = mat4(0.0);
    metricDerivatives(e, dX, dY);
    return christoffelWith(dX, dY, inverseMetricAt(e), u, v);
}

// Riemann normal coordinates to second order (docs/physics.md, "Local objects";
// spacetime::normal; the first-order transport is written out in restFramePhoton).
vec4 normalDisplacement(vec4 at, vec4 d) { return d + 0.5 * christoffel(at, d, d); }

