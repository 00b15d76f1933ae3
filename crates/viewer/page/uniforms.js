// @ts-check
// godel view: the shading pass's inputs for given settings (the `shade` crate's
// ShadeSettings, as Shading::new prepares them) and, in look mode, a view: the uniforms, the
// per-object table, the reference squares, and what the overlay layer depends on.
'use strict';

import { referenceSquare, linearToSrgb8, toneMap, LINEAR_STOPS, windowBounds } from './overlays.js';
import { cross } from './look.js';
import { textureLayer, polarizationLayer } from './data.js';

/** @typedef {import('./contract').Info} Info */
/** @typedef {import('./contract').ShadeSettings} ShadeSettings */
/** @typedef {import('./contract').TextureChoice} TextureChoice */
/** @typedef {import('./contract').GpuTexture} GpuTexture */
/** @typedef {import('./contract').LookView} LookView */
/** @typedef {import('./data.js').Data} Data */
/** @typedef {import('./gl.js').Uniforms} Uniforms */

/**
 * A look-around picture: the view shaded, the sphere it is read from, and whether it is read
 * smoothly (bilinear; else one sample per pixel from the nearest sphere pixel, while dragging).
 * @typedef {{ view: LookView, sphere: import('./look.js').Sphere, smooth: boolean }} ShadedLook
 */

/**
 * The picture the shading pass makes: its size, and the look it shows (null: the data file's
 * own pixels).
 * @typedef {{ width: number, height: number, look: ShadedLook | null }} Picture
 */

/**
 * What a shading program is compiled for (shaders.js, shadeSource).
 * @typedef {object} Features
 * @property {boolean} texture
 * @property {boolean} time
 * @property {boolean} travel
 * @property {boolean} frequency
 * @property {boolean} light
 * @property {boolean} polarization
 * @property {boolean} look
 * @property {boolean} smooth
 * @property {number} supersample samples per pixel along each side
 * @property {number} camera 0 pinhole, 1 panorama or sphere, 2 fisheye
 * @property {boolean} images
 * @property {boolean} refs
 * @property {boolean} overlay
 */

// The texture a choice names, as (kind, a, b, c) for the shader, and the image it needs.
/**
 * @param {TextureChoice} choice
 * @param {number} k
 * @param {Data} data
 * @returns {{ texel: number[] } | { image: string }}
 */
function textureOf(choice, k, data) {
  /** @type {TextureChoice | GpuTexture} */
  let t = choice;
  if (t.kind === 'scene') t = data.sceneTextures[k];
  switch (t.kind) {
    case 'checker':
      if (!(t.rows >= 1 && t.cols >= 1)) throw new Error('checker rows and cols must be at least 1');
      return { texel: [0, t.rows, t.cols, 0] };
    case 'gradient': return { texel: [1, 0, 0, 0] };
    case 'uniform': return { texel: [2, ...t.color] };
    case 'earth': return { image: 'earth' };
    case 'image':
      if ('image' in t) return { image: t.image };
      throw new Error(`the page cannot read image files named in the settings (${t.path}); `
        + 'save the settings and use `godel shade`');
    default: throw new Error(`unknown texture kind '${/** @type {{ kind: string }} */ (t).kind}'`);
  }
}

// The images the settings' textures need (fetched before shading).
/**
 * @param {ShadeSettings} settings
 * @param {Info} info
 * @param {Data} data
 */
export function imagesFor(settings, info, data) {
  /** @type {Set<string>} */
  const names = new Set();
  info.objects.forEach((name, k) => {
    const o = settings.objects[name] || info.defaults.objects[name];
    for (const choice of [o.texture, o.window_texture]) {
      const t = textureOf(choice, k, data);
      if ('image' in t) names.add(t.image);
    }
  });
  return [...names];
}

// Texels per object in the object table.
export const OBJECT_TEXELS = 5;

// The object table: OBJECT_TEXELS RGBA32F texels per object (one row each; one row of zeros
// when the file has no objects): texture moves, first and second texture, (T, Y(T)), and the
// polarization axis (x, y, z, 1), (0, 0, 0, 0) for unpolarized light.
/**
 * @param {ShadeSettings} settings
 * @param {Info} info
 * @param {Data} data
 */
export function objectTable(settings, info, data) {
  const table = new Float32Array(Math.max(info.objects.length, 1) * 4 * OBJECT_TEXELS);
  const bb = data.blackbody;
  info.objects.forEach((name, k) => {
    const o = settings.objects[name] || info.defaults.objects[name];
    /** @param {TextureChoice} choice */
    const texel = (choice) => {
      const t = textureOf(choice, k, data);
      if (!('image' in t)) return t.texel;
      const image = data.images.get(t.image);
      if (!image) throw new Error(`the image ${t.image} is not loaded`);
      return [3, image.y0, image.width, image.height];
    };
    const axis = o.polarization;
    if (axis && !(axis.every(Number.isFinite) && axis.some((c) => c !== 0))) {
      throw new Error(`objects.${name}.polarization must be a non-zero direction`);
    }
    table.set([
      o.scale_u, o.scale_v, o.offset_u - o.rotation_deg / 360, o.offset_v,
      ...texel(o.texture), ...texel(o.window_texture),
      o.temperature, bb.luminance(o.temperature), 0, 0,
      ...(axis ? [...axis, 1] : [0, 0, 0, 0]),
    ], k * 4 * OBJECT_TEXELS);
  });
  return table;
}

/** @type {Record<import('./contract').Camera['kind'], number>} */
const CAMERAS = { pinhole: 0, panorama: 1, sphere: 1, fisheye: 2 };

// What the shading program is compiled for (shaders.js, shadeSource), given the uniforms.
/**
 * @param {ShadeSettings} settings
 * @param {Info} info
 * @param {Data} data
 * @param {ShadedLook | null} look
 * @param {Uniforms} uniforms
 * @returns {Features}
 */
export function featuresFor(settings, info, data, look, uniforms) {
  /** @param {string} name */
  const third = (name) => /** @type {number[]} */ (uniforms[name][1])[2];
  const on = new Set(settings.shaders);
  return {
    texture: textureLayer(settings),
    time: on.has('time'),
    travel: settings.time.mode === 'travel',
    frequency: on.has('frequency'),
    light: on.has('light'),
    polarization: polarizationLayer(settings, info, Boolean(look)),
    look: Boolean(look),
    smooth: Boolean(look && look.smooth),
    // Samples per pixel along each side, box-filtered by the shading pass: the file's, or
    // in a look the view's (a sampled sphere is refused as a sphere, as `godel look`
    // refuses it).
    supersample: look ? Math.round(Math.sqrt(look.view.samples)) : info.supersample,
    camera: look ? CAMERAS[look.view.camera.kind] : 0,
    images: imagesFor(settings, info, data).length > 0,
    refs: third('uRef0') > 0 || third('uRef1') > 0,
    overlay: Boolean(uniforms.uOverlayOn && uniforms.uOverlayOn[1]),
  };
}

// Uniforms for a picture of width × height; `look` is null for the data file's own pixels,
// else {view, sphere} (the `look` crate's view and the sphere's axes).
/**
 * @param {ShadeSettings} settings
 * @param {Info} info
 * @param {Data} data
 * @param {number} width
 * @param {number} height
 * @param {ShadedLook | null} look
 * @returns {Uniforms}
 */
export function uniformsFor(settings, info, data, width, height, look) {
  const on = new Set(settings.shaders);
  const bb = data.blackbody;
  const physical = settings.brightness === 'physical';
  const time = settings.time;
  const [winLo, winHi] = windowBounds(time.t0, time.dt);
  const nodes = bb.unit.length;
  // 2^ev in f32, as Shading::new computes it (2f64.powf(ev) as f32).
  const gain = Math.fround(2 ** settings.ev);
  const sources = settings.light.sources;
  /** @type {number[][]} */
  const lightW = [];
  for (let k = 0; k < info.lights; k += 1) {
    const s = sources[k];
    lightW.push(!s ? [1, 1, 1] : s.on ? s.color.map((c) => Math.fround(c) * Math.fround(s.intensity))
      : [0, 0, 0]);
  }
  if (lightW.length > 16) throw new Error('the page shades at most 16 light channels');
  /** @type {Uniforms} */
  const u = {
    uWinLo: ['f', winLo],
    uWinHi: ['f', winHi],
    uTravelLo: ['f', time.travel_min],
    uTravelHi: ['f', time.travel_max],
    uStops: ['f3', LINEAR_STOPS],
    uPhysical: ['i', physical ? 1 : 0],
    uExposure: ['f', settings.exposure],
    uAmbient: ['f', settings.light.ambient],
    uGain: ['f', gain],
    uLights: ['i', lightW.length],
    uLightW: ['f3', lightW.length ? lightW : [[0, 0, 0]]],
    uGtFirst: ['u', bb.gt_first_bin],
    uGtBins: ['i', bb.gt_bins],
    uGtRows: ['i', data.gtRows],
    uTMin: ['f', bb.t_min],
    uTMax: ['f', bb.t_max],
    uLnTMin: ['f', bb.ln_t_min],
    uLnStep: ['f', bb.step],
    uNodeLast: ['f', nodes - 2],
    uUnitLow: ['f3', bb.unit[0]],
    uUnitHigh: ['f3', bb.unit[nodes - 1]],
    uLnY: ['f4', [bb.ln_y[0], bb.ln_y[1], bb.ln_y[nodes - 2], bb.ln_y[nodes - 1]]],
    uSize: ['i2', [info.width, info.height]],
    uOut: ['i2', [width, height]],
    // The polarization layer's grid (crates/shade/src/polarization.rs, tick_spacing).
    uTickStep: ['i', Math.max(Math.floor(Math.min(width, height) / 16), 12)],
  };
  if (look) Object.assign(u, lookUniforms(look.view, look.sphere));
  // Reference squares of the first two objects' unshifted colours (frequency layer).
  /** @type {number[][]} */
  const refs = [[0, 0, 0, 0], [0, 0, 0, 0]];
  /** @type {number[][]} */
  const refColours = [[0, 0, 0], [0, 0, 0]];
  if (on.has('frequency') && settings.reference_squares) {
    info.objects.slice(0, 2).forEach((name, k) => {
      const square = referenceSquare(k, width, height);
      if (!square) return;
      const t = (settings.objects[name] || info.defaults.objects[name]).temperature;
      refs[k] = [...square, square[2]];
      // The colour a pixel at g = 1 shows: scaled by 2^ev and through the display tone
      // curve, as shade draws it (colour.rs, display_srgb8).
      refColours[k] = bb.colour(1, t, physical, settings.exposure)
        .map((c) => linearToSrgb8(toneMap(Math.fround(c * gain))) / 255);
    });
  }
  u.uRef0 = ['i4', refs[0]];
  u.uRef1 = ['i4', refs[1]];
  u.uRefColour0 = ['f3', refColours[0]];
  u.uRefColour1 = ['f3', refColours[1]];
  return u;
}

// What the server's overlay layer (crates/shade/src/layer.rs: orientation marks, travel-time
// and polarization legends, reference-square labels) depends on for these settings and
// picture, as a string; null when it draws nothing. Shading::overlays_shown decides the same.
/**
 * @param {ShadeSettings} settings
 * @param {Info} info
 * @param {Picture} p
 * @returns {string | null}
 */
export function overlayKey(settings, info, p) {
  const on = new Set(settings.shaders);
  const t = settings.time;
  const legend = on.has('time') && t.mode === 'travel' && t.legend;
  const squares = on.has('frequency') && settings.reference_squares && info.objects.length > 0;
  const polarization = polarizationLayer(settings, info, Boolean(p.look));
  if (!legend && !squares && !settings.grid && !polarization) return null;
  /** @param {string} name */
  const temperature = (name) => (settings.objects[name] || info.defaults.objects[name]).temperature;
  return JSON.stringify({
    size: [p.width, p.height],
    marks: settings.grid ? (p.look ? p.look.view.camera : 'file') : null,
    legend: legend ? [t.travel_min, t.travel_max] : null,
    polarization,
    squares: squares ? info.objects.slice(0, 2).map(temperature) : null,
  });
}

/**
 * @param {LookView} view
 * @param {import('./look.js').Sphere} sphere
 * @returns {Uniforms}
 */
function lookUniforms(view, sphere) {
  const c = view.camera;
  const rad = Math.PI / 180;
  /** @type {[number, number]} */
  let angles;
  if (c.kind === 'pinhole') {
    angles = [Math.tan(0.5 * c.fov_deg * rad), 0];
  } else if (c.kind === 'fisheye') {
    angles = [0.5 * c.fov_deg * rad, 0];
  } else {
    angles = c.kind === 'sphere' ? [2 * Math.PI, Math.PI] : [c.h_fov_deg * rad, c.v_fov_deg * rad];
  }
  const { speed, direction } = view.velocity;
  return {
    uCamAngles: ['f2', angles],
    uF: ['f3', view.forward],
    uR: ['f3', cross(view.forward, view.up)],
    uUp: ['f3', view.up],
    uVDir: ['f3', direction],
    uSpeed: ['f', speed],
    uGamma: ['f', 1 / Math.sqrt(1 - speed * speed)],
    uF0: ['f3', sphere.forward],
    uR0: ['f3', cross(sphere.forward, sphere.up)],
    uUp0: ['f3', sphere.up],
  };
}
