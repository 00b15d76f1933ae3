// godel view: what the page fetches from the server once and keeps on the GPU: the data
// file's channels (each fetched when a layer first needs it), the image textures (stacked in
// one atlas texture of linear RGB), the black-body tables. Routes: crates/viewer/src/gpu_routes.rs.
'use strict';

import { parseArray } from './gl.js';
import { Blackbody, srgb8ToLinear } from './overlays.js';

// 8-bit sRGB → linear, the `shade` crate's table (texture.rs).
const LINEAR = Float32Array.from({ length: 256 }, (_, k) => srgb8ToLinear(k));

// How many arrays the page asks for at once: within the server's waiting places (four per
// core, crates/viewer/src/limit.rs) even on one core, so one page alone never meets a 503.
const PARALLEL = 4;
// A 503 (the server busy with other tabs or scripts) is retried this many times, waiting a
// little longer each time (about 10 s in all), then shown as an error.
const BUSY_RETRIES = 20;

const sleep = (ms) => new Promise((resolve) => { setTimeout(resolve, ms); });

// `fetch(url, init)`, asked again while the server answers 503 (busy), at most BUSY_RETRIES
// times.
export async function fetchPatiently(url, init) {
  let response = await fetch(url, init);
  for (let k = 1; response.status === 503 && k <= BUSY_RETRIES; k += 1) {
    await sleep(50 * k);
    response = await fetch(url, init);
  }
  return response;
}

async function fetchOk(url) {
  const response = await fetchPatiently(url);
  if (!response.ok) {
    const text = await response.text();
    let message = text;
    try { message = JSON.parse(text).error || text; } catch (_) { /* not JSON */ }
    const error = new Error(`${url}: ${message}`);
    error.status = response.status;
    throw error;
  }
  return response;
}

export const fetchJson = async (url) => (await fetchOk(url)).json();
const fetchArray = async (url) => parseArray(await (await fetchOk(url)).arrayBuffer());

// Whether the settings show the texture layer: named, or the polarization layer alone, which
// draws its ticks over it (crates/shade/src/shading.rs).
export function textureLayer(settings) {
  const s = settings.shaders;
  return s.includes('texture') || (s.length === 1 && s[0] === 'polarization');
}

// Whether the settings' polarization layer draws anything on the data file's own pixels (not
// looking around): some object's light polarized.
export function polarizationLayer(settings, info, look = false) {
  return !look && settings.shaders.includes('polarization')
    && info.objects.some((name) => (settings.objects[name] || info.defaults.objects[name])
      .polarization);
}

// Which channels the layers of `settings` read (as Shading::pixel reads the record); looking
// around (`look`), also those that tell one image from another where the sphere is read
// smoothly (t_emit, u, v: crates/look/src/sample.rs).
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
  constructor(gpu, info) {
    this.gpu = gpu;
    this.info = info;
    this.loaded = new Set();   // channels on the GPU
    this.lightPlanes = [];
    this.images = new Map();   // name → {width, height, rgb, y0}
    this.fetched = [];         // [url, bytes, ms] of each array, for the benchmarks
    this.channelUrl = (name) => `/api/gpu/channel/${name}`;
    this.epoch = 0;            // bumped whenever the frame whose channels are loaded changes
  }

  // Explore mode (explore.js): the channels of another frame, from `channelUrl(name)`; the
  // ones on the GPU are fetched again when a layer needs them.
  reset(channelUrl) {
    this.channelUrl = channelUrl;
    this.loaded.clear();
    this.lightPlanes = [];
    this.epoch += 1;
  }

  // Channels put on the GPU by the page itself (a frame traced there, traced.js).
  provide(names) {
    names.forEach((n) => this.loaded.add(n));
    this.epoch += 1;
  }

  // The scene textures' description and the black-body tables (uploaded here).
  async start() {
    const [textures, blackbody, gt] = await Promise.all([
      fetchJson('/api/gpu/textures'),
      fetchJson('/api/gpu/blackbody'),
      this.array('/api/gpu/blackbody/gt'),
    ]);
    this.sceneTextures = textures.objects;
    this.blackbody = new Blackbody(blackbody);
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
    this.gpu.uploadFloatRgba('gt', 1024, rows * 2, packed);
    this.gtRows = rows;
  }

  async array(url) {
    const started = performance.now();
    const a = await fetchArray(url);
    this.fetched.push([url, a.data.byteLength, performance.now() - started]);
    return a;
  }

  // The size of the sample grid the channels hold: the picture's times the samples per
  // pixel along each side (crates/datafile/src/samples.rs).
  sampleSize() {
    const s = this.info.supersample || 1;
    return [this.info.width * s, this.info.height * s];
  }

  missing(names) {
    return names.filter((n) => !this.loaded.has(n));
  }

  // The arrays at `urls`, at most PARALLEL requests at a time, in order.
  async arrays(urls) {
    const out = [];
    for (let i = 0; i < urls.length; i += PARALLEL) {
      out.push(...await Promise.all(urls.slice(i, i + PARALLEL).map((u) => this.array(u))));
    }
    return out;
  }

  // Fetches and uploads the channels not yet on the GPU. Channels of a frame replaced while
  // they loaded (explore: a frame traced in the page, fly.js) are dropped: the caller asks
  // again for the frame shown now.
  async ensure(names) {
    const missing = this.missing(names);
    const epoch = this.epoch;
    const arrays = await this.arrays(missing.map(this.channelUrl));
    if (this.epoch !== epoch) return;
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
  async ensureImages(names) {
    const missing = names.filter((n) => !this.images.has(n));
    if (missing.length === 0) return;
    const arrays = await this.arrays(missing.map((n) => `/api/gpu/image/${n}`));
    missing.forEach((name, i) => {
      const a = arrays[i];
      this.images.set(name, { width: a.width, height: a.height, rgb: a.data });
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
