// godel view: the controls, built from the file's info. Each control is described once
// (kind, path into its target object, range) and reads its input into the target on change:
// the settings (the `shade` crate's ShadeSettings) or, for a full-sphere file, the look.
// Kinds: 'range' and 'select' set a value; 'check' a boolean; 'layer' adds or removes a
// shader in settings.shaders; 'texture' picks a texture choice (an object with a kind);
// 'polarized' and 'axis' (a range: the azimuth or elevation of the axis) set an object's
// polarization axis (a unit vector in its body axes, or null: unpolarized).
'use strict';

import { PROJECTIONS, SAMPLES } from './look.js';

const $ = (id) => document.getElementById(id);

export const LAYERS = ['texture', 'frequency', 'time', 'light', 'polarization'];

// ---- polarization axes: azimuth (x towards y) and elevation (towards z), degrees

export function axisAngles(axis) {
  const [x, y, z] = axis;
  const deg = 180 / Math.PI;
  return [Math.atan2(y, x) * deg, Math.atan2(z, Math.hypot(x, y)) * deg];
}

export function axisFrom([azimuth, elevation]) {
  const rad = Math.PI / 180;
  const c = Math.cos(elevation * rad);
  return [c * Math.cos(azimuth * rad), c * Math.sin(azimuth * rad), Math.sin(elevation * rad)];
}

// The last axis each object had, so that switching its polarization off and on keeps it.
const lastAxis = new Map();
const DEFAULT_AXIS = [1, 0, 0];
const axisOf = (target, c) => getPath(target, c.path) || lastAxis.get(c.axis) || DEFAULT_AXIS;
const axisValue = (target, c) => Math.round(axisAngles(axisOf(target, c))[c.part] / c.step) * c.step;

// A texture choice of each kind, as the shade crate reads it.
const TEXTURES = {
  scene: { kind: 'scene' },
  checker: { kind: 'checker', rows: 8, cols: 16 },
  gradient: { kind: 'gradient' },
  uniform: { kind: 'uniform', color: [0.8, 0.8, 0.8] },
  earth: { kind: 'earth' },
};

// ---- settings paths: ['objects', 'ball', 'temperature'] → settings.objects.ball.temperature
// (arrays of keys, since object names may contain dots)

function getPath(object, path) {
  return path.reduce((o, key) => (o == null ? undefined : o[key]), object);
}

function setPath(object, path, value) {
  const parent = getPath(object, path.slice(0, -1));
  parent[path[path.length - 1]] = value;
}

export function describeControls(info, view) {
  const d = info.defaults;
  const tMax = Math.max(d.time.travel_max, 1);
  const groups = [];
  if (view && view.sphere) {
    const presets = [['forward', 'the view\u2019s centre']];
    info.objects.forEach((name, k) => {
      if (view.object_directions[k]) presets.push([`object:${k}`, `towards ${name}`]);
    });
    for (const axis of ['+x', '-x', '+y', '-y', '+z', '-z']) presets.push([axis, `along ${axis}`]);
    groups.push({
      title: 'Look around (drag to turn, wheel to zoom)',
      target: 'look',
      controls: [
        { id: 'projection', label: 'projection', path: ['projection'], kind: 'select',
          options: Object.keys(PROJECTIONS) },
        { id: 'fov', label: 'field of view (°)', path: ['fov'], kind: 'range', min: 5, max: 360,
          step: 1 },
        { id: 'yaw', label: 'turn right (°)', path: ['yaw'], kind: 'range', min: -180, max: 180,
          step: 0.5 },
        { id: 'pitch', label: 'turn up (°)', path: ['pitch'], kind: 'range', min: -90, max: 90,
          step: 0.5 },
        { id: 'speed', label: 'speed (c)', path: ['speed'], kind: 'range', min: 0, max: 0.99,
          step: 0.01 },
        { id: 'direction', label: 'moving', path: ['preset'], kind: 'select',
          options: presets.map((p) => p[0]), labels: presets.map((p) => p[1]) },
        { id: 'samples', label: 'samples per pixel', path: ['samples'], kind: 'select',
          options: SAMPLES },
      ],
    });
  }
  groups.push({
    title: 'Shader layers (multiplied)',
    controls: LAYERS.map((layer) => ({
      id: `layer-${layer}`, label: layer, kind: 'layer', layer,
      // Polarization: a file with the pol_* channels, shaded as it is (not looked around).
      disabled: (layer === 'light' && info.lights === 0)
        || (layer === 'polarization' && (!info.polarization || Boolean(view && view.sphere))),
    })),
  }, {
    title: 'Picture',
    controls: [
      { id: 'ev', label: 'exposure compensation (EV)', path: ['ev'], kind: 'range',
        min: -6, max: 6, step: 0.1 },
    ],
  }, {
    title: 'Overlays',
    controls: [
      { id: 'grid', label: 'orientation marks', path: ['grid'], kind: 'check' },
    ],
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
  });
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
        // The emitter's polarization axis (polarization layer): re-shaded, never re-traced.
        { id: `polarized-${k}`, label: 'light polarized', path: path('polarization'),
          kind: 'polarized', axis: `axis-${k}` },
        { id: `axis-azimuth-${k}`, label: 'polarization axis azimuth (°)',
          path: path('polarization'), kind: 'axis', part: 0, axis: `axis-${k}`, box: `polarized-${k}`,
          min: -180, max: 180, step: 0.5 },
        { id: `axis-elevation-${k}`, label: 'polarization axis elevation (°)',
          path: path('polarization'), kind: 'axis', part: 1, axis: `axis-${k}`, box: `polarized-${k}`,
          min: -90, max: 90, step: 0.5 },
      ],
    });
  });
  return groups;
}

function inputFor(c, target) {
  let input;
  if (c.kind === 'select' || c.kind === 'texture') {
    input = document.createElement('select');
    const options = c.kind === 'texture' ? Object.keys(TEXTURES) : c.options;
    options.forEach((option, i) => input.append(new Option(c.labels ? c.labels[i] : option,
      option)));
    const current = getPath(target, c.path);
    if (c.kind === 'texture' && !(current.kind in TEXTURES)) {
      // A choice the page cannot make (an image file) stays selectable as it is.
      TEXTURES[current.kind] = current;
      input.append(new Option(current.kind, current.kind));
    }
    input.value = c.kind === 'texture' ? current.kind : current;
  } else if (c.kind === 'check' || c.kind === 'layer' || c.kind === 'polarized') {
    input = document.createElement('input');
    input.type = 'checkbox';
    input.checked = c.kind === 'layer' ? target.shaders.includes(c.layer)
      : Boolean(getPath(target, c.path));
  } else if (c.kind === 'axis') {
    input = document.createElement('input');
    input.type = 'range';
    for (const key of ['min', 'max', 'step']) input[key] = c[key];
    input.value = axisValue(target, c);
  } else {
    input = document.createElement('input');
    input.type = c.kind;
    for (const key of ['min', 'max', 'step']) input[key] = c[key];
    input.value = getPath(target, c.path);
  }
  input.id = c.id;
  input.disabled = Boolean(c.disabled);
  return input;
}

// Reads a control into its target.
function apply(c, input, target) {
  if (c.kind === 'layer') {
    const on = new Set(target.shaders);
    if (input.checked) on.add(c.layer); else on.delete(c.layer);
    target.shaders = LAYERS.filter((layer) => on.has(layer));
  } else if (c.kind === 'check') {
    setPath(target, c.path, input.checked);
  } else if (c.kind === 'polarized') {
    setPath(target, c.path, input.checked ? axisOf(target, c) : null);
  } else if (c.kind === 'axis') {
    const angles = axisAngles(axisOf(target, c));
    angles[c.part] = Number(input.value);
    const axis = axisFrom(angles);
    lastAxis.set(c.axis, axis);
    setPath(target, c.path, axis);
    // Turning the axis polarizes the object's light.
    $(c.box).checked = true;
  } else if (c.kind === 'texture') {
    setPath(target, c.path, structuredClone(TEXTURES[input.value]));
  } else if (c.kind === 'select') {
    setPath(target, c.path, input.value);
  } else {
    setPath(target, c.path, Number(input.value));
  }
}

// Builds the form; `targets` maps a group's target name to its object ('settings' default);
// `changed(group target name)` runs after every change. Returns a function that writes the
// targets' current values back into the inputs (after the mouse turned the view, or a script
// changed the settings).
export function buildControls(groups, targets, changed) {
  const form = $('controls');
  form.textContent = '';
  const bound = [];
  for (const group of groups) {
    const name = group.target || 'settings';
    const title = document.createElement('div');
    title.className = 'group';
    title.textContent = group.title;
    form.append(title);
    for (const c of group.controls) {
      const label = document.createElement('label');
      label.htmlFor = c.id;
      label.textContent = c.label;
      const input = inputFor(c, targets[name]);
      const output = document.createElement('output');
      output.htmlFor = c.id;
      const ranged = c.kind === 'range' || c.kind === 'axis';
      output.value = ranged ? input.value : '';
      input.addEventListener(ranged ? 'input' : 'change', () => {
        apply(c, input, targets[name]);
        if (ranged) output.value = input.value;
        changed(name);
      });
      form.append(label, input, output);
      bound.push({ c, input, output, name });
    }
  }
  return () => {
    for (const { c, input, output, name } of bound) {
      const target = targets[name];
      if (c.kind === 'layer') {
        input.checked = target.shaders.includes(c.layer);
        continue;
      }
      const value = getPath(target, c.path);
      if (value === undefined) continue;
      if (c.kind === 'polarized') {
        input.checked = Boolean(value);
        continue;
      }
      if (c.kind === 'axis') {
        if (value) lastAxis.set(c.axis, value);
        input.value = axisValue(target, c);
        output.value = input.value;
        continue;
      }
      if (c.kind === 'check') input.checked = value;
      else if (c.kind === 'texture') input.value = value.kind in TEXTURES ? value.kind : '';
      else input.value = value;
      if (c.kind === 'range') output.value = input.value;
    }
  };
}
