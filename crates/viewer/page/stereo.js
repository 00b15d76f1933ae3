// @ts-check
// godel view: a stereo pair's picture. Viewing one eye's data file of a stereo pair
// (NAME.left.exr) with the other eye's beside it, the Stereo panel shows both eyes shaded by
// the server with the page's settings (POST /api/stereo/png, as "Save PNG" sends them) in
// the layout chosen (the pair's at first: side by side, over-under, or an anaglyph for
// red/cyan glasses). The picture follows the settings and the layout, a little after the
// last change (a slider dragged asks once), and one request at a time: what changed while
// one was under way is asked for when it ends. The page's own canvas stays the one eye,
// shaded on the GPU; without the other eye's file the panel says so.
'use strict';

import { errorText, messageOf, postJson } from './api.js';
import { $ } from './dom.js';

/** How long the settings rest before the picture is asked for, in ms. */
const SETTLE_MS = 250;

/**
 * The Stereo panel's state, read by the tests: whether a picture is wanted or being made,
 * how many were shown, the last refusal (null once a picture came).
 * @typedef {object} StereoState
 * @property {boolean} busy
 * @property {number} shown
 * @property {string | null} error
 */

/**
 * Shows the Stereo panel when the file is one eye of a stereo pair; returns what to call
 * when the settings change (nothing to do for a mono file or without the other eye).
 * @param {import('./viewer.js').LoadedViewer} viewer
 * @param {(message: string) => void} showError shows a message as the page's errors
 * @returns {() => void}
 */
export function startStereo(viewer, showError) {
  const pair = viewer.info.stereo;
  if (!pair) return () => {};
  $('stereo-panel').hidden = false;
  const status = $('stereo-status');
  if (!pair.partner) {
    status.textContent = `the ${pair.eye} eye of a stereo pair; the other eye\u2019s data file `
      + 'is not beside it, so only this eye is shown';
    return () => {};
  }
  $('stereo-pair').hidden = false;
  const select = $('stereo-layout', HTMLSelectElement);
  const img = $('stereo-image', HTMLImageElement);
  select.value = pair.layout;
  /** @type {StereoState} */
  const state = { busy: false, shown: 0, error: null };
  viewer.stereo = state;
  /** @type {ReturnType<typeof setTimeout> | undefined} */
  let timer;
  let inFlight = false;
  // What the picture on show (or refused) was asked with: layout and settings.
  let asked = '';
  const wish = () => `${select.value}\n${JSON.stringify(viewer.settings)}`;

  const ask = async () => {
    if (inFlight) return; // asked again when this one ends
    const key = wish();
    if (key === asked) {
      state.busy = false;
      return;
    }
    inFlight = true;
    asked = key;
    status.textContent = 'shading both eyes…';
    try {
      const url = `/api/stereo/png?layout=${encodeURIComponent(select.value)}`;
      const response = await postJson(url, JSON.stringify(viewer.settings), { patient: true });
      if (!response.ok) throw new Error(await errorText(response));
      const shown = URL.createObjectURL(await response.blob());
      const before = img.src;
      img.src = shown;
      await img.decode();
      if (before.startsWith('blob:')) URL.revokeObjectURL(before);
      state.shown += 1;
      state.error = null;
      status.textContent = `both eyes, ${select.value} (${img.naturalWidth}×${img.naturalHeight})`;
    } catch (e) {
      state.error = `stereo picture: ${messageOf(e)}`;
      status.textContent = 'no stereo picture';
      showError(state.error);
    } finally {
      inFlight = false;
    }
    if (wish() === asked) state.busy = false;
    else settle();
  };
  const settle = () => {
    state.busy = true;
    clearTimeout(timer);
    timer = setTimeout(ask, SETTLE_MS);
  };
  select.addEventListener('change', settle);
  settle();
  return settle;
}
