// godel explore: flying, with every frame traced in this page on the GPU (the exact tracer's
// kernel, trace.js) — no server round trip per frame. The view (`viewer.explore.view()`) is
// the observer and camera with exactly the scene file's `[observer]` and `[camera]` fields
// (README "Scenes"), so that a scene with them traces the frame shown; `godel-view` events
// (and `viewer.explore.onView`) announce each change.
//
// The kernel's uniforms are the view's fields as they are (crates/gpu/src/input.rs,
// `KernelInput::new`: the time split into f32 hi + lo, the velocity as speed and direction,
// the axes in the observer's frame); the scene table and defines come once from the server.
// What depends on the observer's position alone, its static frame and its isometry to the
// origin (`obs_static`, `obs_to`: gpu::input::ObserverUniforms, made in f64), comes from the
// server with every position: the position changes only through the server's answers (the
// kernel input of the start or of an event typed or dragged, POST /api/explore/move), and
// no frame is traced from a position whose uniforms have not come yet. The kernel boosts
// that static frame by the velocity, which the page sets itself every animation frame.
// The browser test checks the page's uniforms against the server's for the same view
// (POST /api/explore/input).
//
// Flight starts from the scene's observer: its event, axes and velocity (a scene's moving
// observer is seen moving, as `godel render` sees it). W/S, A/D, R/F (Space/Shift) give the
// observer a velocity of the chosen speed along its forward, right and up axes while held
// (aberration and Doppler follow: it is the kernel's observer velocity); letting go of them
// stops it (speed 0), and Stop (or X) does at any time; otherwise the velocity stays, the
// scene's included. The observer moves along the geodesic of its 4-velocity by the proper
// time the rate gives (POST /api/explore/move, spacetime::worldline: at most one request in
// flight, proper time accumulating meanwhile, so the page never waits for it); "fall freely"
// keeps the velocity the geodesic carries instead (also once the keys are let go). Dragging
// turns, Q/E roll, the wheel zooms (pointer and wheel events: touch and trackpads too).
//
// The page checks what it shows (crates/viewer/src/page_check.rs): the first frame traced,
// then a frame at most every CHECK_EVERY_MS while the view changes, sends a few of its samples
// (status and object) to the server, which traces them again with the CPU exact tracer; where
// they disagree (a driver that runs the kernel wrongly), the page stops tracing and shows the
// server's frames (explore.js), the header naming the renderer refused and why.
//
// Dynamic resolution: while the view changes, each animation frame traces a smaller grid of
// one sample per pixel, its pixel count steered so that a frame takes about TARGET_MS; at
// rest the page traces the scene's full size in steps (half size, full size at one sample a
// pixel, full samples: traceFull), in tiles, each cancelled by the next change.
'use strict';

import { KernelTracer } from './trace.js';
import { STATUS, sampleRecord, tracedLightRay } from './hovered.js';
import { fetchJson } from './data.js';
import { cross, dot, normalize } from './look.js';

const $ = (id) => document.getElementById(id);

// The frame time aimed at while moving (15 frames/s and more).
const TARGET_MS = 50;
// The fewest pixels a moving frame has (its width), and the smoothing of its size.
const MIN_WIDTH = 16;
// At rest, a frame of half the width and height comes first where the full size would take
// longer than this (at the kernel's last measured speed; always before the first).
const QUICK_MS = 1000;
// Radians per CSS pixel dragged (times the field of view's share), roll per second.
const ROLL_PER_S = 1.0;
// Proper time added per animation frame at most (a stalled tab does not jump).
const MAX_DT = 0.1;
// The page's check of its tracer: at most one frame in this many ms (the first always), and
// at most this many of its samples among those that hit, and as many among the others.
const CHECK_EVERY_MS = 5000;
const CHECK_PER_SIDE = 24;

const KEYS = {
  KeyW: [1, 0, 0], KeyS: [-1, 0, 0], KeyD: [0, 1, 0], KeyA: [0, -1, 0],
  KeyR: [0, 0, 1], Space: [0, 0, 1], KeyF: [0, 0, -1], ShiftLeft: [0, 0, -1],
  ShiftRight: [0, 0, -1],
};

// A time as f32 hi + lo (gpu::input::split_time).
export function splitTime(t) {
  const hi = Math.fround(t);
  return [hi, Math.fround(t - hi)];
}

// Rodrigues: `v` turned by `angle` about the unit axis `k`.
function turn(v, k, angle) {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  const kv = cross(k, v);
  const d = dot(k, v) * (1 - c);
  return v.map((x, i) => x * c + kv[i] * s + k[i] * d);
}

// The server's observer uniforms (`obs_static`, `obs_to`) in `uniforms`, kept with the
// position they belong to.
export function observerOf(uniforms, position) {
  return { position: { x: position.x, y: position.y, z: position.z },
    obs_static: uniforms.obs_static, obs_to: uniforms.obs_to };
}

// Whether `observer` (observerOf) belongs to `position`.
export function observerAt(observer, position) {
  const p = observer.position;
  return p.x === position.x && p.y === position.y && p.z === position.z;
}

// The kernel's uniforms for `view` traced on a `width` × `height` grid (gpu::input::Uniforms
// from KernelInput::new), the scene's own ones (`base`: metric, a, max_past, …) otherwise;
// `observer` (observerOf) the server's for the view's position.
export function uniformsFor(base, view, observer, width, height) {
  const c = view.camera;
  const fov = c.kind === 'panorama' ? [c.h_fov_deg, c.v_fov_deg]
    : c.kind === 'sphere' ? [360, 180] : [c.fov_deg, 0];
  const p = view.position;
  if (!observerAt(observer, p)) throw new Error('the observer\'s uniforms are of another position');
  return { ...base, obs_t: splitTime(view.time), obs_x: [p.x, p.y, p.z].map(Math.fround),
    obs_static: observer.obs_static, obs_to: observer.obs_to,
    velocity: [view.velocity.speed, ...view.velocity.direction].map(Math.fround),
    forward: view.forward.map(Math.fround), up: view.up.map(Math.fround),
    fov: fov.map(Math.fround), size: [width, height] };
}

// Starts flying in explore mode; false where the kernel cannot trace the scene here (the
// reason is shown and the server's frames stay).
export async function startFly(viewer, explore, map, status) {
  if (viewer.look) {
    status('tracing on the server: a full sphere (--sphere) is looked around in, not flown');
    return false;
  }
  const gl = viewer.gpu().gl;
  let tracer;
  let input;
  let sceneView;
  const s = explore.event;
  // The kernel's input seen from an event (its observer uniforms too).
  const inputAt = (e) => fetchJson(`/api/gpu/input?${new URLSearchParams({
    draw_buffers: tracer.maxDrawBuffers, t: e.t, x: e.x, y: e.y, z: e.z })}`);
  try {
    tracer = new KernelTracer(gl, await (await fetch('/api/gpu/kernel')).text());
    input = await inputAt(s);
    sceneView = (await fetchJson('/api/view')).view;
  } catch (e) {
    status(`tracing on the server: ${e.message || e}`);
    return false;
  }
  if (!sceneView) {
    status('tracing on the server: the scene has no camera view the page can fly');
    return false;
  }
  const ss = input.supersample;
  const [fullW, fullH] = [input.uniforms.size[0] / ss, input.uniforms.size[1] / ss];
  const c = sceneView.camera;
  const camera = { kind: c.kind, width: fullW, height: fullH, samples: ss * ss };
  for (const k of ['fov_deg', 'h_fov_deg', 'v_fov_deg']) if (c[k] !== undefined) camera[k] = c[k];
  const fly = {
    view: {
      time: s.t, position: { x: s.x, y: s.y, z: s.z },
      velocity: { speed: sceneView.velocity.speed, direction: [...sceneView.velocity.direction] },
      forward: normalize(sceneView.forward), up: normalize(sceneView.up), camera,
    },
    // The server's uniforms of the observer's position (observerOf).
    observer: observerOf(input.uniforms, s),
    keys: new Set(),
    keyed: false,        // the keys set the velocity (letting go of them stops the observer)
    speed: 0.5,
    rate: 1,
    playing: false,
    fall: false,
    pendingTau: 0,
    moving: false,       // in flight: a request for the observer's motion is under way
    version: 0,          // bumped by every change of the view
    traced: null,        // {version, width, height, level} of the frame shown
    busy: false,         // a moving frame's trace is under way (it waits only to compile)
    refining: false,     // a full frame's trace is under way (a change cancels it)
    slots: null,         // the slots of the frame shown (hover, tests)
    tauMoved: 0,         // proper time the observer has moved (for tests)
    width: Math.min(fullW, MIN_WIDTH), // the moving frames' width
    raysPerMs: null,     // the kernel's speed here, from the last frame at rest
    rafs: 0,             // animation frames while the view changed
    drawn: 0,            // frames traced and shown
    frameMs: [],         // wall times of the last frames shown
    log: [],             // for tests and benches: {version, width, height, level, rafs,
                         // drawn, at (performance.now() when shown), ms (at rest: since the
                         // first step began, traceFull)}
    error: null,
    check: { at: null, busy: false, done: 0, last: null }, // the checks of frames traced
    refused: null,       // why this page's tracer was refused (then the server traces)
  };
  explore.fly = fly;
  explore.view = () => structuredClone(fly.view);
  explore.onView = null;
  explore.uniforms = (width, height) => uniformsFor(input.uniforms, fly.view, fly.observer,
    width, height);
  // The sample that stands for pixel (col, row) of the frame shown (the one nearest the
  // pixel's centre, as the server's picture_sample), or null outside the frame.
  const sampleOf = (col, row) => {
    const traced = fly.slots;
    if (!traced) return null;
    const s = fly.slotsSupersample;
    const [x, y] = [s * col + (s >> 1), s * row + (s >> 1)];
    return x < traced.width && y < traced.height ? [x, y] : null;
  };
  // The slots of sample (x, y) of the frame `traced`, read back once for the record panel
  // and the map's ray of the same hover.
  let lastRead = { traced: null, x: -1, y: -1, slots: null };
  const readHovered = (traced, x, y) => {
    const r = lastRead;
    if (r.traced !== traced || r.x !== x || r.y !== y) {
      lastRead = { traced, x, y, slots: tracer.readSample(traced, x, y) };
    }
    return lastRead.slots;
  };
  // The record of pixel (col, row) of the frame shown (viewer.js's hover), read from the
  // frame's slots (hovered.js), as /api/pixel answers for the server's frames; resolves to
  // null outside.
  explore.hoverRecord = async (col, row) => {
    const at = sampleOf(col, row);
    if (!at) return null;
    const slots = await readHovered(fly.slots, at[0], at[1]);
    return { col, row, ...sampleRecord(slots, input, viewer.info.objects) };
  };
  // Which frame the hovered records are of (it changes with every frame shown).
  explore.hoverFrame = () => fly.drawn;
  // The light ray of pixel (col, row) of the frame shown (map.js's hover), made in this page:
  // the record is read from the frame's slots and its path traced by the kernel's closed
  // forms (hovered.js), no server call. Null outside the frame; the load answers null once
  // the frame is gone.
  explore.hoverRay = (col, row) => {
    const at = sampleOf(col, row);
    if (!at) return null;
    const traced = fly.slots;
    const view = fly.slotsView;
    return {
      key: `${fly.drawn} ${col} ${row}`,
      load: async () => {
        if (fly.slots !== traced) return null;
        const slots = await readHovered(traced, at[0], at[1]);
        const event = { t: view.time, ...view.position };
        return { ...(await tracedLightRay(tracer, traced.input, event, slots)), col, row };
      },
    };
  };
  // For tests: the shown frame's slots as floats (base64 per slot).
  explore.readSlots = () => {
    const t = fly.slots;
    return { width: t.width, height: t.height,
      slots: tracer.readSlots(t).map((f) => viewer.base64(new Uint8Array(f.buffer))) };
  };
  $('fly-panel').hidden = false;
  $('explore-hint').textContent = 'Move the observer\u2019s event: each change is traced in '
    + 'this browser (Fly, below). PageUp/PageDown change z; drag the observer on the map; '
    + 'hover the picture for a pixel\u2019s light ray on the map.';
  // The server traces its own frames of the first event (coarse, then full, on all cores):
  // unseen while the page flies, so its full frame is given up (the newest request wins,
  // and asks for the coarse frame only) and leaves the cores to this page's GPU.
  fetch('/api/explore/event', { method: 'POST', headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ ...explore.event, refine: false }) }).catch(() => {});

  const changed = () => {
    fly.version += 1;
    const v = structuredClone(fly.view);
    if (typeof explore.onView === 'function') explore.onView(v);
    window.dispatchEvent(new CustomEvent('godel-view', { detail: v }));
  };
  const event = () => ({ t: fly.view.time, ...fly.view.position });
  const right = () => cross(fly.view.forward, fly.view.up);

  // The velocity the keys give (in the observer's axes), or null where none is held.
  const keyVelocity = () => {
    let d = [0, 0, 0];
    const axes = [fly.view.forward, right(), fly.view.up];
    for (const k of fly.keys) {
      const a = KEYS[k];
      for (let i = 0; i < 3; i += 1) d = d.map((x, j) => x + a[i] * axes[i][j]);
    }
    const n = Math.hypot(...d);
    return n > 1e-9 ? { speed: fly.speed, direction: d.map((x) => x / n) } : null;
  };

  // The observer's motion over the proper time accumulated: one request at a time.
  async function move() {
    if (fly.moving || fly.pendingTau === 0) return;
    const tau = fly.pendingTau;
    fly.pendingTau = 0;
    fly.moving = true;
    const v = fly.view;
    try {
      const response = await fetch('/api/explore/move', {
        method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify({ time: v.time, position: v.position, velocity: v.velocity, tau }),
      });
      const answer = await response.json();
      if (!response.ok) throw new Error(answer.error || `${response.status}`);
      v.time = answer.time;
      v.position = answer.position;
      fly.observer = observerOf(answer.observer, answer.position);
      if (fly.fall) v.velocity = answer.velocity;
      fly.tauMoved += tau;
      fly.error = null;
      changed();
      map.update(event());
      explore.showEvent(event());
    } catch (e) {
      fly.error = e.message || String(e);
      fly.playing = false;
      fly.keys.clear();
      status(`cannot move the observer: ${fly.error}`);
    } finally {
      fly.moving = false;
    }
  }

  // Shows a traced frame of `view` at `level`: 'moving' (fewer pixels, one sample), 'half'
  // (half the full width and height, one sample), 'size' (the full size, one sample) or
  // 'full' (the full size and samples). Its slots are kept until the next one (the hovered
  // pixel's record is read from them). `ms`: at rest, the time since its steps began.
  function show(traced, view, version, level, note, ms = null) {
    if (fly.refused) return; // a trace that was under way: the server's frames are shown now
    const full = level === 'full';
    const channels = tracer.channels(traced, viewer.info.objects.length);
    if (fly.slots) fly.slots.slots.forEach((t) => gl.deleteTexture(t));
    fly.slots = traced;
    fly.slotsView = view;
    fly.slotsSupersample = full ? ss : 1;
    const [pw, ph] = full ? [fullW, fullH] : [traced.width, traced.height];
    viewer.showTracedFrame(channels, note(pw, ph), { width: pw, height: ph,
      supersample: full ? ss : 1 });
    fly.drawn += 1;
    if (level !== 'moving') {
      // The panel's line said which server frame was shown: now it says where this one is seen from.
      const v = fly.view;
      const p = v.position;
      status(`frame traced in this browser at t = ${v.time.toFixed(2)}, x = ${p.x.toFixed(3)}, `
        + `y = ${p.y.toFixed(3)}, z = ${p.z.toFixed(3)}, moving at ${v.velocity.speed.toFixed(2)} c`);
    }
    fly.traced = { version, width: pw, height: ph, level };
    explore.hover(); // the map's light ray of the pixel under the pointer, in this frame
    fly.log.push({ version, width: pw, height: ph, level, rafs: fly.rafs, drawn: fly.drawn,
      at: performance.now(), ms });
    if (fly.log.length > 2000) fly.log.shift();
    // For tests: called while this frame's slots are the ones `readSlots` reads.
    if (typeof explore.onShown === 'function') explore.onShown(level);
    checkFrame(traced, view);
  }

  // The GPU's name, for the check and the header (the unmasked one where the browser says it).
  const debugInfo = gl.getExtension('WEBGL_debug_renderer_info');
  const renderer = String(debugInfo ? gl.getParameter(debugInfo.UNMASKED_RENDERER_WEBGL)
    : gl.getParameter(gl.RENDERER));

  // Up to CHECK_PER_SIDE samples among the hits of slot 0 (`s0`: status and object of each
  // sample, the kernel's layout) and as many among the others traced, at a fixed stride, as
  // gpu::check chooses its own; as the server reads them.
  const chooseSamples = (s0, width) => {
    const count = s0.length / 4;
    const code = (i) => s0[4 * i + 1];
    const sides = [(c) => c === 0, (c) => c !== 0 && STATUS[c] !== 'not traced'];
    return sides.flatMap((side) => {
      const all = [];
      for (let i = 0; i < count; i += 1) if (side(code(i))) all.push(i);
      const stride = Math.max(1, Math.ceil(all.length / CHECK_PER_SIDE));
      return all.filter((_, k) => k % stride === 0).map((i) => ({
        x: i % width, y: Math.floor(i / width), status: STATUS[code(i)] ?? 'failed',
        object: code(i) === 0 ? Math.round(s0[4 * i]) : -1 }));
    });
  };

  // Checks the frame `traced` of `view` just shown, where one is due (the first, then one
  // every CHECK_EVERY_MS at most, one at a time; frames of one sample a pixel, the check's
  // grid): its samples are read now, before a newer frame frees them.
  async function checkFrame(traced, view) {
    const now = performance.now();
    if (fly.check.busy || (fly.check.at !== null && now - fly.check.at < CHECK_EVERY_MS)
      || traced.width * traced.height > fullW * fullH) return;
    fly.check.busy = true;
    fly.check.at = now;
    try {
      const [s0] = await tracer.readLater([traced.slots[0]], 0, 0, traced.width, traced.height);
      const samples = chooseSamples(s0, traced.width);
      if (samples.length === 0) return;
      const camera = { ...view.camera, width: traced.width, height: traced.height, samples: 1 };
      const response = await fetch('/api/explore/check', {
        method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify({ view: { ...view, camera }, renderer, samples }),
      });
      const answer = await response.json();
      if (!response.ok) throw new Error(answer.error || `${response.status}`);
      fly.check.last = answer;
      fly.check.done += 1;
      if (answer.verdict === 'disagree') {
        explore.refusedCheck = answer;
        refuse(answer.reason);
      }
    } catch (e) {
      fly.check.last = { verdict: 'failed', reason: e.message || String(e) };
    } finally {
      fly.check.busy = false;
    }
  }

  // The tracer here disagrees with the CPU: this page traces no more, the server does.
  function refuse(reason) {
    fly.refused = `the GPU renderer ${renderer} was refused: ${reason}`;
    fly.keys.clear();
    $('fly-panel').hidden = true;
    explore.traceOnServer(`${fly.refused}; frames traced on the server`);
  }
  const failed = (e) => {
    fly.error = e.message || String(e);
    status(`cannot trace on the GPU: ${fly.error}`);
  };

  // The view changed: a smaller frame of one sample per pixel, in one draw that is not waited
  // for (the kernel compiles on the first). Its width is steered by the time between
  // animation frames towards TARGET_MS.
  async function traceMoving(frameMs) {
    if (frameMs > 0 && fly.drawn > 0) {
      const scale = Math.min(1.25, Math.max(0.8, Math.sqrt(TARGET_MS / frameMs)));
      fly.width = Math.min(fullW, Math.max(MIN_WIDTH, fly.width * scale));
    }
    // The frame rate steers by the time between animation frames, which lags the GPU's work
    // (a frame is not waited for): never more rays than the GPU traces in TARGET_MS.
    if (fly.raysPerMs !== null) {
      const most = Math.sqrt(fly.raysPerMs * TARGET_MS * fullW / fullH);
      fly.width = Math.max(MIN_WIDTH, Math.min(fly.width, most));
    }
    const w = Math.max(Math.min(MIN_WIDTH, fullW), Math.min(fullW, Math.round(fly.width)));
    const h = Math.max(1, Math.round(w * fullH / fullW));
    const version = fly.version;
    const view = structuredClone(fly.view);
    fly.busy = true;
    try {
      const traced = await tracer.trace({ ...input, uniforms: uniformsFor(input.uniforms,
        fly.view, fly.observer, w, h) }, { whole: true });
      const now = performance.now();
      fly.frameMs.push(now);
      if (fly.frameMs.length > 30) fly.frameMs.shift();
      const n = fly.frameMs.length;
      const fps = n > 1 ? (n - 1) * 1000 / (now - fly.frameMs[0]) : 0;
      show(traced, view, version, 'moving', (pw, ph) => `${pw}×${ph} traced on the GPU · `
        + `${fps.toFixed(0)} frames/s`);
    } catch (e) {
      failed(e);
    } finally {
      fly.busy = false;
    }
  }

  // At rest: the full size, in tiles, in up to three steps, each shown as it comes (the next
  // change cancels them): half the width and height at one sample a pixel where the full size
  // would take more than QUICK_MS (a quarter of its rays), the full size at one sample a pixel
  // where the scene asks for ss × ss (ss² times fewer rays), then the full samples.
  async function traceFull() {
    const version = fly.version;
    const view = structuredClone(fly.view);
    const { observer } = fly;
    const cancelled = () => fly.version !== version;
    const steps = [];
    const [halfW, halfH] = [Math.round(fullW / 2), Math.max(1, Math.round(fullH / 2))];
    if (halfW >= MIN_WIDTH
      && (fly.raysPerMs === null || (fullW * fullH) / fly.raysPerMs > QUICK_MS)) {
      steps.push(['half', halfW, halfH]);
    }
    if (ss > 1) steps.push(['size', fullW, fullH]);
    steps.push(['full', fullW * ss, fullH * ss]);
    fly.refining = true;
    const started = performance.now();
    try {
      for (const [level, w, h] of steps) {
        const traced = await tracer.trace({ ...input, uniforms: uniformsFor(input.uniforms,
          view, observer, w, h) }, { cancelled });
        const ms = Math.round(performance.now() - started);
        fly.raysPerMs = (traced.width * traced.height) / Math.max(traced.traceMs, 1);
        const next = level === 'half' ? `${fullW}×${fullH}` : `${ss * ss} samples a pixel`;
        show(traced, view, version, level, (pw, ph) => (level === 'full'
          ? `${pw}×${ph}${ss > 1 ? ` · ${ss * ss} samples a pixel` : ''} traced on the GPU in ${ms} ms`
          : `${pw}×${ph} traced on the GPU in ${ms} ms · refining to ${next}`), ms);
      }
      fly.frameMs = [];
    } catch (e) {
      if (fly.version === version) failed(e);
    } finally {
      fly.refining = false;
    }
  }

  let last = null;
  // Asked for again after the frame is traced and shown, so that the next animation frame
  // shades it (viewer.js's draw, asked for by showing it) before tracing the next.
  async function tick(now) {
    try {
      await step(now);
    } finally {
      if (!fly.refused) requestAnimationFrame(tick);
    }
  }
  async function step(now) {
    if (fly.refused) return;
    const frameMs = last === null ? 0 : now - last;
    const dt = Math.min(MAX_DT, frameMs / 1000);
    last = now;
    const v = fly.view;
    // Roll.
    const roll = (fly.keys.has('KeyE') ? 1 : 0) - (fly.keys.has('KeyQ') ? 1 : 0);
    if (roll !== 0 && dt > 0) {
      v.up = normalize(turn(v.up, v.forward, roll * ROLL_PER_S * dt));
      changed();
    }
    // The velocity: the keys' while held; once they are let go, at rest (the geodesic's when
    // falling); otherwise as it was (the scene's, until a key or Stop changes it).
    const keyed = keyVelocity();
    if (keyed) {
      fly.keyed = true;
      if (keyed.speed !== v.velocity.speed || keyed.direction.some((x, i) => x !== v.velocity.direction[i])) {
        v.velocity = keyed;
        changed();
      }
    } else if (fly.keyed) {
      fly.keyed = false;
      if (!fly.fall) stop();
    }
    // Proper time runs while playing (at the rate) and while a key moves the observer.
    const running = fly.playing || keyed !== null;
    if (running && dt > 0) {
      fly.pendingTau += (fly.playing ? fly.rate : Math.abs(fly.rate) || 1) * dt;
      move();
    } else if (!running) {
      fly.pendingTau = 0;
    }
    if (fly.error !== null) return;
    // A position whose uniforms are still on their way from the server waits for them.
    if (!observerAt(fly.observer, v.position)) return;
    // While time runs every animation frame is traced (the observer's newest event may not
    // be back from the server yet: then the same view again).
    const stale = fly.traced === null || fly.traced.version !== fly.version;
    if (stale || (running && fly.traced.level !== 'full')) {
      fly.rafs += 1;
      // Waited for: it resolves in this task once the kernel is compiled (one draw, no
      // fence), so that the shading asked for comes in the next animation frame.
      if (!fly.busy) await traceMoving(frameMs);
    } else if (fly.traced.level !== 'full' && !fly.busy && !fly.refining && !running && !fly.moving) {
      traceFull();
    }
  }

  // Stop: the observer at rest where it is (its direction kept for the next speed).
  function stop() {
    const v = fly.view;
    if (v.velocity.speed === 0) return;
    v.velocity = { speed: 0, direction: v.velocity.direction };
    changed();
  }

  // ---- the controls
  const typing = (e) => e.target instanceof HTMLInputElement && e.target.type !== 'range'
    && e.target.type !== 'checkbox';
  window.addEventListener('keydown', (e) => {
    if (typing(e) || fly.refused) return;
    if (e.code === 'KeyX') {
      stop();
      e.preventDefault();
    } else if (e.code in KEYS || e.code === 'KeyQ' || e.code === 'KeyE') {
      fly.keys.add(e.code);
      e.preventDefault();
    }
  });
  window.addEventListener('keyup', (e) => { fly.keys.delete(e.code); });
  window.addEventListener('blur', () => fly.keys.clear());

  const canvas = $('image');
  const picture = canvas.parentElement;
  let drag = null;
  // Captured before the viewer's own pan and zoom of the picture (viewer.js).
  picture.addEventListener('pointerdown', (e) => {
    if (e.target !== canvas || fly.refused) return;
    e.stopPropagation();
    drag = [e.clientX, e.clientY];
    canvas.setPointerCapture(e.pointerId);
  }, true);
  picture.addEventListener('pointermove', (e) => {
    if (!drag || e.target !== canvas) return;
    e.stopPropagation();
    const fov = (camera.fov_deg || camera.h_fov_deg || 360) * Math.PI / 180;
    const perPx = fov / Math.max(canvas.clientWidth, 1);
    const [dx, dy] = [e.clientX - drag[0], e.clientY - drag[1]];
    drag = [e.clientX, e.clientY];
    const v = fly.view;
    // Drag the world: right turns the view left; up tilts it down.
    const yawed = turn(v.forward, v.up, dx * perPx);
    const r = normalize(cross(yawed, v.up));
    v.forward = normalize(turn(yawed, r, dy * perPx));
    v.up = normalize(cross(r, v.forward));
    changed();
  }, true);
  const endDrag = (e) => {
    if (drag && e.target === canvas) e.stopPropagation();
    drag = null;
  };
  picture.addEventListener('pointerup', endDrag, true);
  picture.addEventListener('pointercancel', endDrag, true);
  picture.addEventListener('wheel', (e) => {
    if (e.target !== canvas || camera.kind === 'sphere' || fly.refused) return;
    e.preventDefault();
    e.stopPropagation();
    const f = Math.exp(e.deltaY * 0.001);
    const clamp = (x, hi) => Math.min(hi, Math.max(1, x));
    if (camera.kind === 'panorama') {
      const h = clamp(camera.h_fov_deg * f, 360);
      camera.v_fov_deg = clamp(camera.v_fov_deg * h / camera.h_fov_deg, 180);
      camera.h_fov_deg = h;
    } else {
      camera.fov_deg = clamp(camera.fov_deg * f, camera.kind === 'pinhole' ? 170 : 360);
    }
    changed();
  }, { capture: true, passive: false });

  const speed = $('fly-speed');
  const rate = $('fly-rate');
  const sync = () => {
    $('fly-speed-value').textContent = `${fly.speed.toFixed(2)} c`;
    $('fly-play').textContent = fly.playing ? 'Pause' : 'Play';
  };
  speed.addEventListener('input', () => { fly.speed = Number(speed.value); sync(); });
  rate.addEventListener('change', () => {
    const r = Number(rate.value);
    if (rate.value.trim() === '' || !Number.isFinite(r)) {
      status('rate: not a number');
      rate.value = String(fly.rate);
      return;
    }
    fly.rate = r;
  });
  $('fly-play').addEventListener('click', () => { fly.playing = !fly.playing; sync(); });
  $('fly-reverse').addEventListener('click', () => { fly.rate = -fly.rate; rate.value = String(fly.rate); });
  $('fly-stop').addEventListener('click', stop);
  $('fly-fall').addEventListener('change', () => { fly.fall = $('fly-fall').checked; });
  speed.value = String(fly.speed);
  rate.value = String(fly.rate);
  sync();
  // The event fields and the map move the observer too.
  // Its observer uniforms come from the server (the newest event's are kept).
  explore.setEvent = async (e) => {
    fly.view.time = e.t;
    fly.view.position = { x: e.x, y: e.y, z: e.z };
    changed();
    try {
      const mine = observerOf((await inputAt(e)).uniforms, e);
      if (observerAt(mine, fly.view.position)) fly.observer = mine;
    } catch (err) {
      // No frame is traced from this event: the next one asks again.
      status(`cannot move the observer: ${err.message || err}`);
    }
  };
  changed();
  requestAnimationFrame(tick);
  return true;
}
