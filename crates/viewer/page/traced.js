// @ts-check
// godel view: the frame traced on the GPU. The "Trace on the GPU" switch (or the URL
// parameter ?trace=gpu) makes the page trace the data file's own scene with the exact
// tracer's kernel (trace.js, in WebGL2) and shade that frame instead of the file's: every
// layer and control works on it as on the file's, and the header says how long it took.
// Unchecking it stops a trace under way and fetches the file's channels again. Hover still
// shows the file's records.
'use strict';

import { getJson, getText, messageOf } from './api.js';
import { $ } from './dom.js';
import { KernelTracer } from './trace.js';

/** @typedef {import('./trace.js').Traced} Traced */

/**
 * The "Trace on the GPU" switch's state: whether a trace is under way, the frame traced (its
 * slots kept for tests to read back), why the last trace failed.
 * @typedef {object} TracedState
 * @property {boolean} tracing
 * @property {Traced | null} traced
 * @property {string | null} error
 * @property {() => object} readSlots for tests: the traced slots as floats (base64 per slot)
 */

/** @param {import('./viewer.js').LoadedViewer} viewer */
export function startTraced(viewer) {
  const box = $('trace-gpu', HTMLInputElement);
  const status = $('trace-status');
  // Explore mode traces on the server (its GPU frames come with a later version).
  if (viewer.explore) return;
  $('trace-panel').hidden = false;
  /** @type {KernelTracer | null} */
  let tracer = null;
  /** @type {import('./contract').KernelInput | null} */
  let input = null;
  /** @type {TracedState} */
  const state = { tracing: false, traced: null, error: null, readSlots };
  viewer.traced = state;

  /** @param {boolean} on */
  const show = async (on) => {
    if (state.tracing) return; // unchecked while tracing: the trace stops after its draw
    if (!on) {
      viewer.showFileFrame();
      status.textContent = 'showing the data file\u2019s frame';
      return;
    }
    state.tracing = true;
    state.error = null;
    status.classList.remove('failed');
    viewer.hold(true);
    try {
      const gl = viewer.gpu().gl;
      if (!tracer) tracer = new KernelTracer(gl, await getText('/api/gpu/kernel'));
      if (!input) {
        input = /** @type {import('./contract').KernelInput} */ (await getJson(
          `/api/gpu/input?draw_buffers=${tracer.maxDrawBuffers}`));
      }
      status.textContent = 'compiling the kernel…';
      // Let the status show before the (blocking) compilation.
      await new Promise((resolve) => { requestAnimationFrame(() => setTimeout(resolve, 0)); });
      const traced = await tracer.trace(input, {
        progress: (done, total) => {
          status.textContent = `tracing on the GPU: ${Math.round(100 * done / total)} %`;
        },
        cancelled: () => !box.checked,
      });
      if (state.traced) state.traced.slots.forEach((t) => gl.deleteTexture(t));
      state.traced = traced;
      const channels = tracer.channels(traced, viewer.info.objects.length);
      const ms = Math.round(traced.traceMs);
      const rays = traced.width * traced.height;
      viewer.showTracedFrame(channels, `traced on the GPU in ${ms} ms`);
      status.textContent = `${rays} rays in ${ms} ms (${Math.round(rays / traced.traceMs * 1e3)}`
        + ` rays/s; kernel compiled in ${Math.round(traced.compileMs)} ms)`;
    } catch (e) {
      // Said in the panel (the page's error line clears with the next picture drawn).
      if (box.checked) {
        state.error = messageOf(e);
        status.textContent = `cannot trace on the GPU: ${state.error}; showing the data `
          + 'file\u2019s frame';
        status.classList.add('failed');
      } else {
        status.textContent = 'showing the data file\u2019s frame';
      }
      box.checked = false;
      viewer.showFileFrame();
    } finally {
      state.tracing = false;
      viewer.hold(false);
    }
  };
  box.addEventListener('change', () => show(box.checked));
  // For tests: the traced slots as floats (base64 per slot), the grid's size, the kernel's
  // source as compiled and the defines the server sent.
  function readSlots() {
    const t = state.traced;
    if (!t || !tracer) throw new Error('no frame has been traced on the GPU');
    const slots = tracer.readSlots(t).map((f) => viewer.base64(new Uint8Array(f.buffer)));
    return { width: t.width, height: t.height, slots, traceMs: t.traceMs,
      compileMs: t.compileMs, source: t.source, defines: t.input.defines,
      drawBuffers: t.input.draw_buffers };
  }
  if (new URLSearchParams(window.location.search).get('trace') === 'gpu') {
    box.checked = true;
    show(true);
  }
}
