// ---------------------------------------------------------------------------------------
// The record of one sample: slots of four channels (crates/gpu/src/input.rs lists them):
// 0 (object, status, u, v), 1 (g, t_emit, lambda, cos_i), 2 (x, y, z, view_x),
// 3 (dir_x, dir_y, dir_z, view_y), 4 (view_z, pol_x, pol_y, pol_z), then four lights each from 5.

// The pixel's screen-up and screen-right (docs/physics.md, "Polarization", "The pixel's
// screen"; render::polarization::screen): the camera's up projected orthogonal to the
// pixel's direction n (forward where n is along up), and n × that, as vectors of the
// observer's frame.
void pixelScreen(mat4 frame, vec3 n) {
    vec3 s = u_up - dot(u_up, n) * n;
    if (dot(s, s) < 1e-12) s = u_forward - dot(u_forward, n) * n;
    s = normalize(s);
    hp.up = frame * vec4(0.0, s);
    hp.right = frame * vec4(0.0, cross(n, s));
}

// The screen vectors parallel-transported along the pixel's ray r from the observer `obs` to
// the hit at `within` into loop `loop`, `lambda` in all (render::polarization::exact): pushed
// to the origin by the observer's isometry, transported there in closed form over the whole
// parameter ("Parallel transport along closed forms") and pushed back. The ray's event in
// its origin frame is taken at `within`: later loops retrace the first shifted in t and z,
// which moves no vector. Minkowski: components are kept (Cartesian coordinates, no Γ). A
// Gödel-type member: integrated along the closed form (typeTransport).
void transportScreen(Ray r, vec4 obs, int loop, float within, float lambda) {
#ifdef MEMBER
    hitRay = r;   // transported by surface() (memberTransports)
    hitLoop = loop;
    hitWithin = within;
    return;
#endif
    if (!godel()) return;
    vec4 e0 = vec4(0.0), k0 = vec4(0.0);
    ogeoAt(r.geo, within, e0, k0);
    Iso to = observerToOrigin();
    mat4 legs = pushLegs(to, obs, mat4(hp.up, hp.right, vec4(0.0), vec4(0.0)), 2);
    legs = pushLegs(r.back, e0, transportLegs(r.geo, lambda, e0, legs, 2), 2);
    hp.up = legs[0];
    hp.right = legs[1];
}

// The outputs: slots [u_slot0, u_slot0 + DRAW_BUFFERS) of `slots`.
// Whether main's round was cut short by llvmpipe's loop limit: it then writes the previous
// round's slots (zeros in a first round) and its progress.
bool roundCut = false;
bool cutRecord = false;   // and the sample ended out of work (its record's status slot)

vec4 slotOut(int layer) {
    if (cutRecord && layer == 0) return vec4(-1.0, float(WORK_LIMIT), 0.0, 0.0);
    if (!roundCut || layer >= STATE) return slots[layer];
    ivec2 frag = ivec2(gl_FragCoord.xy);
    return u_round > 0 ? texelFetch(u_prev, ivec3(frag, layer), 0) : vec4(0.0);
}

void writeSlots() {
    o0 = slotOut(u_slot0);
#if DRAW_BUFFERS > 1
    o1 = slotOut(u_slot0 + 1);
#endif
#if DRAW_BUFFERS > 2
    o2 = slotOut(u_slot0 + 2);
#endif
#if DRAW_BUFFERS > 3
    o3 = slotOut(u_slot0 + 3);
#endif
#if DRAW_BUFFERS > 4
    o4 = slotOut(u_slot0 + 4);
#endif
#if DRAW_BUFFERS > 5
    o5 = slotOut(u_slot0 + 5);
#endif
#if DRAW_BUFFERS > 6
    o6 = slotOut(u_slot0 + 6);
#endif
#if DRAW_BUFFERS > 7
    o7 = slotOut(u_slot0 + 7);
#endif
}

// ---------------------------------------------------------------------------------------
// Rounds (docs/physics.md, "The GPU kernel", "Rounds"). A sample is traced in rounds of draws
// (crates/gpu/src/host.rs; the page's trace.js): each round goes on from where the previous
// one left the sample, for at most its budget of passes, and keeps what it finished up to the
// last checkpoint it reached: the start of a loop of the pixel's search where a pass begins
// (a pass may go on over loops that need no search: render_intersect), every SPAN_CHECK
// probes of a bisection in it, the search's end, and each step of the
// shadow rays' enumeration. At a checkpoint the sample's state is a few numbers (Progress),
// written into its state slots; the next round makes everything else again from them, and
// the searches are memoryless there (a loop probes its objects afresh; a bisection's
// checkpoint is reached again through its loop, with the same probes).
// So a record does not depend on how its work was cut into rounds: not on draw sizes, the
// driver's grouping of samples, timing or load. llvmpipe ends every loop of a shader once its
// loops have run 65535 passes in all, per group of samples and silently: a round cut short
// so is told by a last loop that must run twice, and dropped (the sample runs it again with
// half the budget).

const int PH_PIXEL = 0;    // the pixel's search, in loop `counter`: at its start (seg < 0),
                           // or in a bisection (Span)
const int PH_LIGHTS = 1;   // the shadow rays: light `counter`, grid index `idx`; `sub` ≥ 0: in
                           // the occlusion search of the step's ray, at the start of stretch `sub`
const int PH_DONE = 2;     // finished with `status`
// Ints kept in f32 between rounds: exact up to 2^24.
const int MAX_COUNT = 16777215;
// Rounds cut one after the other before a checkpoint: a sample whose work between two
// checkpoints does not fit a round under llvmpipe's limit beside its neighbours' work.
const int MAX_CUTS = 6;

struct Progress {
    int phase; int budget; int probes;
    int status;   // PH_DONE: the sample's status
    int cuts;     // else: rounds cut by llvmpipe's limit since the last checkpoint
    int counter; int idx; int sub;
    float sum;   // the current light's sum so far (−1: unknown, one of its searches ran out of work)
    Found hit;   // the pixel's hit (PH_LIGHTS; PH_DONE with status HIT); PH_PIXEL in a
                 // bisection: the segment's earliest crossing so far
    Span span;   // PH_PIXEL: a bisection's checkpoint (render_intersect)
};

// The progress in three slots, every number an integer below 2^24 or a float kept as it is:
//   (phase (the hosts read it), budget + 2^21 · cuts, probes, PH_DONE ? status : span index
//    mod 2^15),
//   (counter, PH_PIXEL ? span seg + 16 · depth + 512 · (index / 2^15) (−1: none) : idx, sum
//    (PH_PIXEL: span a), hit target + 1 + 4096 · span obj),
//   (PH_PIXEL ? span seed : hit loop, hit lambda, hit tau, PH_PIXEL ? span probes : sub).
// (Depth ≤ SEARCH_DEPTH < 32 and index < 2^SEARCH_DEPTH = 2^30; segments < EXACT_SEGMENTS =
// 16; budget ≤ MAX_BUDGET = 2^20; objects < 4096: a scene with more takes no bisection
// checkpoints, main.)
Progress readProgress() {
    vec4 s0 = slots[STATE], s1 = slots[STATE + 1], s2 = slots[STATE + 2];
    int phase = toInt(s0.x, PH_PIXEL, PH_DONE);
    int pack = toInt(s0.y, 0, MAX_COUNT);
    int cuts = min(pack >> 21, MAX_CUTS);
    int targets = toInt(s1.w, 0, MAX_COUNT);
    int code = toInt(s1.y, -1, MAX_COUNT);
    Found hit = Found(HIT, (targets & 4095) - 1, toInt(s2.x, 0, MAX_COUNT), s2.y, s2.z);
    Span span = NO_SPAN;
    int idx = code;
    int sub = toInt(s2.w, -1, MAX_COUNT);
    if (phase == PH_PIXEL) {
        idx = -1;
        sub = -1;
        hit.loop_ = toInt(s1.x, 0, MAX_COUNT);
        if (code >= 0) {
            span = Span(code & 15, targets >> 12, (code >> 4) & 31,
                        ((code >> 9) << 15) + toInt(s0.w, 0, 32767), toInt(s2.w, 0, SEARCH_PROBES), s1.z, s2.x);
        }
    }
    return Progress(phase, clamp(pack & 2097151, MIN_BUDGET, MAX_BUDGET), toInt(s0.z, 0, PIXEL_PROBES),
                    phase == PH_DONE ? toInt(s0.w, 0, WORK_LIMIT) : NOT_TRACED, phase == PH_DONE ? 0 : cuts,
                    toInt(s1.x, 0, MAX_COUNT), idx, sub, s1.z, hit, span);
}

void writeProgress(Progress p) {
    bool pixel = p.phase == PH_PIXEL;
    Span sp = p.span;
    bool inSpan = pixel && sp.seg >= 0;
    float code = float(p.idx), sum = p.sum, first = float(p.hit.loop_), last = float(p.sub);
    if (pixel) {
        code = inSpan ? float(sp.seg + 16 * sp.depth + 512 * (sp.index >> 15)) : -1.0;
        sum = sp.a;
        first = sp.seed;
        last = float(sp.probes);
    }
    float w = p.phase == PH_DONE ? float(p.status) : float(sp.index & 32767);
    slots[STATE] = vec4(float(p.phase), float(p.budget + 2097152 * p.cuts), float(p.probes), w);
    slots[STATE + 1] = vec4(float(p.counter), code, sum, float(p.hit.target + 1 + 4096 * (inSpan ? sp.obj : 0)));
    slots[STATE + 2] = vec4(first, p.hit.lambda, p.hit.tau, last);
}

// Whether the checkpoint p lies after q (the order of the work: phase, loop or light, then
// the pixel's segment, object and bisection probes, or the lights' grid index and stretch).
bool after(Progress p, Progress q) {
    if (p.phase != q.phase) return p.phase > q.phase;
    if (p.counter != q.counter) return p.counter > q.counter;
    if (p.phase == PH_PIXEL) {
        if (p.span.seg != q.span.seg) return p.span.seg > q.span.seg;
        if (p.span.obj != q.span.obj) return p.span.obj > q.span.obj;
        return p.span.probes > q.span.probes;
    }
    if (p.idx != q.idx) return p.idx > q.idx;
    return p.sub > q.sub;
}

// Checkpoints: the start of loop `loop` of the pixel's search; a step of the shadow rays
// (the enumeration's state); the end.
Progress atLoop(Progress p, int loop) {
    p.phase = PH_PIXEL;
    p.counter = loop;
    p.span = NO_SPAN;
    p.hit = NO_FOUND;
    p.probes = probes_left;
    return p;
}
// In a bisection (render_intersect's nextSpan): the new span's end probe requested.
Progress atSpan(Progress p) {
    p.phase = PH_PIXEL;
    p.counter = mach.loop_;
    p.span = Span(mach.seg, mach.obj, bis.depth, bis.index, bis.probes, bis.a, bis.seedA);
    p.hit = mach.best;
    p.probes = probes_left;
    return p;
}
Progress atStretch(Progress step, int stretch) {
    step.sub = stretch;
    step.probes = probes_left;
    return step;
}
Progress atLightStep(Progress p, Found hit) {
    p.phase = PH_LIGHTS;
    p.counter = shadow.light;
    p.idx = shadow.idx;
    p.sub = -1;
    p.sum = shadow.failed ? -1.0 : shadow.sum;
    p.hit = hit;
    p.probes = probes_left;
    return p;
}
Progress atEnd(Progress p, int status, Found hit) {
    p.phase = PH_DONE;
    p.status = status;
    p.hit = hit;
    p.probes = probes_left;
    return p;
}

// Starts the pixel's search along r; -1, or the sample's status where no search is needed.
int startPixel(Ray r, vec4 obs, float pt, float tBound) {
    bool any = setSearched(obs, r.geo, INF, -1, INF);
    if (!r.geo.ok) return FAILED;
#ifdef MEMBER
    // render::tracer: a returning ray must go to the past; one near no object escapes where
    // it never returns, or reaches the time bound within the loops (escape_unsearched).
    bool returns = r.lret < INF;
    if (returns && (!finite(r.shift.x) || !(r.shift.x < 0.0))) return FAILED;
    if (!any && (!returns || float(u_max_loops) * r.shift.x < tBound)) return ESCAPED;
#if MEMBER_CAUSAL != 0
    escapeSetUp(r);
#endif
    float total = returns ? float(u_max_loops + 1) * float(r.nseg) : float(MAX_FAMILY_SEGMENTS);
    memberSearch(r, toInt(total, 1, 1 << 30), pt, tBound);
    return -1;
#endif
    if (godel()) {
        if (!finite(r.shift.x) || !(r.shift.x < 0.0)) return FAILED;
        // A ray near no object escapes (if it reaches the time bound within the loops).
        if (!any) return float(u_max_loops) * r.shift.x < tBound ? ESCAPED : WORK_LIMIT;
        startSearch(r, u_max_loops + 1, EXACT_SEGMENTS, r.lret, pt, true, tBound);
    } else {
        float lmax = u_max_past / max(abs(r.k0.x), 1e-30);
        startLongSearch(r, toInt(ceil(lmax), 1, MAX_SEGMENTS), lmax, pt, true, tBound);
    }
    return -1;
}

// The pixel's hit f: its event, body frame, surface and shift (h*, which the lights use) and
// the record's slots; its status (escaped where the hit lies before the time bound, failed
// where it has no surface or shift).
int takeHit(Found f, Ray r, mat4 frame, vec3 n, vec4 obs, vec4 k, float tBound) {
    rayAt(r, f.loop_, f.lambda, hp.x, hp.k);
    float lambda = f.lambda + float(f.loop_) * r.lret;
    pixelScreen(frame, n);
    transportScreen(r, obs, f.loop_, f.lambda, lambda);
    hp.target = f.target;
    hp.at.tau = f.tau;
    bool ok = surface();
    // g = (p·u_obs)/(p·u_emit), the backward ray's momentum at both ends.
    float g = dot(frame[0], metricAt(obs) * k) / dot(hp.uemit, metricAt(hp.x) * hp.k);
    if (hp.x.x < tBound) return ESCAPED;
    if (!ok || !(g > 0.0 && finite(g))) return FAILED;
    slots[0] = vec4(float(hp.target), 0.0, hp.uv);
    slots[1] = vec4(g, hp.x.x, lambda, hp.cosI);
    slots[2].xyz = hp.x.yzw;
    slots[3].xyz = hp.dir;
    slots[4].yzw = hp.pol;
    return HIT;
}

// The record's status slot, for a sample finished with `status` after its probes (the hit's
// other slots are takeHit's).
void finishRecord(int status, int probes) {
    if (status != HIT) slots[0] = vec4(-1.0, float(status), 0.0, 0.0);
#ifdef COUNT_PROBES
    slots[2].w = float(PIXEL_PROBES - probes);   // benchmarks: the probes in view_x
#endif
}

#if !defined(RAY_PATH) && !defined(PROBE)
// One round of one sample (u_finish 0: its progress, its lights', and its record once it is
// finished), or its record from its final progress (u_finish 1: where the host's render
// targets cannot take every slot in one draw, its rounds write only the lights' and the
// progress's slots, and this draw the record's).
void main() {
    ivec2 frag = ivec2(gl_FragCoord.xy);
    ivec2 pix = u_origin + frag;
    for (int s = 0; s < ALL_SLOTS + 8; s++) slots[s] = vec4(0.0);
    // The previous round's slots: the record (of a sample finished before), the lights and
    // the progress.
    if (u_round > 0) {
        for (int layer = 0; layer < ALL_SLOTS; layer++) slots[layer] = texelFetch(u_prev, ivec3(frag, layer), 0);
    }
    // (No ?: between structures: WebGL forbids it.)
    Progress at = Progress(PH_PIXEL, clamp(u_budget, MIN_BUDGET, MAX_BUDGET), PIXEL_PROBES,
                           NOT_TRACED, 0, 0, -1, -1, 0.0, NO_FOUND, NO_SPAN);
    if (u_round > 0) at = readProgress();
    if (u_finish == 0 && at.phase == PH_DONE) {   // finished in an earlier round: kept as it is
        writeSlots();
        return;
    }
    probes_left = at.probes;
    Progress cp = at;   // the last checkpoint reached
    bool moved = false; // whether it lies past the round's start

    vec3 d = vec3(0.0);
    bool traced = cameraDirection(vec2(pix) + 0.5, d);
    vec3 right = cross(u_forward, u_up);
    vec3 n = d.x * u_forward + d.y * right + d.z * u_up;
    slots[2].w = n.x;
    slots[3].w = n.y;
    slots[4].x = n.z;
    loadObjects();
    vec4 obs = vec4(0.0, u_obs_x);
    // The static frame is the host's; the boost is made here, as the page sets the velocity
    // of each flying frame itself.
    mat4 frame = boostFrame(u_obs_static, u_velocity.x, u_velocity.yzw);
    vec4 k = frame * vec4(-1.0, n);                 // the past-directed photon
    float pt = (metricAt(obs) * k).x;               // p_t, conserved
    Ray r = makeRay(obs, k, observerToOrigin());
    float tBound = -u_max_past;

    // The finishing draw's status (a hit's slots are made again by takeHit below).
    int finished = !traced ? NOT_TRACED : at.phase == PH_DONE ? at.status : WORK_LIMIT;
    bool searching = false;
    bool pixelSearch = false;
    int resume = -1;   // the stretch at which the restored step's occlusion search goes on
    Found hit = at.hit;
    Progress step = at;   // the current step of the shadow rays, as a checkpoint
    if (!traced) {
        cp = atEnd(at, NOT_TRACED, NO_FOUND);
    } else if (at.phase == PH_PIXEL) {
        int decided = startPixel(r, obs, pt, tBound);
        if (decided >= 0) {
            cp = atEnd(at, decided, NO_FOUND);
        } else {
            mach.loop_ = at.counter;
            searching = true;
            pixelSearch = true;
            Span sp = at.span;
            if (sp.seg >= 0) {   // back to a bisection's checkpoint, through its loop
                Found best = Found(ESCAPED, -1, 0, 0.0, NO_TAU);
                if (at.hit.target >= 0) best = at.hit;
                res = Resume(true, sp, best, at.probes);
            }
        }
    } else if (at.phase == PH_LIGHTS) {
        shadow.light = at.counter;
        shadow.idx = at.idx;
        shadow.failed = at.sum < 0.0;
        shadow.sum = max(at.sum, 0.0);
        resume = at.sub;
    }
    if (cp.phase == PH_DONE) moved = true;
    // The hit is taken (takeHit: its event, surface, shift and record slots) at the top of the
    // loop below, its one call site (GLSL inlines every call: one copy of the surface's code
    // keeps the kernel's compilation short): for the finishing draw, for a round that resumes
    // the lights, and once the pixel's search has found it (`fresh`).
    bool take = u_finish != 0 ? finished == HIT : traced && at.phase == PH_LIGHTS;
    bool fresh = false;

    // The passes: the pixel's search, then the shadow rays light by light, each step of their
    // enumeration a checkpoint, the search of one ray's occlusion between two steps. A
    // search's passes run in a loop of their own: llvmpipe runs every statement of a loop's
    // body on each pass, masked, so the enumeration's code stays out of the search's loop.
    spent = 0;
    for (int job = 0; job < MAX_BUDGET && (take || (u_finish == 0 && cp.phase != PH_DONE && spent < at.budget)); job++) {
        if (take) {
            take = false;
            int status = takeHit(hit, r, frame, n, obs, k, tBound);
            if (u_finish != 0) {
                finished = status;
                break;
            }
            if (fresh) {
                fresh = false;
                moved = true;
                if (status != HIT || minkowski() || HAS_LIGHTS == 0 || u_lights == 0) {
                    cp = atEnd(cp, status, hit);
                    break;
                }
                shadow.light = 0;
                shadow.idx = -1;
                shadow.sum = 0.0;
                shadow.failed = false;
                cp = atLightStep(cp, hit);
            } else if (shadow.idx >= 0 && shadow.light < u_lights) {
                lightGeometry();   // a resumed light's, from the hit just taken
            }
            continue;
        }
        if (searching) {
            for (int pass = 0; pass < MAX_BUDGET && mach.mode != M_DONE && spent < at.budget; pass++) {
                spent++;
                // A loop's or a stretch's start, or a bisection's checkpoint in the pixel's
                // search: a checkpoint (none before the round's start).
                bool atSpanCheck = pixelSearch && mach.check && req.tag == Q_SPAN && N_OBJECTS < 4096;
                if ((mach.mode == M_LOOP && req.tag == Q_NONE) || atSpanCheck) {
                    Progress p = atStretch(step, mach.loop_);   // (no ?: of structures in WebGL)
                    if (pixelSearch) p = atLoop(cp, mach.loop_);
                    if (atSpanCheck) p = atSpan(cp);
                    if (!after(at, p)) {
                        moved = moved || after(p, at);
                        cp = p;
                    }
                }
                searchPass();
            }
            if (mach.mode != M_DONE) break;   // the round's budget is spent
            searching = false;
            Found f = mach.result;
            if (pixelSearch) {
                pixelSearch = false;
                if (f.status != HIT) {
                    moved = true;
                    cp = atEnd(cp, f.status, f);
                    break;
                }
                hit = f;
                take = true;
                fresh = true;
                continue;
            }
            if (f.status == WORK_LIMIT || f.status == FAILED) {   // occlusion unknown
                shadow.failed = true;
            } else if (f.status != HIT) {
                shadow.sum += shadow.weight;
            }
            continue;
        }
#if HAS_LIGHTS != 0
        // Steps of the shadow rays' enumeration, in a loop of their own until one needs an
        // occlusion search: a light's set-up or end, sixteen cells of its grid, or a root's
        // refinement and its ray's set-up.
        for (int pass = 0; pass < MAX_BUDGET && !searching && spent < at.budget; pass++) {
            spent++;
            step = atLightStep(cp, hit);
            if (!after(at, step)) {
                moved = moved || after(step, at);
                cp = step;
            }
            if (shadow.light >= u_lights) {
                cp = atEnd(cp, HIT, hit);
                break;
            }
            if (shadow.idx < 0) {
                if (!startLight()) endLight();
            } else if (shadow.idx >= shadow.total || shadow.failed) {
                endLight();
            } else if (gridPass()) {
                for (int it = 0; it < REFINE_STEPS && shadow.iter >= 0; it++) {
                    spent++;
                    if (rootStep()) break;
                }
                int use = shadowRaySetUp();
                if (use == 1) shadow.sum += shadow.weight;
                if (use == 2) {
                    searching = true;
                    if (resume >= 0) {   // the restored step's search, where it was (aimed before)
                        mach.loop_ = resume;
                        mach.mode = M_LOOP;
                    }
                    resume = -1;
                }
            }
        }
        if (!searching && cp.phase != PH_DONE) break;   // the round's budget is spent
#endif
    }

    if (u_finish != 0) {
        finishRecord(finished, at.probes);
        writeSlots();
        return;
    }

    // llvmpipe's loop limit: a loop that must run twice tells whether this round was cut.
    int passes = 0;
    for (int i = 0; i < u_two; i++) passes++;
    Progress next = cp;
    next.budget = at.budget;
    if (passes != 2) {
        // Cut short: nothing of this round is kept; again with half the budget. After
        // MAX_CUTS cuts without a checkpoint the pixel's search is out of work, or the
        // light's occlusion unknown.
        roundCut = true;
        next = at;
        next.budget = max(at.budget / 2, MIN_BUDGET);
        next.cuts = at.cuts + 1;
        if (next.cuts > MAX_CUTS && at.phase == PH_LIGHTS) {
            next.sum = -1.0;
            next.cuts = 0;
        } else if (next.cuts > MAX_CUTS) {
            next = atEnd(at, WORK_LIMIT, NO_FOUND);
            cutRecord = true;
        }
    } else if (moved) {
        next.cuts = 0;
    } else {
        // No checkpoint reached: more passes next round, up to MAX_BUDGET; beyond that the
        // pixel's search is out of work, or the light's occlusion unknown.
        if (at.budget < MAX_BUDGET) next.budget = min(at.budget * 2, MAX_BUDGET);
        else if (at.phase == PH_LIGHTS) next.sum = -1.0;
        else next = atEnd(at, WORK_LIMIT, NO_FOUND);
    }
    // A sample finished in this round: its record (a hit's slots are the hit's, made by
    // takeHit in this round).
    if (passes == 2 && next.phase == PH_DONE) finishRecord(next.status, next.probes);
    writeProgress(next);
    writeSlots();
}
#endif

