// @ts-check
// godel view: the exact tracer on the GPU, in the page. Runs the kernel of crates/gpu
// (crates/gpu/src/kernel/, served at /api/gpu/kernel) in WebGL2 as crates/gpu/src/host.rs runs it
// offscreen: compiled after `#version 300 es` and the input's defines, the scene table
// uploaded as RGBA32F texels, the sample grid drawn tile by tile (each draw short, so that no
// GPU watchdog fires and the page stays responsive), each tile in rounds (docs/physics.md,
// "Rounds": a round takes each sample on from its last checkpoint, reading the previous
// round's progress from one array texture and writing it into the other) until every sample
// is finished, then the records into float render targets: one RGBA32F texture per slot of
// four channels of a record. A conversion pass then writes the channels
// the shading reads (crates/viewer/src/gpu.rs: id, u, v, g, t_emit, cos_i, pol, dir, the light
// planes) into textures: the frame never leaves the GPU.
//
// Reusable: `new KernelTracer(gl, kernelSource)`, `await tracer.trace(input)` with an input
// as /api/gpu/input sends it (crates/viewer/src/kernel_routes.rs: uniforms, table, slots,
// light_channels, draw_buffers, defines), whose uniforms the caller may change (the
// observer's event, …) between traces; `tracer.channels(traced, objects)` gives the textures.
'use strict';

import { linkProgram } from './gl.js';

/** @typedef {import('./contract').KernelInput} KernelInput */

/**
 * A traced frame: its sample grid's size, its slots (one RGBA32F texture each, the caller's
 * to delete), the input traced, the kernel's source as compiled, and the times taken.
 * @typedef {object} Traced
 * @property {number} width
 * @property {number} height
 * @property {WebGLTexture[]} slots
 * @property {KernelInput} input
 * @property {string} source
 * @property {number} compileMs
 * @property {number} traceMs
 */

/**
 * The channels the shading reads, as textures named as the data file's channels (the light
 * planes as one array texture, null without lights).
 * @typedef {Record<string, WebGLTexture | null>} Channels
 */

/**
 * How a trace runs: `progress(done, total)` after each tile, `cancelled()` checked between
 * draws, `whole` the grid in one tile.
 * @typedef {{ progress?: (done: number, total: number) => void, cancelled?: () => boolean,
 *   whole?: boolean }} TraceOptions
 */

// The kernel's statuses (datafile::record::RayStatus codes).
const HIT = 0;
const WORK_LIMIT = 5;
// What one draw should take (each draw is waited for: long enough that the wait costs little,
// measured on SwiftShader; short enough for GPU watchdogs and a responsive page), and its
// side's bounds, in samples.
const DRAW_MS = 250;
const MIN_SIDE = 8;
const MAX_SIDE = 256;
const FIRST_SIDE = 16;
// A NaN as bits: the value of a light whose occlusion search ran out of work (host.rs).
const NAN_BITS = '0x7fc00000u';

// The conversion pass: each output channel from the slots, as host.rs's `collect` reads a
// record and crates/viewer/src/gpu.rs (`Channel::encode`, `id_code`) encodes it for the page.
const CONVERT_HEAD = `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform sampler2D u_record;   // slot 0: object, status, u, v
uniform sampler2D u_slot;     // the slot holding the channel
uniform int u_component;
`;

const CONVERT_FLOAT = `${CONVERT_HEAD}
uniform bool u_light;         // a light: negative (out of work) is NaN
out vec4 o;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  bool hit = int(texelFetch(u_record, p, 0).y) == ${HIT};
  float v = texelFetch(u_slot, p, 0)[u_component];
  if (u_light && v < 0.0) v = uintBitsToFloat(${NAN_BITS});
  o = vec4(hit ? v : 0.0, 0.0, 0.0, 0.0);
}`;

// Three channels of a slot from `u_component` on (pol, dir), RGBA32F (RGB32F cannot be drawn
// into), zeros where nothing was hit.
const CONVERT_VECTOR = `${CONVERT_HEAD}
out vec4 o;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  bool hit = int(texelFetch(u_record, p, 0).y) == ${HIT};
  vec4 s = texelFetch(u_slot, p, 0);
  vec3 v = u_component == 0 ? s.xyz : s.yzw;
  o = hit ? vec4(v, 0.0) : vec4(0.0);
}`;

const CONVERT_UINT = `${CONVERT_HEAD}
uniform int u_objects;
uniform bool u_id;            // the id (else cos_i, 16 bits)
out uvec4 o;
// viewer::gpu::id_code: 0 background, 1 failed, 2 step budget or work limit, 3 not traced,
// 4 + k object k.
uint idCode(int object, int status) {
  if (status == 2 || status == 5) return 2u;
  if (status == 4) return 3u;
  if (status != 0 && status != 1) return 1u;
  if (object < 0) return 0u;
  return object < u_objects ? 4u + uint(object) : 1u;
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 record = texelFetch(u_record, p, 0);
  int status = int(record.y);
  if (u_id) {
    o = uvec4(idCode(int(record.x), status), 0u, 0u, 0u);
  } else {
    float c = texelFetch(u_slot, p, 0)[u_component];
    c = status == ${HIT} && !isnan(c) ? clamp(c, 0.0, 1.0) : 0.0;
    o = uvec4(uint(floor(c * 65535.0 + 0.5)), 0u, 0u, 0u);
  }
}`;

// Where each channel the shading reads lies in a record: [slot, component]
// (gpu::input::SLOT_CHANNELS).
/** @type {Record<string, [number, number]>} */
const FLOAT_CHANNELS = { u: [0, 2], v: [0, 3], g: [1, 0], t_emit: [1, 1] };
/** @type {[number, number]} */
const COS_I = [1, 3];
// Three channels from the slot's first or second component.
/** @type {Record<string, [number, number]>} */
const VECTOR_CHANNELS = { dir: [3, 0], pol: [4, 1] };

export class KernelTracer {
  // `kernel`: the source of /api/gpu/kernel. Throws, saying why, where WebGL2 cannot run it.
  /**
   * @param {WebGL2RenderingContext} gl
   * @param {string} kernel
   */
  constructor(gl, kernel) {
    if (!gl.getExtension('EXT_color_buffer_float')) {
      throw new Error('this browser\u2019s WebGL2 cannot draw into float textures '
        + '(EXT_color_buffer_float is missing): the page cannot trace on the GPU here');
    }
    this.gl = gl;
    this.kernel = kernel;
    /** @type {number} */
    this.maxDrawBuffers = gl.getParameter(gl.MAX_DRAW_BUFFERS);
    /** @type {number} */
    this.maxSize = gl.getParameter(gl.MAX_TEXTURE_SIZE);
    /** @type {Map<string, { program: WebGLProgram, source: string }>} kernels by defines */
    this.programs = new Map();
    /** @type {Set<WebGLProgram>} those that have drawn once */
    this.warm = new Set();
    this.vao = gl.createVertexArray();
    /**
     * The conversion passes' programs, linked when first needed.
     * @type {{ float: WebGLProgram, uint: WebGLProgram, vector: WebGLProgram } | null}
     */
    this.convert = null;
  }

  // The kernel compiled with `defines` (once per distinct defines): {program, source}, the
  // source as host.rs compiles it (`#version 300 es`, the defines, the kernel).
  /** @param {string} defines */
  program(defines) {
    let compiled = this.programs.get(defines);
    if (!compiled) {
      const source = `#version 300 es\n${defines}${this.kernel}`;
      compiled = { program: linkProgram(this.gl, source, 'the GPU kernel'), source };
      this.programs.set(defines, compiled);
    }
    return compiled;
  }

  // An RGBA32F array texture of `layers` layers (a round's slots, one layer each).
  /**
   * @param {number} width
   * @param {number} height
   * @param {number} layers
   */
  arrayTexture(width, height, layers) {
    const gl = this.gl;
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, t);
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, gl.RGBA32F, width, height, layers);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    return t;
  }

  /**
   * @param {number} width
   * @param {number} height
   */
  floatTexture(width, height) {
    const gl = this.gl;
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, t);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, width, height);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    return t;
  }

  // Sets the input's uniforms `u` (a view's, crates/viewer/src/kernel_routes.rs) on
  // `program`, in use.
  /**
   * @param {WebGLProgram} program
   * @param {import('./contract').KernelUniforms} u
   */
  setUniforms(program, u) {
    const gl = this.gl;
    /** @param {string} name */
    const at = (name) => gl.getUniformLocation(program, `u_${name}`);
    // The metric is no uniform: the defines say it (GODEL), as for every other switch.
    gl.uniform1f(at('a'), u.a);
    gl.uniform2fv(at('obs_t'), u.obs_t);
    gl.uniform3fv(at('obs_x'), u.obs_x);
    gl.uniformMatrix4fv(at('obs_static'), false, u.obs_static);
    gl.uniform4fv(at('obs_to'), u.obs_to);
    gl.uniform4fv(at('velocity'), u.velocity);
    gl.uniform3fv(at('forward'), u.forward);
    gl.uniform3fv(at('up'), u.up);
    gl.uniform1i(at('camera'), u.camera);
    gl.uniform2fv(at('fov'), u.fov);
    gl.uniform2iv(at('size'), u.size);
    gl.uniform1f(at('max_past'), u.max_past);
    gl.uniform1i(at('max_loops'), u.max_loops);
    gl.uniform1i(at('lights'), u.lights);
    gl.uniform4fv(at('member'), u.member);
    gl.uniform1i(at('table'), 0);
    gl.uniform1i(at('prev'), 1);
    // The bound of the loop that tells a round cut short by a loop limiter (render_tracer.glsl).
    gl.uniform1i(at('two'), 2);
  }

  // Resolves once the GPU has done everything asked of it, without blocking the page.
  /** @returns {Promise<void>} */
  finished() {
    const gl = this.gl;
    const sync = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl.flush();
    return new Promise((resolve, reject) => {
      if (!sync) {
        reject(new Error('the GPU context was lost while tracing'));
        return;
      }
      const poll = () => {
        if (gl.isContextLost()) {
          reject(new Error('the GPU context was lost while tracing'));
          return;
        }
        if (gl.getSyncParameter(sync, gl.SYNC_STATUS) !== gl.SIGNALED) {
          setTimeout(poll, 1);
          return;
        }
        gl.deleteSync(sync);
        resolve();
      };
      poll();
    });
  }

  // Traces the sample grid of `input`: resolves to {width, height, slots (one RGBA32F
  // texture each, the caller's to delete), input, source (the kernel's, as compiled),
  // compileMs, traceMs}. `progress(done, total)` is
  // called after each tile; `cancelled()` (optional) stops between draws (rejects). `whole`:
  // the grid in one tile (a small frame while flying, fly.js: no wait between tiles).
  /**
   * @param {KernelInput} input
   * @param {TraceOptions} [options]
   * @returns {Promise<Traced>}
   */
  async trace(input, { progress = () => {}, cancelled = () => false, whole = false } = {}) {
    const gl = this.gl;
    const u = input.uniforms;
    const [width, height] = u.size;
    if (width > this.maxSize || height > this.maxSize) {
      throw new Error(`the sample grid is ${width}×${height}; this browser\u2019s WebGL `
        + `textures are at most ${this.maxSize}×${this.maxSize}`);
    }
    const buffers = input.draw_buffers;
    if (buffers > this.maxDrawBuffers) {
      throw new Error(`the input asks for ${buffers} render targets; this WebGL2 has `
        + `${this.maxDrawBuffers}`);
    }
    const compileStart = performance.now();
    const { program, source } = this.program(input.defines);

    const table = this.floatTexture(256, input.table_rows);
    gl.bindTexture(gl.TEXTURE_2D, table);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, 256, input.table_rows, gl.RGBA, gl.FLOAT,
      Float32Array.from(input.table));
    /** @type {WebGLTexture[]} */
    const slots = [];
    for (let s = 0; s < input.slots; s += 1) slots.push(this.floatTexture(width, height));
    /** @type {WebGLFramebuffer[]} */
    const framebuffers = [];
    const framebuffer = () => {
      const fb = gl.createFramebuffer();
      framebuffers.push(fb);
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      return fb;
    };
    // The rounds' slots (docs/physics.md, "Rounds"; host.rs draws them alike): two array
    // textures, a round reading one and writing the other; the draws of a round (and of a
    // finishing draw, where the plan has one) each write `buffers` layers from its first
    // slot, so that every draw has the same render targets (a driver compiles a shader again
    // for each set). Then one framebuffer on each array's progress layer, read after each
    // round, and one per record slot of each array and per slot texture, for the copy.
    const { plan } = input;
    const layers = [0, 1].map(() => this.arrayTexture(width, height, plan.layers));
    /**
     * @param {WebGLTexture} texture
     * @param {import('./contract').Span} range
     */
    const drawsInto = (texture, range) => {
      /** @type {{ fb: WebGLFramebuffer, first: number }[]} */
      const list = [];
      for (let first = range.start; first < range.end; first += buffers) {
        const fb = framebuffer();
        const attachments = [];
        for (let i = 0; i < buffers; i += 1) {
          gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, texture, 0, first + i);
          attachments.push(gl.COLOR_ATTACHMENT0 + i);
        }
        gl.drawBuffers(attachments);
        if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) {
          throw new Error('this WebGL2 cannot draw into float array textures');
        }
        list.push({ fb, first });
      }
      return list;
    };
    const roundDraws = layers.map((texture) => drawsInto(texture, plan.rounds));
    const finishRange = plan.finish;
    const finishDraws = finishRange ? layers.map((texture) => drawsInto(texture, finishRange))
      : null;
    /**
     * @param {WebGLTexture} texture
     * @param {number} layer
     */
    const layerFb = (texture, layer) => {
      const fb = framebuffer();
      gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, texture, 0, layer);
      return fb;
    };
    const progressFbs = layers.map((texture) => layerFb(texture, input.slots));
    const recordFbs = layers.map((texture) => slots.map((_, s) => layerFb(texture, s)));
    const slotFbs = slots.map((texture) => {
      const fb = framebuffer();
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
      return fb;
    });

    gl.useProgram(program);
    this.setUniforms(program, u);
    // The render targets cover the whole grid and a draw's viewport is its tile, so
    // gl_FragCoord is already the sample's place in the grid.
    gl.uniform2i(gl.getUniformLocation(program, 'u_origin'), 0, 0);
    const slot0 = gl.getUniformLocation(program, 'u_slot0');
    const round = gl.getUniformLocation(program, 'u_round');
    const finish = gl.getUniformLocation(program, 'u_finish');
    gl.uniform1i(gl.getUniformLocation(program, 'u_budget'), input.first_budget);
    /** @param {number} from */
    const bind = (from) => {
      gl.useProgram(program);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, table);
      gl.activeTexture(gl.TEXTURE1);
      gl.bindTexture(gl.TEXTURE_2D_ARRAY, layers[from]);
      gl.bindVertexArray(this.vao);
      gl.enable(gl.SCISSOR_TEST);
    };
    // One round of a tile (or its finishing draw): reads layers[from], writes `targets`.
    /**
     * @param {{ fb: WebGLFramebuffer, first: number }[]} targets
     * @param {number} roundNo
     * @param {boolean} finishing
     */
    const draw = (targets, roundNo, finishing) => {
      gl.uniform1i(round, roundNo > 0 ? 1 : 0);
      gl.uniform1i(finish, finishing ? 1 : 0);
      for (const { fb, first } of targets) {
        gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
        gl.uniform1i(slot0, first);
        gl.drawArrays(gl.TRIANGLES, 0, 3);
      }
    };
    // Before each wait: the page draws its picture meanwhile (viewer.js, on the default
    // framebuffer), which must not be clipped to this tracer's tile.
    const unbind = () => {
      gl.disable(gl.SCISSOR_TEST);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    };
    bind(0);

    const total = width * height;
    let done = 0;
    let side = whole ? Math.max(width, height) : FIRST_SIDE;
    let compileMs = 0;
    let traceStart = 0;
    try {
      // Drivers compile a program when it first draws (SwiftShader: seconds for this kernel):
      // one sample drawn and waited for first counts as compiling, not as tracing.
      if (!this.warm.has(program)) {
        gl.viewport(0, 0, 1, 1);
        gl.scissor(0, 0, 1, 1);
        draw(roundDraws[1].slice(0, 1), 0, false);
        unbind();
        await this.finished();
        this.warm.add(program);
      }
      compileMs = performance.now() - compileStart;
      traceStart = performance.now();
      for (let row0 = 0; row0 < height;) {
        const rows = Math.min(side, height - row0);
        for (let col0 = 0; col0 < width;) {
          if (cancelled()) throw new Error('tracing was cancelled');
          const cols = Math.min(side, width - col0);
          const started = performance.now();
          // Rounds until every sample of the tile is finished (a sample left unfinished is
          // written as out of work), each round's progress read back.
          let from = 0;
          const phases = new Float32Array(cols * rows * 4);
          for (let r = 0; r < input.max_rounds; r += 1) {
            if (r > 0 && cancelled()) throw new Error('tracing was cancelled');
            bind(from); // the page may have drawn while this tracer waited
            gl.viewport(col0, row0, cols, rows);
            gl.scissor(col0, row0, cols, rows);
            draw(roundDraws[1 - from], r, false);
            from = 1 - from;
            gl.bindFramebuffer(gl.FRAMEBUFFER, progressFbs[from]);
            gl.readPixels(col0, row0, cols, rows, gl.RGBA, gl.FLOAT, phases);
            let finished = true;
            for (let i = 0; i < phases.length; i += 4) {
              if (phases[i] !== input.phase_done) { finished = false; break; }
            }
            unbind();
            if (finished) break;
            if (!whole) await this.finished();
          }
          if (finishDraws) {
            bind(from);
            gl.viewport(col0, row0, cols, rows);
            gl.scissor(col0, row0, cols, rows);
            draw(finishDraws[1 - from], 1, true);
            from = 1 - from;
          }
          // The record's slots into the slot textures, and a sample left unfinished after
          // the rounds out of work (its record's status). The copy of the whole grid is not
          // waited for: its frame is shaded in the same animation frame, the GPU working
          // through it in order.
          gl.disable(gl.SCISSOR_TEST);
          slots.forEach((_, s) => {
            gl.bindFramebuffer(gl.READ_FRAMEBUFFER, recordFbs[from][s]);
            gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, slotFbs[s]);
            gl.blitFramebuffer(col0, row0, col0 + cols, row0 + rows, col0, row0, col0 + cols,
              row0 + rows, gl.COLOR_BUFFER_BIT, gl.NEAREST);
          });
          gl.bindTexture(gl.TEXTURE_2D, slots[0]);
          for (let i = 0; i < phases.length; i += 4) {
            if (phases[i] === input.phase_done) continue;
            const at = i / 4;
            gl.texSubImage2D(gl.TEXTURE_2D, 0, col0 + (at % cols), row0 + Math.floor(at / cols),
              1, 1, gl.RGBA, gl.FLOAT, new Float32Array([-1, WORK_LIMIT, 0, 0]));
          }
          unbind();
          if (!whole) await this.finished();
          done += cols * rows;
          col0 += cols;
          progress(done, total);
          // The next draw's side, for about DRAW_MS a draw.
          const took = Math.max(performance.now() - started, 0.1);
          const scale = Math.min(2, Math.max(0.5, Math.sqrt(DRAW_MS / took)));
          if (!whole) side = Math.round(Math.min(MAX_SIDE, Math.max(MIN_SIDE, side * scale)));
        }
        row0 += rows;
      }
    } catch (e) {
      slots.forEach((t) => gl.deleteTexture(t));
      throw e;
    } finally {
      unbind();
      gl.deleteTexture(table);
      framebuffers.forEach((fb) => gl.deleteFramebuffer(fb));
      layers.forEach((t) => gl.deleteTexture(t));
    }
    return { width, height, slots, input, source, compileMs,
      traceMs: performance.now() - traceStart };
  }

  // The channels the shading reads, from a traced frame: {id (R32UI), u, v, g, t_emit
  // (R32F), cos_i (R16UI), pol and dir (RGBA32F), light (R32F array, a layer per light; null
  // without lights)},
  // new textures the caller owns. `objects`: how many objects the scene has.
  /**
   * @param {Traced} traced
   * @param {number} objects
   * @returns {Channels}
   */
  channels(traced, objects) {
    const gl = this.gl;
    const { width, height, slots, input } = traced;
    const convert = this.convert ??= {
      float: linkProgram(this.gl, CONVERT_FLOAT, 'the channel conversion'),
      uint: linkProgram(this.gl, CONVERT_UINT, 'the channel conversion'),
      vector: linkProgram(this.gl, CONVERT_VECTOR, 'the channel conversion'),
    };
    /** @param {number} internal */
    const target = (internal) => {
      const t = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D, t);
      gl.texStorage2D(gl.TEXTURE_2D, 1, internal, width, height);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      return t;
    };
    const fb = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    gl.viewport(0, 0, width, height);
    gl.bindVertexArray(this.vao);
    // Draws `program` into `attach()`'s target, reading slot `slot` component `component`.
    /**
     * @param {WebGLProgram} program
     * @param {[number, number]} where
     * @param {(loc: (name: string) => WebGLUniformLocation | null) => void} set
     * @param {() => void} attach
     */
    const pass = (program, [slot, component], set, attach) => {
      attach();
      gl.drawBuffers([gl.COLOR_ATTACHMENT0]);
      gl.useProgram(program);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, slots[0]);
      gl.uniform1i(gl.getUniformLocation(program, 'u_record'), 0);
      gl.activeTexture(gl.TEXTURE1);
      gl.bindTexture(gl.TEXTURE_2D, slots[slot]);
      gl.uniform1i(gl.getUniformLocation(program, 'u_slot'), 1);
      gl.uniform1i(gl.getUniformLocation(program, 'u_component'), component);
      set((name) => gl.getUniformLocation(program, name));
      gl.drawArrays(gl.TRIANGLES, 0, 3);
    };
    /** @param {WebGLTexture} texture */
    const into = (texture) => () => gl.framebufferTexture2D(gl.FRAMEBUFFER,
      gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
    /** @type {Channels} */
    const out = { light: null };
    for (const [name, where] of Object.entries(FLOAT_CHANNELS)) {
      const t = target(gl.R32F);
      out[name] = t;
      pass(convert.float, where, (loc) => gl.uniform1i(loc('u_light'), 0), into(t));
    }
    const id = target(gl.R32UI);
    out.id = id;
    pass(convert.uint, [0, 0], (loc) => {
      gl.uniform1i(loc('u_id'), 1);
      gl.uniform1i(loc('u_objects'), objects);
    }, into(id));
    const cosI = target(gl.R16UI);
    out.cos_i = cosI;
    pass(convert.uint, COS_I, (loc) => gl.uniform1i(loc('u_id'), 0), into(cosI));
    for (const [name, where] of Object.entries(VECTOR_CHANNELS)) {
      const t = target(gl.RGBA32F);
      out[name] = t;
      pass(convert.vector, where, () => {}, into(t));
    }
    const lights = input.light_channels.length;
    if (lights > 0) {
      const t = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D_ARRAY, t);
      gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, gl.R32F, width, height, lights);
      gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      input.light_channels.forEach((where, k) => {
        pass(convert.float, where, (loc) => gl.uniform1i(loc('u_light'), 1),
          () => gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, t, 0, k));
      });
      out.light = t;
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(fb);
    return out;
  }

  // The traced slots' floats over the rectangle (x, y, width, height) of the sample grid:
  // one Float32Array of width × height × 4 per slot, grid row y first.
  /**
   * @param {Traced} traced
   * @param {number} x
   * @param {number} y
   * @param {number} width
   * @param {number} height
   */
  readRect(traced, x, y, width, height) {
    const gl = this.gl;
    const fb = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    const out = traced.slots.map((t) => {
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, t, 0);
      gl.readBuffer(gl.COLOR_ATTACHMENT0);
      const data = new Float32Array(width * height * 4);
      gl.readPixels(x, y, width, height, gl.RGBA, gl.FLOAT, data);
      return data;
    });
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(fb);
    return out;
  }

  // The floats of `width` × `height` texels of each of `textures` from (x, y), read back
  // without blocking the page (a pixel-pack buffer, then a fence: the frame in flight goes
  // on being traced meanwhile): resolves to one Float32Array of width × height × 4 per
  // texture, grid row y first.
  /**
   * @param {WebGLTexture[]} textures
   * @param {number} x
   * @param {number} y
   * @param {number} width
   * @param {number} height
   * @returns {Promise<Float32Array[]>}
   */
  async readLater(textures, x, y, width, height) {
    const gl = this.gl;
    const bytes = width * height * 16;
    const buffer = gl.createBuffer();
    const fb = gl.createFramebuffer();
    try {
      gl.bindBuffer(gl.PIXEL_PACK_BUFFER, buffer);
      gl.bufferData(gl.PIXEL_PACK_BUFFER, bytes * textures.length, gl.STREAM_READ);
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      textures.forEach((t, k) => {
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, t, 0);
        gl.readBuffer(gl.COLOR_ATTACHMENT0);
        gl.readPixels(x, y, width, height, gl.RGBA, gl.FLOAT, k * bytes);
      });
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      gl.bindBuffer(gl.PIXEL_PACK_BUFFER, null);
      await this.finished();
      const all = new Float32Array(width * height * 4 * textures.length);
      gl.bindBuffer(gl.PIXEL_PACK_BUFFER, buffer);
      gl.getBufferSubData(gl.PIXEL_PACK_BUFFER, 0, all);
      gl.bindBuffer(gl.PIXEL_PACK_BUFFER, null);
      return textures.map((_, k) => all.subarray(k * width * height * 4,
        (k + 1) * width * height * 4));
    } finally {
      gl.deleteFramebuffer(fb);
      gl.deleteBuffer(buffer);
    }
  }

  // One sample's four channels of every slot (the hovered pixel's record, fly.js), read back
  // without blocking the page.
  /**
   * @param {Traced} traced
   * @param {number} x
   * @param {number} y
   */
  readSample(traced, x, y) {
    return this.readLater(traced.slots, x, y, 1, 1);
  }

  // The traced slots as floats (for tests), the whole grid.
  /** @param {Traced} traced */
  readSlots(traced) {
    return this.readRect(traced, 0, 0, traced.width, traced.height);
  }
}
