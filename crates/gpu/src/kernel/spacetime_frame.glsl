// ---------------------------------------------------------------------------------------
// Frames (docs/physics.md, "Frames"; spacetime::frame): the static frame by Gram–Schmidt of
// (∂t, ∂x, ∂y, ∂z), boosts. A frame is a mat4 whose columns are e0..e3.

mat4 staticFrame(vec4 at) {
    mat4 g = metricAt(at);
    vec4 e0 = vec4(1.0, 0.0, 0.0, 0.0);
    e0 = e0 / sqrt(-dotg(g, e0, e0));
    vec4 v = vec4(0.0, 1.0, 0.0, 0.0);
    v += dotg(g, v, e0) * e0;
    vec4 e1 = v / sqrt(dotg(g, v, v));
    v = vec4(0.0, 0.0, 1.0, 0.0);
    v += dotg(g, v, e0) * e0;
    v -= dotg(g, v, e1) * e1;
    vec4 e2 = v / sqrt(dotg(g, v, v));
    v = vec4(0.0, 0.0, 0.0, 1.0);
    v += dotg(g, v, e0) * e0;
    v -= dotg(g, v, e1) * e1;
    v -= dotg(g, v, e2) * e2;
    return mat4(e0, e1, e2, v / sqrt(dotg(g, v, v)));
}

// The standard boost: Λ⁰₀ = γ, Λ⁰ᵢ = Λⁱ₀ = γ v nᵢ, Λⁱⱼ = δᵢⱼ + (γ − 1) nᵢ nⱼ.
mat4 boostFrame(mat4 f, float speed, vec3 n) {
    float gam = 1.0 / sqrt(1.0 - speed * speed);
    mat4 out_ = mat4(0.0);
    out_[0] = f * vec4(gam, gam * speed * n);
    for (int i = 0; i < 3; i++) {
        vec3 row = (gam - 1.0) * n[i] * n;
        row[i] += 1.0;
        out_[i + 1] = f * vec4(gam * speed * n[i], row);
    }
    return out_;
}

// The dual rows c_a = η_aa g(e_a, ·): frame components of a vector v are dot(c_a, v).
mat4 dualFrame(mat4 g, mat4 f) {
    mat4 d = mat4(0.0);
    for (int a = 0; a < 4; a++) d[a] = (a == 0 ? -1.0 : 1.0) * (g * f[a]);
    return d;
}
vec4 components(mat4 dual, vec4 v) { return vec4(dot(dual[0], v), dot(dual[1], v), dot(dual[2], v), dot(dual[3], v)); }

