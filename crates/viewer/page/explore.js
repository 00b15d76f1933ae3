// @ts-check
// godel explore: the Explore panel, shown only when the server is in explore mode
// (crates/viewer/src/explore_routes.rs). The observer's event (t, x, y, z) is sent to the
// server, which traces it again, a coarse frame first, then the full one; the page polls for
// the newest frame and swaps its channels in (viewer.showFrame), shading them on the GPU as
// usual. Requests never block the page: at most one event request is in flight (the newest
// event waits for it), and a frame of a generation older than the newest request sent is
// dropped. The map beside the picture (map.js) follows the event, shows the light ray of the
// hovered pixel of the frame shown, and moves the observer when its marker is dragged.
// "Save observer keyframe" downloads a sequence-script keyframe at the event; `state.view()`
// is the view on screen for "Render exactly" and "Record" (keep.js).
//
// Where the GPU kernel can trace the scene in this browser, the page traces every frame
// itself and flies (fly.js); `?trace=server` (or a browser that cannot) keeps the server's
// frames, and the status line says why; so does a page whose tracer disagrees with the
// server's CPU tracer (fly.js checks it), from then on, and its header says why.
'use strict';

import { errorText, getJson, messageOf, postJson } from './api.js';
import { exploreChannels } from './data.js';
import { $, query } from './dom.js';
import { startFly } from './fly.js';
import { startKeep } from './keep.js';
import { createMap } from './map.js';

/** @typedef {import('./contract').ObserverEvent} ObserverEvent */
/** @typedef {import('./contract').View} View */
/** @typedef {import('./contract').Level} Level */

/**
 * Explore mode's state (viewer.explore; tests read it): the observer's event, the newest
 * generation this page asked for and the frame on the GPU, whether an event request is in
 * flight (and the newest event waits for it: `again`), Play, the last error; the view on
 * screen, the map; and the hooks the flight (fly.js) adds while this page traces its own
 * frames (absent before, and removed when its tracer is refused: then `refused` says why).
 * @typedef {object} Explore
 * @property {ObserverEvent} event
 * @property {number} requested
 * @property {{ generation: number, level: Level } | null} shown
 * @property {boolean} inFlight
 * @property {boolean} again
 * @property {boolean} playing
 * @property {string | null} error
 * @property {() => View} view the view on screen as the scene file's fields (keep.js)
 * @property {import('./map.js').MapPanel} map
 * @property {() => void} hover the map's ray of the pixel under the pointer, in the frame shown
 * @property {(e: ObserverEvent) => void} showEvent the fields follow the flight
 * @property {(note: string) => void} traceOnServer the page's tracer was refused
 * @property {string} [refused]
 * @property {import('./contract').CheckAnswer} [refusedCheck]
 * @property {import('./fly.js').FlightNumbers | null} [fly]
 * @property {((view: View) => void) | null} [onView]
 * @property {((level: string) => void) | null} [onShown] set by tests
 * @property {(width: number, height: number) => import('./contract').KernelUniforms} [uniforms]
 * @property {(col: number, row: number) => Promise<import('./hovered.js').SampleRecord
 *   & { col: number, row: number } | null>} [hoverRecord]
 * @property {() => number} [hoverFrame]
 * @property {(col: number, row: number) => import('./map.js').TracedRay | null} [hoverRay]
 * @property {() => { width: number, height: number, slots: string[] }} [readSlots]
 * @property {(e: ObserverEvent) => Promise<void>} [setEvent]
 */

// How often the page asks for the newest frame (a frame waits half of it on average).
const POLL_MS = 40;
// The time slider spans this much on each side of the scene's observer time.
const T_SPAN = 50;
// What PageUp/PageDown add to z.
const Z_STEP = 0.05;

/** @type {Record<Level, number>} */
const LEVELS = { coarse: 0, full: 1 };

/** @param {import('./viewer.js').LoadedViewer} viewer */
export async function startExplore(viewer) {
  /** @type {import('./contract').Exploring} */
  let info;
  /** @type {View} */
  let own;
  try {
    const answer = /** @type {import('./contract').ExploreInfo} */ (
      await getJson('/api/explore/info'));
    if (!answer.explore) return; // godel view
    info = answer;
    // The view on screen as the scene file's fields (keep.js renders and records it): the
    // scene's own observer and camera, moved to the event.
    own = /** @type {import('./contract').OwnView} */ (await getJson('/api/explore/view')).view;
  } catch (_) {
    return;
  }
  /** @returns {View} */
  const serverView = () => ({ ...structuredClone(own), time: state.event.t,
    position: { x: state.event.x, y: state.event.y, z: state.event.z } });
  // A look-around view leaves room for the map below it.
  viewer.lookShare = 0.4;
  viewer.layout();
  $('explore-panel').hidden = false;
  document.title = 'godel explore';
  query('header h1').textContent = 'godel explore';
  $('map-panel').hidden = false;
  const slider = $('explore-t', HTMLInputElement);
  slider.min = String(info.start.t - T_SPAN);
  slider.max = String(info.start.t + T_SPAN);
  const tValue = $('explore-t-value', HTMLInputElement);
  const rate = $('explore-rate', HTMLInputElement);
  const play = $('explore-play');
  /** @type {Record<'x' | 'y' | 'z', HTMLInputElement>} */
  const fields = { x: $('explore-x', HTMLInputElement), y: $('explore-y', HTMLInputElement),
    z: $('explore-z', HTMLInputElement) };

  const showFields = () => {
    slider.value = String(state.event.t);
    tValue.value = state.event.t.toFixed(2);
    for (const [k, input] of Object.entries(fields)) {
      input.value = String(state.event[/** @type {'x' | 'y' | 'z'} */ (k)]);
    }
  };
  /** @param {string} text */
  const status = (text) => { $('explore-status').textContent = text; };
  const map = createMap($('map-top', HTMLCanvasElement), $('map-side', HTMLCanvasElement),
    $('map-legend'), {
      status,
      dragTo: (x, y) => {
        state.event.x = x;
        state.event.y = y;
        moved();
      },
    });
  /** @type {Explore} */
  const state = {
    event: { ...info.start },
    requested: info.generation, // the newest generation this page asked for
    shown: null,                // {generation, level} of the frame on the GPU
    inFlight: false,
    again: false,
    playing: false,
    error: null,
    view: serverView,
    map,
    hover,
    // The fields follow the flight.
    showEvent: (e) => {
      state.event = { ...e };
      showFields();
    },
    traceOnServer,
  };
  viewer.explore = state;
  // The event changed: show it, trace it, map it.
  const moved = () => {
    showFields();
    send();
    map.update(state.event);
  };

  // Sends the current event; while a request is in flight, the newest event waits for it.
  async function send() {
    if (state.setEvent) {
      state.setEvent(state.event);
      return;
    }
    if (state.inFlight) {
      state.again = true;
      return;
    }
    state.inFlight = true;
    try {
      // While playing, coarse frames only: a full frame would be cancelled by the next
      // time anyway, and would take the cores from its coarse frame.
      /** @type {import('./contract').EventRequest} */
      const asked = { ...state.event, refine: !state.playing };
      const response = await postJson('/api/explore/event', asked);
      if (response.ok) {
        const answer = /** @type {import('./contract').EventAnswer} */ (await response.json());
        state.requested = Math.max(state.requested, answer.generation);
        state.error = null;
      } else {
        state.error = await errorText(response);
        status(state.error);
      }
    } catch (e) {
      state.error = `cannot reach the server: ${messageOf(e)}`;
      status(state.error);
    } finally {
      state.inFlight = false;
    }
    if (state.again) {
      state.again = false;
      send();
    }
  }

  /** @param {import('./contract').FrameInfo} frame */
  const newer = (frame) => state.shown === null || frame.generation > state.shown.generation
    || (frame.generation === state.shown.generation
      && LEVELS[frame.level] > LEVELS[state.shown.level]);

  let polling = false;
  async function poll() {
    if (polling) return;
    polling = true;
    try {
      const answer = /** @type {import('./contract').FrameAnswer} */ (
        await getJson('/api/explore/frame'));
      const frame = answer.frame;
      if (answer.error && answer.generation === state.requested) status(answer.error);
      // A frame of an older generation than the newest request is dropped.
      if (frame && frame.generation >= state.requested && newer(frame)) {
        const url = exploreChannels(frame);
        // The picture keeps the shape of the full frames: a coarse frame (its size rounded)
        // moves nothing below it, such as the map under a dragging mouse.
        if (frame.level === 'full') viewer.aspect = frame.width / frame.height;
        if (viewer.showFrame(frame, url)) {
          state.shown = { generation: frame.generation, level: frame.level };
          hover(); // the ray of the pixel under the mouse in the new frame
          const e = frame.event;
          status(`frame ${frame.generation} (${frame.level}, ${frame.width}×${frame.height})`
            + ` at t = ${e.t.toFixed(2)}, x = ${e.x}, y = ${e.y}, z = ${e.z}`);
        }
      }
    } catch (_) {
      // The next poll tries again.
    } finally {
      polling = false;
    }
  }
  setInterval(() => { if (!state.fly) poll(); }, POLL_MS);

  // `playing`: sent only once the last request has a frame on the page, so that playing
  // never cancels every trace before it ends (the frame rate is that of the coarse frames).
  // The next coarse frame is traced while the page loads and shades this one: the server
  // keeps the frame the newest replaced, and the page takes no new frame while loading.
  /**
   * @param {number} t
   * @param {boolean} [playing]
   */
  const setT = (t, playing = false) => {
    const lo = Number(slider.min);
    const hi = Number(slider.max);
    if (!Number.isFinite(t)) return;
    state.event.t = Math.min(hi, Math.max(lo, t));
    showFields();
    const waiting = state.inFlight || state.shown === null || state.shown.generation < state.requested;
    if (!playing || !waiting) send();
    map.update(state.event);
  };
  slider.addEventListener('input', () => setT(Number(slider.value)));
  tValue.addEventListener('change', () => setT(Number(tValue.value)));
  for (const [k, input] of Object.entries(fields)) {
    input.addEventListener('change', () => {
      const v = Number(input.value);
      if (input.value.trim() === '' || !Number.isFinite(v)) {
        status(`${k}: not a number`);
        showFields();
        return;
      }
      state.event[/** @type {'x' | 'y' | 'z'} */ (k)] = v;
      moved();
    });
  }
  window.addEventListener('keydown', (event) => {
    if (event.target instanceof HTMLInputElement && event.target.type !== 'range') return;
    const dz = event.key === 'PageUp' ? Z_STEP : event.key === 'PageDown' ? -Z_STEP : undefined;
    if (dz === undefined) return;
    event.preventDefault();
    state.event.z = Math.round((state.event.z + dz) * 1e6) / 1e6;
    moved();
  });

  // Play: t advances at the chosen rate (t per second of the wall clock) while playing.
  /** @type {number | null} */
  let last = null;
  /** @param {number} now */
  function tick(now) {
    if (!state.playing) return;
    if (last !== null) {
      const r = Number(rate.value);
      if (Number.isFinite(r) && r !== 0) setT(state.event.t + r * (now - last) / 1000, true);
    }
    last = now;
    requestAnimationFrame(tick);
  }
  play.addEventListener('click', () => {
    state.playing = !state.playing;
    play.textContent = state.playing ? 'Pause' : 'Play';
    last = null;
    if (state.playing) requestAnimationFrame(tick);
    else send(); // paused: the full frame of where time stopped
  });
  // Hovering the picture: the light ray of the pixel under the mouse, in the frame shown.
  /** @type {{ clientX: number, clientY: number } | null} */
  let pointer = null;
  function hover() {
    if (pointer === null) return;
    const pixel = viewer.pixelAt(pointer);
    // Flying: the frame traced in this page (fly.js reads the pixel's record from it).
    const traced = pixel && state.hoverRay ? state.hoverRay(pixel[0], pixel[1]) : null;
    if (traced) map.hoverTraced(traced);
    else if (pixel && !state.fly && state.shown !== null) map.hover(state.shown, pixel[0], pixel[1]);
    else map.clearRay();
  }
  const image = $('image', HTMLCanvasElement);
  image.addEventListener('pointermove', (event) => {
    pointer = { clientX: event.clientX, clientY: event.clientY };
    hover();
  });
  image.addEventListener('pointerleave', () => {
    pointer = null;
    map.clearRay();
  });

  $('explore-save-keyframe').addEventListener('click', async () => {
    // Flying: the view on screen, with the velocity, axes and fields of view flown; else the
    // scene's observer at the panel's event.
    const blob = state.fly
      ? await viewer.download('/api/explore/view-keyframe?frame=0', JSON.stringify(state.view()),
        'keyframe.toml')
      : await viewer.download('/api/explore/keyframe?frame=0', JSON.stringify(state.event),
        'keyframe.toml');
    if (blob) {
      $('explore-keyframe').textContent = await blob.text();
      $('explore-keyframe').hidden = false;
    }
  });
  showFields();
  map.update(state.event);
  // The page's tracer was refused (fly.js checks it against the server's CPU tracer): the
  // server's frames from now on, of the event flown to, coarse then full; `note` says why in
  // the header.
  /** @param {string} note */
  function traceOnServer(note) {
    state.refused = note;
    state.fly = null;
    for (const k of /** @type {const} */ (['hoverRecord', 'hoverFrame', 'hoverRay', 'readSlots',
      'uniforms', 'setEvent'])) delete state[k];
    state.view = serverView;
    play.hidden = false;
    if (rate.parentElement) rate.parentElement.hidden = false;
    viewer.noteFrames(note);
    status(note);
    state.shown = null;
    send();
  }
  if (new URLSearchParams(window.location.search).get('trace') === 'server') {
    status('tracing on the server (?trace=server)');
  } else if (await startFly(viewer, state, map, status)) {
    // Time runs with the flight's own controls (proper time), not the server's Play.
    play.hidden = true;
    if (rate.parentElement) rate.parentElement.hidden = true;
  }
  startKeep(viewer, state);
}
