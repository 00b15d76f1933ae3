// @ts-check
// godel view: cameras and looking around, in f64 as the `look` crate and `scene::Camera`
// compute them (the shader does the same in f32 per pixel): a pixel's direction for any
// camera, the aberration and Doppler factor of a moving observer, the sphere pixel a
// direction falls in; and the look-around view (projection, zoom, turn, velocity) that the
// mouse and the controls change.
'use strict';

/** @typedef {import('./contract').Vec3} Vec3 */
/** @typedef {import('./contract').Camera} Camera */
/** @typedef {import('./contract').LookView} LookView */

/**
 * A look-around view of a full-sphere file, as the controls change it: the projection and its
 * field of view, the turn from the file's axes, the observer's velocity (its direction set
 * from `preset`), the samples per pixel.
 * @typedef {object} Look
 * @property {Projection} projection
 * @property {number} fov degrees
 * @property {number} yaw degrees to the right
 * @property {number} pitch degrees up
 * @property {number} speed
 * @property {string} preset 'forward', 'object:K' or an axis ('+x', …)
 * @property {Vec3} direction the velocity's, static frame
 * @property {string} samples one of SAMPLES
 */

/** @typedef {'pinhole' | 'panorama' | 'fisheye' | 'sphere'} Projection */

/**
 * The axes of a file's own view (ViewInfo.view), and of a sphere of width × height pixels.
 * @typedef {{ forward: Vec3, up: Vec3 }} Axes
 * @typedef {{ width: number, height: number, forward: Vec3, up: Vec3 }} Sphere
 */

/** @type {(a: Vec3, b: Vec3) => number} */
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
/** @type {(a: Vec3, b: Vec3) => Vec3} */
export const cross = (a, b) => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
/** @type {(a: Vec3, s: number) => Vec3} */
const scaled = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
/** @type {(a: Vec3, b: Vec3) => Vec3} */
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
/** @type {(a: Vec3) => Vec3} */
export const normalize = (a) => scaled(a, 1 / Math.sqrt(dot(a, a)));
const RAD = Math.PI / 180;

// Camera-basis direction (forward, right, up) of pixel (col, row) of `camera` (the JSON of
// /api/view: kind, width, height, fov_deg | h_fov_deg, v_fov_deg), or null where it shows
// nothing (crates/scene/src/camera.rs).
/**
 * @param {Camera} camera
 * @param {number} col
 * @param {number} row
 * @returns {Vec3 | null}
 */
export function cameraDirection(camera, col, row) {
  const { width: w, height: h } = camera;
  if (col < 0 || row < 0 || col >= w || row >= h) return null;
  const cx = col + 0.5;
  const cy = row + 0.5;
  /** @type {(hFov: number, vFov: number) => Vec3} */
  const panorama = (hFov, vFov) => {
    const alpha = hFov * RAD * (cx / w - 0.5);
    const beta = vFov * RAD * (0.5 - cy / h);
    return [Math.cos(beta) * Math.cos(alpha), Math.cos(beta) * Math.sin(alpha), Math.sin(beta)];
  };
  switch (camera.kind) {
    case 'pinhole': {
      const t = Math.tan(0.5 * camera.fov_deg * RAD);
      const x = t * (2 * cx / w - 1);
      const y = t * (h / w) * (1 - 2 * cy / h);
      const n = Math.sqrt(1 + x * x + y * y);
      return [1 / n, x / n, y / n];
    }
    case 'panorama': return panorama(camera.h_fov_deg, camera.v_fov_deg);
    case 'sphere': return panorama(360, 180);
    default: { // fisheye
      const dx = 2 * cx / w - 1;
      const dy = 1 - 2 * cy / h;
      const rho = Math.hypot(dx, dy);
      if (rho > 1) return null;
      const theta = rho * 0.5 * camera.fov_deg * RAD;
      const [s, c] = rho > 0 ? [dx / rho, dy / rho] : [0, 1];
      return [Math.cos(theta), Math.sin(theta) * s, Math.sin(theta) * c];
    }
  }
}

// Local-frame direction of a camera-basis direction, for axes forward and up.
/**
 * @param {Vec3} d
 * @param {Vec3} forward
 * @param {Vec3} up
 * @returns {Vec3}
 */
export function toLocal(d, forward, up) {
  const right = cross(forward, up);
  return add(add(scaled(forward, d[0]), scaled(right, d[1])), scaled(up, d[2]));
}

// spacetime::aberrate: the static observer's direction n of the photon a moving observer
// (speed, unit direction) sees along `own`, and the Doppler factor D = γ(1 + n·v).
/**
 * @param {number} speed
 * @param {Vec3} direction
 * @param {Vec3} own
 * @returns {[Vec3, number]}
 */
export function aberrate(speed, direction, own) {
  const gamma = 1 / Math.sqrt(1 - speed * speed);
  const along = dot(own, direction);
  const scale = 1 / (gamma * (1 - speed * along));
  const c = (gamma - 1) * along - gamma * speed;
  return [scaled(add(own, scaled(direction, c)), scale), scale];
}

// SphereSource::position and ::nearest: the sphere pixel (col, row) containing static
// direction n, for a sphere of width × height with axes forward, up.
/**
 * @param {Sphere} sphere
 * @param {Vec3} n
 * @returns {[number, number]}
 */
export function spherePixel(sphere, n) {
  const right = cross(sphere.forward, sphere.up);
  const alpha = Math.atan2(dot(n, right), dot(n, sphere.forward));
  const beta = Math.asin(Math.min(Math.max(dot(n, sphere.up), -1), 1));
  const x = sphere.width * (alpha / (2 * Math.PI) + 0.5);
  const y = sphere.height * (0.5 - beta / Math.PI);
  const w = sphere.width;
  const col = ((Math.floor(x) % w) + w) % w;
  const row = Math.min(Math.max(Math.floor(y), 0), sphere.height - 1);
  return [col, row];
}

// Azimuth (from x towards y) and elevation (towards z) of a unit direction, degrees.
/**
 * @param {Vec3} n
 * @returns {[number, number]}
 */
export function azimuthElevation(n) {
  return [Math.atan2(n[1], n[0]) / RAD, Math.asin(Math.min(Math.max(n[2], -1), 1)) / RAD];
}

// ---- the look-around view

/** @type {Record<Projection, { fov: number, min: number, max: number }>} */
export const PROJECTIONS = {
  pinhole: { fov: 90, min: 5, max: 170 },
  panorama: { fov: 220, min: 20, max: 360 },
  fisheye: { fov: 180, min: 20, max: 360 },
  sphere: { fov: 360, min: 360, max: 360 },
};

// A view of a sphere file: turned by yaw (to the right) and pitch (up), in degrees, from the
// file's own axes, with the projection's field of view, moving with speed along direction.
/**
 * @param {Axes} file
 * @returns {Look}
 */
export function newLook(file) {
  return {
    projection: 'pinhole',
    fov: PROJECTIONS.pinhole.fov,
    yaw: 0,
    pitch: 0,
    speed: 0,
    preset: 'forward',
    direction: [...file.forward],
    // Samples per pixel (`godel look --samples`): 2×2 points in each pixel smooth the edges.
    samples: '4',
  };
}

// The samples per pixel a look offers.
export const SAMPLES = ['1', '4', '9', '16'];

// The camera axes of a look in the moving observer's frame (the file's axes turned).
/**
 * @param {Look} look
 * @param {Axes} file
 * @returns {Axes}
 */
export function lookAxes(look, file) {
  const right = cross(file.forward, file.up);
  const [sy, cy] = [Math.sin(look.yaw * RAD), Math.cos(look.yaw * RAD)];
  const [sp, cp] = [Math.sin(look.pitch * RAD), Math.cos(look.pitch * RAD)];
  const level = add(scaled(file.forward, cy), scaled(right, sy));
  return {
    forward: add(scaled(level, cp), scaled(file.up, sp)),
    up: add(scaled(level, -sp), scaled(file.up, cp)),
  };
}

// The camera of a look on a width × height view (a fisheye uses the largest square).
/**
 * @param {Look} look
 * @param {number} width
 * @param {number} height
 * @returns {Camera}
 */
export function lookCamera(look, width, height) {
  switch (look.projection) {
    case 'pinhole': return { kind: 'pinhole', fov_deg: look.fov, width, height };
    case 'panorama': return { kind: 'panorama', h_fov_deg: look.fov,
      v_fov_deg: Math.min(180, look.fov * height / width), width, height };
    case 'sphere': return { kind: 'sphere', width, height };
    default: {
      const size = Math.min(width, height);
      return { kind: 'fisheye', fov_deg: look.fov, width: size, height: size };
    }
  }
}

// The view as /api/look/* reads it.
/**
 * @param {Look} look
 * @param {Axes} file
 * @param {number} width
 * @param {number} height
 * @returns {LookView}
 */
export function lookView(look, file, width, height) {
  const { forward, up } = lookAxes(look, file);
  return {
    camera: lookCamera(look, width, height),
    forward,
    up,
    velocity: { speed: look.speed, direction: look.direction },
    samples: Number(look.samples || 1),
  };
}

// Radians of view per pixel across the width (for dragging).
/**
 * @param {Look} look
 * @param {number} width
 */
export function radiansPerPixel(look, width) {
  return look.fov * RAD / Math.max(width, 1);
}

// The direction a velocity preset names, static frame: the view's centre, an object, an axis.
/**
 * @param {string} preset
 * @param {Look} look
 * @param {Axes} file
 * @param {(Vec3 | null)[]} objectDirections
 * @returns {Vec3}
 */
export function presetDirection(preset, look, file, objectDirections) {
  /** @type {Record<string, Vec3>} */
  const axes = { '+x': [1, 0, 0], '-x': [-1, 0, 0], '+y': [0, 1, 0], '-y': [0, -1, 0],
    '+z': [0, 0, 1], '-z': [0, 0, -1] };
  if (preset in axes) return axes[preset];
  if (preset.startsWith('object:')) {
    const d = objectDirections[Number(preset.slice(7))];
    if (d) return d;
  }
  return lookAxes(look, file).forward;
}

// Where output pixel (col, row) of a look looks: its own direction, the static one, D, and the
// sphere pixel its centre falls in (whose record the hover shows); null outside the camera's
// picture.
/**
 * @param {LookView} view
 * @param {Sphere} sphere
 * @param {number} col
 * @param {number} row
 * @returns {{ own: Vec3, static: Vec3, doppler: number, source: [number, number] } | null}
 */
export function lookPixel(view, sphere, col, row) {
  const d = cameraDirection(view.camera, col, row);
  if (!d) return null;
  const own = toLocal(d, view.forward, view.up);
  const [n, doppler] = aberrate(view.velocity.speed, view.velocity.direction, own);
  return { own, static: n, doppler, source: spherePixel(sphere, n) };
}
