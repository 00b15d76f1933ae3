// ---------------------------------------------------------------------------------------
// Loop by loop, balls in free fall (render::falling, render::circle; docs/physics.md "Balls
// in free fall"). In the pixel ray's origin frame the ray's loop j runs along a circle of the
// disc at times between (j + 1)Δt and jΔt; a ball point lies within static distance reach of
// the centre's point that the static observer there counts as simultaneous, and within the
// time slack S of it. The centre's worldline is cut into cells of proper time (here per
// loop, at most FALL_CELLS, over the proper times whose time may fall in the loop's window;
// the CPU cuts the whole worldline once per render): each cell lies within m of its middle
// point. The first and the last λ of the loop within M = reach + m of a cell whose time lies in
// the window (its z window and the arc of the ray's circle near the cell, by the hyperbolic law
// of cosines) bound the stretch where the loop must search the ball.

// The least and the largest λ in [lo, hi] at which the closed-form ray g (from the origin) may
// lie within hyperbolic distance m of the disc point w (cosh(m/a) given); NO_TAU for both when
// none; lo and hi when unsure (render::circle::RayCircle::arc, Arc::first_in and last_in).
vec2 arcWindow(OGeo g, vec2 w, float coshM, float lo, float hi) {
    if (!finite(lo) || !finite(hi) || !(lo <= hi)) return vec2(NO_TAU);
    float a = u_a;
    float sg = sign(g.e);
    float big = asinh_(g.rmax / (2.0 * a));
    vec2 h = vec2(-sg * g.cchi.y, sg * g.cchi.x) * halfTanh(g.rmax / (2.0 * a));
    float nh = 1.0 - dot(h, h), nw = 1.0 - dot(w, w);
    float ch = 1.0 + 2.0 * dot(w - h, w - h) / (nh * nw);
    float sh = sqrt(max(ch * ch - 1.0, 0.0));
    float num = ch * cosh(big) - coshM;
    float den = sh * sinh(big);
    if (!finite(num) || !finite(den)) return vec2(lo, hi);
    if (num <= -den) return vec2(lo, hi);   // within m all round the circle
    if (num > den) return vec2(NO_TAU);     // beyond m all round
    // Single precision: the arc widened by 1e-4 rad (the CPU's 1e-9).
    float halfArc = acosA(clamp(num / den, -1.0, 1.0)) + 1e-4;
    float beta = carg(cdiv(w - h, vec2(1.0, 0.0) - cmul(conj2(h), w)));
    float lret = returnParameter(g);
    // ψ(λ) = ψ0 − sgn(E)·β + 2πλ/λ_ret, nearest w at whole turns: the arc is |ψ mod 2π| ≤ halfArc.
    float psi0 = sg * carg(-h) - sg * beta;
    float psiLo = psi0 + 2.0 * PI * lo / lret, psiHi = psi0 + 2.0 * PI * hi / lret;
    float rl = psiLo - 2.0 * PI * floor(psiLo / (2.0 * PI) + 0.5);
    float rh = psiHi - 2.0 * PI * floor(psiHi / (2.0 * PI) + 0.5);
    float fwd = abs(rl) <= halfArc ? 0.0 : (rl < -halfArc ? -halfArc - rl : 2.0 * PI - halfArc - rl);
    float back = abs(rh) <= halfArc ? 0.0 : (rh > halfArc ? rh - halfArc : rh + 2.0 * PI - halfArc);
    float first = lo + fwd * lret / (2.0 * PI), last = hi - back * lret / (2.0 * PI);
    return first <= hi && last >= lo ? vec2(first, last) : vec2(NO_TAU);
}

// The proper time of the falling ball i at which its own origin frame's time is t (its
// closed form's time rises at least at (1 + p_z²)/γ per proper time), and how far off it
// may be.
vec2 ballTimeToTau(int i, float t) {
    OGeo b = objs[i].geo;
    float low = (1.0 + b.pz * b.pz) / b.e;
    float tau = t / objs[i].rate;
    float off = 0.0;
    for (int it = 0; it < TIME_STEPS + 1; it++) {
        vec4 e = vec4(0.0), k = vec4(0.0);
        ogeoAt(b, tau, e, k);
        off = t - e.x;
        tau += off / max(k.x, low);
    }
    return vec2(tau, abs(off) / low);
}

// The falling ball i's first and last λ within reach in loop j of the ray `ray` (a pixel ray,
// to the past, or a shadow ray, to the future), from the loop's start (NO_TAU: the loop needs
// no search of the ball), or 0 and INF where the test does not apply (Minkowski); and the
// proper time of the cell that set the first λ (NO_TAU: none),
// the seed of the ball's first probe there (tauGuess's Newton steps from t can stray for a
// fast ball, whose dt/dτ may come near 0).
vec3 fallingWindow(int i, int j, Ray ray) {
    if (!godel()) return vec3(0.0, INF, NO_TAU);
    float a = u_a;
    float gam = objs[i].gamma;
    float sv = sqrt(max(gam * gam - 1.0, 0.0));
    float r = objs[i].radius;
    // Reach and time slack (render::falling), with a margin for single precision.
    float reach = FALL_REACH_PER_RADIUS * r + 1e-4 * a;
    float slack = FALL_REACH_PER_RADIUS * SQRT2 * r + 1e-4 * a;
    float up = gam + SQRT2 * sv;
    Iso toO = inverseIso(ray.back);
    vec4 start = applyIso(toO, objs[i].start);
    // The loop's window of times, and the ball's own time there: the isometry from the
    // ball's origin frame to the ray's shifts times by at most A (docs/physics.md, "Isometries").
    float tj = float(j) * ray.shift.x, tk = float(j + 1) * ray.shift.x;
    float tLo = min(tj, tk) - slack, tHi = max(tj, tk) + slack;
    float wmax = objs[i].geo.rmax / sqrt(objs[i].geo.rmax * objs[i].geo.rmax + 4.0 * a * a);
    float shiftA = 2.0 * SQRT2 * a * asinA(min(length(disc(start.yz)) * wmax, 1.0));
    vec2 t1 = ballTimeToTau(i, tLo - start.x - shiftA), t2 = ballTimeToTau(i, tHi - start.x + shiftA);
    float tau1 = t1.x - t1.y, tau2 = t2.x + t2.y;
    // z is linear along both: no cell can be near when the ball's z range over [τ1, τ2] is
    // farther than the reach (plus the cells' extent) from the loop's.
    float zb1 = start.w + objs[i].u0.w * tau1, zb2 = start.w + objs[i].u0.w * tau2;
    float zr1 = float(j) * ray.shift.y, zr2 = float(j + 1) * ray.shift.y;
    float zGap = max(max(min(zb1, zb2) - max(zr1, zr2), min(zr1, zr2) - max(zb1, zb2)), 0.0);
    float cell = max(FALL_CELL_PER_RADIUS * r, 1e-3 * a);
    if (zGap > reach + 0.5 * sv * max(cell, (tau2 - tau1) / float(FALL_CELLS))) {
        return vec3(NO_TAU);
    }
    int cells = toInt(ceil((tau2 - tau1) / cell), 1, FALL_CELLS);
    float dtau = (tau2 - tau1) / float(cells);
    float near = reach + 0.5 * sv * dtau;
    float coshM = cosh(near / a);
    float sl = slack + 0.5 * up * dtau;
    float l0 = float(j) * ray.lret, l1 = l0 + ray.lret;
    // The ray's time t(λ) lies within `dev` of its mean αλ (timeDeviation).
    float alpha = ray.shift.x / ray.lret, dev = timeDeviation(ray.geo);
    bool timed = abs(alpha) > 0.0 && finite(alpha) && finite(dev);
    float first = INF, last = NO_TAU, seed = NO_TAU;
    for (int c = 0; c < FALL_CELLS; c++) {
        if (c >= cells || (first <= l0 && last >= l1)) break;
        float tau = tau1 + (float(c) + 0.5) * dtau;
        vec4 p = applyIso(toO, worldAt(i, tau).ev);
        if (p.x < tLo + slack - sl || p.x > tHi - slack + sl) continue;
        float lo = l0, hi = l1;
        if (ray.geo.pz == 0.0) {
            if (abs(p.w) > near) continue;
        } else {
            float za = (p.w - near) / ray.geo.pz, zb = (p.w + near) / ray.geo.pz;
            lo = max(min(za, zb), l0);
            hi = min(max(za, zb), l1);
        }
        if (timed) {
            // Where the ray's time may lie within sl of the cell's (widened for f32).
            float band = sl + dev + 1e-4 * a + 1e-5 * abs(p.x);
            float ta = (p.x - band) / alpha, tb = (p.x + band) / alpha;
            lo = max(lo, min(ta, tb));
            hi = min(hi, max(ta, tb));
            if (!(lo <= hi)) continue;
        }
        vec2 w = arcWindow(ray.geo, disc(p.yz), coshM, lo, hi);
        if (w.y > NO_TAU) {
            if (w.x < first) seed = tau;
            first = min(first, w.x);
            last = max(last, w.y);
        }
    }
    return last > NO_TAU ? vec3(first - l0, last - l0, seed) : vec3(NO_TAU);
}


// The falling ball i's window over the stretch [l0, l1] (λ from the start) of a shadow ray
// searched as one chain (startLongSearch): the hull of its loops' windows there, from l0
// (NO_TAU: none); the loops of the closed form that the stretch meets, at most three. Where
// `loop` ≥ 0, loop `loop`'s own window (fallingWindow) instead: both through one call of it
// (the kernel is inlined whole: a second call site would compile the windows twice).
vec3 stretchWindow(int i, Ray ray, float l0, float l1, int loop) {
    vec3 w = vec3(INF, NO_TAU, NO_TAU);
    int k0 = loop;
    if (loop < 0) {
        if (!godel()) return vec3(0.0, INF, NO_TAU);
        k0 = toInt(floor(l0 / ray.lret), 0, 1 << 20);
        // Beyond three loops (a stretch longer than two returns): searched whole.
        if (float(k0 + 3) * ray.lret <= l1) return vec3(0.0, l1 - l0, NO_TAU);
    }
    for (int k = 0; k < 3; k++) {
        float start = float(k0 + k) * ray.lret;
        if (loop < 0 && start > l1) break;
        vec3 lw = fallingWindow(i, k0 + k, ray);
        if (loop >= 0) return lw;
        if (!(lw.y > NO_TAU)) continue;
        float first = max(lw.x + start, l0), last = min(lw.y + start, l1);
        if (!(first <= last)) continue;
        if (first < w.x) w.z = lw.z;
        w.x = min(w.x, first);
        w.y = max(w.y, last);
    }
    return w.y > NO_TAU ? vec3(w.x - l0, w.y - l0, w.z) : vec3(NO_TAU);
}
