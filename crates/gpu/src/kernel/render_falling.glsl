// ---------------------------------------------------------------------------------------
// Loop by loop, balls in free fall (render::falling, render::circle; docs/physics.md "Balls
// in free fall"). In the pixel ray's origin frame the ray's loop j runs along a circle of the
// disc at times between (j + 1)Δt and jΔt; a ball point lies within static distance reach of
// the centre's point that the static observer there counts as simultaneous, and within the
// time slack S of it. The centre's worldline is cut into cells of proper time (here per
// loop, at most FALL_CELLS, over the proper times whose time may fall in the loop's window;
// the CPU cuts the whole worldline once per render): each cell lies within m of its middle
// point. The last λ of the loop within M = reach + m of a cell whose time lies in the window
// (its z window and the arc of the ray's circle near the cell, by the hyperbolic law of
// cosines) is the last λ where the loop must search the ball.

// The largest λ in [lo, hi] at which the closed-form ray g (from the origin) may lie within
// hyperbolic distance m of the disc point w (cosh(m/a) given); NO_TAU when none; hi when
// unsure (render::circle::RayCircle::arc and Arc::last_in).
float lastWithin(OGeo g, vec2 w, float coshM, float lo, float hi) {
    if (!finite(lo) || !finite(hi) || !(lo <= hi)) return NO_TAU;
    float a = u_a;
    float sg = sign(g.e);
    float big = asinh_(g.rmax / (2.0 * a));
    vec2 h = vec2(-sg * g.cchi.y, sg * g.cchi.x) * halfTanh(g.rmax / (2.0 * a));
    float nh = 1.0 - dot(h, h), nw = 1.0 - dot(w, w);
    float ch = 1.0 + 2.0 * dot(w - h, w - h) / (nh * nw);
    float sh = sqrt(max(ch * ch - 1.0, 0.0));
    float num = ch * cosh(big) - coshM;
    float den = sh * sinh(big);
    if (!finite(num) || !finite(den)) return hi;
    if (num <= -den) return hi;     // within m all round the circle
    if (num > den) return NO_TAU;   // beyond m all round
    // Single precision: the arc widened by 1e-4 rad (the CPU's 1e-9).
    float halfArc = acosA(clamp(num / den, -1.0, 1.0)) + 1e-4;
    float beta = carg(cdiv(w - h, vec2(1.0, 0.0) - cmul(conj2(h), w)));
    float lret = returnParameter(g);
    float psiHi = sg * carg(-h) - sg * beta + 2.0 * PI * hi / lret;
    float r = psiHi - 2.0 * PI * floor(psiHi / (2.0 * PI) + 0.5);
    float back = abs(r) <= halfArc ? 0.0 : (r > halfArc ? r - halfArc : r + 2.0 * PI - halfArc);
    float l = hi - back * lret / (2.0 * PI);
    return l >= lo ? l : NO_TAU;
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

// The falling ball i's last λ within reach in loop j of the pixel ray `ray`, from the loop's
// start (NO_TAU: the loop needs no search of the ball), or INF where the test does not apply
// (Minkowski).
float fallingLast(int i, int j, Ray ray) {
    if (!godel()) return INF;
    float a = u_a;
    float gam = objs[i].gamma;
    float sv = sqrt(max(gam * gam - 1.0, 0.0));
    float r = objs[i].radius;
    // Reach and time slack (render::falling), widened for single precision.
    float reach = 1.25 * r + 1e-4 * a;
    float slack = 1.25 * SQRT2 * r + 1e-4 * a;
    float up = gam + SQRT2 * sv;
    Iso toO = inverseIso(ray.back);
    vec4 start = applyIso(toO, objs[i].start);
    // The loop's window of times, and the ball's own time there: the isometry from the
    // ball's origin frame to the ray's shifts times by at most A (docs/physics.md, "Isometries").
    float tLo = float(j + 1) * ray.shift.x - slack, tHi = float(j) * ray.shift.x + slack;
    float wmax = objs[i].geo.rmax / sqrt(objs[i].geo.rmax * objs[i].geo.rmax + 4.0 * a * a);
    float shiftA = 2.0 * SQRT2 * a * asinA(min(length(disc(start.yz)) * wmax, 1.0));
    vec2 t1 = ballTimeToTau(i, tLo - start.x - shiftA), t2 = ballTimeToTau(i, tHi - start.x + shiftA);
    float tau1 = t1.x - t1.y, tau2 = t2.x + t2.y;
    // z is linear along both: no cell can be near when the ball's z range over [τ1, τ2] is
    // farther than the reach (plus the cells' extent) from the loop's.
    float zb1 = start.w + objs[i].u0.w * tau1, zb2 = start.w + objs[i].u0.w * tau2;
    float zr1 = float(j) * ray.shift.y, zr2 = float(j + 1) * ray.shift.y;
    float zGap = max(max(min(zb1, zb2) - max(zr1, zr2), min(zr1, zr2) - max(zb1, zb2)), 0.0);
    if (zGap > reach + 0.5 * sv * max(max(r, 1e-3), (tau2 - tau1) / float(FALL_CELLS))) {
        return NO_TAU;
    }
    int cells = toInt(ceil((tau2 - tau1) / max(r, 1e-3)), 1, FALL_CELLS);
    float dtau = (tau2 - tau1) / float(cells);
    float near = reach + 0.5 * sv * dtau;
    float coshM = cosh(near / a);
    float sl = slack + 0.5 * up * dtau;
    float l0 = float(j) * ray.lret, l1 = l0 + ray.lret;
    float last = NO_TAU;
    for (int c = 0; c < FALL_CELLS; c++) {
        if (c >= cells || last >= l1) break;
        vec4 p = applyIso(toO, worldAt(i, tau1 + (float(c) + 0.5) * dtau).ev);
        if (p.x < tLo + slack - sl || p.x > tHi - slack + sl) continue;
        float lo = l0, hi = l1;
        if (ray.geo.pz == 0.0) {
            if (abs(p.w) > near) continue;
        } else {
            float za = (p.w - near) / ray.geo.pz, zb = (p.w + near) / ray.geo.pz;
            lo = max(min(za, zb), l0);
            hi = min(max(za, zb), l1);
        }
        float l = lastWithin(ray.geo, disc(p.yz), coshM, max(lo, last), hi);
        if (l > NO_TAU) last = l;
    }
    return last > NO_TAU ? last - l0 : NO_TAU;
}

