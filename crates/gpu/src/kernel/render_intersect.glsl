// ---------------------------------------------------------------------------------------
// The intersection search (render::intersect, render::tracer; docs/physics.md "The
// intersection search") as one state machine with one probe call: a ray is searched loop by
// loop (later loops are the first one's copies) and segment by segment; per segment and
// object, conservative advancement from the last probe, else a depth-first bisection that
// drops spans excluded by the rate bound or, near a ball at rest, by the chord of its
// rest-frame path (chordExcludes; at most SEARCH_DEPTH halvings and SEARCH_PROBES
// probes), and the Illinois refinement of a crossing. Spans are dyadic pieces of the
// searched stretch, so the span after a finished one follows from its depth and index (its
// start probe is the finished span's end probe). A right half's end probe is its parent's,
// kept where that halving was the last (`pending`: the top of the CPU's stack, the common
// case, its left half dropped whole), else probed again.
//
// A long bisection is a checkpoint of the sample's rounds (render_tracer's main) every
// SPAN_CHECK probes, at the request of a span's end probe: a round resumes there by going
// through its loop again without bisecting (its start and end probes, each the same as
// before), then the bisection from its depth and index (Resume). The kept end probe is
// dropped at every such checkpoint, whether or not a round ends there, so a resumed
// bisection takes the probes of one that ran on.

// The most loops without a search that one pass passes over.
const int LOOPS_PER_PASS = 16;
const int M_LOOP = 0;      // at the start of loop mach.loop_
const int M_AIM = 1;       // aimed occlusion before a shadow ray's search (startAim)
const int M_SCAN = 2;      // the next object of the segment
const int M_BISECT = 3;    // the span [bis.a, bis.b] of object mach.obj, both end probes known
const int M_REFINE = 4;    // Illinois steps on a crossing
const int M_DONE = 5;

// What a requested probe is for.
const int Q_NONE = 0;
const int Q_AIM = 1;       // where a shadow ray most likely passes deepest into ball mach.obj
const int Q_END = 2;       // the segment's end probe of object mach.obj
const int Q_SPAN = 3;      // the end probe of the span [bis.a, bis.b]
const int Q_REFINE = 4;    // a refinement step at req.lambda
const int Q_ROOT = 5;      // the crossing's own probe (its τ; the plane's extent)
const int Q_RESUME = 6;    // a resumed bisection's probe at its span's start (Resume)
const int Q_FRESH = 7;     // object mach.obj's probe where its part of the segment starts,
                           // where it has none there (objectPart; M_SCAN)

// Probes of a bisection between two of its checkpoints.
const int SPAN_CHECK = 256;

// The passes that the sample's round has spent (render_tracer's main holds them against the
// round's budget). A pass that goes on over loops or segments without a probe counts one for
// each, as the pass each took before: a round's budget then bounds its work, and with it the
// loops' iterations that llvmpipe's limit counts, as it did.
int spent = 0;

struct Found { int status; int target; int loop_; float lambda; float tau; };
const Found NO_FOUND = Found(0, -1, 0, 0.0, 0.0);

// The search plan (startSearch): `loops` copies of a stretch of length `span` cut into `segs`
// segments (a Gödel pixel ray's loops), or, where `cont`, `loops` stretches one after the other
// of the ray's `total` segments (a straight ray, a shadow ray: cut so that each stretch's start
// is a checkpoint of the rounds, main); pixel rays stop at the time bound. Shadow rays: the lit
// object `skipObj` is not searched from segment `skipSeg` on (its last). The first loop's box.
// `ends`: the status where the plan's loops or segments run out (a Gödel or member pixel ray:
// out of work; a straight ray or a shadow ray: escaped).
struct Plan {
    Ray ray;
    int loops; int segs; int total; bool cont;
    float span; float pt; float tBound; bool pixel;
    int skipObj; int skipSeg;
    vec3 boxLo; vec3 boxHi;
    int ends;
};
Plan plan = Plan(NO_RAY, 0, 0, 0, false, 0.0, 0.0, 0.0, false, -1, 0, vec3(0.0), vec3(0.0), ESCAPED);

// The machine's place: its mode, loop, segment [lo, hi] and object, the part [plo, phi] of the
// segment that searches the object (objectPart), the segment's earliest crossing so far, and
// the search's result.
// `check`: the pending request is a checkpoint's (nextSpan). `fresh`: the object's start probe
// was just taken at plo (Q_FRESH).
struct Machine {
    int mode; int loop_; int seg; int obj; float lo; float hi; float plo; float phi;
    Found best; Found result; bool check; bool fresh;
};
Machine mach = Machine(0, 0, 0, 0, 0.0, 0.0, 0.0, 0.0, NO_FOUND, NO_FOUND, false, false);
// The probes at the start and the end of the segment, per object, and the λ where each was
// taken. Two arrays, written only at constant indices (setEndProbe; the end probes become
// the next segment's start probes by a copy): drivers that store at a runtime index into
// one buffer of both went wrong (docs/physics.md, "The GPU kernel").
Probe startProbe[N_OBJECTS], endProbe[N_OBJECTS];
float startAt[N_OBJECTS], endAt[N_OBJECTS];
// Bisection of one object's stretch [start, start + len]: the span [a, b] at depth `depth` and
// index `index`, with its end probes pa, pb and the τ seeds they were probed with (seedA:
// where pa is a probe, pb's before); the probes it took, and their count at its last
// checkpoint.
struct Bisection {
    float start; float len; float a; float b; int depth; int index; int probes; int mark;
    Probe pa; Probe pb; float seedA; float seedB;
};
Bisection bis = Bisection(0.0, 0.0, 0.0, 0.0, 0, 0, 0, 0, NO_PROBE, NO_PROBE, 0.0, 0.0);
// The end probe the last halving left for its right half, at depth `pendingDepth` (0: none),
// and its τ seed.
Probe pending = NO_PROBE;
float pendingSeed = 0.0;
int pendingDepth = 0;
// A bisection's checkpoint (render_tracer's Progress keeps it between rounds): segment `seg`
// (−1: none, the loop's start), object `obj`, span at `depth` and `index` (odd: a right
// sibling) starting at `a`, probed with the seed `seed`, after `probes` probes of the
// bisection.
struct Span { int seg; int obj; int depth; int index; int probes; float a; float seed; };
const Span NO_SPAN = Span(-1, 0, 0, 0, 0, 0.0, 0.0);
// The checkpoint to resume at (`on`), the segment's earliest crossing so far, and the sample's
// probes left. Until the machine reaches it, segments and objects before it are not bisected:
// none crossed there, or the search would have ended.
struct Resume { bool on; Span at; Found best; int left; };
Resume res = Resume(false, NO_SPAN, NO_FOUND, 0);
// Refinement of a crossing: the bracket [lo, hi], f there, the Illinois side, the steps.
struct Refinement { float lo; float hi; float flo; float fhi; int side; int iter; };
Refinement ill = Refinement(0.0, 0.0, 0.0, 0.0, 0, 0);
// Aimed occlusion (startAim): the ball at rest `obj`, its next copy, and its arc.
struct Aim { int obj; int copy; AimBall ball; };
Aim aim = Aim(-1, 0, NO_AIM_BALL);
// The probe requested by a step (for what, of which object, where), and its answer.
struct Request { int tag; int obj; int loop_; float lambda; float seed; Probe answer; vec4 x; };
Request req = Request(Q_NONE, 0, 0, 0.0, 0.0, NO_PROBE, vec4(0.0));

// Whether ball i in free fall is searched only within its windows (fbWindow): on a Gödel pixel
// ray's loops, and on a shadow ray's stretches.
bool windowed(int i) {
    return isFree(i) && (plan.pixel ? !plan.cont : godel());
}

// The part of the segment [l0, l1] (from the loop's start) where the current loop searches
// object i: a ball in free fall only between its first and last λ within reach (fbWindow);
// none where x > y.
vec2 objectPart(int i, float l0, float l1) {
    if (!windowed(i)) return vec2(l0, l1);
    return vec2(max(l0, fbWindow[i].x), min(l1, fbWindow[i].y));
}

// Object i's probe at the segment's start, or at its end, taken at λ = at: stored at the
// loop's constant indices, never at the runtime index i.
void setStartProbe(int i, Probe p, float at) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) {
            startProbe[j] = p;
            startAt[j] = at;
        }
    }
}
void setEndProbe(int i, Probe p, float at) {
    for (int j = 0; j < N_OBJECTS; j++) {
        if (j == i) {
            endProbe[j] = p;
            endAt[j] = at;
        }
    }
}

void request(int tag, float lambda, float seed) {
    req.tag = tag;
    req.obj = mach.obj;
    req.loop_ = mach.loop_;
    req.lambda = lambda;
    req.seed = seed;
}

float loopOffset() { return float(mach.loop_) * plan.span; }

#ifdef MEMBER
// A member's ray searched in stretches of EXACT_SEGMENTS segments (memberSearch): the loop and
// the parameter within it of l into stretch j, from the segments' count (a loop holds a whole
// number of them), so that later loops keep their digits as loop copies.
void memberPlace(Ray r, int j, float l, out int loop, out float within) {
    loop = 0; within = 0.0;
    int g0 = j * EXACT_SEGMENTS;
    if (r.nseg > 0) {
        loop = g0 / r.nseg;
        within = float(g0 - loop * r.nseg) * r.h + l;
        if (within >= r.lret) {
            loop++;
            within -= r.lret;
        }
    } else {
        within = float(g0) * r.h + l;
    }
}
#endif

// The searched ray's event and tangent at parameter l of loop (or stretch) j.
void searchRayAt(int j, float l, out vec4 ev, out vec4 k) {
    ev = vec4(0.0); k = vec4(0.0);
    // One call of rayAt (GLSL inlines each call site).
    int loop = plan.cont ? 0 : j;
    float at = plan.cont ? l + float(j) * plan.span : l;
#ifdef MEMBER
    if (plan.cont && plan.pixel) memberPlace(plan.ray, j, l, loop, at);
#endif
    rayAt(plan.ray, loop, at, ev, k);
}

void finish(int status) {
    mach.result = Found(status, -1, 0, 0.0, NO_TAU);
    mach.mode = M_DONE;
}

// The loop's box, for skipping loops that come near no object (render::segment::loop_bounds):
// segment ends, grown by a quarter of the longest chord.
void loopBox() {
    vec4 x = vec4(0.0), k = vec4(0.0), prev = vec4(0.0);
    float grow = 0.0;
    for (int s = 0; s <= plan.segs; s++) {
        rayAt(plan.ray, 0, plan.span * float(s) / float(plan.segs), x, k);
        if (s == 0) { plan.boxLo = x.yzw; plan.boxHi = x.yzw; prev = x; }
        plan.boxLo = min(plan.boxLo, x.yzw);
        plan.boxHi = max(plan.boxHi, x.yzw);
        grow = max(grow, 0.25 * length(x.yzw - prev.yzw));
        prev = x;
    }
    plan.boxLo -= grow;
    plan.boxHi += grow;
}

void startSearch(Ray r, int loops, int segs, float span, float pt, bool pixel, float tBound) {
    plan.ray = r;
    plan.loops = loops;
    plan.segs = segs;
    plan.span = span;
    plan.pt = pt;
    plan.pixel = pixel;
    plan.tBound = tBound;
    plan.cont = false;
    plan.total = loops * segs;
    mach.loop_ = 0;
    mach.mode = M_LOOP;
    plan.skipObj = -1;
    plan.skipSeg = MAX_SEGMENTS + 1;
    req.tag = Q_NONE;
    for (int i = 0; i < N_OBJECTS; i++) {
        startProbe[i] = NO_PROBE;
        endProbe[i] = NO_PROBE;
        startAt[i] = 0.0;
        endAt[i] = 0.0;
    }
    pending = NO_PROBE;
    pendingSeed = 0.0;
    pendingDepth = 0;
    plan.boxLo = vec3(0.0);
    plan.boxHi = vec3(0.0);
    plan.ends = pixel && godel() ? WORK_LIMIT : ESCAPED;
#ifndef MEMBER
    if (loops > 1) loopBox();   // (a member's searches are long ones, of one loop)
#endif
}

// A search of the ray r over λ ∈ [0, length] in `total` segments, as stretches of
// EXACT_SEGMENTS segments one after the other (searchRayAt).
void startLongSearch(Ray r, int total, float length, float pt, bool pixel, float tBound) {
    int loops = (total + EXACT_SEGMENTS - 1) / EXACT_SEGMENTS;
    startSearch(r, 1, EXACT_SEGMENTS, length * float(EXACT_SEGMENTS) / float(total), pt, pixel, tBound);
    plan.loops = loops;
    plan.cont = true;
    plan.total = total;
}

#ifdef MEMBER
// A member's pixel ray (render::tracer::exact's first_loop_family, and later loops as copies):
// `total` segments of r.h in stretches of EXACT_SEGMENTS, out of work where they run out.
void memberSearch(Ray r, int total, float pt, float tBound) {
    startLongSearch(r, total, float(total) * r.h, pt, true, tBound);
    plan.span = float(EXACT_SEGMENTS) * r.h;
    plan.ends = WORK_LIMIT;
}
#endif

// A shadow ray's search (Gödel's closed forms) starts with aimed occlusion (render_reject's
// aimBall): a ball at rest found inside where aimed at blocks the ray without the search.
void startAim() {
    if (!godel() || plan.pixel) return;
    mach.mode = M_AIM;
    aim = Aim(-1, 0, NO_AIM_BALL);
}

// The span after the finished span [bis.a, bis.b] of the current bisection: climb while it is a
// right half, then take the right sibling, whose start probe is bis.b's and whose end probe is
// the kept one (its parent's end), else probed again.
void nextSpan() {
    // The trailing ones of the index are the levels to climb: 2^k = (i + 1) & −(i + 1).
    int up = toInt(log2(float((bis.index + 1) & -(bis.index + 1))) + 0.5, 0, SEARCH_DEPTH);
    bis.depth -= up;
    bis.index >>= up;
    if (bis.depth <= 0) {
        mach.mode = M_SCAN;   // no crossing of this object in the segment
        return;
    }
    bis.index++;
    bis.pa = bis.pb;
    bis.seedA = bis.seedB;
    bis.a = bis.b;
    bis.b = bis.start + bis.len * float(bis.index + 1) / exp2(float(bis.depth));
    if (pendingDepth == bis.depth) {
        pendingDepth = 0;
        bis.pb = pending;
        bis.seedB = pendingSeed;
        return;   // on with the span (M_BISECT), no probe taken
    }
    if (bis.probes == SEARCH_PROBES) { finish(WORK_LIMIT); return; }
    bis.probes++;
    mach.check = bis.probes - bis.mark >= SPAN_CHECK;
    if (mach.check) {
        bis.mark = bis.probes;
        pendingDepth = 0;   // a checkpoint: a resumed bisection has none kept
    }
    request(Q_SPAN, bis.b, bis.pa.tau);
}

// Whether segment `seg`'s object `obj` lies before the resumed checkpoint.
bool beforeResume(int seg, int obj) {
    return res.on && (seg < res.at.seg || (seg == res.at.seg && obj < res.at.obj));
}

// Segment mach.seg of the loop (or stretch) begins: scanned from its first object (M_SCAN), or
// the long search ends.
void startSegment() {
    if (mach.loop_ * plan.segs + mach.seg >= plan.total) { finish(plan.ends); return; }   // a long search's end
    mach.lo = plan.span * float(mach.seg) / float(plan.segs);
    mach.hi = plan.span * float(mach.seg + 1) / float(plan.segs);
    mach.best = Found(ESCAPED, -1, 0, 0.0, NO_TAU);
    mach.obj = -1;
    mach.mode = M_SCAN;
}

// One step of the machine: takes the answer to its last request, then either requests a
// probe or moves on.
void machineStep() {
    int tag = req.tag;
    req.tag = Q_NONE;
    mach.check = false;
    if (tag == Q_AIM && req.answer.f <= 0.0) {
        mach.result = Found(HIT, mach.obj, 0, req.lambda, NO_TAU);   // inside: blocked
        mach.mode = M_DONE;
        return;
    } else if (tag == Q_FRESH) {
        setStartProbe(mach.obj, req.answer, req.lambda + loopOffset());
        mach.fresh = true;
        mach.obj--;   // the scan takes up the same object again (M_SCAN)
    } else if (tag == Q_END) {
        setEndProbe(mach.obj, req.answer, req.lambda + loopOffset());
        if (beforeResume(mach.seg, mach.obj)) {
            mach.mode = M_SCAN;   // bisected before the checkpoint, with no crossing
        } else {
            if (res.on) mach.best = res.best;
            bis.pb = req.answer;
            bis.seedB = req.seed;
            float limit = mach.best.status == HIT ? mach.best.lambda : mach.phi;
            bis.start = mach.plo;
            bis.len = min(limit, mach.phi) - mach.plo;
            bis.a = bis.start;
            bis.b = bis.start + bis.len;
            bis.depth = 0;
            bis.index = 0;
            bis.probes = 0;
            bis.mark = 0;
            pendingDepth = 0;
            mach.mode = M_BISECT;
            if (res.on && (mach.seg != res.at.seg || mach.obj != res.at.obj)) {
                finish(FAILED);   // the way back missed its checkpoint (never, if probes repeat)
                return;
            }
            if (res.on) {
                // The checkpoint's span, as nextSpan makes it after its left sibling, whose end
                // is probed again as it was.
                bis.depth = res.at.depth;
                bis.index = res.at.index - 1;
                bis.probes = res.at.probes - 1;
                bis.mark = res.at.probes - SPAN_CHECK;
                request(Q_RESUME, res.at.a, res.at.seed);
                return;
            }
        }
    } else if (tag == Q_SPAN) {
        bis.pb = req.answer;
        bis.seedB = req.seed;
    } else if (tag == Q_RESUME) {
        bis.b = req.lambda;
        bis.pb = req.answer;
        bis.seedB = req.seed;
        res.on = false;
        probes_left = res.left;   // the probes of the way back were counted before
        nextSpan();
        return;
    } else if (tag == Q_ROOT) {
        if (accepts(mach.obj, req.x)) {
            if (mach.best.status != HIT || req.lambda < mach.best.lambda) {
                mach.best = Found(HIT, mach.obj, mach.loop_, req.lambda, req.answer.tau);
            }
            mach.mode = M_SCAN;
        } else {
            mach.mode = M_BISECT;   // a plane crossed beyond its extent: on with the next span
            nextSpan();
            if (mach.mode != M_SCAN) return;
        }
    } else if (tag == Q_REFINE) {
        float fm = req.answer.f, m = req.lambda;
        if (fm == 0.0 || ill.hi - ill.lo <= 4.0 * 1.1920929e-7 * max(max(abs(ill.hi), abs(ill.lo)), 1e-30)) {
            request(Q_ROOT, m, bis.pa.tau);
            return;
        }
        if ((fm > 0.0) == (ill.fhi > 0.0)) {
            ill.hi = m; ill.fhi = fm;
            if (ill.side == 1) ill.flo *= 0.5;
            ill.side = 1;
        } else {
            ill.lo = m; ill.flo = fm;
            if (ill.side == -1) ill.fhi *= 0.5;
            ill.side = -1;
        }
    }

    if (mach.mode == M_AIM) {
        // Each searched ball at rest, each copy of its arc; one probe a pass.
        float h = plan.span / float(plan.segs);
        for (int it = 0; it < N_OBJECTS * (MAX_AIMS + 1) + 1; it++) {
            if (aim.copy < aim.ball.copies) {
                float l = aimAt(aim.ball, plan.ray.geo, oCz[aim.obj], objs[aim.obj].radius, aim.copy);
                aim.copy++;
                if (l >= 0.0) {
                    mach.obj = aim.obj;
                    request(Q_AIM, l, NO_TAU);
                    return;
                }
                continue;
            }
            aim.obj++;
            if (aim.obj >= N_OBJECTS) break;
            aim.copy = 0;
            aim.ball = NO_AIM_BALL;
            if (searched[aim.obj] && isRest(aim.obj)) {
                // The lit object only up to its last segment, as its search.
                int segs = aim.obj == plan.skipObj ? min(plan.skipSeg, plan.total) : plan.total;
                aim.ball = aimBall(aim.obj, plan.ray.geo, oCw[aim.obj], oNear[aim.obj], oCz[aim.obj], float(segs) * h);
            }
        }
        mach.mode = M_LOOP;   // the search, from the next pass (a checkpoint)
        return;
    }
    // Skip a loop whose box meets no searched object's box, up to LOOPS_PER_PASS loops a pass
    // (a pass that begins at a loop's start is a checkpoint of the sample's rounds: main; the
    // loops passed over after it are taken again from it where a round is cut); stop at the
    // time bound.
    for (int pass = 0; pass < LOOPS_PER_PASS && mach.mode == M_LOOP; pass++) {
        if (pass > 0) spent++;
        if (mach.loop_ >= plan.loops) {
            finish(plan.ends);
            return;
        }
        float dz = float(mach.loop_) * plan.ray.shift.y;
        if (plan.pixel && !plan.cont && float(mach.loop_) * plan.ray.shift.x < plan.tBound) { finish(ESCAPED); return; }
        vec3 lo = plan.boxLo + vec3(0.0, 0.0, dz), hi = plan.boxHi + vec3(0.0, 0.0, dz);
        bool near = mach.loop_ == 0 || plan.cont;   // the box is of copies of the first loop
        for (int i = 0; i < N_OBJECTS; i++) {
            vec3 olo = vec3(0.0), ohi = vec3(0.0);
            if (!searched[i]) continue;
            if (windowed(i)) {
                // Balls in free fall: searched between the loop's (or the stretch's) first and
                // last λ within their reach.
                vec3 window = stretchWindow(i, plan.ray, loopOffset(), loopOffset() + plan.span,
                                            plan.cont ? -1 : mach.loop_);
                storeFallingWindow(i, window);
                near = near || window.y > NO_TAU;
            } else {
                near = near || !objectBox(i, olo, ohi) || (all(lessThanEqual(olo, hi)) && all(lessThanEqual(lo, ohi)));
            }
        }
        if (!near) {
            mach.loop_++;
            continue;
        }
        // No probe of an earlier loop is taken on: each loop's start is a checkpoint of the
        // rounds, which keep no probes (M_SCAN probes each object afresh where it needs one).
        for (int i = 0; i < N_OBJECTS; i++) {
            startProbe[i] = NO_PROBE;
            startAt[i] = NO_TAU;
        }
        mach.seg = 0;
        startSegment();   // (leaves M_LOOP: the loop ends)
    }
    if (mach.mode == M_LOOP) return;   // on from the next loop in the next pass
    // A span whose end probe was kept (nextSpan) is taken up in the same pass: the next span
    // after it is probed (the kept probe is used up), so two rounds of this loop suffice.
    for (int kept = 0; kept < 2 && mach.mode == M_BISECT; kept++) {
        bool finiteBoth = finite(bis.pa.f) && finite(bis.pb.f);
        if (bis.b > bis.a && (finite(bis.pa.f) || finite(bis.pb.f))) {
            if (finiteBoth && crossed(bis.pa.f, bis.pb.f)) {
                // A shadow ray is blocked by any crossing: the first one found of an object
                // that takes every crossing ends its search unrefined (the CPU's Want::Any).
                if (!plan.pixel && acceptsAny(mach.obj)) {
                    mach.result = Found(HIT, mach.obj, mach.loop_, bis.b, NO_TAU);
                    mach.mode = M_DONE;
                    return;
                }
                if (isPlane(mach.obj)) {
                    // z − height is linear in λ (its start probe is measured at the segment's
                    // start: a plane never vouches for spans): the crossing is the line's root.
                    float at = clamp(bis.pa.f / (bis.pa.f - bis.pb.f), 0.0, 1.0);
                    request(Q_ROOT, bis.a + (bis.b - bis.a) * at, bis.pa.tau);
                    return;
                }
                ill.lo = bis.a; ill.hi = bis.b; ill.flo = bis.pa.f; ill.fhi = bis.pb.f;
                ill.side = 0; ill.iter = 0;
                mach.mode = M_REFINE;
            } else {
                float rate = max(bis.pa.rate, bis.pb.rate);
                // A plane's span whose ends are on one side holds no crossing (f linear).
                bool out_ = finiteBoth && (isPlane(mach.obj)
                                           || excluded(bis.pa.f, bis.pb.f, rate, bis.b - bis.a)
                                           || chordExcludes(mach.obj, bis.pa, bis.pb, bis.b - bis.a));
                if (!(out_ || bis.depth >= SEARCH_DEPTH)) {
                    // Halve: the earlier half first.
                    if (bis.probes == SEARCH_PROBES) { finish(WORK_LIMIT); return; }
                    bis.probes++;
                    pending = bis.pb;
                    pendingSeed = bis.seedB;
                    pendingDepth = bis.depth + 1;
                    bis.b = 0.5 * (bis.a + bis.b);
                    bis.depth++;
                    bis.index *= 2;
                    request(Q_SPAN, bis.b, bis.pa.tau);
                    return;
                }
            }
        }
        if (mach.mode != M_BISECT) break;   // on to the refinement
        // The span is done (excluded, at the depth bound, or the object undefined on it).
        nextSpan();
        if (mach.mode == M_BISECT && req.tag == Q_NONE) continue;
        if (mach.mode != M_SCAN) return;
    }
    if (mach.mode == M_BISECT) return;   // (not reached: a span's end probe is kept once)
    if (mach.mode == M_REFINE) {
        if (ill.iter == REFINE_STEPS) {
            request(Q_ROOT, 0.5 * (ill.lo + ill.hi), bis.pa.tau);
            return;
        }
        float m = ill.fhi != ill.flo ? (ill.lo * ill.fhi - ill.hi * ill.flo) / (ill.fhi - ill.flo) : 0.5 * (ill.lo + ill.hi);
        if (!finite(m) || !(m > ill.lo && m < ill.hi)) m = 0.5 * (ill.lo + ill.hi);
        ill.iter++;
        request(Q_REFINE, m, bis.pa.tau);
        return;
    }
    // The segments of a loop that ask for no probe are passed over in one pass: each object of
    // the segment, then its end, as steps of one flat loop (not nested: docs/physics.md,
    // "Rounds", on llvmpipe's loop limit).
    for (int st = 0; st < EXACT_SEGMENTS * (N_OBJECTS + 1) && mach.mode == M_SCAN; st++) {
        float off = loopOffset();
        mach.obj++;
        if (mach.obj < N_OBJECTS) {
            if (!searched[mach.obj]) continue;
            Probe p = startProbe[mach.obj];
            float at = startAt[mach.obj];
            bool fresh = mach.fresh;
            mach.fresh = false;
            vec2 part = objectPart(mach.obj, mach.lo, mach.hi);
            if (!(part.x <= part.y)) {
                // Outside the ball's window in this loop: its last probe kept, to be taken
                // afresh where the window starts.
                setEndProbe(mach.obj, p, at);
                continue;
            }
            mach.plo = part.x;
            mach.phi = part.y;
            if (mach.obj == plan.skipObj && mach.loop_ * plan.segs + mach.seg >= plan.skipSeg) {
                setEndProbe(mach.obj, p, at);
                continue;
            }
            // GPU only: a segment that provably stays clear of a ball at rest or a plane is
            // not searched ("Whole-ray rejection", applied per segment). A plane's end probe is
            // its height there (linear in λ); a ball's none (a later segment probes afresh).
            if (objectMisses(mach.obj, plan.ray.geo, mach.lo + off, mach.hi + off)) {
                if (isRest(mach.obj)) {
                    setEndProbe(mach.obj, NO_PROBE, NO_TAU);
                } else {
                    float fEnd = plan.ray.geo.pz * (mach.hi + off) - oCz[mach.obj];
                    setEndProbe(mach.obj, Probe(fEnd, p.rate, NO_TAU, vec3(0.0), false, 0.0), mach.hi + off);
                }
                continue;
            }
            bool known = at > NO_TAU;   // a probe of this loop
            float clear = abs(p.f);
            if (isRest(mach.obj) && known && finite(clear) && p.rate > 0.0 && mach.hi + off < at + min(clear / p.rate, MAX_SKIP)) {
                setEndProbe(mach.obj, p, at);   // provably no crossing of this object within the segment
                continue;
            }
            // A probe where the part starts: the last one if it was taken there; a ball at
            // rest's taken before still bounds |f| there from below (same side; its rest-frame
            // coordinates are its own place's); else one taken afresh, once (a ball in free
            // fall whose window starts later: the bound a probe gives further on could have
            // crossed zero; a plane's root needs its value there).
            bool here = fresh || at == part.x + off;
            if (!here && !(known && isRest(mach.obj))) {
                request(Q_FRESH, part.x, windowed(mach.obj) ? fbWindow[mach.obj].z : NO_TAU);
                return;
            }
            bis.pa = p;   // (no ?: of structures in WebGL)
            if (!here) bis.pa = Probe(p.f - sign(p.f) * p.rate * (part.x + off - at), p.rate, p.tau, p.xi, false, p.energy);
            // Searched only up to another object's earlier crossing in the segment (which ends
            // the search): the end probe there, where the span ends (its value at hi bounds
            // nothing over the shorter span). A resumed round's way back, whose segment has no
            // crossing yet, probes at hi; the bisection it resumes probes its spans afresh.
            float end = mach.best.status == HIT ? min(mach.best.lambda, part.y) : part.y;
            request(Q_END, end, bis.pa.tau);
            return;
        }
        // Every object scanned: the segment's earliest crossing ends the search.
        if (mach.best.status == HIT) {
            mach.result = mach.best;
            // A long search's hit as a parameter from the ray's start (a member's pixel ray: as
            // its loop and the parameter within it).
            if (plan.cont) mach.result = Found(HIT, mach.best.target, 0, mach.best.lambda + loopOffset(), mach.best.tau);
#ifdef MEMBER
            if (plan.cont && plan.pixel) {
                int loop = 0;
                float within = 0.0;
                memberPlace(plan.ray, mach.loop_, mach.best.lambda, loop, within);
                mach.result = Found(HIT, mach.best.target, loop, within, mach.best.tau);
            }
#endif
            mach.mode = M_DONE;
            return;
        }
        if (plan.pixel) {
            vec4 x = vec4(0.0), k = vec4(0.0);
            searchRayAt(mach.loop_, mach.hi, x, k);
            if (x.x < plan.tBound) { finish(ESCAPED); return; }
#if defined(MEMBER) && MEMBER_CAUSAL != 0
            // A causal member's escape stop and far stretches (render_escape).
            int step_ = escapeStep(plan.ray, mach.loop_ * plan.segs + mach.seg + 1, x, plan.tBound);
            if (step_ == -2) { finish(ESCAPED); return; }
            if (step_ == -3) { finish(WORK_LIMIT); return; }
            if (step_ >= 0) {
                // Beyond every object until the loop comes back: on from that stretch.
                mach.loop_ = step_;
                mach.mode = M_LOOP;
                return;
            }
#endif
        }
        for (int i = 0; i < N_OBJECTS; i++) {   // the end probes start the next segment
            startProbe[i] = endProbe[i];
            startAt[i] = endAt[i];
        }
        mach.seg++;
        if (mach.seg < plan.segs) {
            spent++;   // (as a pass of its own)
            startSegment();
        } else {
            mach.loop_++;
            mach.mode = M_LOOP;
        }
    }
}

// One pass of the machine: the probe it asked for, if any (the kernel's one call of
// probeObject), then its next step.
void searchPass() {
    if (req.tag != Q_NONE) {
        if (probes_left <= 0) { finish(WORK_LIMIT); return; }
        vec4 k = vec4(0.0);
        searchRayAt(req.loop_, req.lambda, req.x, k);
        req.answer = probeObject(req.obj, req.x, k, plan.pt, req.seed);
        // A probe answers a finite distance or FAR (INF, the CPU's infinity: nothing known);
        // anything else (a driver's NaN) ends the search, and the sample is marked failed:
        // no search goes on from a value it cannot order.
        if (!(finite(req.answer.f) || req.answer.f == INF) || !finite(req.answer.rate)) {
            finish(FAILED);
            return;
        }
    }
    machineStep();
}

