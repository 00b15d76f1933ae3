// @ts-check
// godel explore: keeping what one flies (docs/guide/src/explore.md; the server's side is
// crates/viewer/src/keep_routes.rs). Everything here reads the view on screen only through
// `viewer.explore.view()`: the scene file's observer fields and camera.
//
// - "Render exactly" sends that view, at the size and samples chosen here, to the server's
//   CPU exact tracer (one render at a time), shows its progress, and then links its PNG and
//   data file (EXR) for download: the files `godel render` writes for the scene with the
//   view's fields.
// - "Record" samples the view while one flies: a keyframe whenever it changed, at most one
//   per MIN_GAP_S of wall-clock time (the newest view when the gap has passed) and at most
//   the server's max_keyframes; Stop adds the view at the end, so that the sequence lasts as
//   long as the flight. The server turns the keyframes into a sequence script for
//   `godel sequence`, linked for download.
'use strict';

import { errorText, getJson, messageOf, postJson } from './api.js';
import { $ } from './dom.js';

/** @typedef {import('./contract').View} View */
/** @typedef {import('./contract').RecordedView} RecordedView */

/**
 * What is kept (tests read it): the exact render asked for (its job, state and view), and the
 * recording (whether under way, its keyframes, the script made of them).
 * @typedef {object} KeepState
 * @property {number | null} job
 * @property {import('./contract').JobState | null} state
 * @property {View | null} view
 * @property {boolean} recording
 * @property {RecordedView[]} keyframes
 * @property {string | null} script
 */

// At most one keyframe per this many seconds of wall-clock time.
const MIN_GAP_S = 0.25;
// How often the view is sampled while recording, and an exact render's progress asked for.
const SAMPLE_MS = 50;
const PROGRESS_MS = 250;
// The samples per pixel a render may ask for (square numbers, as the scene file's).
const SAMPLES = [1, 4, 9, 16, 25, 36, 49, 64];

// A busy server (503: its shading slots taken by other tabs or frames) is asked again.
/**
 * @param {string} url
 * @param {unknown} body
 */
const post = (url, body) => postJson(url, body, { patient: true });

/**
 * @param {import('./viewer.js').LoadedViewer} viewer
 * @param {import('./explore.js').Explore} explore
 */
export async function startKeep(viewer, explore) {
  /** @type {import('./contract').OwnView} */
  let limits;
  try {
    limits = /** @type {import('./contract').OwnView} */ (await getJson('/api/explore/view'));
  } catch (_) {
    return;
  }
  /** @type {KeepState} */
  const keep = { job: null, state: null, view: null, recording: false, keyframes: [],
    script: null };
  viewer.keep = keep;
  const own = explore.view();
  const width = $('keep-width', HTMLInputElement);
  const height = $('keep-height', HTMLInputElement);
  width.value = String(own.camera.width);
  height.value = String(own.camera.height);
  const samples = $('keep-samples', HTMLSelectElement);
  for (const n of new Set([...SAMPLES, own.camera.samples])) {
    const option = document.createElement('option');
    option.value = String(n);
    option.textContent = String(n);
    samples.append(option);
  }
  samples.value = String(own.camera.samples);

  // ---- Render exactly
  /** @param {string} text */
  const status = (text) => { $('keep-status').textContent = text; };
  /**
   * @param {string} id
   * @param {string | null} url
   */
  const show = (id, url) => {
    const link = $(id, HTMLAnchorElement);
    link.hidden = url === null;
    if (url) {
      link.href = url;
      link.download = '';
    }
  };
  /** @type {number | null} */
  let polling = null;
  async function progress() {
    /** @type {import('./contract').ExactJob | null} */
    let job;
    try {
      job = /** @type {import('./contract').ExactStatus} */ (
        await getJson('/api/explore/exact')).job;
    } catch (e) {
      status(`cannot reach the server: ${messageOf(e)}`);
      return;
    }
    if (!job || job.id !== keep.job) return;
    keep.state = job.state;
    const rendering = job.state === 'rendering';
    const bar = $('keep-progress', HTMLProgressElement);
    bar.hidden = !rendering;
    $('keep-cancel').hidden = !rendering;
    $('keep-render', HTMLButtonElement).disabled = rendering;
    if (rendering) {
      bar.value = job.total > 0 ? job.done / job.total : 0;
      status(`rendering exactly: ${job.done} of ${job.total || '…'} rays`);
      return;
    }
    if (polling !== null) clearInterval(polling);
    polling = null;
    if (job.state === 'done') {
      show('keep-png', job.png);
      show('keep-exr', job.exr);
      status(`rendered exactly: ${job.summary}`);
    } else if (job.state === 'failed') {
      status(`the exact render failed: ${job.error}`);
    } else {
      status('the exact render was cancelled');
    }
  }
  $('keep-render').addEventListener('click', async () => {
    const view = explore.view();
    view.camera.width = Number(width.value);
    view.camera.height = Number(height.value);
    view.camera.samples = Number(samples.value);
    show('keep-png', null);
    show('keep-exr', null);
    let response;
    try {
      response = await post('/api/explore/exact', view);
    } catch (e) {
      status(`cannot reach the server: ${messageOf(e)}`);
      return;
    }
    if (!response.ok) {
      status(await errorText(response));
      return;
    }
    keep.job = /** @type {import('./contract').ExactStarted} */ (await response.json()).job;
    keep.view = view;
    keep.state = 'rendering';
    status('rendering exactly…');
    if (polling === null) polling = window.setInterval(progress, PROGRESS_MS);
  });
  $('keep-cancel').addEventListener('click', () => post('/api/explore/exact/cancel', {}));

  // ---- Record
  /** @param {string} text */
  const recordStatus = (text) => { $('keep-record-status').textContent = text; };
  let started = 0;
  /** @type {number | null} */
  let sampler = null;
  let lastText = '';
  let pending = false;
  const now = () => (performance.now() - started) / 1000;
  /**
   * @param {number} seconds
   * @param {View} view
   */
  const take = (seconds, view) => {
    keep.keyframes.push({ seconds, view });
    lastText = JSON.stringify(view);
    pending = false;
  };
  function sample() {
    const view = explore.view();
    if (JSON.stringify(view) !== lastText) pending = true;
    const last = keep.keyframes[keep.keyframes.length - 1];
    const seconds = now();
    if (pending && seconds - last.seconds >= MIN_GAP_S) take(seconds, view);
    recordStatus(`recording: ${keep.keyframes.length} keyframes, ${seconds.toFixed(1)} s`);
    // One place is kept for the view at Stop.
    if (keep.keyframes.length >= limits.max_keyframes - 1) stop();
  }
  function start() {
    keep.recording = true;
    keep.keyframes = [];
    keep.script = null;
    show('keep-script', null);
    started = performance.now();
    take(0, explore.view());
    sampler = window.setInterval(sample, SAMPLE_MS);
    $('keep-record').textContent = 'Stop';
  }
  async function stop() {
    if (sampler !== null) clearInterval(sampler);
    keep.recording = false;
    $('keep-record').textContent = 'Record';
    const last = keep.keyframes[keep.keyframes.length - 1];
    take(Math.max(now(), last.seconds + MIN_GAP_S), explore.view());
    const n = keep.keyframes.length;
    let response;
    try {
      /** @type {import('./contract').RecordRequest} */
      const recording = { keyframes: keep.keyframes };
      response = await post('/api/explore/record', recording);
    } catch (e) {
      recordStatus(`cannot reach the server: ${messageOf(e)}`);
      return;
    }
    if (!response.ok) {
      recordStatus(await errorText(response));
      return;
    }
    const disposition = response.headers.get('Content-Disposition') || '';
    const name = (disposition.match(/filename="([^"]+)"/) || [])[1] || 'flight.toml';
    const text = await response.text();
    keep.script = text;
    const link = $('keep-script', HTMLAnchorElement);
    if (link.href.startsWith('blob:')) URL.revokeObjectURL(link.href);
    link.href = URL.createObjectURL(new Blob([text], { type: 'application/toml' }));
    link.download = name;
    link.hidden = false;
    const seconds = keep.keyframes[n - 1].seconds;
    recordStatus(`recorded ${n} keyframes over ${seconds.toFixed(1)} s: render the script with `
      + `godel sequence ${name}`);
  }
  $('keep-record').addEventListener('click', () => (keep.recording ? stop() : start()));
}
