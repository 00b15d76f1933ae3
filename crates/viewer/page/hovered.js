// @ts-check
// godel explore: the hovered sample of a frame traced in this page (flying), read and shown
// without the server. Its record is read from the frame's slots (the kernel's layout,
// gpu::host::sample_record and light_value), with the fields the server's /api/pixel gives
// for its own frames (crates/viewer/src/state.rs, `pixel`). Its light ray, for the map
// (map.js), is traced by the GPU kernel's own closed forms: crates/gpu/src/kernel/ (render_map.glsl)
// compiled with RAY_PATH, the twin of render::map::light_ray (docs/physics.md, "The explore
// map"), with the fields of the server's /api/explore/ray: status, object, points
// [{t, x, y, z, r}] from the observer into the past, emission, travel_time.
'use strict';

/** @typedef {import('./contract').RayStatusName} RayStatusName */
/** @typedef {import('./contract').KernelInput} KernelInput */
/** @typedef {import('./contract').ObserverEvent} ObserverEvent */
/** @typedef {import('./contract').MapPoint} MapPoint */

/**
 * A sample's record as /api/pixel answers it, but for the pixel and the directions, which
 * the caller knows.
 * @typedef {Omit<import('./contract').PixelRecord, 'col' | 'row' | 'azimuth_deg'
 *   | 'elevation_deg'>} SampleRecord
 */

/**
 * A sample's light ray as /api/explore/ray answers it, but for the pixel.
 * @typedef {Omit<import('./contract').LightRay, 'col' | 'row'>} SampleRay
 */

// datafile::RayStatus by code, with the names crates/viewer/src/state.rs gives them.
/** @type {RayStatusName[]} */
export const STATUS = ['hit', 'escaped', 'step budget', 'failed', 'not traced', 'work limit'];
const HIT = 0;
const NOT_TRACED = 4;
// Points per row of the target the points are drawn into.
const ROW = 64;

// The record of the sample whose slots are `slots` (arrays of four floats, every slot of
// the kernel `input`, whose `light_channels` say where each light is), as /api/pixel
// answers it; `objects`: the scene's object names.
/**
 * @param {ArrayLike<number>[]} slots
 * @param {Pick<KernelInput, 'light_channels'>} input
 * @param {string[]} objects
 * @returns {SampleRecord}
 */
export function sampleRecord(slots, input, objects) {
  const [s0, s1, s2] = slots;
  const code = s0[1];
  const hit = code === HIT;
  const object = hit ? s0[0] : -1;
  // The fields of a miss mean nothing (NaN in the data file, null in JSON); a light out of
  // work is NaN (negative in the kernel, gpu::host::light_value), 0 where nothing was hit.
  /** @param {number} v */
  const field = (v) => (hit ? v : null);
  /** @param {[number, number]} where */
  const light = ([slot, component]) => {
    const v = slots[slot][component];
    return hit ? (v < 0 ? null : v) : 0;
  };
  return {
    object,
    object_name: objects[object] ?? null,
    status: STATUS[code] ?? 'failed',
    u: field(s0[2]),
    v: field(s0[3]),
    g: field(s1[0]),
    t_emit: field(s1[1]),
    travel_time: hit ? 0 - s1[1] : null,
    x: field(s2[0]),
    y: field(s2[1]),
    z: field(s2[2]),
    lights: input.light_channels.map(light),
  };
}

// The light ray of the sample whose slots are `slots` (every slot of the kernel `input`), in
// a frame traced with `input` (trace.js's `traced.input`: {defines, draw_buffers,
// uniforms, light_channels}) from the observer's event `event` ({t, x, y, z}): resolves once
// the GPU has traced it, without blocking the page.
/**
 * @param {import('./trace.js').KernelTracer} tracer
 * @param {KernelInput} input
 * @param {ObserverEvent} event
 * @param {ArrayLike<number>[]} slots
 * @returns {Promise<SampleRay>}
 */
export async function tracedLightRay(tracer, input, event, slots) {
  const record = sampleRecord(slots, input, []);
  /** @type {SampleRay} */
  const answer = {
    status: record.status,
    object: record.object >= 0 ? record.object : null,
    points: [],
    emission: null,
    travel_time: null,
  };
  // The direction the pixel's ray was launched along (none where it was not traced).
  const [s0, s1, s2, s3, s4] = slots;
  /** @type {[number, number, number]} */
  const n = [s2[3], s3[3], s4[0]];
  const length = Math.hypot(...n);
  if (s0[1] === NOT_TRACED || !(length > 0 && Number.isFinite(length))) return answer;
  const withHit = s0[1] === HIT && Number.isFinite(s1[2]);

  if (input.draw_buffers < 2) throw new Error('the light ray needs two render targets a draw');
  const gl = tracer.gl;
  const { program } = tracer.program(`${input.defines}#define RAY_PATH 1\n`);
  /** @param {string} name */
  const at = (name) => gl.getUniformLocation(program, `u_${name}`);
  // Draws the kernel's first `outputs` slots on `width` × `height` targets: resolves to
  // their floats, row by row (read back without blocking the page).
  /**
   * @param {number} width
   * @param {number} height
   * @param {number} outputs
   * @param {number} points
   * @param {number} end
   */
  const draw = async (width, height, outputs, points, end) => {
    const targets = Array.from({ length: outputs }, () => tracer.floatTexture(width, height));
    const fb = gl.createFramebuffer();
    try {
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      const buffers = targets.map((t, k) => {
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + k, gl.TEXTURE_2D, t, 0);
        return gl.COLOR_ATTACHMENT0 + k;
      });
      while (buffers.length < input.draw_buffers) buffers.push(gl.NONE);
      gl.drawBuffers(buffers);
      gl.useProgram(program);
      tracer.setUniforms(program, input.uniforms);
      gl.uniform4f(at('ray'), n[0], n[1], n[2], end);
      gl.uniform3f(at('emission'), s2[0], s2[1], s2[2]);
      gl.uniform1i(at('points'), points);
      gl.uniform1i(at('row'), ROW);
      gl.uniform1i(at('slot0'), 0);
      gl.bindVertexArray(tracer.vao);
      gl.disable(gl.SCISSOR_TEST);
      gl.viewport(0, 0, width, height);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      return await tracer.readLater(targets, 0, 0, width, height);
    } finally {
      gl.deleteFramebuffer(fb);
      targets.forEach((t) => gl.deleteTexture(t));
    }
  };
  // The end parameter, the number of points after the observer's and the emission event's
  // distance from the observer's axis.
  const [[end, count, emissionR, ok]] = await draw(1, 1, 1, 0, withHit ? s1[2] : -1);
  if (ok !== 1) return answer;
  const width = Math.min(count, ROW);
  const height = Math.ceil(count / ROW);
  // Each point's event (slot 0) and distance from the observer's axis (slot 1), in one draw
  // (WebGL2 has at least four draw buffers).
  const [events, radii] = await draw(width, height, 2, count, end);
  // The first point is the observer's event itself, as render::map draws it.
  answer.points.push({ ...event, r: 0 });
  for (let i = 0; i < count; i += 1) {
    const k = 4 * i;
    answer.points.push({ t: event.t + events[k], x: events[k + 1], y: events[k + 2],
      z: events[k + 3], r: radii[k] });
  }
  if (withHit) {
    // The record's t_emit and emission event, as sampleRecord reads a hit's.
    answer.emission = { t: event.t + s1[1], x: s2[0], y: s2[1], z: s2[2], r: emissionR };
    answer.travel_time = record.travel_time;
  }
  return answer;
}
