// @ts-check
// godel view: what the page fetches from the server once and keeps on the GPU: the data
// file's channels (each fetched when a layer first needs it), the image textures (stacked in
// one atlas texture of linear RGB), the black-body tables. Routes: crates/viewer/src/gpu_routes.rs.
'use strict';

import { getJson, ok, fetchPatiently } from './api.js';
import { parseArrays } from './gl.js';
import { Blackbody, srgb8ToLinear } from './overlays.js';

/** @typedef {import('./contract').Info} Info */
/** @typedef {import('./contract').ShadeSettings} ShadeSettings */
/** @typedef {import('./contract').GpuTexture} GpuTexture */
/** @typedef {import('./gl.js').Gpu} Gpu */
/** @typedef {import('./gl.js').WireArray} WireArray */
/**
 * The URLs that answer the channels `names`, in order: each one array or a sequence of them.
 * @typedef {(names: string[]) => string[]} ChannelUrls
 */

/**
 * An image texture in the atlas: its size, 8-bit sRGB samples, and its first row there.
 * @typedef {{ width: number, height: number, rgb: WireArray['data'], y0: number }} AtlasImage
 */

// 8-bit sRGB → linear, the `shade` crate's table (texture.rs).
const LINEAR = Float32Array.from({ length: 256 }, (_, k) => srgb8ToLinear(k));

// How many arrays the page asks for at once: within the server's waiting places (four per
// core, crates/viewer/src/limit.rs) even on one core, so one page alone never meets a 503
// (which api.js's fetchPatiently asks again).
const PARALLEL = 4;

/**
 * The arrays at `url` (crates/viewer/src/wire.rs: one, or a sequence); a refusal throws,
 * naming the URL.
 * @param {string} url
 */
const fetchArrays = async (url) => parseArrays(await (await ok(await fetchPatiently(url), url))
  .arrayBuffer());

// The channels of explore's server `frame` (crates/viewer/src/explore_routes.rs): all that a
// picture needs in one request, as each request costs the browser's cores a few milliseconds.
/**
 * @param {import('./contract').FrameInfo} frame
 * @returns {ChannelUrls}
 */
export function exploreChannels(frame) {
  return (names) => [`/api/explore/channels?names=${names.join(',')}`
    + `&generation=${frame.generation}&level=${frame.level}`];
}

// Whether the settings show the texture layer: named, or the polarization layer alone, which
// draws its ticks over it (crates/shade/src/shading.rs).
/** @param {ShadeSettings} settings */
export function textureLayer(settings) {
  const s = settings.shaders;
  return s.includes('texture') || (s.length === 1 && s[0] === 'polarization');
}

// Whether the settings' polarization layer draws anything on the data file's own pixels (not
// looking around): some object's light polarized.
/**
 * @param {ShadeSettings} settings
 * @param {Info} info
 */
export function polarizationLayer(settings, info, look = false) {
  return !look && settings.shaders.includes('polarization')
    && info.objects.some((name) => (settings.objects[name] || info.defaults.objects[name])
      .polarization);
}

// Which channels the layers of `settings` read (as Shading::pixel reads the record); looking
// around (`look`), also those that tell one image from another where the sphere is read
// smoothly (t_emit, u, v: crates/look/src/sample.rs).
/**
 * @param {ShadeSettings} settings
 * @param {Info} info
 * @returns {string[]}
 */
export function channelsFor(settings, info, look = false) {
  const on = new Set(settings.shaders);
  const need = new Set(look ? ['id', 'u', 'v', 't_emit'] : ['id']);
  const travel = settings.time.mode === 'travel';
  const texture = textureLayer(settings);
  const paints = texture || (on.has('time') && !travel) || on.has('light');
  if (paints) ['u', 'v'].forEach((c) => need.add(c));
  if ((texture || (on.has('time') && !travel)) && !on.has('light')) need.add('cos_i');
  if (on.has('time')) need.add('t_emit');
  if (on.has('frequency')) need.add('g');
  if (on.has('light')) for (let k = 0; k < info.lights; k += 1) need.add(`light_${k}`);
  if (polarizationLayer(settings, info, look)) ['pol', 'dir'].forEach((c) => need.add(c));
  return [...need];
}

export class Data {
  /**
   * The data's holder on `gpu` for the file `info` describes, with its scene textures and
   * black-body tables (Data.load fetches them).
   * @param {Gpu} gpu
   * @param {Info} info
   * @param {GpuTexture[]} sceneTextures
   * @param {Blackbody} blackbody
   * @param {number} gtRows the rows of the g·T table's texture
   */
  constructor(gpu, info, sceneTextures, blackbody, gtRows) {
    this.gpu = gpu;
    this.info = info;
    this.sceneTextures = sceneTextures;
    this.blackbody = blackbody;
    this.gtRows = gtRows;
    /** @type {Set<string>} channels on the GPU */
    this.loaded = new Set();
    /** @type {WireArray[]} */
    this.lightPlanes = [];
    /** @type {Map<string, AtlasImage>} */
    this.images = new Map();
    /** @type {[string, number, number][]} [url, bytes, ms] of each array, for the benchmarks */
    this.fetched = [];
    /** @type {ChannelUrls} */
    this.channelUrls = (names) => names.map((n) => `/api/gpu/channel/${n}`);
    this.epoch = 0;            // bumped whenever the frame whose channels are loaded changes
  }

  // Explore mode (explore.js): the channels of another frame, from `channelUrls(names)`; the
  // ones on the GPU are fetched again when a layer needs them.
  /** @param {ChannelUrls} channelUrls */
  reset(channelUrls) {
    this.channelUrls = channelUrls;
    this.loaded.clear();
    this.lightPlanes = [];
    this.epoch += 1;
  }

  // Channels put on the GPU by the page itself (a frame traced there, traced.js).
  /** @param {string[]} names */
  provide(names) {
    names.forEach((n) => this.loaded.add(n));
    this.epoch += 1;
  }

  // The data of the file `info` describes on `gpu`: first the scene textures' description
  // and the black-body tables (uploaded here).
  /**
   * @param {Gpu} gpu
   * @param {Info} info
   */
  static async load(gpu, info) {
    /** @type {[string, number, number][]} */
    const fetched = [];
    const [textures, blackbody, gt] = await Promise.all([
      /** @type {Promise<import('./contract').SceneTextures>} */ (getJson('/api/gpu/textures')),
      /** @type {Promise<import('./contract').Blackbody>} */ (getJson('/api/gpu/blackbody')),
      timedArray('/api/gpu/blackbody/gt', fetched),
    ]);
    // Repack the bins × 2 table into rows of 1024 bins (any WebGL2 takes 2048-wide textures).
    const bins = gt.width;
    const rows = Math.ceil(bins / 1024);
    const packed = new Float32Array(1024 * rows * 2 * 4);
    for (let part = 0; part < 2; part += 1) {
      for (let i = 0; i < bins; i += 1) {
        const to = ((part * rows + (i >> 10)) * 1024 + (i & 1023)) * 4;
        packed.set(gt.data.subarray((part * bins + i) * 4, (part * bins + i + 1) * 4), to);
      }
    }
    gpu.uploadFloatRgba('gt', 1024, rows * 2, packed);
    const data = new Data(gpu, info, textures.objects, new Blackbody(blackbody), rows);
    data.fetched.push(...fetched);
    return data;
  }

  // The size of the sample grid the channels hold: the picture's times the samples per
  // pixel along each side (crates/datafile/src/samples.rs).
  sampleSize() {
    const s = this.info.supersample || 1;
    return [this.info.width * s, this.info.height * s];
  }

  /** @param {string[]} names */
  missing(names) {
    return names.filter((n) => !this.loaded.has(n));
  }

  // The arrays at `urls` (each one array or a sequence), at most PARALLEL requests at a
  // time, in order.
  /** @param {string[]} urls */
  async arrays(urls) {
    /** @type {WireArray[]} */
    const out = [];
    for (let i = 0; i < urls.length; i += PARALLEL) {
      const got = await Promise.all(urls.slice(i, i + PARALLEL)
        .map((u) => timedArrays(u, this.fetched)));
      got.forEach((arrays) => out.push(...arrays));
    }
    return out;
  }

  // Fetches and uploads the channels not yet on the GPU. Channels of a frame replaced while
  // they loaded (explore: a frame traced in the page, fly.js) are dropped: the caller asks
  // again for the frame shown now.
  /** @param {string[]} names */
  async ensure(names) {
    const missing = this.missing(names);
    const epoch = this.epoch;
    if (missing.length === 0) return;
    const arrays = await this.arrays(this.channelUrls(missing));
    if (this.epoch !== epoch) return;
    if (arrays.length !== missing.length) {
      throw new Error(`the server sent ${arrays.length} arrays for the channels `
        + missing.join(', '));
    }
    const [width, height] = this.sampleSize();
    missing.forEach((name, i) => {
      const a = arrays[i];
      if (a.width !== width || a.height !== height) {
        throw new Error(`channel ${name} is ${a.width}×${a.height}, the file's samples ${width}×${height}`);
      }
      const light = name.match(/^light_(\d+)$/);
      if (light) {
        this.lightPlanes[Number(light[1])] = a;
      } else {
        this.gpu.upload(name, a);
      }
      this.loaded.add(name);
    });
    if (missing.some((n) => n.startsWith('light_'))) {
      const planes = this.lightPlanes.filter(Boolean);
      if (planes.length === this.info.lights) {
        this.gpu.uploadLights(planes, width, height);
      }
    }
  }

  // Fetches the named images not yet in the atlas and rebuilds it.
  /** @param {string[]} names */
  async ensureImages(names) {
    const missing = names.filter((n) => !this.images.has(n));
    if (missing.length === 0) return;
    const arrays = await this.arrays(missing.map((n) => `/api/gpu/image/${n}`));
    missing.forEach((name, i) => {
      const a = arrays[i];
      this.images.set(name, { width: a.width, height: a.height, rgb: a.data, y0: 0 });
    });
    let width = 1;
    let height = 0;
    for (const image of this.images.values()) {
      image.y0 = height;
      width = Math.max(width, image.width);
      height += image.height;
    }
    this.gpu.checkSize(width, height, 'the images of the textures, stacked');
    // Decoded to linear here, as the CPU decodes texels before filtering them.
    const rgba = new Float32Array(width * height * 4);
    for (const image of this.images.values()) {
      for (let p = 0; p < image.width * image.height; p += 1) {
        const row = image.y0 + Math.floor(p / image.width);
        const at = (row * width + (p % image.width)) * 4;
        rgba[at] = LINEAR[image.rgb[p * 3]];
        rgba[at + 1] = LINEAR[image.rgb[p * 3 + 1]];
        rgba[at + 2] = LINEAR[image.rgb[p * 3 + 2]];
        rgba[at + 3] = 1;
      }
    }
    this.gpu.uploadFloatRgba('atlas', width, height, rgba);
  }
}

// The arrays at `url`, noted in `fetched` as [url, bytes, ms] (for the benchmarks).
/**
 * @param {string} url
 * @param {[string, number, number][]} fetched
 */
async function timedArrays(url, fetched) {
  const started = performance.now();
  const arrays = await fetchArrays(url);
  const bytes = arrays.reduce((sum, a) => sum + a.data.byteLength, 0);
  fetched.push([url, bytes, performance.now() - started]);
  return arrays;
}

// The one array at `url`.
/**
 * @param {string} url
 * @param {[string, number, number][]} fetched
 */
async function timedArray(url, fetched) {
  const arrays = await timedArrays(url, fetched);
  if (arrays.length !== 1) throw new Error(`${url} answered ${arrays.length} arrays, not one`);
  return arrays[0];
}
