// ---------------------------------------------------------------------------------------
// The metric (docs/physics.md, "The Gödel metric"; spacetime::godel, spacetime::minkowski).

bool godel() { return GODEL != 0; }

mat4 metricAt(vec4 e) {
    if (!godel()) return mat4(-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    float a = u_a, x = e.y, y = e.z;
    float k = 0.25 / (a * a);
    float m = 1.0 / (4.0 * a * a + x * x + y * y);
    float gtx = y / (SQRT2 * a), gty = -x / (SQRT2 * a);
    float gxx = 1.0 - k * y * y - m * x * x;
    float gxy = (k - m) * x * y;
    float gyy = 1.0 - k * x * x - m * y * y;
    return mat4(-1.0, gtx, gty, 0.0,
                gtx, gxx, gxy, 0.0,
                gty, gxy, gyy, 0.0,
                0.0, 0.0, 0.0, 1.0);
}

mat4 inverseMetricAt(vec4 e) {
    if (!godel()) return mat4(-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    float a = u_a, x = e.y, y = e.z;
    float k = 0.25 / (a * a);
    float c = 1.0 / (1.0 + k * (x * x + y * y));
    float q = k * (1.0 + c);
    float gtx = c * y / (SQRT2 * a), gty = -c * x / (SQRT2 * a);
    return mat4(1.0 - 2.0 * c, gtx, gty, 0.0,
                gtx, c + q * x * x, q * x * y, 0.0,
                gty, q * x * y, c + q * y * y, 0.0,
                0.0, 0.0, 0.0, 1.0);
}

float dotg(mat4 g, vec4 u, vec4 v) { return dot(u, g * v); }

// The metric's derivatives ∂x g and ∂y g (the others vanish; spacetime::godel,
// metric_derivatives).
void metricDerivatives(vec4 e, out mat4 dX, out mat4 dY) {
    dX = mat4(0.0); dY = mat4(0.0);
    float a = u_a, x = e.y, y = e.z;
    float k = 0.25 / (a * a);
    float m = 1.0 / (4.0 * a * a + x * x + y * y);
    float m2 = m * m;
    float w = 1.0 / (SQRT2 * a);
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

// Γ^μ_αβ u^α v^β = ½ g^μν (∂_α g_νβ u^α v^β + ∂_β g_να u^α v^β − ∂_ν g_αβ u^α v^β), from the
// derivatives and the inverse metric at the point (Minkowski: all zero).
vec4 christoffelWith(mat4 dX, mat4 dY, mat4 ginv, vec4 u, vec4 v) {
    mat4 du = u.y * dX + u.z * dY;
    mat4 dv = v.y * dX + v.z * dY;
    vec4 low = du * v + dv * u - vec4(0.0, dot(u, dX * v), dot(u, dY * v), 0.0);
    return 0.5 * (ginv * low);
}

vec4 christoffel(vec4 e, vec4 u, vec4 v) {
    if (!godel()) return vec4(0.0);
    mat4 dX = mat4(0.0), dY = mat4(0.0);
    metricDerivatives(e, dX, dY);
    return christoffelWith(dX, dY, inverseMetricAt(e), u, v);
}

// Riemann normal coordinates to second order (docs/physics.md, "Local objects";
// spacetime::normal; the first-order transport is written out in restFramePhoton).
vec4 normalDisplacement(vec4 at, vec4 d) { return d + 0.5 * christoffel(at, d, d); }

