// @ts-check
// godel view: numbers the page computes once per change on the CPU, mirroring the `shade`
// crate so that the picture equals `godel shade`: the black-body grid (colour and luminance
// of a temperature, crates/shade/src/blackbody.rs), 8-bit sRGB (colour.rs), the
// travel-time colour map's stops (legend.rs), the reference squares (frequency_shader.rs),
// and f32 bounds equivalent to the f64 time window. The overlay layer (marks, legend,
// labels) is not drawn here: the server draws it (crates/shade/src/layer.rs, /api/overlay).
'use strict';

/** @typedef {import('./contract').Vec3} Vec3 */

const f32 = Math.fround;

// ---- 8-bit sRGB, in f32 as the crate computes it

/**
 * @param {number} s
 */
export function srgbToLinear(s) {
  s = Number.isNaN(s) ? 0 : Math.min(Math.max(f32(s), 0), 1);
  return s <= 0.04045 ? f32(s / 12.92) : f32(Math.pow(f32(f32(s + 0.055) / 1.055), 2.4));
}

/**
 * @param {number} k
 */
export function srgb8ToLinear(k) {
  return srgbToLinear(f32(k / 255));
}

// The display tone curve of crates/shade/src/colour.rs (tone_map), in f32 as Rust computes
// it: identity up to 0.8, then 0.8 + 0.2·y/(1 + y), y = (x − 0.8)/0.2.
/**
 * @param {number} x
 */
export function toneMap(x) {
  if (Number.isNaN(x)) return 0;
  x = f32(x);
  if (x <= f32(0.8)) return x;
  if (!Number.isFinite(x)) return 1;
  const y = f32(f32(x - f32(0.8)) / f32(f32(1) - f32(0.8)));
  return f32(f32(0.8) + f32(f32(f32(1) - f32(0.8)) * f32(y / f32(1 + y))));
}

/**
 * @param {number} x
 */
export function linearToSrgb8(x) {
  x = Number.isNaN(x) ? 0 : Math.min(Math.max(f32(x), 0), 1);
  const s = x <= 0.0031308 ? f32(12.92 * x)
    : f32(f32(1.055 * f32(Math.pow(x, f32(1 / 2.4)))) - 0.055);
  return Math.round(f32(s * 255));
}

// ---- the black-body grid (BlackbodyTable): served by /api/gpu/blackbody

export class Blackbody {
  /** @param {import('./contract').Blackbody} table */
  constructor(table) {
    this.t_min = table.t_min;
    this.t_max = table.t_max;
    this.gt_shift = table.gt_shift;
    this.gt_first_bin = table.gt_first_bin;
    this.gt_bins = table.gt_bins;
    this.ln_t_min = table.ln_t_min;
    this.step = table.step;
    this.unit = table.unit;
    this.ln_y = table.ln_y;
  }

  /**
   * @param {number} t
   * @returns {[number, number]}
   */
  locate(t) {
    const s = (Math.log(t) - this.ln_t_min) / this.step;
    const last = this.unit.length - 2;
    const i = Math.min(Math.max(Math.floor(s), 0), last);
    return [i, s - i];
  }

  /**
   * @param {number} t
   * @returns {Vec3}
   */
  unitColour(t) {
    if (!(t > 0 && Number.isFinite(t))) return [0, 0, 0];
    const [i, f0] = this.locate(t);
    const f = Math.min(Math.max(f0, 0), 1);
    const a = this.unit[i];
    const b = this.unit[i + 1];
    return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])];
  }

  /** @param {number} t */
  luminance(t) {
    if (!(t > 0 && Number.isFinite(t))) return 0;
    const [i, f] = this.locate(t);
    const a = this.ln_y[i];
    const b = this.ln_y[i + 1];
    return Math.exp(a + f * (b - a));
  }

  // blackbody_colour(g, t, brightness) of frequency_shader.rs, as f32.
  /**
   * @param {number} g
   * @param {number} t
   * @param {boolean} physical
   * @param {number} exposure
   * @returns {number[]}
   */
  colour(g, t, physical, exposure) {
    const shifted = g * t;
    let rgb;
    if (!physical) {
      rgb = normalizeMax(this.unitColour(shifted));
    } else {
      const scale = exposure * this.luminance(shifted) / this.luminance(t);
      rgb = this.unitColour(shifted).map((c) => c * scale);
      const max = Math.max(...rgb);
      if (max > 1) rgb = rgb.map((c) => c / max);
    }
    return rgb.map(f32);
  }
}

/**
 * @param {number[]} rgb
 */
function normalizeMax(rgb) {
  const max = Math.max(...rgb);
  return max > 0 && Number.isFinite(max) ? rgb.map((c) => c / max) : [0, 0, 0];
}

// ---- reference squares: reference_square(k, width, height)

/**
 * @param {number} k
 * @param {number} width
 * @param {number} height
 * @returns {[number, number, number] | null}
 */
export function referenceSquare(k, width, height) {
  const most = Math.max(16, Math.floor(Math.max(width, height) / 120));
  const side = Math.min(Math.max(Math.floor(Math.min(width, height) / 8), 8), most);
  const gap = Math.floor(side / 4);
  const x0 = gap + k * (side + gap);
  const y0 = gap;
  return x0 + side <= width && y0 + side <= height ? [x0, y0, side] : null;
}

// ---- travel-time false colour: the stops (the shader interpolates them)

const STOPS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
export const LINEAR_STOPS = STOPS.map((s) => s.map(srgb8ToLinear));

// ---- the time window: f32 bounds [lo, hi] such that for every f32 t,
// lo ≤ t ≤ hi exactly when t0 ≤ t ≤ t0 + dt in f64 (as shading.rs compares).

const buffer = new DataView(new ArrayBuffer(4));

/**
 * @param {number} x
 * @param {boolean} up
 */
function nextF32(x, up) {
  if (x === 0) return up ? 1.401298464324817e-45 : -1.401298464324817e-45;
  buffer.setFloat32(0, x);
  const bits = buffer.getInt32(0);
  buffer.setInt32(0, (x > 0) === up ? bits + 1 : bits - 1);
  return buffer.getFloat32(0);
}

/**
 * @param {number} t0
 * @param {number} dt
 * @returns {[number, number]}
 */
export function windowBounds(t0, dt) {
  const hi64 = t0 + dt;
  let lo = f32(t0);
  if (lo < t0) lo = nextF32(lo, true);
  let hi = f32(hi64);
  if (hi > hi64) hi = nextF32(hi, false);
  return [lo, hi];
}
