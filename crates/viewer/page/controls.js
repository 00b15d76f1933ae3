// @ts-check
// godel view: the controls, built from the file's info. Each control is described once
// (kind, path into its target object, range) and reads its input into the target on change:
// the settings (the `shade` crate's ShadeSettings) or, for a full-sphere file, the look.
// Kinds: 'range' and 'select' set a value; 'check' a boolean; 'layer' adds or removes a
// shader in settings.shaders; 'texture' picks a texture choice (an object with a kind);
// 'polarized' and 'axis' (a range: the azimuth or elevation of the axis) set an object's
// polarization axis (a unit vector in its body axes, or null: unpolarized).
'use strict';

import { $ } from './dom.js';
import { PROJECTIONS, SAMPLES } from './look.js';

/** @typedef {import('./contract').Info} Info */
/** @typedef {import('./contract').ViewInfo} ViewInfo */
/** @typedef {import('./contract').Vec3} Vec3 */
/** @typedef {import('./contract').ShaderKind} ShaderKind */

/**
 * A control: its input's id and label, its kind, where it reads into its target (`path`),
 * and what its kind needs (options, range, layer, the axis it turns).
 * @typedef {object} Control
 * @property {string} id
 * @property {string} label
 * @property {'range' | 'select' | 'check' | 'layer' | 'texture' | 'polarized' | 'axis'} kind
 * @property {(string | number)[]} [path]
 * @property {string[]} [options]
 * @property {string[]} [labels]
 * @property {number} [min]
 * @property {number} [max]
 * @property {number} [step]
 * @property {ShaderKind} [layer]
 * @property {boolean} [disabled]
 * @property {string} [axis] the polarization axis an 'axis' or 'polarized' control shares
 * @property {number} [part] 0: the axis's azimuth, 1: its elevation
 * @property {string} [box] the 'polarized' checkbox an 'axis' control checks
 */

/**
 * A group of controls and the name of their target ('settings' when absent).
 * @typedef {{ title: string, target?: string, controls: Control[] }} Group
 */

/**
 * What controls read into, by name (the settings, the look): objects walked by path.
 * @typedef {Record<string, any>} Targets
 */

/** @type {ShaderKind[]} */
export const LAYERS = ['texture', 'frequency', 'time', 'light', 'polarization'];

// ---- polarization axes: azimuth (x towards y) and elevation (towards z), degrees

/**
 * @param {Vec3} axis
 * @returns {[number, number]}
 */
export function axisAngles(axis) {
  const [x, y, z] = axis;
  const deg = 180 / Math.PI;
  return [Math.atan2(y, x) * deg, Math.atan2(z, Math.hypot(x, y)) * deg];
}

/**
 * @param {[number, number]} angles
 * @returns {Vec3}
 */
export function axisFrom([azimuth, elevation]) {
  const rad = Math.PI / 180;
  const c = Math.cos(elevation * rad);
  return [c * Math.cos(azimuth * rad), c * Math.sin(azimuth * rad), Math.sin(elevation * rad)];
}

// The last axis each object had, so that switching its polarization off and on keeps it.
/** @type {Map<string | undefined, Vec3>} */
const lastAxis = new Map();
/** @type {Vec3} */
const DEFAULT_AXIS = [1, 0, 0];
/**
 * @param {any} target
 * @param {Control} c
 * @returns {Vec3}
 */
const axisOf = (target, c) => getPath(target, c.path) || lastAxis.get(c.axis) || DEFAULT_AXIS;
/**
 * @param {any} target
 * @param {Control} c
 */
const axisValue = (target, c) => {
  const step = Number(c.step);
  return Math.round(axisAngles(axisOf(target, c))[Number(c.part)] / step) * step;
};

// A texture choice of each kind, as the shade crate reads it.
/** @type {Record<string, import('./contract').TextureChoice>} */
const TEXTURES = {
  scene: { kind: 'scene' },
  checker: { kind: 'checker', rows: 8, cols: 16 },
  gradient: { kind: 'gradient' },
  uniform: { kind: 'uniform', color: [0.8, 0.8, 0.8] },
  earth: { kind: 'earth' },
};

// ---- settings paths: ['objects', 'ball', 'temperature'] → settings.objects.ball.temperature
// (arrays of keys, since object names may contain dots)

/**
 * @param {any} object
 * @param {(string | number)[] | undefined} path
 * @returns {any}
 */
function getPath(object, path = []) {
  return path.reduce((o, key) => (o == null ? undefined : o[key]), object);
}

/**
 * @param {any} object
 * @param {(string | number)[] | undefined} path
 * @param {unknown} value
 */
function setPath(object, path = [], value) {
  const parent = getPath(object, path.slice(0, -1));
  parent[path[path.length - 1]] = value;
}

/**
 * The controls of a file described by `info` and `view` (/api/info, /api/view).
 * @param {Info} info
 * @param {ViewInfo | null} view
 * @returns {Group[]}
 */
export function describeControls(info, view) {
  const d = info.defaults;
  const tMax = Math.max(d.time.travel_max, 1);
  /** @type {Group[]} */
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
    /** @type {Control[]} */
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
    /** @param {string} field */
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

/**
 * The input of control `c`, showing its value in `target`.
 * @param {Control} c
 * @param {any} target
 * @returns {HTMLInputElement | HTMLSelectElement}
 */
function inputFor(c, target) {
  /** @type {HTMLInputElement | HTMLSelectElement} */
  let input;
  if (c.kind === 'select' || c.kind === 'texture') {
    const select = document.createElement('select');
    const options = c.kind === 'texture' ? Object.keys(TEXTURES) : c.options ?? [];
    options.forEach((option, i) => select.append(new Option(c.labels ? c.labels[i] : option,
      option)));
    const current = getPath(target, c.path);
    if (c.kind === 'texture' && !(current.kind in TEXTURES)) {
      // A choice the page cannot make (an image file) stays selectable as it is.
      TEXTURES[current.kind] = current;
      select.append(new Option(current.kind, current.kind));
    }
    select.value = c.kind === 'texture' ? current.kind : current;
    input = select;
  } else if (c.kind === 'check' || c.kind === 'layer' || c.kind === 'polarized') {
    input = document.createElement('input');
    input.type = 'checkbox';
    input.checked = c.kind === 'layer' ? target.shaders.includes(c.layer)
      : Boolean(getPath(target, c.path));
  } else {
    input = rangeInput(c);
    input.value = c.kind === 'axis' ? String(axisValue(target, c)) : getPath(target, c.path);
  }
  input.id = c.id;
  input.disabled = Boolean(c.disabled);
  return input;
}

// An input of type 'range' (an axis) or the control's kind, with the control's range.
/** @param {Control} c */
function rangeInput(c) {
  const input = document.createElement('input');
  input.type = c.kind === 'axis' ? 'range' : c.kind;
  for (const key of /** @type {const} */ (['min', 'max', 'step'])) input[key] = String(c[key]);
  return input;
}

// Reads a control into its target.
/**
 * @param {Control} c
 * @param {HTMLInputElement | HTMLSelectElement} input
 * @param {any} target
 */
function apply(c, input, target) {
  const checked = input instanceof HTMLInputElement && input.checked;
  if (c.kind === 'layer') {
    const on = new Set(target.shaders);
    if (checked) on.add(c.layer); else on.delete(c.layer);
    target.shaders = LAYERS.filter((layer) => on.has(layer));
  } else if (c.kind === 'check') {
    setPath(target, c.path, checked);
  } else if (c.kind === 'polarized') {
    setPath(target, c.path, checked ? axisOf(target, c) : null);
  } else if (c.kind === 'axis') {
    const angles = axisAngles(axisOf(target, c));
    angles[Number(c.part)] = Number(input.value);
    const axis = axisFrom(angles);
    lastAxis.set(c.axis, axis);
    setPath(target, c.path, axis);
    // Turning the axis polarizes the object's light.
    $(String(c.box), HTMLInputElement).checked = true;
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
/**
 * @param {Group[]} groups
 * @param {Targets} targets
 * @param {(target: string) => void} changed
 * @returns {() => void}
 */
export function buildControls(groups, targets, changed) {
  const form = $('controls');
  form.textContent = '';
  /**
   * @type {{ c: Control, input: HTMLInputElement | HTMLSelectElement,
   *   output: HTMLOutputElement, name: string }[]}
   */
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
      /** @param {boolean} on */
      const check = (on) => { if (input instanceof HTMLInputElement) input.checked = on; };
      if (c.kind === 'layer') {
        check(target.shaders.includes(c.layer));
        continue;
      }
      const value = getPath(target, c.path);
      if (value === undefined) continue;
      if (c.kind === 'polarized') {
        check(Boolean(value));
        continue;
      }
      if (c.kind === 'axis') {
        if (value) lastAxis.set(c.axis, value);
        input.value = String(axisValue(target, c));
        output.value = input.value;
        continue;
      }
      if (c.kind === 'check') check(value);
      else if (c.kind === 'texture') input.value = value.kind in TEXTURES ? value.kind : '';
      else input.value = value;
      if (c.kind === 'range') output.value = input.value;
    }
  };
}
