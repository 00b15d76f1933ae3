// @ts-check
// godel view: the WebGL2 side. Uploads the arrays the server sends (crates/viewer/src/wire.rs)
// as textures, runs the shading pass (shaders.js) into an offscreen RGBA8 texture the size
// of the picture, and draws that texture on the canvas at any zoom with trilinear filtering.
'use strict';

import { VERTEX, shadeSource, displaySource } from './shaders.js';

/** @typedef {import('./uniforms.js').Features} Features */

/**
 * An array the server sent (crates/viewer/src/wire.rs): width × height samples of
 * `components` each.
 * @typedef {{ width: number, height: number, components: number,
 *   data: Uint8Array | Uint16Array | Uint32Array | Float32Array }} WireArray
 */

/**
 * The shading pass's uniforms by name: [kind, value] (kind: 'i', 'u', 'f', or a vector: 'i2',
 * 'i4', 'f2', 'f3', 'f4'; arrays of vectors flat).
 * @typedef {Record<string, [string, number | number[] | number[][]]>} Uniforms
 */

// ---- the wire format: 16-byte header, then little-endian samples

/**
 * @type {Record<number, Uint8ArrayConstructor | Uint16ArrayConstructor
 *   | Uint32ArrayConstructor | Float32ArrayConstructor>}
 */
const TYPES = { 1: Uint8Array, 2: Uint16Array, 3: Uint32Array, 4: Float32Array };

/**
 * The array at byte `at` of `buffer`.
 * @param {ArrayBuffer} buffer
 * @param {number} [at]
 * @returns {WireArray}
 */
export function parseArray(buffer, at = 0) {
  if (buffer.byteLength < at + 16) throw new Error('the server sent a truncated array');
  const view = new DataView(buffer, at);
  const magic = String.fromCharCode(...new Uint8Array(buffer, at, 4));
  const Type = TYPES[view.getUint8(12)];
  if (magic !== 'GDL1' || !Type) throw new Error('the server sent an array in an unknown format');
  const width = view.getUint32(4, true);
  const height = view.getUint32(8, true);
  const components = view.getUint8(13);
  const length = width * height * components;
  if (buffer.byteLength < at + 16 + length * Type.BYTES_PER_ELEMENT) {
    throw new Error('the server sent a truncated array');
  }
  const data = new Type(buffer, at + 16, length);
  return { width, height, components, data };
}

// The arrays of a sequence (crates/viewer/src/wire.rs): one after another, each padded to a
// multiple of 4 bytes; a single array is a sequence of one.
/**
 * @param {ArrayBuffer} buffer
 * @returns {WireArray[]}
 */
export function parseArrays(buffer) {
  const out = [];
  for (let at = 0; at < buffer.byteLength;) {
    const a = parseArray(buffer, at);
    out.push(a);
    at += Math.ceil((16 + a.data.byteLength) / 4) * 4;
  }
  return out;
}

// Texture formats by typed array and component count.
/**
 * @param {WebGL2RenderingContext} gl
 * @param {WireArray['data']} data
 * @param {number} components
 * @returns {[number, number, number]}
 */
function formatOf(gl, data, components) {
  if (data instanceof Float32Array) {
    return [[gl.R32F, gl.RG32F, gl.RGB32F, gl.RGBA32F][components - 1],
      [gl.RED, gl.RG, gl.RGB, gl.RGBA][components - 1], gl.FLOAT];
  }
  const integer = [gl.RED_INTEGER, gl.RG_INTEGER, gl.RGB_INTEGER, gl.RGBA_INTEGER][components - 1];
  if (data instanceof Uint8Array) return [gl.R8UI, integer, gl.UNSIGNED_BYTE];
  if (data instanceof Uint16Array) return [gl.R16UI, integer, gl.UNSIGNED_SHORT];
  return [gl.R32UI, integer, gl.UNSIGNED_INT];
}

// A program of the full-screen vertex shader and `fragment`; `what` names it in errors. The
// shading here and the traced frames (trace.js) compile through this one function.
/**
 * @param {WebGL2RenderingContext} gl
 * @param {string} fragment
 * @param {string} what
 * @returns {WebGLProgram}
 */
export function linkProgram(gl, fragment, what) {
  /** @type {(type: number, source: string) => WebGLShader} */
  const shader = (type, source) => {
    const s = gl.createShader(type);
    if (!s) throw new Error(`the GPU context was lost while compiling ${what}`);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) {
      const log = gl.getShaderInfoLog(s);
      gl.deleteShader(s);
      throw new Error(`${what} did not compile: ${log}`);
    }
    return s;
  };
  const p = gl.createProgram();
  const [v, f] = [shader(gl.VERTEX_SHADER, VERTEX), shader(gl.FRAGMENT_SHADER, fragment)];
  gl.attachShader(p, v);
  gl.attachShader(p, f);
  gl.linkProgram(p);
  gl.deleteShader(v);
  gl.deleteShader(f);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) {
    if (gl.isContextLost()) throw new Error(`the GPU context was lost while compiling ${what}`);
    throw new Error(`${what} did not link: ${gl.getProgramInfoLog(p)}`);
  }
  return p;
}

export class Gpu {
  /** @param {HTMLCanvasElement} canvas */
  constructor(canvas) {
    const gl = canvas.getContext('webgl2', { antialias: false, alpha: false, depth: false,
      preserveDrawingBuffer: true, premultipliedAlpha: false });
    if (!gl) {
      throw new Error('this browser offers no WebGL2: the viewer shades on the graphics card '
        + 'and needs it (enable hardware acceleration, or start chromium with '
        + '--use-angle=swiftshader --enable-unsafe-swiftshader for software rendering)');
    }
    this.gl = gl;
    this.canvas = canvas;
    this.maxSize = gl.getParameter(gl.MAX_TEXTURE_SIZE);
    this.shadePrograms = new Map(); // by features, compiled when first needed
    this.displayPrograms = [this.program(displaySource(false)), this.program(displaySource(true))];
    this.vao = gl.createVertexArray();
    /** @type {Record<string, WebGLTexture>} */
    this.textures = {};
    /** @type {Record<string, string>} the size of each texture uploadFloatRgba rewrites */
    this.sizes = {};
    /** @type {Map<WebGLProgram, Map<string, WebGLUniformLocation | null>>} */
    this.locations = new Map();
    /**
     * The offscreen picture; its mipmaps are made again when it is next drawn filtered.
     * @type {{ texture: WebGLTexture, framebuffer: WebGLFramebuffer, width: number,
     *   height: number, mipmapsStale: boolean } | null}
     */
    this.shaded = null;
    /** @type {[number, number, Features, Uniforms] | null} the last shading pass, for profiling */
    this.lastShade = null;
    // 1×1 stand-ins for textures a pass does not read.
    this.blank = {
      float: this.texture2d(1, 1, gl.R32F, gl.RED, gl.FLOAT, new Float32Array(1)),
      uint: this.texture2d(1, 1, gl.R8UI, gl.RED_INTEGER, gl.UNSIGNED_BYTE, new Uint8Array(1)),
      rgba: this.texture2d(1, 1, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4)),
      array: this.arrayTexture(1, 1, 1, new Float32Array(1)),
    };
  }

  /** @param {string} fragment */
  program(fragment) {
    return linkProgram(this.gl, fragment, 'a shading program');
  }

  /**
   * @param {number} width
   * @param {number} height
   * @param {string} what
   */
  checkSize(width, height, what) {
    if (width > this.maxSize || height > this.maxSize) {
      throw new Error(`${what} is ${width}×${height}; this browser's WebGL textures are at most `
        + `${this.maxSize}×${this.maxSize}`);
    }
  }

  /**
   * @param {number} width
   * @param {number} height
   * @param {number} internal
   * @param {number} format
   * @param {number} type
   * @param {ArrayBufferView | ImageBitmap | null} data
   * @param {number} [filter]
   */
  texture2d(width, height, internal, format, type, data, filter) {
    const gl = this.gl;
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, t);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    if (data instanceof ImageBitmap) {
      gl.texImage2D(gl.TEXTURE_2D, 0, internal, width, height, 0, format, type, data);
    } else {
      gl.texImage2D(gl.TEXTURE_2D, 0, internal, width, height, 0, format, type, data);
    }
    const f = filter || gl.NEAREST;
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, f);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, f);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    return t;
  }

  /**
   * @param {number} width
   * @param {number} height
   * @param {number} layers
   * @param {Float32Array} data
   */
  arrayTexture(width, height, layers, data) {
    const gl = this.gl;
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, t);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage3D(gl.TEXTURE_2D_ARRAY, 0, gl.R32F, width, height, layers, 0, gl.RED, gl.FLOAT,
      data);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    return t;
  }

  // Stores a parsed array as texture `name` (replacing any earlier one).
  /**
   * @param {string} name
   * @param {WireArray} array
   */
  upload(name, array) {
    this.checkSize(array.width, array.height, name);
    const [internal, format, type] = formatOf(this.gl, array.data, array.components);
    this.replace(name, this.texture2d(array.width, array.height, internal, format, type,
      array.data));
  }

  // The light planes, one layer each.
  /**
   * @param {WireArray[]} planes
   * @param {number} width
   * @param {number} height
   */
  uploadLights(planes, width, height) {
    const data = new Float32Array(width * height * planes.length);
    planes.forEach((p, k) => data.set(p.data, k * width * height));
    this.replace('light', this.arrayTexture(width, height, planes.length, data));
  }

  /**
   * @param {string} name
   * @param {number} width
   * @param {number} height
   * @param {Uint8Array} bytes
   */
  uploadRgba(name, width, height, bytes) {
    const gl = this.gl;
    this.replace(name, this.texture2d(width, height, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, bytes));
  }

  // An image decoded by the browser (the overlay layer's PNG), its bytes as they are: not
  // premultiplied by alpha, no colour conversion.
  /**
   * @param {string} name
   * @param {ImageBitmap} bitmap
   */
  uploadBitmap(name, bitmap) {
    const gl = this.gl;
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
    this.replace(name, this.texture2d(bitmap.width, bitmap.height, gl.RGBA8, gl.RGBA,
      gl.UNSIGNED_BYTE, bitmap));
  }

  // Small tables that change with the settings (the objects') are rewritten in place: a new
  // texture per frame would make the driver set up its state afresh each time.
  /**
   * @param {string} name
   * @param {number} width
   * @param {number} height
   * @param {Float32Array} floats
   */
  uploadFloatRgba(name, width, height, floats) {
    const gl = this.gl;
    const sizes = this.sizes;
    const size = `${width}×${height}`;
    if (this.textures[name] && sizes[name] === size) {
      gl.bindTexture(gl.TEXTURE_2D, this.textures[name]);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, floats);
      return;
    }
    this.replace(name, this.texture2d(width, height, gl.RGBA32F, gl.RGBA, gl.FLOAT, floats));
    sizes[name] = size;
  }

  /**
   * @param {string} name
   * @param {WebGLTexture} texture
   */
  replace(name, texture) {
    if (this.textures[name]) this.gl.deleteTexture(this.textures[name]);
    this.textures[name] = texture;
  }

  /**
   * @param {WebGLProgram} program
   * @param {string} name
   * @returns {WebGLUniformLocation | null}
   */
  location(program, name) {
    let known = this.locations.get(program);
    if (!known) {
      known = new Map();
      this.locations.set(program, known);
    }
    let at = known.get(name);
    if (at === undefined) {
      at = this.gl.getUniformLocation(program, name);
      known.set(name, at);
    }
    return at;
  }

  /** @param {Features} features */
  shadeProgram(features) {
    const key = JSON.stringify(features);
    let program = this.shadePrograms.get(key);
    if (!program) {
      program = this.program(shadeSource(features));
      this.shadePrograms.set(key, program);
    }
    return program;
  }

  // The offscreen picture, resized when the picture's size changes.
  /**
   * @param {number} width
   * @param {number} height
   */
  target(width, height) {
    const gl = this.gl;
    if (this.shaded && this.shaded.width === width && this.shaded.height === height) {
      return this.shaded;
    }
    this.checkSize(width, height, 'the picture');
    if (this.shaded) {
      gl.deleteTexture(this.shaded.texture);
      gl.deleteFramebuffer(this.shaded.framebuffer);
    }
    const texture = this.texture2d(width, height, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, null,
      gl.LINEAR);
    const framebuffer = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
    this.shaded = { texture, framebuffer, width, height, mipmapsStale: true };
    return this.shaded;
  }

  // The shading pass, with the program of `features`: `uniforms` maps names to [kind, value]
  // (kind: 'i', 'u', 'f', or a vector: 'i2', 'i4', 'f2', 'f3', 'f4'; arrays of vectors flat).
  /**
   * @param {number} width
   * @param {number} height
   * @param {Features} features
   * @param {Uniforms} uniforms
   */
  shade(width, height, features, uniforms) {
    this.lastShade = [width, height, features, uniforms];
    const gl = this.gl;
    const target = this.target(width, height);
    const program = this.shadeProgram(features);
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.framebuffer);
    gl.viewport(0, 0, width, height);
    gl.useProgram(program);
    /** @type {[string, string, 'float' | 'uint' | 'rgba'][]} */
    const samplers = [
      ['uId', 'id', 'uint'], ['uU', 'u', 'float'], ['uV', 'v', 'float'], ['uG', 'g', 'float'],
      ['uT', 't_emit', 'float'], ['uCos', 'cos_i', 'uint'], ['uObjects', 'objects', 'float'],
      ['uGt', 'gt', 'float'], ['uAtlas', 'atlas', 'float'], ['uOverlay', 'overlay', 'rgba'],
      ['uPol', 'pol', 'float'], ['uDir', 'dir', 'float'],
    ];
    samplers.forEach(([uniform, name, kind], unit) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, this.textures[name] || this.blank[kind]);
      gl.uniform1i(this.location(program, uniform), unit);
    });
    const unit = samplers.length;
    gl.activeTexture(gl.TEXTURE0 + unit);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.textures.light || this.blank.array);
    gl.uniform1i(this.location(program, 'uLight'), unit);
    for (const [name, [kind, value]] of Object.entries(uniforms)) {
      const at = this.location(program, name);
      if (at === null) continue; // unused by the compiled shader
      if (typeof value === 'number') {
        switch (kind) {
          case 'i': gl.uniform1i(at, value); break;
          case 'u': gl.uniform1ui(at, value); break;
          case 'f': gl.uniform1f(at, value); break;
          default: throw new Error(`uniform kind ${kind} of a number`);
        }
        continue;
      }
      const v = value.flat();
      switch (kind) {
        case 'i2': gl.uniform2iv(at, v); break;
        case 'i4': gl.uniform4iv(at, v); break;
        case 'f2': gl.uniform2fv(at, v); break;
        case 'f3': gl.uniform3fv(at, v); break;
        case 'f4': gl.uniform4fv(at, v); break;
        default: throw new Error(`uniform kind ${kind} of a vector`);
      }
    }
    gl.bindVertexArray(this.vao);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    target.mipmapsStale = true;
  }

  // Draws the offscreen picture on the canvas: its top-left corner at canvas pixel `offset`,
  // `zoom` canvas pixels per picture pixel; filtered (mipmaps made when first needed) unless
  // it is shown texel for texel.
  /**
   * @param {[number, number]} offset
   * @param {number} zoom
   */
  display(offset, zoom) {
    const gl = this.gl;
    const shaded = this.shaded;
    if (!shaded) return;
    const filtered = zoom !== 1 || !Number.isInteger(offset[0]) || !Number.isInteger(offset[1]);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, shaded.texture);
    if (filtered && shaded.mipmapsStale) {
      gl.generateMipmap(gl.TEXTURE_2D);
      shaded.mipmapsStale = false;
    }
    // Without mipmaps a mipmapping filter would leave the texture incomplete (black).
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER,
      filtered ? gl.LINEAR_MIPMAP_LINEAR : gl.NEAREST);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    const p = this.displayPrograms[filtered ? 1 : 0];
    gl.useProgram(p);
    gl.uniform1i(this.location(p, 'uShaded'), 0);
    gl.uniform2f(this.location(p, 'uShadedSize'), shaded.width, shaded.height);
    gl.uniform2f(this.location(p, 'uCanvas'), this.canvas.width, this.canvas.height);
    gl.uniform2f(this.location(p, 'uOffset'), offset[0], offset[1]);
    gl.uniform1f(this.location(p, 'uZoom'), zoom);
    gl.bindVertexArray(this.vao);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  // The offscreen picture's RGBA bytes, row 0 (the top of the picture) first.
  readShaded() {
    const gl = this.gl;
    if (!this.shaded) throw new Error('nothing has been shaded yet');
    const { framebuffer, width, height } = this.shaded;
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    const out = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, out);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return { width, height, bytes: out };
  }

  // Waits until the GPU has drawn everything asked of it (reading one pixel back).
  finish() {
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
  }

  // The canvas's RGBA bytes, top row first.
  readCanvas() {
    const gl = this.gl;
    const { width, height } = this.canvas;
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    const raw = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, raw);
    const out = new Uint8Array(raw.length);
    const row = width * 4;
    for (let y = 0; y < height; y += 1) {
      out.set(raw.subarray((height - 1 - y) * row, (height - y) * row), y * row);
    }
    return { width, height, bytes: out };
  }
}
