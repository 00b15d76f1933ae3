// @ts-check
// godel view: the page. Fetches the data file's description and, once, the arrays the GPU
// shades from (data.js); every control change, drag or wheel step redraws in the next
// animation frame without asking the server (gl.js, shaders.js). The server still answers
// hover records (/api/pixel) and makes the saved PNG and keyframe. For a full-sphere data
// file the page looks around (look.js): any projection, turn, zoom and observer velocity.
'use strict';

import { HttpError, errorText, getJson, messageOf, postJson } from './api.js';
import { describeControls, buildControls } from './controls.js';
import { Data, channelsFor } from './data.js';
import { $, query } from './dom.js';
import { startExplore } from './explore.js';
import { Gpu } from './gl.js';
import * as L from './look.js';
import { startStereo } from './stereo.js';
import { startTraced } from './traced.js';
import { uniformsFor, featuresFor, objectTable, imagesFor, overlayKey, OBJECT_TEXELS }
  from './uniforms.js';

/** @typedef {import('./contract').Info} Info */
/** @typedef {import('./contract').ViewInfo} ViewInfo */
/** @typedef {import('./contract').LookView} LookView */
/** @typedef {import('./contract').ShadeSettings} ShadeSettings */
/** @typedef {import('./uniforms.js').Picture} Picture */

/**
 * The page (window.godelViewer): what it shows, its counters, and what the other modules and
 * the tests and scripts call. The file's description, view and settings are null until loaded
 * (LoadedViewer: after start), and explore mode, the GPU-traced frame and *Render exactly*
 * add their own state (absent otherwise).
 * @typedef {object} Viewer
 * @property {Info | null} info /api/info
 * @property {ViewInfo | null} view /api/view
 * @property {ShadeSettings | null} settings
 * @property {L.Look | null} look the look-around state, for a full-sphere file
 * @property {number} frames pictures drawn on the canvas
 * @property {number} shadings shading passes run
 * @property {number[]} frameTimes the animation frames (document.timeline's time) of the last
 *   pictures drawn (at most 600)
 * @property {number | null} firstPicture ms from navigation start to the first picture
 * @property {{ described?: number, tables?: number, channels?: number }} timeline ms from
 *   navigation start (first load)
 * @property {import('./contract').PixelRecord | import('./hovered.js').SampleRecord | null} record
 *   the last pixel record shown
 * @property {string | null} error the last error message shown
 * @property {number} aspect the picture's width / height for the layout (explore: the full
 *   frames', so that coarse frames keep their place)
 * @property {number} lookShare the share of the window's height a look-around view takes
 *   (explore: less, so that the map below stays in view)
 * @property {import('./explore.js').Explore} [explore]
 * @property {import('./traced.js').TracedState} [traced]
 * @property {import('./keep.js').KeepState} [keep]
 * @property {import('./stereo.js').StereoState} [stereo] the Stereo panel (stereo.js)
 * @property {() => boolean} idle
 * @property {() => { width: number, height: number, bytes: string }} readPicture
 * @property {() => { width: number, height: number, bytes: string }} readCanvas
 * @property {(bytes: Uint8Array) => string} base64
 * @property {(w: number | null, h?: number) => void} setViewSize
 * @property {() => string} saveBody
 * @property {() => string} frameQuery
 * @property {(text: string) => Promise<boolean>} sendRaw
 * @property {() => void} changed
 * @property {() => void} finish
 * @property {() => [string, number, number][]} fetched
 * @property {() => Gpu} gpu
 * @property {(event: { clientX: number, clientY: number }) => [number, number] | null} pixelAt
 * @property {(url: string, body: string, fallbackName: string) => Promise<Blob | null>} download
 * @property {() => void} layout
 * @property {() => number} zoom
 * @property {(frame: import('./contract').FrameInfo,
 *   channelUrls: import('./data.js').ChannelUrls, movingSize?: [number, number] | null)
 *   => boolean} showFrame
 * @property {(name: string, write: (inPicture: boolean) => void) => void} withPicture
 * @property {(on: boolean) => void} hold
 * @property {(channels: import('./trace.js').Channels, note: string,
 *   size?: { width: number, height: number, supersample: number } | null,
 *   movingSize?: [number, number] | null) => void} showTracedFrame
 * @property {(note: string) => void} noteFrames
 * @property {() => void} showFileFrame
 */

/**
 * The page once the file's description is loaded (start).
 * @typedef {Viewer & { info: Info, view: ViewInfo, settings: ShadeSettings }} LoadedViewer
 */

/** @type {Viewer} */
const viewer = {
  info: null,
  view: null,
  settings: null,
  look: null,
  frames: 0,
  shadings: 0,
  frameTimes: [],
  firstPicture: null,
  timeline: {},
  record: null,
  error: null,
  aspect: 1,
  lookShare: 0.6,
  // What the other modules, tests and scripts call: the functions below.
  idle,
  readPicture,
  readCanvas,
  base64,
  setViewSize,
  saveBody,
  frameQuery,
  sendRaw,
  changed: () => { syncControls(); changed(); },
  finish: () => gpuOf().finish(),
  fetched: () => dataOf().fetched,
  gpu: gpuOf,
  pixelAt,
  download,
  layout: () => layout(),
  zoom: () => (lookMode() ? 1 : pan.zoom),
  showFrame,
  withPicture,
  hold,
  showTracedFrame,
  noteFrames,
  showFileFrame,
};
window.godelViewer = viewer;

/** @type {Gpu | null} */
let gpu = null;
/** @type {Data | null} */
let data = null;

// The page's loaded parts, for what runs only once start has made them.
function gpuOf() {
  if (!gpu) throw new Error('the page has no WebGL2 context yet');
  return gpu;
}
function dataOf() {
  if (!data) throw new Error('the data file\u2019s tables are not loaded yet');
  return data;
}
/** @returns {LoadedViewer} */
function loaded() {
  if (!isLoaded(viewer)) throw new Error('the data file\u2019s description is not loaded yet');
  return viewer;
}
/**
 * @param {Viewer} v
 * @returns {v is LoadedViewer}
 */
function isLoaded(v) {
  return v.info !== null && v.view !== null && v.settings !== null;
}

/** @param {string} message */
function showError(message) {
  viewer.error = message;
  $('error').textContent = message;
  $('error').hidden = false;
}

function clearError() {
  viewer.error = null;
  $('error').hidden = true;
}

// ---- what is on the canvas: the picture's size, and where it lies

// Writes the header line about the file (set at start; its size follows explore frames).
let describe = () => {};
// Where the frame shown comes from, when not from the data file (e.g. "traced on the GPU in
// 812 ms"): the header says it.
let frameNote = '';
// The Stereo panel's refresh after a change of the settings (stereo.js; start sets it).
let stereoChanged = () => {};
// Explore: whether the frame last given to showFrame has been shaded (or failed to load).
let frameDrawn = true;
// Explore: what the page writes about a frame whose channels are still being fetched (its
// header line, the observer's event and place on the map: fly.js), by name, the newest of each
// kept; written in the animation frame that draws its picture (`wordsWithPicture`), so that
// the browser composites the page once a picture, not once for the words and again for it.
/** @type {Map<string, (inPicture: boolean) => void>} */
const wordsDue = new Map();
/** @type {[number, number] | null} canvas pixels set by a script, else the layout decides */
let fixedSize = null;
// Explore: while a moving frame of a flight is shown, the size of the flight's full frame
// (the canvas holds at most that many pixels: layout), else null.
/** @type {[number, number] | null} */
let moving = null;
/** @type {{ zoom: number, offset: [number, number], fitted: boolean }} */
const pan = { zoom: 1, offset: [0, 0], fitted: true };
// The canvas point of the last pointer move while the button is down.
/** @type {[number, number] | null} */
let dragging = null;

function lookMode() {
  return viewer.look !== null;
}

// The look and the file's own view it turns, in look mode; else null.
function looking() {
  const look = viewer.look;
  const file = viewer.view?.view;
  return look && file ? { look, file } : null;
}

// The picture the shading pass makes: {width, height, look} (look: view and sphere, or null).
/** @returns {Picture} */
function picture() {
  const canvas = $('image', HTMLCanvasElement);
  const { info, view: fileView } = loaded();
  const l = looking();
  if (!l) return { width: info.width, height: info.height, look: null };
  // The velocity's direction follows its preset (the view's centre turns with the view).
  l.look.direction = L.presetDirection(l.look.preset, l.look, l.file,
    fileView.object_directions);
  const view = L.lookView(l.look, l.file, canvas.width, canvas.height);
  // While the mouse turns the view, one sample per pixel from the nearest sphere pixel (the
  // frame rate); once it lets go, the chosen samples, read smoothly as `godel look` reads.
  if (dragging) view.samples = 1;
  return { width: view.camera.width, height: view.camera.height,
    look: { view, sphere: sphere(), smooth: !dragging } };
}

/** @returns {L.Sphere} */
function sphere() {
  const { info, view } = loaded();
  const v = view.view;
  if (!v) throw new Error('the data file has no view to look around in');
  return { width: info.width, height: info.height, forward: v.forward, up: v.up };
}

function fit() {
  const canvas = $('image', HTMLCanvasElement);
  const { info } = loaded();
  pan.zoom = Math.min(canvas.width / info.width, canvas.height / info.height);
  pan.offset = [(canvas.width - info.width * pan.zoom) / 2,
    (canvas.height - info.height * pan.zoom) / 2];
  pan.fitted = true;
}

function layout() {
  const canvas = $('image', HTMLCanvasElement);
  const room = $('picture').clientWidth;
  const dpr = window.devicePixelRatio || 1;
  let css;
  if (fixedSize) {
    css = [fixedSize[0] / dpr, fixedSize[1] / dpr];
  } else if (lookMode()) {
    css = [room, Math.round(Math.min(window.innerHeight * viewer.lookShare, room / 2))];
  } else {
    const aspect = viewer.aspect;
    const w = Math.min(room, window.innerHeight * 0.6 * aspect);
    css = [w, w / aspect];
  }
  const sameBox = canvas.style.width === `${css[0]}px` && canvas.style.height === `${css[1]}px`;
  canvas.style.width = `${css[0]}px`;
  canvas.style.height = `${css[1]}px`;
  let w = Math.max(1, Math.round(css[0] * dpr));
  let h = Math.max(1, Math.round(css[1] * dpr));
  // Flying, fitted, with a full frame smaller than the box: the canvas holds the full frame's
  // pixels (the box's shape kept; the same size all flight long, as a new size costs a new
  // buffer) and the browser scales them to the box. On a software renderer drawing the box's
  // pixels took a quarter of each frame's time.
  if (moving && pan.fitted && !fixedSize && !lookMode()) {
    const s = Math.max(moving[0] / w, moving[1] / h);
    if (s < 1) [w, h] = [Math.max(1, Math.round(w * s)), Math.max(1, Math.round(h * s))];
  }
  if (canvas.width !== w || canvas.height !== h) {
    // The same box with other canvas pixels (flying, above): a zoomed or panned picture
    // keeps its place in the box.
    if (sameBox && !pan.fitted) {
      const k = w / canvas.width;
      pan.zoom *= k;
      pan.offset = [pan.offset[0] * k, pan.offset[1] * k];
    }
    canvas.width = w;
    canvas.height = h;
    shadeDirty = true;
  }
  if (!lookMode() && pan.fitted) fit();
  changed(false);
}

// ---- drawing: coalesced into animation frames

let frameQueued = false;
let shadeDirty = true;   // the picture must be shaded again (else only displayed)
/** @type {number | null} the frame (data.js epoch) whose channels or images are being fetched */
let loading = null;
// Whether the frame shown is still loading: a load for a frame replaced meanwhile (a frame
// traced in the page, fly.js) holds nothing up, and its channels are dropped (data.js).
const loadingNow = () => loading !== null && data !== null && loading === data.epoch;
let held = false;        // the page traces a frame on the GPU (traced.js): nothing is drawn

// The overlay layer (orientation marks, legend, labels), drawn by the server for the
// settings (crates/shade/src/layer.rs) and composited by the shading pass: the key it was
// made for (overlayKey), its size, whether it draws anything; the one wanted next, whether
// one is being fetched, whether the last answer was for a frame replaced meanwhile.
/**
 * @type {{ key: string | null, size: [number, number] | null, drawn: boolean,
 *   wanted: { key: string, url: string, body: string } | null, busy: boolean,
 *   stale: boolean }}
 */
const overlay = { key: null, size: null, drawn: false, wanted: null, busy: false, stale: false };

function overlayPending() {
  return overlay.busy || (overlay.wanted !== null && overlay.wanted.key !== overlay.key);
}

// Fetches the wanted overlay (one request at a time; the latest wish wins), then redraws.
async function fetchOverlay() {
  const want = overlay.wanted;
  if (overlay.busy || want === null || want.key === overlay.key) return;
  overlay.busy = true;
  try {
    const response = await postJson(want.url, want.body);
    if (response.status === 410) {
      // Explore: that frame was replaced meanwhile; asked again when the next one shows.
      overlay.drawn = false;
      overlay.stale = true;
    } else if (!response.ok) {
      showError(await errorText(response));
      overlay.drawn = false;
    } else if (response.status === 204) {
      overlay.drawn = false;
    } else {
      const bitmap = await createImageBitmap(await response.blob(),
        { premultiplyAlpha: 'none', colorSpaceConversion: 'none' });
      gpuOf().uploadBitmap('overlay', bitmap);
      overlay.size = [bitmap.width, bitmap.height];
      bitmap.close();
      overlay.drawn = true;
    }
  } catch (e) {
    showError(`cannot load the overlay from the viewer's server: ${messageOf(e)}`);
    overlay.drawn = false;
  } finally {
    overlay.key = want.key;
    overlay.busy = false;
  }
  changed();
}

// Writes `write` (named `name`) with the picture of the frame given to showFrame, or now when
// that picture is drawn already; `write(true)`: in the picture's animation frame.
/**
 * @param {string} name
 * @param {(inPicture: boolean) => void} write
 */
function withPicture(name, write) {
  if (frameDrawn) {
    write(false);
  } else {
    wordsDue.set(name, write);
  }
}
function wordsWithPicture() {
  const due = [...wordsDue.values()];
  wordsDue.clear();
  due.forEach((write) => write(true));
}

// A change: `shade` false when only the display (zoom, pan) changed.
function changed(shade = true) {
  if (shade) {
    shadeDirty = true;
    stereoChanged();
  }
  if (!frameQueued) {
    frameQueued = true;
    requestAnimationFrame(draw);
  }
}

async function draw() {
  frameQueued = false;
  if (loadingNow() || held || !gpu || !data) return;
  const { info, settings } = loaded();
  let need;
  let images;
  try {
    need = channelsFor(settings, info, lookMode());
    images = imagesFor(settings, info, data);
  } catch (e) {
    showError(messageOf(e));
    return;
  }
  const d = data;
  if (d.missing(need).length || images.some((n) => !d.images.has(n))) {
    const epoch = d.epoch;
    loading = epoch;
    // (Explore's next frame: the picture shown meanwhile is the last one, no word needed.)
    if (!(viewer.explore && viewer.frames > 0)) {
      $('status').textContent = 'loading the data file\u2019s channels…';
    }
    try {
      await d.ensure(need);
      await d.ensureImages(images);
    } catch (e) {
      // Nothing more to wait for: the next frame may come (unless another frame came meanwhile).
      if (d.epoch === epoch) frameDrawn = true;
      wordsWithPicture();
      // Explore: the frame was superseded while its channels loaded (410 Gone, or replaced by
      // a frame traced in the page); the newer frame comes, and no error flashes up meanwhile.
      const gone = e instanceof HttpError && e.status === 410;
      if (!(viewer.explore && (gone || d.epoch !== epoch))) {
        showError(`cannot load the data for the GPU: ${messageOf(e)}`);
      }
      return;
    } finally {
      if (loading === epoch) loading = null;
    }
    if (!viewer.timeline.channels) viewer.timeline.channels = performance.now();
    changed();
    return;
  }
  const p = picture();
  try {
    if (shadeDirty) {
      const uniforms = uniformsFor(settings, info, d, p.width, p.height, p.look);
      const key = overlayKey(settings, info, p);
      if (key === null) {
        overlay.wanted = null;
      } else if (key !== overlay.key) {
        /** @type {import('./contract').LookRequest | ShadeSettings} */
        const body = p.look ? { settings, view: p.look.view } : settings;
        overlay.wanted = { key,
          url: (p.look ? '/api/look/overlay' : '/api/overlay') + frameQuery(),
          body: JSON.stringify(body) };
        fetchOverlay();
      }
      // Until the new layer comes, the last one of the same size stays (no flicker).
      const shown = key !== null && overlay.drawn && overlay.size !== null
        && overlay.size[0] === p.width && overlay.size[1] === p.height;
      uniforms.uOverlayOn = ['i', shown ? 1 : 0];
      const table = objectTable(settings, info, d);
      gpu.uploadFloatRgba('objects', OBJECT_TEXELS, table.length / (4 * OBJECT_TEXELS), table);
      gpu.shade(p.width, p.height, featuresFor(settings, info, d, p.look, uniforms),
        uniforms);
      viewer.shadings += 1;
      frameDrawn = true;
      shadeDirty = false;
    }
    const canvas = $('image', HTMLCanvasElement);
    if (lookMode()) {
      gpu.display([Math.floor((canvas.width - p.width) / 2),
        Math.floor((canvas.height - p.height) / 2)], 1);
    } else {
      gpu.display(pan.offset, pan.zoom);
    }
  } catch (e) {
    frameDrawn = true;
    wordsWithPicture();
    showError(messageOf(e));
    return;
  }
  wordsWithPicture();
  if (viewer.firstPicture === null) {
    gpu.finish(); // the first picture counts when it is on the canvas, not when asked for
    viewer.firstPicture = performance.now();
  }
  const now = performance.now();
  viewer.frames += 1;
  // (the animation frame's time: the same for all that is drawn in it, the map's too)
  viewer.frameTimes.push(Number(document.timeline.currentTime ?? now));
  if (viewer.frameTimes.length > 600) viewer.frameTimes.shift();
  const recent = viewer.frameTimes.filter((t) => t > now - 1000).length;
  $('status').textContent = `${p.width}×${p.height} shaded on the GPU · ${recent} frames/s`;
  clearError();
}

// Nothing waiting to be drawn or fetched (for tests and scripts).
function idle() {
  return !frameQueued && !loadingNow() && !held && !shadeDirty && !overlayPending();
}

// ---- the mouse: drag to turn (look) or pan, wheel to zoom, hover for the record

/**
 * @param {{ clientX: number, clientY: number }} event
 * @returns {[number, number]}
 */
function canvasPoint(event) {
  const canvas = $('image', HTMLCanvasElement);
  const rect = canvas.getBoundingClientRect();
  return [(event.clientX - rect.left) * canvas.width / rect.width,
    (event.clientY - rect.top) * canvas.height / rect.height];
}

// The picture pixel under canvas point c, or null.
/**
 * @param {[number, number]} c
 * @returns {[number, number] | null}
 */
function picturePixel(c) {
  const canvas = $('image', HTMLCanvasElement);
  const p = picture();
  const [ox, oy, zoom] = lookMode()
    ? [Math.floor((canvas.width - p.width) / 2), Math.floor((canvas.height - p.height) / 2), 1]
    : [pan.offset[0], pan.offset[1], pan.zoom];
  const col = Math.floor((c[0] - ox) / zoom);
  const row = Math.floor((c[1] - oy) / zoom);
  if (col < 0 || row < 0 || col >= p.width || row >= p.height) return null;
  return [col, row];
}

/**
 * @param {PointerEvent} event
 * @param {[number, number]} from
 */
function onDrag(event, from) {
  const c = canvasPoint(event);
  const [dx, dy] = [c[0] - from[0], c[1] - from[1]];
  dragging = c;
  const look = viewer.look;
  if (look) {
    const deg = L.radiansPerPixel(look, picture().width) * 180 / Math.PI;
    look.yaw = ((look.yaw - dx * deg + 540) % 360) - 180;
    look.pitch = Math.min(90, Math.max(-90, look.pitch + dy * deg));
    syncControls();
    changed();
  } else {
    pan.offset = [pan.offset[0] + dx, pan.offset[1] + dy];
    pan.fitted = false;
    changed(false);
  }
}

/** @param {WheelEvent} event */
function onWheel(event) {
  event.preventDefault();
  const factor = Math.exp(event.deltaY * 0.001);
  const look = viewer.look;
  if (look) {
    const range = L.PROJECTIONS[look.projection];
    look.fov = Math.min(range.max, Math.max(range.min, look.fov * factor));
    syncControls();
    changed();
  } else {
    const c = canvasPoint(event);
    const zoom = Math.min(64, Math.max(0.05, pan.zoom / factor));
    pan.offset = [c[0] - (c[0] - pan.offset[0]) * zoom / pan.zoom,
      c[1] - (c[1] - pan.offset[1]) * zoom / pan.zoom];
    pan.zoom = zoom;
    pan.fitted = false;
    changed(false);
  }
}

let syncControls = () => {};

// ---- hover: the record of the data pixel under the mouse, and where it looks

/**
 * The hover wanted: the data file's pixel [col, row], and what the page adds to its record.
 * @typedef {{ pixel: [number, number], view?: [number, number], doppler: number,
 *   direction: string, staticDirection: string }} HoverWish
 */
/** @type {HoverWish | null} */
let hoverWanted = null;
let hoverBusy = false;
/** @type {(HoverWish & { frame: unknown }) | null} */
let hoverShown = null;

/** @param {PointerEvent} event */
function hoverAt(event) {
  const q = picturePixel(canvasPoint(event));
  if (!q) return;
  /** @param {L.Vec3} n */
  const deg = (n) => L.azimuthElevation(n).map((x) => x.toFixed(2)).join('°, ') + '°';
  const shownLook = picture().look;
  if (viewer.look && shownLook) {
    const at = L.lookPixel(shownLook.view, sphere(), q[0], q[1]);
    if (!at) return;
    hoverWanted = { pixel: at.source, view: q, doppler: at.doppler, direction: deg(at.own),
      staticDirection: viewer.look.speed > 0 ? deg(at.static) : '–' };
  } else {
    const v = loaded().view.view;
    const d = v && L.cameraDirection(v.camera, q[0], q[1]);
    hoverWanted = { pixel: q, doppler: 1, direction: d && v ? deg(L.toLocal(d, v.forward, v.up))
      : '–', staticDirection: '–' };
  }
  fetchHover();
}

async function fetchHover() {
  if (hoverBusy || hoverWanted === null) return;
  // Flying (fly.js): the record is read from the frame the page traced, no server call.
  const flying = viewer.explore?.hoverRecord;
  // In explore mode, the record of the frame on the GPU (not of a newer one still loading).
  const frame = flying ? viewer.explore?.hoverFrame?.() : viewer.explore?.shown ?? null;
  const wanted = { ...hoverWanted, frame };
  if (hoverShown && JSON.stringify(hoverShown) === JSON.stringify(wanted)) return;
  hoverBusy = true;
  try {
    const [col, row] = wanted.pixel;
    let record;
    if (flying) {
      record = await flying(col, row);
      if (record === null) return; // outside the frame shown
    } else {
      const which = frame && typeof frame === 'object'
        ? `&generation=${frame.generation}&level=${frame.level}` : '';
      const response = await fetch(`/api/pixel?col=${col}&row=${row}${which}`);
      if (response.status === 410) return; // that frame was replaced meanwhile: hover again
      if (!response.ok) {
        showError(await errorText(response));
        return;
      }
      record = /** @type {import('./contract').PixelRecord} */ (await response.json());
    }
    showRecord(record, wanted);
    hoverShown = wanted;
  } catch (e) {
    showError(flying ? `cannot read the hovered record: ${messageOf(e)}`
      : `cannot reach the viewer's server: ${e}`);
  } finally {
    hoverBusy = false;
  }
  fetchHover(); // the mouse may have moved meanwhile
}

/**
 * @param {number | null | undefined} x
 * @param {number} digits
 */
const number = (x, digits) => (x === null || x === undefined ? '–' : Number(x).toFixed(digits));

/**
 * @param {import('./hovered.js').SampleRecord & { col: number, row: number }} r
 * @param {HoverWish} at
 */
function showRecord(r, at) {
  viewer.record = r;
  const hit = r.object >= 0;
  const g = hit ? Math.fround(Number(r.g) * at.doppler) : r.g;
  const fields = {
    pixel: at.view ? `${r.col}, ${r.row} (view ${at.view[0]}, ${at.view[1]})` : `${r.col}, ${r.row}`,
    object: r.object_name === null ? 'none' : r.object_name,
    status: r.status,
    u: number(r.u, 4),
    v: number(r.v, 4),
    g: number(g, 4),
    t_emit: number(r.t_emit, 4),
    travel_time: number(r.travel_time, 4),
    lights: r.lights.length ? r.lights.map((x) => number(x, 3)).join(', ') : '–',
    direction: at.direction,
    static_direction: at.staticDirection,
    doppler: number(at.doppler, 4),
  };
  const always = ['pixel', 'object', 'status', 'direction', 'static_direction', 'doppler'];
  for (const [field, text] of Object.entries(fields)) {
    const keep = always.includes(field) || hit;
    query(`#record [data-field="${field}"]`).textContent = keep ? text : '–';
  }
}

// ---- saving: the server shades the PNG (look + shade for a turned or boosted view)

// Explore mode: the frame on screen, named in the requests the server answers for it
// (crates/viewer/src/explore_routes.rs: saved pictures, overlays); '' otherwise.
function frameQuery() {
  const f = viewer.explore?.shown;
  return f ? `?generation=${f.generation}&level=${f.level}` : '';
}

// The settings and view the server would shade for "Save PNG".
function saveBody() {
  const { settings } = loaded();
  const look = picture().look;
  if (!lookMode() || !look) return JSON.stringify(settings);
  /** @type {import('./contract').LookRequest} */
  const body = { settings, view: look.view };
  return JSON.stringify(body);
}

// POSTs `body` to `url` and downloads the answer, named as the server says (else
// `fallbackName`); null, the error shown, when refused.
/**
 * @param {string} url
 * @param {string} body
 * @param {string} fallbackName
 */
async function download(url, body, fallbackName) {
  const response = await postJson(url, body);
  if (!response.ok) {
    showError(await errorText(response));
    return null;
  }
  const disposition = response.headers.get('Content-Disposition') || '';
  const name = (disposition.match(/filename="([^"]+)"/) || [])[1] || fallbackName;
  const blob = await response.blob();
  const link = document.createElement('a');
  link.href = URL.createObjectURL(blob);
  link.download = name;
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(link.href), 10000);
  return blob;
}

async function saveKeyframe() {
  const blob = await download('/api/keyframe', JSON.stringify(loaded().settings),
    'keyframe.toml');
  if (blob) {
    $('keyframe').textContent = await blob.text();
    $('keyframe').hidden = false;
  }
}

// ---- for tests and scripts

/** @param {Uint8Array} bytes */
function base64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 8192) s += String.fromCharCode(...bytes.subarray(i, i + 8192));
  return btoa(s);
}
// The shaded picture (RGBA, top row first), and the canvas as shown.
function readPicture() {
  const p = gpuOf().readShaded();
  return { ...p, bytes: base64(p.bytes) };
}
function readCanvas() {
  const p = gpuOf().readCanvas();
  return { ...p, bytes: base64(p.bytes) };
}
// Fixes the canvas at w × h pixels (null: back to the layout).
/**
 * @param {number | null} w
 * @param {number} [h]
 */
function setViewSize(w, h) {
  fixedSize = w ? [w, Number(h)] : null;
  layout();
}
// Sends `text` to the server as settings, as the page did before it shaded on the GPU: for
// checking that the server's messages show.
/** @param {string} text */
async function sendRaw(text) {
  const response = await postJson('/api/image', text);
  if (!response.ok) showError(await errorText(response));
  return response.ok;
}
// The data pixel [col, row] under a pointer event's clientX, clientY (looking around: the
// sphere's pixel seen there), or null (explore.js).
/** @param {{ clientX: number, clientY: number }} event */
function pixelAt(event) {
  const q = picturePixel(canvasPoint(event));
  const look = picture().look;
  if (!q || !lookMode() || !look) return q;
  const at = L.lookPixel(look.view, sphere(), q[0], q[1]);
  return at ? at.source : null;
}

// ---- start

async function start() {
  try {
    [viewer.info, viewer.view] = /** @type {[Info, ViewInfo]} */ (await Promise.all([
      getJson('/api/info'), getJson('/api/view')]));
  } catch (e) {
    showError(`cannot load the data file's description: ${messageOf(e)}`);
    return;
  }
  const info = viewer.info;
  viewer.timeline.described = performance.now();
  viewer.aspect = info.width / info.height;
  viewer.settings = structuredClone(info.defaults);
  if (!isLoaded(viewer)) return;
  const page = viewer;
  // A sampled sphere is shown as a picture: `godel look` refuses it, and so does the page.
  const camera = page.view.view?.camera;
  const sampledSphere = info.supersample > 1 && camera && (camera.kind === 'sphere'
    || (camera.kind === 'panorama' && camera.h_fov_deg === 360 && camera.v_fov_deg === 180));
  describe = () => {
    $('file').textContent = `${info.file} · ${info.scene_name} · ${info.width}×${info.height}`
      + (info.supersample > 1 ? ` · ${info.supersample}×${info.supersample} rays per pixel` : '')
      + (page.view.sphere ? ' · full sphere: drag to look around' : '')
      + (sampledSphere ? ` · no looking around: ${page.view.sphere_error}` : '')
      + (frameNote ? ` · ${frameNote}` : '');
  };
  describe();
  try {
    gpu = new Gpu($('image', HTMLCanvasElement));
    data = await Data.load(gpu, info);
    viewer.timeline.tables = performance.now();
  } catch (e) {
    showError(messageOf(e));
    return;
  }
  if (page.view.sphere && page.view.view) viewer.look = L.newLook(page.view.view);
  const targets = { settings: page.settings, look: viewer.look };
  syncControls = buildControls(describeControls(info, page.view), targets, (target) => {
    if (target === 'look') lookChanged();
    changed();
  });
  const canvas = $('image', HTMLCanvasElement);
  canvas.addEventListener('pointerdown', (event) => {
    dragging = canvasPoint(event);
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (dragging) onDrag(event, dragging);
    hoverAt(event);
  });
  canvas.addEventListener('pointerup', () => {
    dragging = null;
    if (lookMode()) changed();
  });
  canvas.addEventListener('wheel', onWheel, { passive: false });
  canvas.addEventListener('dblclick', () => { if (!lookMode()) { fit(); changed(false); } });
  window.addEventListener('resize', layout);
  $('save-png').addEventListener('click', () => download(
    (lookMode() ? '/api/look/png' : '/api/png') + frameQuery(), saveBody(), 'view.png'));
  $('save-keyframe').addEventListener('click', saveKeyframe);
  layout();
  await startExplore(page);
  startTraced(page);
  stereoChanged = startStereo(page, showError);
}

// Explore (explore.js): shows another frame, whose channels are at `channelUrls(names)`; false
// (try again later) while the last one is not drawn yet, so that every frame taken is seen.
// `movingSize`: a moving frame of the flight (fly.js), whose full frame has that size.
/**
 * @param {import('./contract').FrameInfo} frame
 * @param {import('./data.js').ChannelUrls} channelUrls
 * @param {[number, number] | null} [movingSize]
 */
function showFrame(frame, channelUrls, movingSize = null) {
  if (loadingNow() || !data || !frameDrawn) return false;
  const { info } = loaded();
  frameDrawn = false;
  moving = movingSize;
  // A zoomed or panned picture keeps its place on the canvas at the new size.
  if (!pan.fitted) pan.zoom *= info.width / frame.width;
  Object.assign(info, { width: frame.width, height: frame.height,
    supersample: frame.supersample });
  // The camera is the same but for its size (coarse or full): hover directions follow.
  const camera = viewer.view?.view?.camera;
  if (camera) Object.assign(camera, { width: frame.width, height: frame.height });
  withPicture('describe', () => describe());
  if (overlay.stale) {
    overlay.key = null;
    overlay.stale = false;
  }
  data.reset(channelUrls);
  layout();
  changed();
  return true;
}

// The frame traced on the GPU (traced.js): while `on`, nothing is drawn; then `channels`
// (textures named as the data file's channels, gl.js) replace the file's, and `note` says so
// in the header, until showFileFrame fetches the file's channels again.
/** @param {boolean} on */
function hold(on) {
  held = on;
  if (!on) changed();
}
// `size` ({width, height, supersample}, explore's flight: fly.js): the traced frame's, where
// it is not the file's; `movingSize`: a moving frame of the flight, whose full frame has that
// size.
/**
 * @param {import('./trace.js').Channels} channels
 * @param {string} note
 * @param {{ width: number, height: number, supersample: number } | null} [size]
 * @param {[number, number] | null} [movingSize]
 */
function showTracedFrame(channels, note, size = null, movingSize = null) {
  const { info } = loaded();
  // A new size, or a flight's moving frames begun or ended: the canvas is laid out again.
  const relayout = size !== null || moving?.[0] !== movingSize?.[0]
    || moving?.[1] !== movingSize?.[1];
  moving = movingSize;
  if (size) {
    if (!pan.fitted) pan.zoom *= info.width / size.width;
    Object.assign(info, size);
    const camera = viewer.view?.view?.camera;
    if (camera) Object.assign(camera, { width: size.width, height: size.height });
  }
  if (relayout) layout();
  for (const [name, texture] of Object.entries(channels)) {
    if (texture) gpuOf().replace(name, texture);
  }
  const names = ['id', 'u', 'v', 'g', 't_emit', 'cos_i', 'pol', 'dir'];
  for (let k = 0; k < info.lights; k += 1) names.push(`light_${k}`);
  dataOf().provide(names);
  frameNote = note;
  describe();
  changed();
}
// Explore's frames from the server after the page's tracer was refused (explore.js): `note`
// stays in the header for every frame shown.
/** @param {string} note */
function noteFrames(note) {
  withPicture('describe', () => {
    frameNote = note;
    describe();
  });
}
function showFileFrame() {
  if (!frameNote) return;
  const d = dataOf();
  d.reset(d.channelUrls);
  frameNote = '';
  describe();
  changed();
}

// After a look control: the preset's direction, the projection's field of view.
/** @type {L.Projection} the projection whose field of view the look has */
let lookProjection = 'pinhole';
function lookChanged() {
  const look = viewer.look;
  if (!look) return;
  const range = L.PROJECTIONS[look.projection];
  if (look.projection !== lookProjection) {
    look.fov = range.fov;
    lookProjection = look.projection;
  }
  look.fov = Math.min(range.max, Math.max(range.min, look.fov));
  syncControls();
}

start();
