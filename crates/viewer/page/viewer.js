// godel view: builds the controls from /api/info, sends the settings (JSON) to the server
// on every change and draws the RGBA picture it answers; shows a pixel's record on hover.
// Slider events are coalesced: at most one picture request is in flight, and when it comes
// back only the newest settings are sent (stale intermediate positions are dropped).
'use strict';

const viewer = {
  info: null,
  settings: null,
  frames: 0,        // pictures drawn
  roundTrips: [],   // ms from the first unserved change to its picture on screen
  serverTimings: [], // Server-Timing of each picture: {shade, encode}
  record: null,     // the last pixel record shown
  error: null,      // the last error message shown
  busy: false,      // a picture request is in flight
};
window.godelViewer = viewer;

const $ = (id) => document.getElementById(id);

function showError(message) {
  viewer.error = message;
  $('error').textContent = message;
  $('error').hidden = false;
}

function clearError() {
  viewer.error = null;
  $('error').hidden = true;
}

// Error answers are {"error": "..."}; anything else is shown as text.
async function errorText(response) {
  const text = await response.text();
  try {
    return JSON.parse(text).error || text;
  } catch (_) {
    return `${response.status} ${response.statusText}: ${text}`;
  }
}

// ---- settings paths: ['objects', 'ball', 'temperature'] → settings.objects.ball.temperature
// (arrays of keys, since object names may contain dots)

function getPath(object, path) {
  return path.reduce((o, key) => (o == null ? undefined : o[key]), object);
}

function setPath(object, path, value) {
  const parent = getPath(object, path.slice(0, -1));
  parent[path[path.length - 1]] = value;
}

// ---- the controls: one description per control, built from the file's info.
// Kinds: 'range' and 'select' set a value; 'check' a boolean; 'layer' adds or removes a
// shader in settings.shaders; 'texture' picks a texture choice (an object with a kind).

const LAYERS = ['texture', 'frequency', 'time', 'light'];

// A texture choice of each kind, as the shade crate reads it.
const TEXTURES = {
  scene: { kind: 'scene' },
  checker: { kind: 'checker', rows: 8, cols: 16 },
  gradient: { kind: 'gradient' },
  uniform: { kind: 'uniform', color: [0.8, 0.8, 0.8] },
  earth: { kind: 'earth' },
};

function describeControls(info) {
  const d = info.defaults;
  const tMax = Math.max(d.time.travel_max, 1);
  const groups = [{
    title: 'Shader layers (multiplied)',
    controls: LAYERS.map((layer) => ({
      id: `layer-${layer}`, label: layer, kind: 'layer', layer,
      disabled: layer === 'light' && info.lights === 0,
    })),
  }, {
    title: 'Frequency',
    controls: [
      { id: 'brightness', label: 'brightness', path: ['brightness'], kind: 'select',
        options: ['normalized', 'physical'] },
      { id: 'exposure', label: 'exposure', path: ['exposure'], kind: 'range',
        min: 0, max: 4, step: 0.01 },
      { id: 'reference-squares', label: 'reference squares', path: ['reference_squares'],
        kind: 'check' },
    ],
  }, {
    title: 'Picture',
    controls: [
      { id: 'grid', label: 'orientation marks', path: ['grid'], kind: 'check' },
      { id: 'ev', label: 'exposure (stops)', path: ['ev'], kind: 'range',
        min: -4, max: 4, step: 0.1 },
    ],
  }, {
    title: 'Time',
    controls: [
      { id: 'time-mode', label: 'mode', path: ['time', 'mode'], kind: 'select',
        options: ['window', 'travel'] },
      { id: 'time-t0', label: 'window start t0', path: ['time', 't0'], kind: 'range',
        min: -Math.ceil(tMax * 1.1), max: 0, step: 0.01 },
      { id: 'time-dt', label: 'window length Δt', path: ['time', 'dt'], kind: 'range',
        min: 0.01, max: Math.ceil(tMax), step: 0.01 },
      { id: 'time-legend', label: 'legend', path: ['time', 'legend'], kind: 'check' },
    ],
  }];
  if (info.lights > 0) {
    const controls = [{ id: 'light-ambient', label: 'ambient', path: ['light', 'ambient'],
      kind: 'range', min: 0, max: 1, step: 0.01 }];
    for (let k = 0; k < info.lights; k += 1) {
      controls.push(
        { id: `light-${k}-on`, label: `light ${k} on`, path: ['light', 'sources', k, 'on'],
          kind: 'check' },
        { id: `light-${k}-intensity`, label: `light ${k} intensity`,
          path: ['light', 'sources', k, 'intensity'], kind: 'range', min: 0, max: 5, step: 0.01 },
      );
    }
    groups.push({ title: 'Light', controls });
  }
  info.objects.forEach((name, k) => {
    const path = (field) => ['objects', name, field];
    groups.push({
      title: `Object ${name}`,
      controls: [
        { id: `texture-${k}`, label: 'texture', path: path('texture'), kind: 'texture' },
        { id: `window-texture-${k}`, label: 'texture in window', path: path('window_texture'),
          kind: 'texture' },
        { id: `offset-u-${k}`, label: 'u offset', path: path('offset_u'), kind: 'range',
          min: -1, max: 1, step: 0.001 },
        { id: `offset-v-${k}`, label: 'v offset', path: path('offset_v'), kind: 'range',
          min: -1, max: 1, step: 0.001 },
        { id: `rotation-${k}`, label: 'rotation (°)', path: path('rotation_deg'), kind: 'range',
          min: -180, max: 180, step: 0.5 },
        { id: `temperature-${k}`, label: 'temperature (K)', path: path('temperature'),
          kind: 'range', min: 1000, max: 20000, step: 10 },
      ],
    });
  });
  return groups;
}

function inputFor(c) {
  let input;
  if (c.kind === 'select' || c.kind === 'texture') {
    input = document.createElement('select');
    const options = c.kind === 'texture' ? Object.keys(TEXTURES) : c.options;
    for (const option of options) input.append(new Option(option, option));
    const current = getPath(viewer.settings, c.path);
    if (c.kind === 'texture' && !(current.kind in TEXTURES)) {
      // A choice the page cannot make (an image file) stays selectable as it is.
      TEXTURES[current.kind] = current;
      input.append(new Option(current.kind, current.kind));
    }
    input.value = c.kind === 'texture' ? current.kind : current;
  } else if (c.kind === 'check' || c.kind === 'layer') {
    input = document.createElement('input');
    input.type = 'checkbox';
    input.checked = c.kind === 'layer'
      ? viewer.settings.shaders.includes(c.layer)
      : getPath(viewer.settings, c.path);
  } else {
    input = document.createElement('input');
    input.type = c.kind;
    for (const key of ['min', 'max', 'step']) input[key] = c[key];
    input.value = getPath(viewer.settings, c.path);
  }
  input.id = c.id;
  input.disabled = Boolean(c.disabled);
  return input;
}

// Reads a control into the settings.
function apply(c, input) {
  if (c.kind === 'layer') {
    const on = new Set(viewer.settings.shaders);
    if (input.checked) on.add(c.layer); else on.delete(c.layer);
    viewer.settings.shaders = LAYERS.filter((layer) => on.has(layer));
  } else if (c.kind === 'check') {
    setPath(viewer.settings, c.path, input.checked);
  } else if (c.kind === 'texture') {
    setPath(viewer.settings, c.path, structuredClone(TEXTURES[input.value]));
  } else if (c.kind === 'select') {
    setPath(viewer.settings, c.path, input.value);
  } else {
    setPath(viewer.settings, c.path, Number(input.value));
  }
}

function buildControls(groups) {
  const form = $('controls');
  form.textContent = '';
  for (const group of groups) {
    const title = document.createElement('div');
    title.className = 'group';
    title.textContent = group.title;
    form.append(title);
    for (const c of group.controls) {
      const label = document.createElement('label');
      label.htmlFor = c.id;
      label.textContent = c.label;
      const input = inputFor(c);
      const output = document.createElement('output');
      output.htmlFor = c.id;
      output.value = c.kind === 'range' ? input.value : '';
      input.addEventListener(c.kind === 'range' ? 'input' : 'change', () => {
        apply(c, input);
        if (c.kind === 'range') output.value = input.value;
        changed();
      });
      form.append(label, input, output);
    }
  }
}

// ---- the picture: coalesced requests

let dirtySince = null;   // time of the first change not yet sent
let frameQueued = false; // a requestAnimationFrame callback is pending

function changed() {
  if (dirtySince === null) dirtySince = performance.now();
  if (!frameQueued) {
    frameQueued = true;
    requestAnimationFrame(sendNewest);
  }
}

async function sendNewest() {
  frameQueued = false;
  if (viewer.busy || dirtySince === null) return; // the answer in flight sends again
  const since = dirtySince;
  dirtySince = null;
  await requestPicture(JSON.stringify(viewer.settings), since);
  if (dirtySince !== null) changed();
}

// Sends `body` (settings JSON) and draws the answer; errors are shown on the page.
async function requestPicture(body, since) {
  viewer.busy = true;
  try {
    const response = await fetch('/api/image', { method: 'POST', body,
      headers: { 'Content-Type': 'application/json' } });
    if (!response.ok) {
      showError(await errorText(response));
      return false;
    }
    const width = Number(response.headers.get('X-Image-Width'));
    const height = Number(response.headers.get('X-Image-Height'));
    const bytes = new Uint8ClampedArray(await response.arrayBuffer());
    const canvas = $('image');
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    canvas.getContext('2d').putImageData(new ImageData(bytes, width, height), 0, 0);
    const elapsed = performance.now() - since;
    viewer.frames += 1;
    viewer.roundTrips.push(elapsed);
    const timing = parseServerTiming(response.headers.get('Server-Timing'));
    viewer.serverTimings.push(timing);
    $('status').textContent = `${width}×${height} · shaded in ${timing.shade.toFixed(1)} ms`
      + ` · on screen after ${elapsed.toFixed(0)} ms`;
    clearError();
    return true;
  } catch (e) {
    showError(`cannot reach the viewer's server: ${e}`);
    return false;
  } finally {
    viewer.busy = false;
  }
}

function parseServerTiming(header) {
  const out = { shade: NaN, encode: NaN };
  for (const part of (header || '').split(',')) {
    const m = part.trim().match(/^(\w+);dur=([\d.]+)/);
    if (m) out[m[1]] = Number(m[2]);
  }
  return out;
}

// No picture request in flight or waiting (for tests and scripts).
viewer.idle = () => !viewer.busy && dirtySince === null && !frameQueued;

// Sends `text` as the settings, as the page does: for checking how errors show.
viewer.sendRaw = (text) => requestPicture(text, performance.now());

// ---- hover: the pixel's record

let hoverWanted = null; // [col, row] under the mouse
let hoverBusy = false;
let hoverShown = null;

function pixelUnder(event) {
  const canvas = $('image');
  const rect = canvas.getBoundingClientRect();
  const col = Math.floor((event.clientX - rect.left) / rect.width * canvas.width);
  const row = Math.floor((event.clientY - rect.top) / rect.height * canvas.height);
  if (col < 0 || row < 0 || col >= canvas.width || row >= canvas.height) return null;
  return [col, row];
}

async function fetchHover() {
  if (hoverBusy || hoverWanted === null) return;
  const [col, row] = hoverWanted;
  if (hoverShown && hoverShown[0] === col && hoverShown[1] === row) return;
  hoverBusy = true;
  try {
    const response = await fetch(`/api/pixel?col=${col}&row=${row}`);
    if (!response.ok) {
      showError(await errorText(response));
      return;
    }
    showRecord(await response.json());
    hoverShown = [col, row];
  } catch (e) {
    showError(`cannot reach the viewer's server: ${e}`);
  } finally {
    hoverBusy = false;
  }
  fetchHover(); // the mouse may have moved meanwhile
}

const number = (x, digits) => (x === null || x === undefined ? '–' : Number(x).toFixed(digits));

function showRecord(r) {
  viewer.record = r;
  const fields = {
    pixel: `${r.col}, ${r.row}`,
    object: r.object_name === null ? 'none' : r.object_name,
    status: r.status,
    u: number(r.u, 4),
    v: number(r.v, 4),
    g: number(r.g, 4),
    t_emit: number(r.t_emit, 4),
    travel_time: number(r.travel_time, 4),
    lights: r.lights.length ? r.lights.map((x) => number(x, 3)).join(', ') : '–',
    direction: r.azimuth_deg === null || r.azimuth_deg === undefined ? '–'
      : `az ${number(r.azimuth_deg, 1)}°, el ${number(r.elevation_deg, 1)}°`,
  };
  const hit = r.object >= 0;
  for (const [field, text] of Object.entries(fields)) {
    const keep = ['pixel', 'object', 'status', 'direction'].includes(field) || hit;
    document.querySelector(`#record [data-field="${field}"]`).textContent = keep ? text : '–';
  }
}

// ---- saving

async function download(url, fallbackName) {
  const response = await fetch(url, { method: 'POST', body: JSON.stringify(viewer.settings),
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
  const blob = await download('/api/keyframe', 'keyframe.toml');
  if (blob) {
    $('keyframe').textContent = await blob.text();
    $('keyframe').hidden = false;
  }
}

// ---- start

// As wide as the page, but at most 60% of the window high, keeping the aspect ratio.
function fitCanvas() {
  const canvas = $('image');
  const byHeight = window.innerHeight * 0.6 * canvas.width / canvas.height;
  canvas.style.width = `${Math.min($('picture').clientWidth, byHeight)}px`;
}

async function start() {
  try {
    const response = await fetch('/api/info');
    if (!response.ok) throw new Error(await errorText(response));
    viewer.info = await response.json();
  } catch (e) {
    showError(`cannot load the data file's description: ${e.message || e}`);
    return;
  }
  viewer.settings = structuredClone(viewer.info.defaults);
  $('file').textContent = `${viewer.info.file} · ${viewer.info.scene_name} · `
    + `${viewer.info.width}×${viewer.info.height}`;
  const canvas = $('image');
  canvas.width = viewer.info.width;
  canvas.height = viewer.info.height;
  buildControls(describeControls(viewer.info));
  fitCanvas();
  window.addEventListener('resize', fitCanvas);
  canvas.addEventListener('mousemove', (event) => {
    hoverWanted = pixelUnder(event);
    fetchHover();
  });
  $('save-png').addEventListener('click', () => download('/api/png', 'view.png'));
  $('save-keyframe').addEventListener('click', saveKeyframe);
  changed();
}

start();
