// ---------------------------------------------------------------------------------------
// Complex numbers (vec2) and small helpers.

// Finite, and below 1e38 (INF, 3e38, counts as infinite), told by the bits: the magnitude's
// bit pattern orders as the value does, and NaN's and infinity's lie above 1e38's. No isnan:
// a compiler that assumes no NaN may fold it away.
bool finite(float v) { return (floatBitsToUint(v) & 0x7fffffffu) < 0x7e967699u; }
// A float made an int in [lo, hi] (a count, an index): GLSL leaves the conversion of values
// outside int's range undefined, so v is clamped first, and a v that is not finite gives lo.
int toInt(float v, int lo, int hi) { return finite(v) ? int(clamp(v, float(lo), float(hi))) : lo; }

// Arctangents and arcsines of our own: GLSL leaves their precision to the implementation,
// and Mesa's are approximations (measured on llvmpipe: asin off by 4e-4, atan by 3e-6).
// Cephes' atanf (S. L. Moshier): range reduction to |t| ≤ tan(π/8) and a minimax
// polynomial, relative error ~2e-7.
float atanA(float x) {
    float ax = abs(x);
    float y = 0.0, t = ax;
    if (ax > 2.414213562373095) { y = 0.5 * PI; t = -1.0 / ax; }
    else if (ax > 0.4142135623730950) { y = 0.25 * PI; t = (ax - 1.0) / (ax + 1.0); }
    float z = t * t;
    y += (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z - 3.33329491539e-1) * z * t + t;
    return x < 0.0 ? -y : y;
}
float atan2s(float y, float x) {
    if (x == 0.0 && y == 0.0) return 0.0;
    float ax = abs(x), ay = abs(y);
    float r = ay <= ax ? atanA(ay / ax) : 0.5 * PI - atanA(ax / ay);
    if (x < 0.0) r = PI - r;
    return y < 0.0 ? -r : r;
}
float asinA(float x) { return atan2s(x, sqrt(max((1.0 - x) * (1.0 + x), 0.0))); }
// The same, four at a time (the shadow rays' grid).
vec4 atanA4(vec4 x) {
    vec4 ax = abs(x);
    bvec4 big = greaterThan(ax, vec4(2.414213562373095));
    bvec4 mid = greaterThan(ax, vec4(0.4142135623730950));
    vec4 t = mix(mix(ax, (ax - 1.0) / (ax + 1.0), mid), -1.0 / max(ax, 1e-30), big);
    vec4 y = mix(mix(vec4(0.0), vec4(0.25 * PI), mid), vec4(0.5 * PI), big);
    vec4 z = t * t;
    y += (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z - 3.33329491539e-1) * z * t + t;
    return mix(y, -y, lessThan(x, vec4(0.0)));
}
// asin of x ∈ [0, 1].
vec4 asinA4(vec4 x) {
    vec4 c = sqrt(max((1.0 - x) * (1.0 + x), 0.0));
    bvec4 low = lessThanEqual(x, c);
    return mix(0.5 * PI - atanA4(c / max(x, 1e-30)), atanA4(x / max(c, 1e-30)), low);
}
float acosA(float x) { return atan2s(sqrt(max((1.0 - x) * (1.0 + x), 0.0)), x); }

vec2 cmul(vec2 p, vec2 q) { return vec2(p.x * q.x - p.y * q.y, p.x * q.y + p.y * q.x); }
vec2 cdiv(vec2 p, vec2 q) { return vec2(p.x * q.x + p.y * q.y, p.y * q.x - p.x * q.y) / dot(q, q); }
vec2 conj2(vec2 p) { return vec2(p.x, -p.y); }
// Cosine and sine of our own, for the same reason: Chromium's software WebGL (SwiftShader)
// computes sin and cos to within 2e-4 only (Vulkan's bound is 2^-11). Cephes' sinf/cosf
// (S. L. Moshier): reduction by π/4 in three parts (exact for |a| < 8192) to an even octant,
// minimax polynomials on [−π/4, π/4], error ~1 ulp.
vec2 cis(float a) {
    float j = floor(abs(a) * 1.27323954473516);   // 4/π
    j += mod(j, 2.0);
    float x = ((abs(a) - j * 0.78515625) - j * 2.4187564849853515625e-4) - j * 3.77489497744594108e-8;
    float z = x * x;
    float s = ((-1.9515295891e-4 * z + 8.3321608736e-3) * z - 1.6666654611e-1) * z * x + x;
    float c = ((2.443315711809948e-5 * z - 1.388731625493765e-3) * z + 4.166664568298827e-2) * z * z - 0.5 * z + 1.0;
    // The quarter turn q: (c, s) rotated by q·π/2, chosen by comparing floats (no conversion
    // to int, no branch: cis is inlined at every call, and SwiftShader took minutes to compile
    // the kernel with a toInt here).
    float q = mod(j * 0.5, 4.0);
    vec2 r = q < 0.5 ? vec2(c, s) : (q < 1.5 ? vec2(-s, c) : (q < 2.5 ? vec2(-c, -s) : vec2(s, -c)));
    return vec2(r.x, a < 0.0 ? -r.y : r.y);
}
float sinA(float a) { return cis(a).y; }
float cosA(float a) { return cis(a).x; }
float carg(vec2 p) { return atan2s(p.y, p.x); }
float asinh_(float x) { return sign(x) * log(abs(x) + sqrt(x * x + 1.0)); }
// tanh(asinh(x)/2) = x/(1 + √(1 + x²)): the disc radius |h| of a ray's circle centre.
float halfTanh(float x) { return x / (1.0 + sqrt(1.0 + x * x)); }
float acosh_(float x) { return log(x + sqrt(max(x * x - 1.0, 0.0))); }
float atanh_(float x) { return 0.5 * log((1.0 + x) / (1.0 - x)); }

// Column c of m, and m with column c set (c < 4): a matrix read and written at a runtime
// index through constant ones, as the kernel stores (drivers have miscompiled stores at
// runtime indices).
vec4 column(mat4 m, int c) { return c == 0 ? m[0] : (c == 1 ? m[1] : (c == 2 ? m[2] : m[3])); }
mat4 withColumn(mat4 m, int c, vec4 v) {
    if (c == 0) m[0] = v;
    else if (c == 1) m[1] = v;
    else if (c == 2) m[2] = v;
    else m[3] = v;
    return m;
}

vec4 tableTexel(int i) { return texelFetch(u_table, ivec2(i % TABLE_WIDTH, i / TABLE_WIDTH), 0); }

