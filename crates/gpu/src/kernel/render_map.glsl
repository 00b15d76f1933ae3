// ---------------------------------------------------------------------------------------
// The explore map's light ray of one sample (compiled with RAY_PATH in place of the pixel
// kernel; render::map::light_ray, docs/physics.md "The explore map"): the page reads a
// sample's record from a frame it traced and draws the sample's path on the map with the
// closed forms above, without the server. The exact geodesic from the observer with the
// tangent the pixel kernel launched along the record's direction, sampled from the observer
// to the record's parameter at the hit, or to the trace's past limit for a ray that hit
// nothing. Draw 1 (u_points = 0, one fragment) gives that end parameter, the number of
// points and the emission event's distance from the observer's axis; draw 2 gives the
// points, one a fragment.
#ifdef RAY_PATH
uniform vec4 u_ray;        // the record's direction in the observer's frame; λ at the hit (< 0: none)
uniform vec3 u_emission;   // the emission event's x, y, z (a hit)
uniform int u_points;      // draw 1: 0; draw 2: the points after the observer's event
uniform int u_row;         // draw 2: points per row of the target

// render::map: points per loop of a ray (a loop returns to the observer's axis), the most
// points, doublings and halvings of the search for the parameter where a ray reaches a time.
const float POINTS_PER_LOOP = 96.0;
const int MAX_RAY_POINTS = 4096;
const int MAP_SEARCH_STEPS = 200;

vec4 rayEvent(Ray r, float l) {
    vec4 ev = vec4(0.0), k = vec4(0.0);
#ifdef MEMBER
    memberRayAt(r, l, ev, k);
    return ev;
#endif
    rayAt(r, 0, l, ev, k);
    return ev;
}

// Whether the ray's event e has ended it: reached relative time t (t decreases along it), or
// in a member with m² > 0 left the scenes' chart, mρ = MAX_M_RHO, where an escaping ray runs
// out as e^{mρ}.
bool ended(vec4 e, float t) {
#ifdef MEMBER
    if (MEMBER_M2 > 0.0 && sqrt(MEMBER_M2) * length(e.yz) > MAX_M_RHO) return true;
#endif
    return e.x <= t;
}

// The parameter at which the past-directed ray has ended: doubling, then bisection, each
// bounded.
float parameterAtTime(Ray r, float t) {
    float hi = 1.0;
    for (int i = 0; i < MAP_SEARCH_STEPS; i++) {
        if (ended(rayEvent(r, hi), t)) break;
        hi *= 2.0;
    }
    float lo = 0.0;
    for (int i = 0; i < MAP_SEARCH_STEPS; i++) {
        float mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        if (!ended(rayEvent(r, mid), t)) lo = mid; else hi = mid;
    }
    return hi;
}

void main() {
    for (int s = 0; s < ALL_SLOTS + 8; s++) slots[s] = vec4(0.0);
    vec4 obs = vec4(0.0, u_obs_x);
    mat4 frame = boostFrame(u_obs_static, u_velocity.x, u_velocity.yzw);
    Ray r = makeRay(obs, frame * vec4(-1.0, normalize(u_ray.xyz)), observerToOrigin());
    if (!r.geo.ok || (godel() && (!finite(r.shift.x) || !(r.shift.x < 0.0)))) {
        slots[0] = vec4(-1.0);   // no closed form: no path
    } else if (u_points == 0) {
        float end = u_ray.w >= 0.0 ? u_ray.w : parameterAtTime(r, -u_max_past);
        // (A member's escaping ray: one loop, as on the CPU.)
        float loops = godel() || (member() && r.lret < INF) ? max(end / r.lret, 1.0) : 1.0;
        float points = min(max(ceil(loops * POINTS_PER_LOOP), 2.0), float(MAX_RAY_POINTS - 1));
        vec4 e = vec4(0.0, u_emission);
        float rEmit = godel() ? length(applyIso(observerToOrigin(), e).yz) : length(e.yz - obs.yz);
#ifdef MEMBER
        rEmit = length(typeApplyIso(MB, TIso(0.0, u_obs_to.xy, u_obs_to.z, u_obs_to.w), e).yz);
#endif
        slots[0] = vec4(end, points, rEmit, 1.0);
    } else {
        ivec2 p = ivec2(gl_FragCoord.xy);
        int i = 1 + p.x + u_row * p.y;
        float l = u_ray.w * float(i) / float(u_points);
#ifdef MEMBER
        // The distance from the observer's axis: ρ in the origin frame, the same in every loop.
        slots[0] = rayEvent(r, l);
        int j = r.lret < INF ? toInt(floor(l / r.lret), 0, MAX_COUNT_SEGMENTS) : 0;
        vec4 e0 = vec4(0.0), k0 = vec4(0.0);
        tgeoAt(r.tex.origin, l - float(j) * r.lret, e0, k0);
        slots[1] = vec4(length(e0.yz), 0.0, 0.0, 0.0);
        writeSlots();
        return;
#endif
        if (godel()) {
            // In the origin frame the distance from the observer's axis is the cylindrical r.
            vec4 e0 = vec4(0.0), k0 = vec4(0.0);
            ogeoAt(r.geo, l, e0, k0);
            slots[0] = applyIso(r.back, e0);
            slots[1] = vec4(length(e0.yz), 0.0, 0.0, 0.0);
        } else {
            slots[0] = obs + l * r.k0;
            slots[1] = vec4(length(slots[0].yz - obs.yz), 0.0, 0.0, 0.0);
        }
    }
    writeSlots();
}
#endif
