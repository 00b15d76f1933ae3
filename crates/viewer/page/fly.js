// @ts-check
// godel explore: flying, with every frame traced in this page on the GPU (the exact tracer's
// kernel, trace.js) — no server round trip per frame. The view (`viewer.explore.view()`) is
// the observer and camera with exactly the scene file's `[observer]` and `[camera]` fields
// (docs/guide/src/scenes.md), so that a scene with them traces the frame shown; `godel-view` events
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
//
// The faster tracer (issue 33): each frame, moving or a step at rest, is traced by whichever
// of this page's kernel and the server's CPU exact tracer traced more rays a millisecond here,
// for this scene: the kernel's speed measured on its frames at rest (the first a quarter of
// the width and height, at most MEASURE_RAYS rays), the CPU's on the frames the server traced
// (the start's, then each step at rest it traces for this page). Until the kernel's is
// measured the kernel traces. A frame of the CPU is one of the view, at the size and samples
// the page asks (POST /api/explore/view-frame), shown from the server's channels as the
// frames of `?trace=server` are; the header says which tracer made each frame. `?trace=page`
// keeps every frame on the kernel.
//
// The flight's state is in four parts, each a typedef below, each changed only by the
// functions its typedef names: the sight (where the observer is and looks), the controls (what
// the user holds and chose), the motion (the observer's moves asked of the server) and the
// frames (the frame pipeline: what is traced, in flight and shown, and its counters). Every
// flag that says something is in flight says which request, and is cleared where it ends.
'use strict';

import { getJson, getText, messageOf, ok, postJson } from './api.js';
import { exploreChannels } from './data.js';
import { $ } from './dom.js';
import { STATUS, sampleRecord, tracedLightRay } from './hovered.js';
import { cross, dot, normalize } from './look.js';
import { KernelTracer } from './trace.js';

/** @typedef {import('./contract').Vec3} Vec3 */
/** @typedef {import('./contract').View} View */
/** @typedef {import('./contract').CameraView} CameraView */
/** @typedef {import('./contract').Velocity} Velocity */
/** @typedef {import('./contract').Position} Position */
/** @typedef {import('./contract').ObserverEvent} ObserverEvent */
/** @typedef {import('./contract').KernelInput} KernelInput */
/** @typedef {import('./contract').KernelUniforms} KernelUniforms */
/** @typedef {import('./contract').ObserverUniforms} ObserverUniforms */
/** @typedef {import('./contract').CheckAnswer} CheckAnswer */
/** @typedef {import('./contract').CheckSample} CheckSample */
/** @typedef {import('./trace.js').Traced} Traced */

/**
 * The server's observer uniforms (`obs_static`, `obs_to`) with the position they belong to.
 * @typedef {ObserverUniforms & { position: Position }} PlacedObserver
 */

/**
 * Where the observer is and looks: the view (the scene file's observer and camera fields),
 * the server's uniforms of its position (a frame is traced only from a position whose
 * uniforms have come), and its version, which every change of the view bumps (frames and
 * checks say which version they show). Changed by changeView (keys, drag, roll, wheel, Stop,
 * the event fields and the map: setEvent), and by a move's answer (move).
 * @typedef {object} Sight
 * @property {View} view
 * @property {PlacedObserver} observer
 * @property {number} version
 */

/**
 * What the user holds and chose: the keys held, whether they set the velocity (letting go of
 * them stops the observer), the speed they give, the proper-time rate, Play, "fall freely",
 * and the drag under way (its last pointer position). Changed by the key, pointer and panel
 * handlers; a failed move lets go of the keys and pauses; a refused tracer lets go of the keys.
 * @typedef {object} Controls
 * @property {Set<string>} keys
 * @property {boolean} keyed
 * @property {number} speed
 * @property {number} rate
 * @property {boolean} playing
 * @property {boolean} fall
 * @property {[number, number] | null} drag
 */

/**
 * The observer's motion along its geodesic: the proper time run and not yet asked for, and
 * whether a move request is in flight (one at a time: the proper time run meanwhile waits)
 * and when the last was sent, the proper time moved so far (tests), and whether the map and
 * the event fields show the newest event. Changed by step (time runs), move and showPlace.
 * @typedef {object} Motion
 * @property {number} pendingTau
 * @property {boolean} moving
 * @property {number} movedAt
 * @property {number} tauMoved
 * @property {boolean} placeShown
 */

/**
 * A frame shown: the view's version it was traced from, its picture's size, its level:
 * 'moving' (fewer pixels, one sample), 'half' (half the full width and height, one sample),
 * 'size' (the full size, one sample) or 'full' (the full size and samples); which tracer made
 * it: 'gpu' (this page's kernel) or 'cpu' (the server's exact tracer).
 * @typedef {{ version: number, width: number, height: number, level: Level,
 *   by: 'gpu' | 'cpu' }} ShownFrame
 * @typedef {'moving' | 'half' | 'size' | 'full'} Level
 */

/**
 * A line of the frames' log (tests and benchmarks): the frame shown, the animation frames and
 * frames drawn so far, when (performance.now()), and at rest the ms since its steps began.
 * @typedef {ShownFrame & { rafs: number, drawn: number, at: number, ms: number | null }} LogEntry
 */

/**
 * The page's checks of its tracer: when the last one began, whether one is in flight, how
 * many the server answered, the last answer (or why it failed).
 * @typedef {object} Checks
 * @property {number | null} at
 * @property {boolean} busy
 * @property {number} done
 * @property {CheckAnswer | { verdict: 'failed', reason: string } | null} last
 */

/**
 * The frame pipeline: the frame shown and its slots (kept until the next one: hover reads
 * them), the traces in flight (a moving frame's, `busy`: one at a time; a full frame's steps,
 * `refining`: cancelled by a change of the view; the two may overlap while a move is under
 * way), the steering of the moving frames' width, the counters, the checks, why tracing
 * stopped (`error`: a move or a trace failed; a move that succeeds clears it), and why this
 * page's tracer was refused (`refused`: from then on the server traces). Changed by step,
 * traceMoving, traceFull, show, checkFrame and refuse.
 * @typedef {object} Frames
 * @property {ShownFrame | null} traced
 * @property {{ traced: Traced, view: View, supersample: number } | null} slots
 * @property {{ generation: number, level: import('./contract').Level } | null} server the
 *   server's frame shown (its records and light rays are the server's), else null
 * @property {boolean} busy
 * @property {boolean} refining
 * @property {number} width
 * @property {number | null} raysPerMs the kernel's speed here, from the last frame at rest
 * @property {number | null} cpuRaysPerMs the server's CPU's, from the last step at rest it
 *   traced (before any, the start's frames)
 * @property {number | null} serverWidth the width of the server's next moving frame, steered
 *   by the time the last took (the rays' cost changes tenfold with the view)
 * @property {number} rafs animation frames while the view changed
 * @property {number} drawn frames traced and shown
 * @property {number[]} frameMs wall times of the last frames shown
 * @property {LogEntry[]} log
 * @property {string | null} error
 * @property {Checks} check
 * @property {string | null} refused
 */

/**
 * The flight's numbers under the names tests and benchmarks read (tests/browser/fly*.mjs,
 * launch.mjs): read-only, from the parts above.
 * @typedef {object} FlightNumbers
 * @property {number} version
 * @property {number} speed
 * @property {boolean} moving
 * @property {number} tauMoved
 * @property {ShownFrame | null} traced
 * @property {boolean} refining
 * @property {number | null} raysPerMs
 * @property {number | null} cpuRaysPerMs
 * @property {number} drawn
 * @property {LogEntry[]} log
 * @property {Checks} check
 * @property {string | null} error
 * @property {string | null} refused
 */

// The frame time aimed at while moving (15 frames/s and more).
const TARGET_MS = 50;
// The fewest pixels a moving frame has (its width), and the smoothing of its size.
const MIN_WIDTH = 16;
// At rest, a frame of half the width and height comes first where the full size would take
// longer than this (at the kernel's last measured speed; always before the first).
const QUICK_MS = 1000;
// The kernel's speed is first measured on a frame of a quarter of the width and height, of at
// most this many rays, traced in one draw: on a software GPU such a frame takes under a second
// (2,048 rays of the reference scene: 0.6 s on SwiftShader, where the quarter of 640×360 took
// 3 s), and a real GPU traces it in one draw, its fixed costs small beside the CPU's
// milliseconds.
const MEASURE_RAYS = 2048;
// Radians per CSS pixel dragged (times the field of view's share), roll per second.
const ROLL_PER_S = 1.0;
// Proper time added per animation frame at most (a stalled tab does not jump).
const MAX_DT = 0.1;
// The least time between two moves of the observer while the server traces a moving frame:
// about a frame's time (at 10 frames/s), so that a frame costs about one move.
const MOVE_GAP_MS = 100;
// The page's check of its tracer: at most one frame in this many ms (the first always), and
// at most this many of its samples among those that hit, and as many among the others.
const CHECK_EVERY_MS = 5000;
const CHECK_PER_SIDE = 24;
// How often the page tries again to show a server frame while the last one is being drawn,
// and how long it waits for one at most (then says why and traces on).
const SERVER_POLL_MS = 10;
const SERVER_WAIT_MS = 600000;
// `?trace=page`: every frame on this page's kernel, however fast the server is.
const PINNED = new URLSearchParams(window.location.search).get('trace') === 'page';
// `?moving=full`: every moving frame at the full size, no dynamic resolution (to measure the
// frame rate at a given frame size: scripts/bench-fly.sh, BENCH_MOVING=full).
const FULL_MOVING = new URLSearchParams(window.location.search).get('moving') === 'full';

/** @param {number} ms */
const sleep = (ms) => new Promise((resolve) => { setTimeout(resolve, ms); });

/** @type {Record<string, Vec3>} */
const KEYS = {
  KeyW: [1, 0, 0], KeyS: [-1, 0, 0], KeyD: [0, 1, 0], KeyA: [0, -1, 0],
  KeyR: [0, 0, 1], Space: [0, 0, 1], KeyF: [0, 0, -1], ShiftLeft: [0, 0, -1],
  ShiftRight: [0, 0, -1],
};

// A time as f32 hi + lo (gpu::input::split_time).
/**
 * @param {number} t
 * @returns {[number, number]}
 */
export function splitTime(t) {
  const hi = Math.fround(t);
  return [hi, Math.fround(t - hi)];
}

// Rodrigues: `v` turned by `angle` about the unit axis `k`.
/**
 * @param {Vec3} v
 * @param {Vec3} k
 * @param {number} angle
 * @returns {Vec3}
 */
function turn(v, k, angle) {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  const kv = cross(k, v);
  const d = dot(k, v) * (1 - c);
  /** @param {number} i */
  const at = (i) => v[i] * c + kv[i] * s + k[i] * d;
  return [at(0), at(1), at(2)];
}

/** @param {Vec3} v @returns {Vec3} */
const f32s = (v) => [Math.fround(v[0]), Math.fround(v[1]), Math.fround(v[2])];

// The server's observer uniforms (`obs_static`, `obs_to`) in `uniforms`, kept with the
// position they belong to.
/**
 * @param {ObserverUniforms} uniforms
 * @param {Position} position
 * @returns {PlacedObserver}
 */
export function observerOf(uniforms, position) {
  return { position: { x: position.x, y: position.y, z: position.z },
    obs_static: uniforms.obs_static, obs_to: uniforms.obs_to };
}

// Whether `observer` (observerOf) belongs to `position`.
/**
 * @param {PlacedObserver} observer
 * @param {Position} position
 */
export function observerAt(observer, position) {
  const p = observer.position;
  return p.x === position.x && p.y === position.y && p.z === position.z;
}

// The kernel's uniforms for `view` traced on a `width` × `height` grid (gpu::input::Uniforms
// from KernelInput::new), the scene's own ones (`base`: metric, a, max_past, …) otherwise;
// `observer` (observerOf) the server's for the view's position.
/**
 * @param {KernelUniforms} base
 * @param {View} view
 * @param {PlacedObserver} observer
 * @param {number} width
 * @param {number} height
 * @returns {KernelUniforms}
 */
export function uniformsFor(base, view, observer, width, height) {
  const c = view.camera;
  const fov = c.kind === 'panorama' ? [Number(c.h_fov_deg), Number(c.v_fov_deg)]
    : c.kind === 'sphere' ? [360, 180] : [Number(c.fov_deg), 0];
  const p = view.position;
  if (!observerAt(observer, p)) throw new Error('the observer\'s uniforms are of another position');
  const { speed, direction } = view.velocity;
  return { ...base, obs_t: splitTime(view.time), obs_x: f32s([p.x, p.y, p.z]),
    obs_static: observer.obs_static, obs_to: observer.obs_to,
    velocity: [Math.fround(speed), ...f32s(direction)],
    forward: f32s(view.forward), up: f32s(view.up),
    fov: [Math.fround(fov[0]), Math.fround(fov[1])], size: [width, height] };
}

// Starts flying in explore mode; false where the kernel cannot trace the scene here (the
// reason is shown and the server's frames stay).
/**
 * @param {import('./viewer.js').LoadedViewer} viewer
 * @param {import('./explore.js').Explore} explore
 * @param {import('./map.js').MapPanel} map
 * @param {(text: string) => void} status
 * @returns {Promise<boolean>}
 */
export async function startFly(viewer, explore, map, status) {
  if (viewer.look) {
    status('tracing on the server: a full sphere (--sphere) is looked around in, not flown');
    return false;
  }
  const gl = viewer.gpu().gl;
  /** @type {KernelTracer} */
  let tracer;
  /** @type {KernelInput} */
  let input;
  /** @type {import('./contract').LookView | null} */
  let sceneView;
  const s = explore.event;
  // The kernel's input seen from an event (its observer uniforms too).
  /** @param {ObserverEvent} e */
  const inputAt = async (e) => /** @type {KernelInput} */ (await getJson(`/api/gpu/input?${
    new URLSearchParams({ draw_buffers: String(tracer.maxDrawBuffers), t: String(e.t),
      x: String(e.x), y: String(e.y), z: String(e.z) })}`));
  try {
    tracer = new KernelTracer(gl, await getText('/api/gpu/kernel'));
    input = await inputAt(s);
    sceneView = /** @type {import('./contract').ViewInfo} */ (await getJson('/api/view')).view;
  } catch (e) {
    status(`tracing on the server: ${messageOf(e)}`);
    return false;
  }
  if (!sceneView) {
    status('tracing on the server: the scene has no camera view the page can fly');
    return false;
  }
  const ss = input.supersample;
  const [fullW, fullH] = [input.uniforms.size[0] / ss, input.uniforms.size[1] / ss];
  // What the viewer is told of a frame shown at `level`: a moving frame's full size, else null.
  /** @param {Level} level @returns {[number, number] | null} */
  const movingSize = (level) => (level === 'moving' ? [fullW, fullH] : null);
  const c = sceneView.camera;
  /** @type {CameraView} */
  const camera = { kind: c.kind, width: fullW, height: fullH, samples: ss * ss };
  if ('fov_deg' in c) camera.fov_deg = c.fov_deg;
  if ('h_fov_deg' in c) {
    camera.h_fov_deg = c.h_fov_deg;
    camera.v_fov_deg = c.v_fov_deg;
  }

  // ---- the state (the typedefs above say what each part holds and what changes it)

  /** @type {Sight} */
  const sight = {
    view: {
      time: s.t, position: { x: s.x, y: s.y, z: s.z },
      velocity: { speed: sceneView.velocity.speed, direction: [...sceneView.velocity.direction] },
      forward: normalize(sceneView.forward), up: normalize(sceneView.up), camera,
    },
    observer: observerOf(input.uniforms, s),
    version: 0,
  };
  /** @type {Controls} */
  const controls = { keys: new Set(), keyed: false, speed: 0.5, rate: 1, playing: false,
    fall: false, drag: null };
  /** @type {Motion} */
  const motion = { pendingTau: 0, moving: false, movedAt: -Infinity, tauMoved: 0,
    placeShown: true };
  /** @type {Frames} */
  const frames = {
    traced: null,
    slots: null,
    server: null,
    busy: false,
    refining: false,
    width: Math.min(fullW, MIN_WIDTH),
    raysPerMs: null,
    cpuRaysPerMs: null,
    serverWidth: null,
    rafs: 0,
    drawn: 0,
    frameMs: [],
    log: [],
    error: null,
    check: { at: null, busy: false, done: 0, last: null },
    refused: null,
  };

  /** @type {FlightNumbers} */
  explore.fly = {
    get version() { return sight.version; },
    get speed() { return controls.speed; },
    get moving() { return motion.moving; },
    get tauMoved() { return motion.tauMoved; },
    get traced() { return frames.traced; },
    get refining() { return frames.refining; },
    get raysPerMs() { return frames.raysPerMs; },
    get cpuRaysPerMs() { return frames.cpuRaysPerMs; },
    get drawn() { return frames.drawn; },
    get log() { return frames.log; },
    get check() { return frames.check; },
    get error() { return frames.error; },
    get refused() { return frames.refused; },
  };
  explore.view = () => structuredClone(sight.view);
  explore.onView = null;
  explore.uniforms = (width, height) => uniformsFor(input.uniforms, sight.view, sight.observer,
    width, height);
  // The sample that stands for pixel (col, row) of the frame shown (the one nearest the
  // pixel's centre, as the server's picture_sample), or null outside the frame.
  /**
   * @param {number} col
   * @param {number} row
   * @returns {[number, number] | null}
   */
  const sampleOf = (col, row) => {
    const shown = frames.slots;
    if (!shown) return null;
    const s = shown.supersample;
    const [x, y] = [s * col + (s >> 1), s * row + (s >> 1)];
    return x < shown.traced.width && y < shown.traced.height ? [x, y] : null;
  };
  // The slots of sample (x, y) of the frame `traced`, read back once for the record panel
  // and the map's ray of the same hover.
  /** @type {{ traced: Traced, x: number, y: number, slots: Promise<Float32Array[]> } | null} */
  let lastRead = null;
  /**
   * @param {Traced} traced
   * @param {number} x
   * @param {number} y
   */
  const readHovered = (traced, x, y) => {
    if (!lastRead || lastRead.traced !== traced || lastRead.x !== x || lastRead.y !== y) {
      lastRead = { traced, x, y, slots: tracer.readSample(traced, x, y) };
    }
    return lastRead.slots;
  };
  // The record of pixel (col, row) of the frame shown (viewer.js's hover), read from the
  // frame's slots (hovered.js), as /api/pixel answers for the server's frames; resolves to
  // null outside.
  explore.hoverRecord = async (col, row) => {
    const server = frames.server;
    if (server) {
      // The server's frame: its record, as /api/pixel answers for it (null once it is gone).
      const response = await fetch(`/api/pixel?col=${col}&row=${row}`
        + `&generation=${server.generation}&level=${server.level}`);
      if (response.status === 410 || response.status === 400) return null;
      const record = /** @type {import('./hovered.js').SampleRecord & { col: number,
        row: number }} */ (await (await ok(response)).json());
      return record;
    }
    const at = sampleOf(col, row);
    const shown = frames.slots;
    if (!at || !shown) return null;
    const slots = await readHovered(shown.traced, at[0], at[1]);
    return { col, row, ...sampleRecord(slots, input, viewer.info.objects) };
  };
  // Which frame the hovered records are of (it changes with every frame shown).
  explore.hoverFrame = () => frames.drawn;
  // The light ray of pixel (col, row) of the frame shown (map.js's hover), made in this page:
  // the record is read from the frame's slots and its path traced by the kernel's closed
  // forms (hovered.js), no server call. Null outside the frame; the load answers null once
  // the frame is gone.
  explore.hoverRay = (col, row) => {
    const server = frames.server;
    if (server) {
      // The server's frame: its light ray from the server (map.js reads /api/explore/ray).
      const { generation, level } = server;
      return { key: `server ${generation} ${col} ${row}`,
        load: () => /** @type {Promise<import('./map.js').SampleRay>} */ (getJson(
          `/api/explore/ray?generation=${generation}&level=${level}&col=${col}&row=${row}`)) };
    }
    const at = sampleOf(col, row);
    const shown = frames.slots;
    if (!at || !shown) return null;
    const { traced, view } = shown;
    return {
      key: `${frames.drawn} ${col} ${row}`,
      load: async () => {
        if (frames.slots?.traced !== traced) return null;
        const slots = await readHovered(traced, at[0], at[1]);
        const event = { t: view.time, ...view.position };
        return { ...(await tracedLightRay(tracer, traced.input, event, slots)), col, row };
      },
    };
  };
  // For tests: the shown frame's slots as floats (base64 per slot).
  explore.readSlots = () => {
    if (!frames.slots) throw new Error('no frame is shown');
    const t = frames.slots.traced;
    return { width: t.width, height: t.height,
      slots: tracer.readSlots(t).map((f) => viewer.base64(new Uint8Array(f.buffer))) };
  };
  $('fly-panel').hidden = false;
  $('explore-hint').textContent = 'Move the observer\u2019s event: each change is traced '
    + 'again (Fly, below). PageUp/PageDown change z; drag the observer on the map; '
    + 'hover the picture for a pixel\u2019s light ray on the map.';
  // The server traces its own frames of the first event (coarse, then full, on all cores):
  // unseen while the page flies, so its full frame is given up (the newest request wins,
  // and asks for the coarse frame only) and leaves the cores to this page's GPU.
  /** @type {import('./contract').EventRequest} */
  const coarseOnly = { ...explore.event, refine: false };
  postJson('/api/explore/event', coarseOnly).catch(() => {});
  // The server's speed so far (its frames of the start), for the choice of tracer: asked now,
  // waited for before the first step at rest.
  const startSpeed = getJson('/api/explore/frame').then((answer) => {
    const a = /** @type {import('./contract').FrameAnswer} */ (answer);
    if (frames.cpuRaysPerMs === null) frames.cpuRaysPerMs = a.cpu_rays_per_ms;
  }).catch(() => {});

  // ---- the sight's transitions

  // The view changed (after `edit`): a new version, announced.
  /** @param {(view: View) => void} edit */
  const changeView = (edit) => {
    edit(sight.view);
    sight.version += 1;
    const v = structuredClone(sight.view);
    if (typeof explore.onView === 'function') explore.onView(v);
    window.dispatchEvent(new CustomEvent('godel-view', { detail: v }));
  };
  /** @returns {ObserverEvent} */
  const event = () => ({ t: sight.view.time, ...sight.view.position });
  const right = () => cross(sight.view.forward, sight.view.up);

  // The velocity the keys give (in the observer's axes), or null where none is held.
  /** @returns {Velocity | null} */
  const keyVelocity = () => {
    /** @type {Vec3} */
    let d = [0, 0, 0];
    const axes = [sight.view.forward, right(), sight.view.up];
    for (const k of controls.keys) {
      const a = KEYS[k];
      if (!a) continue; // Q, E: roll
      for (let i = 0; i < 3; i += 1) {
        d = [d[0] + a[i] * axes[i][0], d[1] + a[i] * axes[i][1], d[2] + a[i] * axes[i][2]];
      }
    }
    const n = Math.hypot(...d);
    return n > 1e-9 ? { speed: controls.speed, direction: [d[0] / n, d[1] / n, d[2] / n] }
      : null;
  };

  // Stop: the observer at rest where it is (its direction kept for the next speed).
  function stop() {
    if (sight.view.velocity.speed === 0) return;
    changeView((v) => { v.velocity = { speed: 0, direction: v.velocity.direction }; });
  }

  // ---- the motion's transitions

  // The observer's motion over the proper time accumulated: one request at a time.
  async function move() {
    if (motion.moving || motion.pendingTau === 0) return;
    const tau = motion.pendingTau;
    motion.pendingTau = 0;
    motion.moving = true;
    motion.movedAt = performance.now();
    const v = sight.view;
    /** @type {import('./contract').MoveRequest} */
    const asked = { time: v.time, position: v.position, velocity: v.velocity, tau };
    try {
      const answer = /** @type {import('./contract').MoveAnswer} */ (await (await ok(
        await postJson('/api/explore/move', asked))).json());
      sight.observer = observerOf(answer.observer, answer.position);
      motion.tauMoved += tau;
      frames.error = null;
      changeView((view) => {
        view.time = answer.time;
        view.position = answer.position;
        if (controls.fall) view.velocity = answer.velocity;
      });
      motion.placeShown = false;
    } catch (e) {
      frames.error = messageOf(e);
      controls.playing = false;
      controls.keys.clear();
      status(`cannot move the observer: ${frames.error}`);
    } finally {
      motion.moving = false;
    }
  }

  // The map and the event fields follow the newest event once per frame shown, and at rest:
  // not at each move (a few per frame), since every change of the page makes the browser
  // composite it again, which a software renderer pays for with the cores that trace.
  // `now`: in the picture's animation frame, where the map is drawn at once.
  /** @param {boolean} [now] */
  function showPlace(now = false) {
    if (motion.placeShown) return;
    motion.placeShown = true;
    map.update(event(), now);
    explore.showEvent(event());
  }

  // ---- the frames' transitions

  // Shows a traced frame of `view` at `level`. Its slots are kept until the next one (the
  // hovered pixel's record is read from them). `ms`: at rest, the time since its steps began.
  /**
   * @param {Traced} traced
   * @param {View} view
   * @param {number} version
   * @param {Level} level
   * @param {(width: number, height: number) => string} note
   * @param {number | null} [ms]
   */
  function show(traced, view, version, level, note, ms = null) {
    if (frames.refused) return; // a trace that was under way: the server's frames are shown now
    const full = level === 'full';
    const channels = tracer.channels(traced, viewer.info.objects.length);
    if (frames.slots) frames.slots.traced.slots.forEach((t) => gl.deleteTexture(t));
    frames.slots = { traced, view, supersample: full ? ss : 1 };
    frames.server = null;
    explore.shown = null;
    const [pw, ph] = full ? [fullW, fullH] : [traced.width, traced.height];
    viewer.showTracedFrame(channels, note(pw, ph), { width: pw, height: ph,
      supersample: full ? ss : 1 }, movingSize(level));
    frames.drawn += 1;
    shown(version, pw, ph, level, 'gpu', ms);
    checkFrame(traced, view);
  }

  // A frame is on screen (`by` the kernel or the server's CPU): the map's ray of the pixel
  // under the pointer follows, and the log and tests hear of it.
  /**
   * @param {number} version
   * @param {number} width
   * @param {number} height
   * @param {Level} level
   * @param {'gpu' | 'cpu'} by
   * @param {number | null} ms
   */
  function shown(version, width, height, level, by, ms) {
    if (level !== 'moving') {
      // The panel's line said which server frame was shown: now it says where this one is seen from.
      const v = sight.view;
      const p = v.position;
      const line = `frame traced ${by === 'gpu' ? 'in this browser' : 'on the server\u2019s CPU'} at `
        + `t = ${v.time.toFixed(2)}, x = ${p.x.toFixed(3)}, y = ${p.y.toFixed(3)}, `
        + `z = ${p.z.toFixed(3)}, moving at ${v.velocity.speed.toFixed(2)} c`;
      viewer.withPicture('status', () => status(line));
    }
    frames.traced = { version, width, height, level, by };
    // With the picture (a server frame's channels are still on their way).
    viewer.withPicture('place', showPlace);
    explore.hover(); // the map's light ray of the pixel under the pointer, in this frame
    frames.log.push({ version, width, height, level, by, rafs: frames.rafs,
      drawn: frames.drawn, at: performance.now(), ms });
    if (frames.log.length > 2000) frames.log.shift();
    // For tests: called while this frame's slots are the ones `readSlots` reads.
    if (typeof explore.onShown === 'function') explore.onShown(level);
  }

  // Whether the server's CPU traces this scene faster than this page's kernel, both measured
  // here (unless `?trace=page`): then it traces the next frame.
  const serverFaster = () => !PINNED && frames.cpuRaysPerMs !== null
    && frames.raysPerMs !== null && frames.cpuRaysPerMs > frames.raysPerMs;
  // The speeds for the header: "the CPU 73 rays/ms, the GPU 9".
  const speeds = () => `the CPU ${Math.round(frames.cpuRaysPerMs ?? 0)} rays/ms here, `
    + `the GPU ${Math.round(frames.raysPerMs ?? 0)}`;

  // One frame of `view` traced on the server's CPU, `width` × `height` pixels of `samples`
  // rays each: asks for it and waits for it; resolves to its FrameInfo, or null once
  // `cancelled()` or once another request (another tab) replaced it. The CPU's speed is
  // measured from it where `measure` (a step at rest: as the kernel's, not from the small
  // moving frames, whose fixed costs per frame would weigh more).
  /**
   * @param {View} view
   * @param {number} width
   * @param {number} height
   * @param {number} samples
   * @param {() => boolean} cancelled
   * @param {boolean} measure
   * @returns {Promise<import('./contract').FrameInfo | null>}
   */
  async function serverFrame(view, width, height, samples, cancelled, measure) {
    const camera = { ...view.camera, width, height, samples };
    // The server answers once the frame is kept, or after a wait of its own (explore_routes.rs):
    // the request that asks for the frame waits for it, and then, if need be, others.
    const asked = /** @type {import('./contract').ViewFrameAnswer} */ (await (await ok(
      await postJson('/api/explore/view-frame?wait=true', { ...view, camera }))).json());
    const deadline = performance.now() + SERVER_WAIT_MS;
    let answer = asked.answer;
    while (!cancelled()) {
      if (answer.generation > asked.generation) return null;
      if (answer.error && answer.generation === asked.generation) throw new Error(answer.error);
      const f = answer.frame;
      if (f && f.generation === asked.generation) {
        if (measure) {
          frames.cpuRaysPerMs = (f.width * f.height * f.supersample * f.supersample)
            / Math.max(f.trace_ms, 1e-3);
        }
        return f;
      }
      if (performance.now() > deadline) {
        throw new Error(`the server's frame did not come within ${SERVER_WAIT_MS / 1000} s`);
      }
      answer = /** @type {import('./contract').FrameAnswer} */ (
        await getJson(`/api/explore/frame?after=${asked.generation}`));
    }
    return null;
  }

  // Shows the server's `frame` of `view` at `level` (its channels fetched by the viewer, which
  // takes a frame once the last one is drawn); false where `cancelled()` first.
  /**
   * @param {import('./contract').FrameInfo} frame
   * @param {number} version
   * @param {Level} level
   * @param {(width: number, height: number) => string} note
   * @param {() => boolean} cancelled
   * @param {number | null} [ms]
   */
  async function showServer(frame, version, level, note, cancelled, ms = null) {
    const url = exploreChannels(frame);
    const deadline = performance.now() + SERVER_WAIT_MS;
    while (!viewer.showFrame(frame, url, movingSize(level))) {
      if (cancelled() || frames.refused || performance.now() > deadline) return false;
      await sleep(SERVER_POLL_MS);
    }
    if (frames.refused) return false; // the server's frames are explore.js's from now on
    if (frames.slots) frames.slots.traced.slots.forEach((t) => gl.deleteTexture(t));
    frames.slots = null;
    frames.server = { generation: frame.generation, level: frame.level };
    explore.shown = frames.server; // saved pictures and overlays name this frame
    viewer.noteFrames(note(frame.width, frame.height));
    frames.drawn += 1;
    shown(version, frame.width, frame.height, level, 'cpu', ms);
    return true;
  }

  // The GPU's name, for the check and the header (the unmasked one where the browser says it).
  const debugInfo = gl.getExtension('WEBGL_debug_renderer_info');
  const renderer = String(debugInfo ? gl.getParameter(debugInfo.UNMASKED_RENDERER_WEBGL)
    : gl.getParameter(gl.RENDERER));

  // Up to CHECK_PER_SIDE samples among the hits of slot 0 (`s0`: status and object of each
  // sample, the kernel's layout) and as many among the others traced, at a fixed stride, as
  // gpu::check chooses its own; as the server reads them.
  /**
   * @param {Float32Array} s0
   * @param {number} width
   * @returns {CheckSample[]}
   */
  const chooseSamples = (s0, width) => {
    const count = s0.length / 4;
    /** @param {number} i */
    const code = (i) => s0[4 * i + 1];
    /** @type {((c: number) => boolean)[]} */
    const sides = [(c) => c === 0, (c) => c !== 0 && STATUS[c] !== 'not traced'];
    return sides.flatMap((side) => {
      /** @type {number[]} */
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
  /**
   * @param {Traced} traced
   * @param {View} view
   */
  async function checkFrame(traced, view) {
    const check = frames.check;
    const now = performance.now();
    if (check.busy || (check.at !== null && now - check.at < CHECK_EVERY_MS)
      || traced.width * traced.height > fullW * fullH) return;
    check.busy = true;
    check.at = now;
    try {
      const [s0] = await tracer.readLater([traced.slots[0]], 0, 0, traced.width, traced.height);
      const samples = chooseSamples(s0, traced.width);
      if (samples.length === 0) return;
      const camera = { ...view.camera, width: traced.width, height: traced.height, samples: 1 };
      /** @type {import('./contract').CheckRequest} */
      const asked = { view: { ...view, camera }, renderer, samples };
      const answer = /** @type {CheckAnswer} */ (await (await ok(
        await postJson('/api/explore/check', asked))).json());
      check.last = answer;
      check.done += 1;
      if (answer.verdict === 'disagree') {
        explore.refusedCheck = answer;
        refuse(String(answer.reason));
      }
    } catch (e) {
      check.last = { verdict: 'failed', reason: messageOf(e) };
    } finally {
      check.busy = false;
    }
  }

  // The tracer here disagrees with the CPU: this page traces no more, the server does. The
  // reason names the renderer ("the GPU (…) disagrees with the CPU exact tracer on …").
  /** @param {string} reason */
  function refuse(reason) {
    frames.refused = `the page's tracer was refused: ${reason}`;
    controls.keys.clear();
    $('fly-panel').hidden = true;
    explore.traceOnServer(`${frames.refused}; frames traced on the server`);
  }
  /** @param {unknown} e */
  const failed = (e) => {
    frames.error = messageOf(e);
    status(`cannot trace on the GPU: ${frames.error}`);
  };

  // The frame rate of the moving frames, counting one shown now (over the last 30).
  const frameRate = () => {
    const now = performance.now();
    frames.frameMs.push(now);
    if (frames.frameMs.length > 30) frames.frameMs.shift();
    const n = frames.frameMs.length;
    return n > 1 ? (n - 1) * 1000 / (now - frames.frameMs[0]) : 0;
  };
  // A moving frame's height for its width, the full frame's shape.
  /** @param {number} w */
  const heightOf = (w) => Math.max(1, Math.round(w * fullH / fullW));
  // A moving frame's width: at least MIN_WIDTH (or the full width, if less), at most the full.
  /** @param {number} w */
  const widthOf = (w) => Math.max(Math.min(MIN_WIDTH, fullW), Math.min(fullW, Math.round(w)));

  // The view changed: a smaller frame of one sample per pixel, in one draw that is not waited
  // for (the kernel compiles on the first). Its width is steered by the time between
  // animation frames towards TARGET_MS.
  /** @param {number} frameMs */
  async function traceMoving(frameMs) {
    if (frameMs > 0 && frames.drawn > 0) {
      const scale = Math.min(1.25, Math.max(0.8, Math.sqrt(TARGET_MS / frameMs)));
      frames.width = Math.min(fullW, Math.max(MIN_WIDTH, frames.width * scale));
    }
    // The frame rate steers by the time between animation frames, which lags the GPU's work
    // (a frame is not waited for): never more rays than the GPU traces in TARGET_MS.
    if (frames.raysPerMs !== null) {
      const most = Math.sqrt(frames.raysPerMs * TARGET_MS * fullW / fullH);
      frames.width = Math.max(MIN_WIDTH, Math.min(frames.width, most));
    }
    const w = FULL_MOVING ? fullW : widthOf(frames.width);
    const h = heightOf(w);
    const version = sight.version;
    const view = structuredClone(sight.view);
    frames.busy = true;
    try {
      const traced = await tracer.trace({ ...input, uniforms: uniformsFor(input.uniforms,
        sight.view, sight.observer, w, h) }, { whole: true });
      const fps = frameRate();
      show(traced, view, version, 'moving', (pw, ph) => `${pw}×${ph} traced on the GPU · `
        + `${fps.toFixed(0)} frames/s`);
    } catch (e) {
      failed(e);
    } finally {
      frames.busy = false;
    }
  }

  // The view changed and the server's CPU is the faster: a smaller frame of one sample a
  // pixel traced there in about half of TARGET_MS (the other half is the round trip): at
  // first of the rays it traces in that time at its speed at rest, then steered by the time
  // the last moving frame took. Not waited for by the animation frames; every one is shown,
  // as the kernel's.
  async function serverMoving() {
    const w = FULL_MOVING ? fullW : widthOf(frames.serverWidth
      ?? Math.sqrt((frames.cpuRaysPerMs ?? 0) * (TARGET_MS / 2) * fullW / fullH));
    const h = heightOf(w);
    const version = sight.version;
    const view = structuredClone(sight.view);
    const refused = () => frames.refused !== null;
    frames.busy = true;
    try {
      const frame = await serverFrame(view, w, h, 1, refused, false);
      if (frame === null) return;
      // The next frame's width, for about TARGET_MS / 2 of tracing.
      const scale = Math.sqrt((TARGET_MS / 2) / Math.max(frame.trace_ms, 1));
      frames.serverWidth = frame.width * Math.min(2, Math.max(0.5, scale));
      const fps = frameRate();
      await showServer(frame, version, 'moving', (pw, ph) => `${pw}×${ph} traced on the `
        + `server\u2019s CPU · ${fps.toFixed(0)} frames/s`, refused);
    } catch (e) {
      failed(e);
    } finally {
      frames.busy = false;
    }
  }

  // At rest: the full size, in tiles, in up to three steps, each shown as it comes (the next
  // change cancels them): half the width and height at one sample a pixel where the full size
  // would take more than QUICK_MS (a quarter of its rays), the full size at one sample a pixel
  // where the scene asks for ss × ss (ss² times fewer rays), then the full samples. Each step
  // on the faster tracer (serverFaster). Where the kernel's speed is not known yet but the
  // server's is, a frame of a quarter of the width and height (a sixteenth of the rays, at
  // most MEASURE_RAYS; shown as a moving frame) measures it first: on a software GPU the half
  // size alone can take many seconds.
  async function traceFull() {
    const version = sight.version;
    const view = structuredClone(sight.view);
    const { observer } = sight;
    const cancelled = () => sight.version !== version;
    frames.refining = true;
    await startSpeed;
    const started = performance.now();
    try {
      if (!PINNED && frames.raysPerMs === null && frames.cpuRaysPerMs !== null) {
        const w = widthOf(Math.min(fullW / 4, Math.sqrt(MEASURE_RAYS * fullW / fullH)));
        const traced = await tracer.trace({ ...input, uniforms: uniformsFor(input.uniforms,
          view, observer, w, heightOf(w)) }, { cancelled, whole: true });
        const ms = Math.round(performance.now() - started);
        frames.raysPerMs = (traced.width * traced.height) / Math.max(traced.traceMs, 1);
        show(traced, view, version, 'moving', (pw, ph) => `${pw}×${ph} traced on the GPU in `
          + `${ms} ms · measuring its speed against the server\u2019s CPU`, ms);
      }
      /** @type {[Level, number, number, number][]} level, picture size, samples along a side */
      const steps = [];
      const [halfW, halfH] = [Math.round(fullW / 2), Math.max(1, Math.round(fullH / 2))];
      const speed = serverFaster() ? frames.cpuRaysPerMs : frames.raysPerMs;
      if (halfW >= MIN_WIDTH && (speed === null || (fullW * fullH) / speed > QUICK_MS)) {
        steps.push(['half', halfW, halfH, 1]);
      }
      if (ss > 1) steps.push(['size', fullW, fullH, 1]);
      steps.push(['full', fullW, fullH, ss]);
      for (const [level, pw, ph, side] of steps) {
        const next = level === 'half' ? `${fullW}×${fullH}` : `${ss * ss} samples a pixel`;
        /**
         * @param {string} by
         * @param {number} ms
         * @returns {(w: number, h: number) => string}
         */
        const note = (by, ms) => (w, h) => (level === 'full'
          ? `${w}×${h}${ss > 1 ? ` · ${ss * ss} samples a pixel` : ''} traced on ${by} in ${ms} ms`
          : `${w}×${h} traced on ${by} in ${ms} ms · refining to ${next}`);
        if (serverFaster()) {
          const frame = await serverFrame(view, pw, ph, side * side, cancelled, true);
          if (frame === null) return;
          const ms = Math.round(performance.now() - started);
          const by = `the server\u2019s CPU (faster here: ${speeds()})`;
          if (!await showServer(frame, version, level, note(by, ms), cancelled, ms)) return;
        } else {
          const traced = await tracer.trace({ ...input, uniforms: uniformsFor(input.uniforms,
            view, observer, pw * side, ph * side) }, { cancelled });
          const ms = Math.round(performance.now() - started);
          frames.raysPerMs = (traced.width * traced.height) / Math.max(traced.traceMs, 1);
          show(traced, view, version, level, note('the GPU', ms), ms);
        }
      }
      frames.frameMs = [];
    } catch (e) {
      if (sight.version === version) failed(e);
    } finally {
      frames.refining = false;
    }
  }

  /** @type {number | null} */
  let last = null;
  // Asked for again after the frame is traced and shown, so that the next animation frame
  // shades it (viewer.js's draw, asked for by showing it) before tracing the next.
  /** @param {number} now */
  async function tick(now) {
    try {
      await step(now);
    } finally {
      if (!frames.refused) requestAnimationFrame(tick);
    }
  }
  // One animation frame: the controls held turn and move the observer, time runs, and the
  // frame the view needs next is traced.
  /** @param {number} now */
  async function step(now) {
    if (frames.refused) return;
    const frameMs = last === null ? 0 : now - last;
    const dt = Math.min(MAX_DT, frameMs / 1000);
    last = now;
    // Roll.
    const roll = (controls.keys.has('KeyE') ? 1 : 0) - (controls.keys.has('KeyQ') ? 1 : 0);
    if (roll !== 0 && dt > 0) {
      changeView((v) => { v.up = normalize(turn(v.up, v.forward, roll * ROLL_PER_S * dt)); });
    }
    // The velocity: the keys' while held; once they are let go, at rest (the geodesic's when
    // falling); otherwise as it was (the scene's, until a key or Stop changes it).
    const keyed = keyVelocity();
    if (keyed) {
      controls.keyed = true;
      const v = sight.view.velocity;
      if (keyed.speed !== v.speed || keyed.direction.some((x, i) => x !== v.direction[i])) {
        changeView((view) => { view.velocity = keyed; });
      }
    } else if (controls.keyed) {
      controls.keyed = false;
      if (!controls.fall) stop();
    }
    // Proper time runs while playing (at the rate) and while a key moves the observer.
    const running = controls.playing || keyed !== null;
    if (running && dt > 0) {
      motion.pendingTau += (controls.playing ? controls.rate : Math.abs(controls.rate) || 1) * dt;
      // While the server traces a moving frame, the next one needs the newest event only when
      // it is asked for: a move at most every MOVE_GAP_MS meanwhile (each request costs the
      // browser's cores, which a software renderer shares with the server).
      if (!(frames.busy && serverFaster() && now - motion.movedAt < MOVE_GAP_MS)) move();
    } else if (!running) {
      motion.pendingTau = 0;
      if (!motion.moving) showPlace();
    }
    if (frames.error !== null) return;
    // A position whose uniforms are still on their way from the server waits for them.
    if (!observerAt(sight.observer, sight.view.position)) return;
    // While time runs every animation frame is traced (the observer's newest event may not
    // be back from the server yet: then the same view again).
    const shown = frames.traced;
    if (shown === null || shown.version !== sight.version || (running && shown.level !== 'full')) {
      frames.rafs += 1;
      // Waited for: it resolves in this task once the kernel is compiled (one draw, no
      // fence), so that the shading asked for comes in the next animation frame.
      if (!frames.busy) {
        if (serverFaster()) serverMoving();
        else await traceMoving(frameMs);
      }
    } else if (shown.level !== 'full' && !frames.busy && !frames.refining && !running
      && !motion.moving) {
      traceFull();
    }
  }

  // ---- the controls: keys, pointer and wheel on the picture, the Fly panel

  /** @param {KeyboardEvent} e */
  const typing = (e) => e.target instanceof HTMLInputElement && e.target.type !== 'range'
    && e.target.type !== 'checkbox';
  window.addEventListener('keydown', (e) => {
    if (typing(e) || frames.refused) return;
    if (e.code === 'KeyX') {
      stop();
      e.preventDefault();
    } else if (e.code in KEYS || e.code === 'KeyQ' || e.code === 'KeyE') {
      controls.keys.add(e.code);
      e.preventDefault();
    }
  });
  window.addEventListener('keyup', (e) => { controls.keys.delete(e.code); });
  window.addEventListener('blur', () => controls.keys.clear());

  const canvas = $('image', HTMLCanvasElement);
  const picture = canvas.parentElement;
  if (!picture) throw new Error('the picture\u2019s canvas has no parent');
  // Captured before the viewer's own pan and zoom of the picture (viewer.js).
  picture.addEventListener('pointerdown', (e) => {
    if (e.target !== canvas || frames.refused) return;
    e.stopPropagation();
    controls.drag = [e.clientX, e.clientY];
    canvas.setPointerCapture(e.pointerId);
  }, true);
  picture.addEventListener('pointermove', (e) => {
    const drag = controls.drag;
    if (!drag || e.target !== canvas) return;
    e.stopPropagation();
    const fov = (camera.fov_deg || camera.h_fov_deg || 360) * Math.PI / 180;
    const perPx = fov / Math.max(canvas.clientWidth, 1);
    const [dx, dy] = [e.clientX - drag[0], e.clientY - drag[1]];
    controls.drag = [e.clientX, e.clientY];
    // Drag the world: right turns the view left; up tilts it down.
    changeView((v) => {
      const yawed = turn(v.forward, v.up, dx * perPx);
      const r = normalize(cross(yawed, v.up));
      v.forward = normalize(turn(yawed, r, dy * perPx));
      v.up = normalize(cross(r, v.forward));
    });
  }, true);
  /** @param {PointerEvent} e */
  const endDrag = (e) => {
    if (controls.drag && e.target === canvas) e.stopPropagation();
    controls.drag = null;
  };
  picture.addEventListener('pointerup', endDrag, true);
  picture.addEventListener('pointercancel', endDrag, true);
  picture.addEventListener('wheel', (e) => {
    if (e.target !== canvas || camera.kind === 'sphere' || frames.refused) return;
    e.preventDefault();
    e.stopPropagation();
    const f = Math.exp(e.deltaY * 0.001);
    /** @type {(x: number, hi: number) => number} */
    const clamp = (x, hi) => Math.min(hi, Math.max(1, x));
    changeView(({ camera: c }) => {
      if (c.kind === 'panorama') {
        const h = clamp(Number(c.h_fov_deg) * f, 360);
        c.v_fov_deg = clamp(Number(c.v_fov_deg) * h / Number(c.h_fov_deg), 180);
        c.h_fov_deg = h;
      } else {
        c.fov_deg = clamp(Number(c.fov_deg) * f, c.kind === 'pinhole' ? 170 : 360);
      }
    });
  }, { capture: true, passive: false });

  const speed = $('fly-speed', HTMLInputElement);
  const rate = $('fly-rate', HTMLInputElement);
  const fall = $('fly-fall', HTMLInputElement);
  const sync = () => {
    $('fly-speed-value').textContent = `${controls.speed.toFixed(2)} c`;
    $('fly-play').textContent = controls.playing ? 'Pause' : 'Play';
  };
  speed.addEventListener('input', () => { controls.speed = Number(speed.value); sync(); });
  rate.addEventListener('change', () => {
    const r = Number(rate.value);
    if (rate.value.trim() === '' || !Number.isFinite(r)) {
      status('rate: not a number');
      rate.value = String(controls.rate);
      return;
    }
    controls.rate = r;
  });
  $('fly-play').addEventListener('click', () => { controls.playing = !controls.playing; sync(); });
  $('fly-reverse').addEventListener('click', () => {
    controls.rate = -controls.rate;
    rate.value = String(controls.rate);
  });
  $('fly-stop').addEventListener('click', stop);
  fall.addEventListener('change', () => { controls.fall = fall.checked; });
  speed.value = String(controls.speed);
  rate.value = String(controls.rate);
  sync();
  // The event fields and the map move the observer too.
  // Its observer uniforms come from the server (the newest event's are kept).
  explore.setEvent = async (e) => {
    changeView((v) => {
      v.time = e.t;
      v.position = { x: e.x, y: e.y, z: e.z };
    });
    try {
      const mine = observerOf((await inputAt(e)).uniforms, e);
      if (observerAt(mine, sight.view.position)) sight.observer = mine;
    } catch (err) {
      // No frame is traced from this event: the next one asks again.
      status(`cannot move the observer: ${messageOf(err)}`);
    }
  };
  changeView(() => {});
  requestAnimationFrame(tick);
  return true;
}
