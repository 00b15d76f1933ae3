// ---------------------------------------------------------------------------------------
// Isometries (docs/physics.md, "Isometries"; spacetime::isometry): X ↦ R_rot(T_{P0}(X)) in
// the disc coordinate w = (x + iy)/√(x² + y² + 4a²).

struct Iso { float t0; vec2 w0; float z0; float rot; };
// The identity, and the value of every Iso before it is set (no variable is read unset).
const Iso NO_ISO = Iso(0.0, vec2(0.0), 0.0, 0.0);

vec2 disc(vec2 xy) { return xy / sqrt(dot(xy, xy) + 4.0 * u_a * u_a); }
vec2 fromDisc(vec2 w) { return 2.0 * u_a * w / sqrt(1.0 - dot(w, w)); }

Iso toOrigin(vec4 p) { return Iso(p.x, disc(p.yz), p.w, 0.0); }
// toOrigin of the observer's event, made by the host in f64 (times are relative to the
// observer's: t0 = 0).
Iso observerToOrigin() { return Iso(0.0, u_obs_to.xy, u_obs_to.z, u_obs_to.w); }
Iso inverseIso(Iso m) { return Iso(-m.t0, -cmul(cis(m.rot), m.w0), -m.z0, -m.rot); }
bool isTranslation(Iso m) { return m.w0 == vec2(0.0) && m.rot == 0.0; }

// The image of an event and of the tangent vector v there (spacetime::Isometry::apply_push).
void applyPush(Iso m, vec4 at, vec4 v, out vec4 e, out vec4 k) {
    e = vec4(0.0); k = vec4(0.0);
    if (isTranslation(m)) {
        e = vec4(at.x - m.t0, at.y, at.z, at.w - m.z0);
        k = v;
        return;
    }
    float a = u_a;
    vec2 w = disc(at.yz);
    vec2 den = vec2(1.0, 0.0) - cmul(conj2(m.w0), w);
    vec2 rot = cis(m.rot);
    vec2 w1 = cmul(rot, cdiv(w - m.w0, den));
    e = vec4(at.x - m.t0 - 2.0 * SQRT2 * a * carg(den), fromDisc(w1), at.w - m.z0);
    // dw = (dx + i dy)/S − (x + i y)(x dx + y dy)/S³.
    float s2 = dot(at.yz, at.yz) + 4.0 * a * a;
    float s = sqrt(s2);
    float rad = dot(at.yz, v.yz) / (s2 * s);
    vec2 dw = v.yz / s - at.yz * rad;
    vec2 dw1 = cmul(rot, cdiv(dw * (1.0 - dot(m.w0, m.w0)), cmul(den, den)));
    // d(x + iy) = 2a dw/√(1 − |w|²) + 2a w Re(w̄ dw)/(1 − |w|²)^{3/2}.
    float n = 1.0 - dot(w1, w1);
    float f = 2.0 * a / sqrt(n);
    float g = f * dot(w1, dw1) / n;
    k = vec4(v.x + 2.0 * SQRT2 * a * cdiv(cmul(conj2(m.w0), dw), den).y, f * dw1 + g * w1, v.w);
}

vec4 applyIso(Iso m, vec4 at) { vec4 e = vec4(0.0), k = vec4(0.0); applyPush(m, at, vec4(0.0), e, k); return e; }
vec4 pushIso(Iso m, vec4 at, vec4 v) { vec4 e = vec4(0.0), k = vec4(0.0); applyPush(m, at, v, e, k); return k; }
// pushIso of the first n columns of v (n ≤ 4; the others as they are), in one loop: the kernel
// is inlined whole, and one call site of the push compiles once where four would four times.
mat4 pushLegs(Iso m, vec4 at, mat4 v, int n) {
    mat4 out_ = v;
    for (int c = 0; c < 4; c++) {
        if (c >= n) break;
        out_ = withColumn(out_, c, pushIso(m, at, column(v, c)));
    }
    return out_;
}

