// godel view: the page. Fetches the data file's description and, once, the arrays the GPU
// shades from (data.js); every control change, drag or wheel step redraws in the next
// animation frame without asking the server (gl.js, shaders.js). The server still answers
// hover records (/api/pixel) and makes the saved PNG and keyframe. For a full-sphere data
// file the page looks around (look.js): any projection, turn, zoom and observer velocity.
'use strict';

import { Gpu } from './gl.js';
import { Data, channelsFor, fetchJson } from './data.js';
import { describeControls, buildControls } from './controls.js';
import { uniformsFor, featuresFor, objectTable, imagesFor, overlayKey, OBJECT_TEXELS }
  from './uniforms.js';
import * as L from './look.js';
import { startExplore } from './explore.js';
import { startTraced } from './traced.js';

const viewer = {
  info: null,      // /api/info
  view: null,      // /api/view
  settings: null,  // ShadeSettings
  look: null,      // the look-around state, for a full-sphere file
  frames: 0,       // pictures drawn on the canvas
  shadings: 0,     // shading passes run
  frameTimes: [],  // performance.now() of the last frames drawn (at most 600)
  firstPicture: null, // ms from navigation start to the first picture on the canvas
  timeline: {},    // ms from navigation start: described, tables, channels (first load)
  record: null,    // the last pixel record shown
  error: null,     // the last error message shown
  aspect: null,    // the picture's width / height for the layout (explore: the full frames',
                   // so that coarse frames keep their place)
  lookShare: 0.6,  // the share of the window's height a look-around view takes (explore: less,
                   // so that the map below stays in view)
};
window.godelViewer = viewer;

const $ = (id) => document.getElementById(id);
let gpu = null;
let data = null;

function showError(message) {
  viewer.error = message;
  $('error').textContent = message;
  $('error').hidden = false;
}

function clearError() {
  viewer.error = null;
  $('error').hidden = true;
}

async function errorText(response) {
  const text = await response.text();
  try {
    return JSON.parse(text).error || text;
  } catch (_) {
    return `${response.status} ${response.statusText}: ${text}`;
  }
}

// ---- what is on the canvas: the picture's size, and where it lies

// Writes the header line about the file (set at start; its size follows explore frames).
let describe = () => {};
// Where the frame shown comes from, when not from the data file (e.g. "traced on the GPU in
// 812 ms"): the header says it.
let frameNote = '';
// Explore: whether the frame last given to showFrame has been shaded (or failed to load).
let frameDrawn = true;
let fixedSize = null;      // [w, h] canvas pixels set by a script, else the layout decides
const pan = { zoom: 1, offset: [0, 0], fitted: true };
let dragging = null;       // the canvas point of the last pointer move while the button is down

function lookMode() {
  return viewer.look !== null;
}

// The picture the shading pass makes: {width, height, look} (look: view and sphere, or null).
function picture() {
  const canvas = $('image');
  if (!lookMode()) return { width: viewer.info.width, height: viewer.info.height, look: null };
  // The velocity's direction follows its preset (the view's centre turns with the view).
  viewer.look.direction = L.presetDirection(viewer.look.preset, viewer.look, viewer.view.view,
    viewer.view.object_directions);
  const view = L.lookView(viewer.look, viewer.view.view, canvas.width, canvas.height);
  // While the mouse turns the view, one sample per pixel from the nearest sphere pixel (the
  // frame rate); once it lets go, the chosen samples, read smoothly as `godel look` reads.
  if (dragging) view.samples = 1;
  return { width: view.camera.width, height: view.camera.height,
    look: { view, sphere: sphere(), smooth: !dragging } };
}

function sphere() {
  const v = viewer.view.view;
  return { width: viewer.info.width, height: viewer.info.height, forward: v.forward, up: v.up };
}

function fit() {
  const canvas = $('image');
  pan.zoom = Math.min(canvas.width / viewer.info.width, canvas.height / viewer.info.height);
  pan.offset = [(canvas.width - viewer.info.width * pan.zoom) / 2,
    (canvas.height - viewer.info.height * pan.zoom) / 2];
  pan.fitted = true;
}

function layout() {
  const canvas = $('image');
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
  canvas.style.width = `${css[0]}px`;
  canvas.style.height = `${css[1]}px`;
  const w = Math.max(1, Math.round(css[0] * dpr));
  const h = Math.max(1, Math.round(css[1] * dpr));
  if (canvas.width !== w || canvas.height !== h) {
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
let loading = null;      // the frame (data.js epoch) whose channels or images are being fetched
// Whether the frame shown is still loading: a load for a frame replaced meanwhile (a frame
// traced in the page, fly.js) holds nothing up, and its channels are dropped (data.js).
const loadingNow = () => loading !== null && data !== null && loading === data.epoch;
let held = false;        // the page traces a frame on the GPU (traced.js): nothing is drawn

// The overlay layer (orientation marks, legend, labels), drawn by the server for the
// settings (crates/shade/src/layer.rs) and composited by the shading pass: the key it was
// made for (overlayKey), its size, whether it draws anything; the one wanted next.
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
    const response = await fetch(want.url, { method: 'POST', body: want.body,
      headers: { 'Content-Type': 'application/json' } });
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
      gpu.uploadBitmap('overlay', bitmap);
      overlay.size = [bitmap.width, bitmap.height];
      bitmap.close();
      overlay.drawn = true;
    }
  } catch (e) {
    showError(`cannot load the overlay from the viewer's server: ${e.message || e}`);
    overlay.drawn = false;
  } finally {
    overlay.key = want.key;
    overlay.busy = false;
  }
  changed();
}

// A change: `shade` false when only the display (zoom, pan) changed.
function changed(shade = true) {
  if (shade) shadeDirty = true;
  if (!frameQueued) {
    frameQueued = true;
    requestAnimationFrame(draw);
  }
}

async function draw() {
  frameQueued = false;
  if (loadingNow() || held || !gpu) return;
  const settings = viewer.settings;
  let need;
  let images;
  try {
    need = channelsFor(settings, viewer.info, lookMode());
    images = imagesFor(settings, viewer.info, data);
  } catch (e) {
    showError(e.message);
    return;
  }
  if (data.missing(need).length || images.some((n) => !data.images.has(n))) {
    const epoch = data.epoch;
    loading = epoch;
    $('status').textContent = 'loading the data file\u2019s channels…';
    try {
      await data.ensure(need);
      await data.ensureImages(images);
    } catch (e) {
      // Nothing more to wait for: the next frame may come (unless another frame came meanwhile).
      if (data.epoch === epoch) frameDrawn = true;
      // Explore: the frame was superseded while its channels loaded (410 Gone, or replaced by
      // a frame traced in the page); the newer frame comes, and no error flashes up meanwhile.
      if (!(viewer.explore && (e.status === 410 || data.epoch !== epoch))) {
        showError(`cannot load the data for the GPU: ${e.message}`);
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
      const uniforms = uniformsFor(settings, viewer.info, data, p.width, p.height, p.look);
      const key = overlayKey(settings, viewer.info, p);
      if (key === null) {
        overlay.wanted = null;
      } else if (key !== overlay.key) {
        overlay.wanted = { key,
          url: (p.look ? '/api/look/overlay' : '/api/overlay') + frameQuery(),
          body: p.look ? JSON.stringify({ settings, view: p.look.view })
            : JSON.stringify(settings) };
        fetchOverlay();
      }
      // Until the new layer comes, the last one of the same size stays (no flicker).
      const shown = key !== null && overlay.drawn && overlay.size !== null
        && overlay.size[0] === p.width && overlay.size[1] === p.height;
      uniforms.uOverlayOn = ['i', shown ? 1 : 0];
      const table = objectTable(settings, viewer.info, data);
      gpu.uploadFloatRgba('objects', OBJECT_TEXELS, table.length / (4 * OBJECT_TEXELS), table);
      gpu.shade(p.width, p.height, featuresFor(settings, viewer.info, data, p.look, uniforms),
        uniforms);
      viewer.shadings += 1;
      frameDrawn = true;
      shadeDirty = false;
    }
    const canvas = $('image');
    if (lookMode()) {
      gpu.display([Math.floor((canvas.width - p.width) / 2),
        Math.floor((canvas.height - p.height) / 2)], 1);
    } else {
      gpu.display(pan.offset, pan.zoom);
    }
  } catch (e) {
    frameDrawn = true;
    showError(e.message);
    return;
  }
  if (viewer.firstPicture === null) {
    gpu.finish(); // the first picture counts when it is on the canvas, not when asked for
    viewer.firstPicture = performance.now();
  }
  const now = performance.now();
  viewer.frames += 1;
  viewer.frameTimes.push(now);
  if (viewer.frameTimes.length > 600) viewer.frameTimes.shift();
  const recent = viewer.frameTimes.filter((t) => t > now - 1000).length;
  $('status').textContent = `${p.width}×${p.height} shaded on the GPU · ${recent} frames/s`;
  clearError();
}

// Nothing waiting to be drawn or fetched (for tests and scripts).
viewer.idle = () => !frameQueued && !loadingNow() && !held && !shadeDirty && !overlayPending();

// ---- the mouse: drag to turn (look) or pan, wheel to zoom, hover for the record

function canvasPoint(event) {
  const canvas = $('image');
  const rect = canvas.getBoundingClientRect();
  return [(event.clientX - rect.left) * canvas.width / rect.width,
    (event.clientY - rect.top) * canvas.height / rect.height];
}

// The picture pixel under canvas point c, or null.
function picturePixel(c) {
  const canvas = $('image');
  const p = picture();
  const [ox, oy, zoom] = lookMode()
    ? [Math.floor((canvas.width - p.width) / 2), Math.floor((canvas.height - p.height) / 2), 1]
    : [pan.offset[0], pan.offset[1], pan.zoom];
  const col = Math.floor((c[0] - ox) / zoom);
  const row = Math.floor((c[1] - oy) / zoom);
  if (col < 0 || row < 0 || col >= p.width || row >= p.height) return null;
  return [col, row];
}

function onDrag(event) {
  const c = canvasPoint(event);
  const [dx, dy] = [c[0] - dragging[0], c[1] - dragging[1]];
  dragging = c;
  if (lookMode()) {
    const deg = L.radiansPerPixel(viewer.look, picture().width) * 180 / Math.PI;
    const look = viewer.look;
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

function onWheel(event) {
  event.preventDefault();
  const factor = Math.exp(event.deltaY * 0.001);
  if (lookMode()) {
    const look = viewer.look;
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

let hoverWanted = null; // {pixel: [col, row] of the data file, ...what the page adds}
let hoverBusy = false;
let hoverShown = null;

function hoverAt(event) {
  const q = picturePixel(canvasPoint(event));
  if (!q) return;
  const deg = (n) => L.azimuthElevation(n).map((x) => x.toFixed(2)).join('°, ') + '°';
  if (lookMode()) {
    const at = L.lookPixel(picture().look.view, sphere(), q[0], q[1]);
    if (!at) return;
    hoverWanted = { pixel: at.source, view: q, doppler: at.doppler, direction: deg(at.own),
      staticDirection: viewer.look.speed > 0 ? deg(at.static) : '–' };
  } else {
    const v = viewer.view.view;
    const d = v && L.cameraDirection(v.camera, q[0], q[1]);
    hoverWanted = { pixel: q, doppler: 1, direction: d ? deg(L.toLocal(d, v.forward, v.up)) : '–',
      staticDirection: '–' };
  }
  fetchHover();
}

async function fetchHover() {
  if (hoverBusy || hoverWanted === null) return;
  // Flying (fly.js): the record is read from the frame the page traced, no server call.
  const flying = viewer.explore?.hoverRecord;
  // In explore mode, the record of the frame on the GPU (not of a newer one still loading).
  const frame = flying ? viewer.explore.hoverFrame() : viewer.explore?.shown ?? null;
  const wanted = { ...hoverWanted, frame };
  if (hoverShown && JSON.stringify(hoverShown) === JSON.stringify(wanted)) return;
  hoverBusy = true;
  try {
    const [col, row] = wanted.pixel;
    let record;
    if (flying) {
      record = await viewer.explore.hoverRecord(col, row);
      if (record === null) return; // outside the frame shown
    } else {
      const which = frame ? `&generation=${frame.generation}&level=${frame.level}` : '';
      const response = await fetch(`/api/pixel?col=${col}&row=${row}${which}`);
      if (response.status === 410) return; // that frame was replaced meanwhile: hover again
      if (!response.ok) {
        showError(await errorText(response));
        return;
      }
      record = await response.json();
    }
    showRecord(record, wanted);
    hoverShown = wanted;
  } catch (e) {
    showError(flying ? `cannot read the hovered record: ${e.message || e}`
      : `cannot reach the viewer's server: ${e}`);
  } finally {
    hoverBusy = false;
  }
  fetchHover(); // the mouse may have moved meanwhile
}

const number = (x, digits) => (x === null || x === undefined ? '–' : Number(x).toFixed(digits));

function showRecord(r, at) {
  viewer.record = r;
  const hit = r.object >= 0;
  const g = hit ? Math.fround(r.g * at.doppler) : r.g;
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
    document.querySelector(`#record [data-field="${field}"]`).textContent = keep ? text : '–';
  }
}

// ---- saving: the server shades the PNG (look + shade for a turned or boosted view)

// Explore mode: the frame on screen, named in the requests the server answers for it
// (crates/viewer/src/explore_routes.rs: saved pictures, overlays); '' otherwise.
function frameQuery() {
  const f = viewer.explore?.shown;
  return f ? `?generation=${f.generation}&level=${f.level}` : '';
}

function saveBody() {
  if (!lookMode()) return JSON.stringify(viewer.settings);
  return JSON.stringify({ settings: viewer.settings, view: picture().look.view });
}

async function download(url, body, fallbackName) {
  const response = await fetch(url, { method: 'POST', body,
    headers: { 'Content-Type': 'application/json' } });
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
  const blob = await download('/api/keyframe', JSON.stringify(viewer.settings), 'keyframe.toml');
  if (blob) {
    $('keyframe').textContent = await blob.text();
    $('keyframe').hidden = false;
  }
}

// ---- for tests and scripts

const base64 = (bytes) => {
  let s = '';
  for (let i = 0; i < bytes.length; i += 8192) s += String.fromCharCode(...bytes.subarray(i, i + 8192));
  return btoa(s);
};
// The shaded picture (RGBA, top row first), and the canvas as shown.
viewer.readPicture = () => { const p = gpu.readShaded(); return { ...p, bytes: base64(p.bytes) }; };
viewer.readCanvas = () => { const p = gpu.readCanvas(); return { ...p, bytes: base64(p.bytes) }; };
viewer.base64 = base64;
// Fixes the canvas at w × h pixels (null: back to the layout).
viewer.setViewSize = (w, h) => { fixedSize = w ? [w, h] : null; layout(); };
// The settings and view the server would shade for "Save PNG", and the query naming the
// frame on screen (explore mode).
viewer.saveBody = saveBody;
viewer.frameQuery = frameQuery;
// Sends `text` to the server as settings, as the page did before it shaded on the GPU: for
// checking that the server's messages show.
viewer.sendRaw = async (text) => {
  const response = await fetch('/api/image', { method: 'POST', body: text,
    headers: { 'Content-Type': 'application/json' } });
  if (!response.ok) showError(await errorText(response));
  return response.ok;
};
viewer.changed = () => { syncControls(); changed(); };
// Waits for the GPU (benchmarks: a frame counts when drawn, not when asked for).
viewer.finish = () => gpu.finish();
// What the page fetched: [url, bytes, ms] per array.
viewer.fetched = () => data.fetched;
// The WebGL side, for profiling from the console.
viewer.gpu = () => gpu;
// The data pixel [col, row] under a pointer event's clientX, clientY (looking around: the
// sphere's pixel seen there), or null (explore.js).
viewer.pixelAt = (event) => {
  const q = picturePixel(canvasPoint(event));
  if (!q || !lookMode()) return q;
  const at = L.lookPixel(picture().look.view, sphere(), q[0], q[1]);
  return at ? at.source : null;
};
// POSTs `body` to `url` and downloads the answer (explore.js's keyframe).
viewer.download = download;
// Lays the page out again (explore.js, after setting `aspect`).
viewer.layout = () => layout();
// Canvas pixels per picture pixel (1 when looking around).
viewer.zoom = () => (lookMode() ? 1 : pan.zoom);

// ---- start

async function start() {
  try {
    [viewer.info, viewer.view] = await Promise.all([fetchJson('/api/info'),
      fetchJson('/api/view')]);
  } catch (e) {
    showError(`cannot load the data file's description: ${e.message || e}`);
    return;
  }
  const info = viewer.info;
  viewer.timeline.described = performance.now();
  viewer.aspect = info.width / info.height;
  viewer.settings = structuredClone(info.defaults);
  // A sampled sphere is shown as a picture: `godel look` refuses it, and so does the page.
  const camera = viewer.view.view?.camera;
  const sampledSphere = info.supersample > 1 && camera && (camera.kind === 'sphere'
    || (camera.kind === 'panorama' && camera.h_fov_deg === 360 && camera.v_fov_deg === 180));
  describe = () => {
    $('file').textContent = `${info.file} · ${info.scene_name} · ${info.width}×${info.height}`
      + (info.supersample > 1 ? ` · ${info.supersample}×${info.supersample} rays per pixel` : '')
      + (viewer.view.sphere ? ' · full sphere: drag to look around' : '')
      + (sampledSphere ? ` · no looking around: ${viewer.view.sphere_error}` : '')
      + (frameNote ? ` · ${frameNote}` : '');
  };
  describe();
  try {
    gpu = new Gpu($('image'));
    data = new Data(gpu, info);
    await data.start();
    viewer.timeline.tables = performance.now();
  } catch (e) {
    showError(e.message);
    return;
  }
  if (viewer.view.sphere) viewer.look = L.newLook(viewer.view.view);
  const targets = { settings: viewer.settings, look: viewer.look };
  syncControls = buildControls(describeControls(info, viewer.view), targets, (target) => {
    if (target === 'look') lookChanged();
    changed();
  });
  const canvas = $('image');
  canvas.addEventListener('pointerdown', (event) => {
    dragging = canvasPoint(event);
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (dragging) onDrag(event);
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
  await startExplore(viewer);
  startTraced(viewer);
}

// Explore mode (explore.js): shade a newly traced frame, of `frame.width` × `frame.height`
// pictures, whose channels come from `channelUrl(name)`; false (try later) while loading.
// Explore (explore.js): shows another frame, whose channels are at `channelUrl(name)`; false
// (try again later) while the last one is not drawn yet, so that every frame taken is seen.
viewer.showFrame = (frame, channelUrl) => {
  if (loadingNow() || !data || !frameDrawn) return false;
  frameDrawn = false;
  // A zoomed or panned picture keeps its place on the canvas at the new size.
  if (!pan.fitted) pan.zoom *= viewer.info.width / frame.width;
  Object.assign(viewer.info, { width: frame.width, height: frame.height,
    supersample: frame.supersample });
  // The camera is the same but for its size (coarse or full): hover directions follow.
  const camera = viewer.view?.view?.camera;
  if (camera) Object.assign(camera, { width: frame.width, height: frame.height });
  describe();
  if (overlay.stale) {
    overlay.key = null;
    overlay.stale = false;
  }
  data.reset(channelUrl);
  layout();
  changed();
  return true;
};

// The frame traced on the GPU (traced.js): while `on`, nothing is drawn; then `channels`
// (textures named as the data file's channels, gl.js) replace the file's, and `note` says so
// in the header, until showFileFrame fetches the file's channels again.
viewer.hold = (on) => {
  held = on;
  if (!on) changed();
};
// `size` ({width, height, supersample}, explore's flight: fly.js): the traced frame's, where
// it is not the file's.
viewer.showTracedFrame = (channels, note, size = null) => {
  if (size) {
    if (!pan.fitted) pan.zoom *= viewer.info.width / size.width;
    Object.assign(viewer.info, size);
    const camera = viewer.view?.view?.camera;
    if (camera) Object.assign(camera, { width: size.width, height: size.height });
    layout();
  }
  for (const [name, texture] of Object.entries(channels)) {
    if (texture) gpu.replace(name, texture);
  }
  const names = ['id', 'u', 'v', 'g', 't_emit', 'cos_i', 'pol', 'dir'];
  for (let k = 0; k < viewer.info.lights; k += 1) names.push(`light_${k}`);
  data.provide(names);
  frameNote = note;
  describe();
  changed();
};
// Explore's frames from the server after the page's tracer was refused (explore.js): `note`
// stays in the header for every frame shown.
viewer.noteFrames = (note) => {
  frameNote = note;
  describe();
};
viewer.showFileFrame = () => {
  if (!frameNote) return;
  data.reset(data.channelUrl);
  frameNote = '';
  describe();
  changed();
};

// After a look control: the preset's direction, the projection's field of view.
function lookChanged() {
  const look = viewer.look;
  const range = L.PROJECTIONS[look.projection];
  if (look.projection !== lookChanged.projection) {
    look.fov = range.fov;
    lookChanged.projection = look.projection;
  }
  look.fov = Math.min(range.max, Math.max(range.min, look.fov));
  syncControls();
}
lookChanged.projection = 'pinhole';

start();
