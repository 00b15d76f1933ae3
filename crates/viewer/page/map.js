// @ts-check
// godel explore: the map beside the picture. Draws what the server's /api/explore/map and
// /api/explore/ray say (crates/render/src/map.rs; docs/physics.md, "The explore map") on two
// canvases:
// - the top view, the x–y plane (the r–φ plane) at equal scales: the observer's optical
//   horizon (r = 2a about the observer's axis, "Conventions"), each object's worldline track
//   and where it is at the observer's time, the observer (a marker that can be dragged), and
//   the light ray of the hovered pixel, from its emission event to the observer;
// - the side view, t against r, the distance from the observer's axis, with the same things.
// In a Gödel-type member (`map.member`, docs/physics.md "The Gödel-type family") lengths are
// the member's own coordinates, the distance from the axis is the proper radius ρ, and the
// horizon is the circle ρ = ρ_c, where closed timelike curves begin (none in a causal member).
// Requests never pile up: at most one map and one ray request are in flight; the newest wish
// waits for it, older wishes are dropped.
'use strict';

import { getJson } from './api.js';

/** @typedef {import('./contract').ExploreMap} ExploreMap */
/** @typedef {import('./contract').ObserverEvent} ObserverEvent */
/** @typedef {import('./contract').MapPoint} MapPoint */
/** @typedef {import('./hovered.js').SampleRay} SampleRay */

/**
 * A plot's size and the room its axes take, CSS pixels.
 * @typedef {{ width: number, height: number, left: number, right: number, top: number,
 *   bottom: number }} Box
 */

/**
 * The top view's window: centre and half-size in map units.
 * @typedef {{ cx: number, cy: number, half: number }} TopWindow
 */

/**
 * A hovered pixel's ray to show: of a server frame (fetched from /api/explore/ray), or of a
 * frame traced in the page (`load` makes it; null once that frame is gone).
 * @typedef {{ generation: number, level: import('./contract').Level, col: number,
 *   row: number }} ServerRayWish
 * @typedef {{ key: string, load: () => Promise<SampleRay | null> }} TracedRay
 */

/**
 * The map panel (createMap): what it shows, and what moves it.
 * @typedef {object} MapPanel
 * @property {string} canvas the top view's canvas id
 * @property {string} side the side view's canvas id
 * @property {ExploreMap | null} fetched the last /api/explore/map answer
 * @property {SampleRay | null} ray the light ray shown
 * @property {ObserverEvent | null} event the observer's event as the page has it now
 * @property {boolean} dragging
 * @property {TopWindow | null} view
 * @property {(x: number, y: number) => { px: number, py: number }} toScreen
 * @property {(px: number, py: number) => { x: number, y: number }} fromScreen
 * @property {(event: ObserverEvent, now?: boolean) => void} update
 * @property {(frame: { generation: number, level: import('./contract').Level }, col: number,
 *   row: number) => void} hover
 * @property {(ray: TracedRay) => void} hoverTraced
 * @property {() => void} clearRay
 * @property {() => boolean} idle
 * @property {(now?: boolean) => void} draw
 * @property {number[]} drawTimes the animation frames (document.timeline's time) of its last
 *   drawings (at most 600; for tests)
 */

export const COLOURS = {
  background: '#161922',
  grid: '#262b38',
  frame: '#4a5066',
  text: '#c8cbe0',
  dim: '#8a8fa8',
  horizon: '#a3acd6',
  observer: '#5ee3ff',
  ray: '#ffd23f',
  objects: ['#ff7a59', '#7ee07e', '#d98cff', '#59b4ff', '#ff5fa2', '#c0c0c0'],
};
const FONT = '12px system-ui, sans-serif';
// CSS pixels of the two canvases, and the room the axes take around each plot.
const TOP = { width: 360, height: 380, left: 40, right: 10, top: 38, bottom: 32 };
const SIDE = { width: 380, height: 240, left: 44, right: 12, top: 38, bottom: 32 };
// How near (CSS pixels) a pointer must come to the observer's marker to pick it up.
const PICK_PX = 14;
// The least time between two map requests: while flying the marker follows every frame,
// the rest (tracks, horizon, the objects at the observer's time) a few times a second. On
// a software renderer a map fetched and drawn every frame cost a sixth of the frame rate.
const MAP_GAP_MS = 250;
// How long a map fetched while the observer moves waits for the next move to be drawn with.
const FOLLOW_MS = 200;

/** @param {number} index */
export const objectColour = (index) => COLOURS.objects[index % COLOURS.objects.length];

// Calls `load(wish)` for the newest wish, one at a time and at least `gapMs` apart, then
// `done(wish, result, error)`.
/**
 * @template W, R
 * @param {(wish: W) => Promise<R>} load
 * @param {(wish: W, result: R | null, error: any) => void} done
 * @param {number} [gapMs]
 */
function latest(load, done, gapMs = 0) {
  let busy = false;
  /** @type {W | null} */
  let waiting = null;
  let started = -Infinity;
  let timer = false;
  async function pump() {
    if (busy || timer || waiting === null) return;
    const wait = started + gapMs - performance.now();
    if (wait > 0) {
      timer = true;
      setTimeout(() => {
        timer = false;
        pump();
      }, wait);
      return;
    }
    const wish = waiting;
    waiting = null;
    busy = true;
    started = performance.now();
    try {
      done(wish, await load(wish), null);
    } catch (e) {
      done(wish, null, e);
    } finally {
      busy = false;
    }
    pump();
  }
  return {
    /** @param {W} wish */
    want: (wish) => {
      waiting = wish;
      pump();
    },
    busy: () => busy || waiting !== null,
  };
}

// A tick step for `span` in about `n` steps: 1, 2 or 5 times a power of ten.
/**
 * @param {number} span
 * @param {number} n
 */
function tickStep(span, n) {
  const raw = span / n;
  const p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((k) => k * p).find((s) => s >= raw) ?? 10 * p;
}

/**
 * @param {number} lo
 * @param {number} hi
 * @param {number} n
 */
function ticks(lo, hi, n) {
  const step = tickStep(hi - lo, n);
  const out = [];
  for (let k = Math.ceil(lo / step - 1e-9); k * step <= hi + 1e-9 && out.length < 50; k += 1) {
    out.push(Math.abs(k * step) < step * 1e-6 ? 0 : k * step);
  }
  return out;
}

/** @param {number} v */
const label = (v) => String(Math.round(v * 1000) / 1000);

// The length the view is sized by: a in Gödel's universe, a member's length scale, 1 in flat
// spacetime.
/** @param {ExploreMap} map */
const lengthUnit = (map) => map.a || map.member?.unit || 1;

// The horizon's words: r = 2a in Gödel's universe (in units of a); in a member the circle
// ρ = ρ_c, in its own coordinates.
/**
 * @param {ExploreMap} m
 * @param {number} radius
 */
const horizonText = (m, radius) => (m.member ? `ρ_c = ${label(radius)}` : `r = ${label(radius)}a`);

// Sizes a canvas to `box` CSS pixels and returns its context, cleared, in CSS pixels.
/**
 * @param {HTMLCanvasElement} canvas
 * @param {Box} box
 */
function prepare(canvas, box) {
  const dpr = window.devicePixelRatio || 1;
  canvas.style.width = `${box.width}px`;
  canvas.style.height = `${box.height}px`;
  const w = Math.round(box.width * dpr);
  const h = Math.round(box.height * dpr);
  if (canvas.width !== w || canvas.height !== h) {
    canvas.width = w;
    canvas.height = h;
  }
  // Drawn on the CPU (`willReadFrequently`): Chromium's GPU-drawn canvas made each drawing
  // wait for the GPU's earlier work, on a software GPU a frame's shading (~90 ms while
  // flying; BENCHMARKS.md, "Fewer probes (issue 33)", third session).
  const g = canvas.getContext('2d', { willReadFrequently: true });
  if (!g) throw new Error('this browser draws no 2D canvas');
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.fillStyle = COLOURS.background;
  g.fillRect(0, 0, box.width, box.height);
  g.font = FONT;
  g.lineJoin = 'round';
  return g;
}

/**
 * @param {CanvasRenderingContext2D} g
 * @param {string} s
 * @param {number} x
 * @param {number} y
 * @param {CanvasTextAlign} [align]
 * @param {CanvasTextBaseline} [baseline]
 */
function text(g, s, x, y, colour = COLOURS.text, align = 'left', baseline = 'alphabetic') {
  g.fillStyle = colour;
  g.textAlign = align;
  g.textBaseline = baseline;
  g.fillText(s, x, y);
}

// Text on a dark backing, kept inside the plot box.
/**
 * @param {CanvasRenderingContext2D} g
 * @param {string} s
 * @param {number} x
 * @param {number} y
 * @param {string} colour
 * @param {Box} box
 */
function tag(g, s, x, y, colour, box) {
  const w = g.measureText(s).width;
  const px = Math.min(Math.max(x, box.left + 2), box.width - box.right - w - 2);
  const py = Math.min(Math.max(y, box.top + 14), box.height - box.bottom - 4);
  g.fillStyle = 'rgba(22, 25, 34, 0.8)';
  g.fillRect(px - 2, py - 12, w + 4, 16);
  text(g, s, px, py, colour);
}

/**
 * @param {CanvasRenderingContext2D} g
 * @param {number[][]} points
 * @param {string} colour
 * @param {number} width
 * @param {number[]} [dash]
 */
function polyline(g, points, colour, width, dash = []) {
  if (points.length < 2) return;
  g.strokeStyle = colour;
  g.lineWidth = width;
  g.setLineDash(dash);
  g.beginPath();
  g.moveTo(points[0][0], points[0][1]);
  for (const p of points.slice(1)) g.lineTo(p[0], p[1]);
  g.stroke();
  g.setLineDash([]);
}

// Arrowheads along a screen polyline, every `every` pixels of its length, pointing from its
// last point to its first (light runs from the emission to the observer); only on the last
// `reach` pixels before the first point, so that a ray looping many times stays legible.
/**
 * @param {CanvasRenderingContext2D} g
 * @param {number[][]} points
 * @param {string} colour
 */
function arrows(g, points, colour, every = 60, reach = 420) {
  /** @param {number} i */
  const length = (i) => Math.hypot(points[i][0] - points[i - 1][0], points[i][1] - points[i - 1][1]);
  let total = 0;
  for (let i = 1; i < points.length; i += 1) total += length(i);
  g.fillStyle = colour;
  let done = 0;              // length from the last point to points[i]
  let next = every / 2;      // where the next arrow goes, measured from the last point
  next = Math.max(next, total - reach + every / 2);
  for (let i = points.length - 1; i > 0; i -= 1) {
    const [x0, y0] = points[i];
    const [x1, y1] = points[i - 1];
    const len = length(i);
    if (len === 0) continue;
    const [ux, uy] = [(x1 - x0) / len, (y1 - y0) / len];
    while (next <= done + len && next < total - 8) {
      const at = next - done;
      const [x, y] = [x0 + ux * at, y0 + uy * at];
      g.beginPath();
      g.moveTo(x + ux * 6, y + uy * 6);
      g.lineTo(x - ux * 4 - uy * 5, y - uy * 4 + ux * 5);
      g.lineTo(x - ux * 4 + uy * 5, y - uy * 4 - ux * 5);
      g.closePath();
      g.fill();
      next += every;
    }
    done += len;
  }
}

/**
 * @param {CanvasRenderingContext2D} g
 * @param {number} x
 * @param {number} y
 * @param {number} radius
 * @param {string} colour
 */
function ring(g, x, y, radius, colour, width = 2) {
  g.strokeStyle = colour;
  g.lineWidth = width;
  g.beginPath();
  g.arc(x, y, radius, 0, 2 * Math.PI);
  g.stroke();
}

/**
 * @param {CanvasRenderingContext2D} g
 * @param {number} x
 * @param {number} y
 * @param {number} radius
 * @param {string} colour
 */
function disc(g, x, y, radius, colour) {
  g.fillStyle = colour;
  g.beginPath();
  g.arc(x, y, radius, 0, 2 * Math.PI);
  g.fill();
}

// The observer: a ring with a cross.
/**
 * @param {CanvasRenderingContext2D} g
 * @param {number} x
 * @param {number} y
 */
function observerMark(g, x, y) {
  ring(g, x, y, 7, COLOURS.observer, 2);
  g.beginPath();
  g.moveTo(x - 11, y);
  g.lineTo(x + 11, y);
  g.moveTo(x, y - 11);
  g.lineTo(x, y + 11);
  g.stroke();
}

// Axes with ticks and a faint grid: `sx`, `sy` map values to CSS pixels.
/**
 * @param {CanvasRenderingContext2D} g
 * @param {Box} box
 * @param {number[]} xs
 * @param {number[]} ys
 * @param {(x: number) => number} sx
 * @param {(y: number) => number} sy
 * @param {string} xName
 * @param {string} yName
 */
function axes(g, box, xs, ys, sx, sy, xName, yName) {
  const [l, r, t, b] = [box.left, box.width - box.right, box.top, box.height - box.bottom];
  g.strokeStyle = COLOURS.grid;
  g.lineWidth = 1;
  g.beginPath();
  for (const v of xs) { g.moveTo(sx(v), t); g.lineTo(sx(v), b); }
  for (const v of ys) { g.moveTo(l, sy(v)); g.lineTo(r, sy(v)); }
  g.stroke();
  g.strokeStyle = COLOURS.frame;
  g.strokeRect(l, t, r - l, b - t);
  g.beginPath();
  for (const v of xs) { g.moveTo(sx(v), b); g.lineTo(sx(v), b + 4); }
  for (const v of ys) { g.moveTo(l - 4, sy(v)); g.lineTo(l, sy(v)); }
  g.stroke();
  for (const v of xs) text(g, label(v), sx(v), b + 6, COLOURS.dim, 'center', 'top');
  for (const v of ys) text(g, label(v), l - 6, sy(v), COLOURS.dim, 'right', 'middle');
  text(g, xName, r, box.height - 4, COLOURS.text, 'right', 'alphabetic');
  text(g, yName, 4, t - 6, COLOURS.text, 'left', 'alphabetic');
}

// The top view's window: centre and half-size in map units, rounded so that small moves of
// the observer keep the scale.
/**
 * @param {ExploreMap} map
 * @param {ObserverEvent} event
 * @returns {TopWindow}
 */
function topWindow(map, event) {
  const xs = [event.x];
  const ys = [event.y];
  for (const [x, y] of map.horizon) { xs.push(x); ys.push(y); }
  for (const o of map.objects) {
    for (const p of o.at ? [...o.track, o.at] : o.track) {
      xs.push(p.x - o.radius, p.x + o.radius);
      ys.push(p.y - o.radius, p.y + o.radius);
    }
  }
  const unit = lengthUnit(map) / 2;
  /** @param {number} v */
  const round = (v) => Math.round(v / unit) * unit;
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const half = Math.ceil((Math.max(x1 - x0, y1 - y0) / 2 * 1.08 + 1e-9) / unit) * unit;
  return { cx: round((x0 + x1) / 2), cy: round((y0 + y1) / 2), half: Math.max(half, unit) };
}

// The map panel: `top` and `side` canvases, `legend` element; `hooks.dragTo(x, y)` moves the
// observer, `hooks.status(text)` reports errors.
/**
 * @param {HTMLCanvasElement} top
 * @param {HTMLCanvasElement} side
 * @param {HTMLElement} legend
 * @param {{ status: (text: string) => void, dragTo: (x: number, y: number) => void }} hooks
 * @returns {MapPanel}
 */
export function createMap(top, side, legend, hooks) {
  const plot = TOP.width - TOP.left - TOP.right;
  // The top view's window; the map has one once it is first drawn.
  const shown = () => {
    if (!map.view) throw new Error('the map is not drawn yet');
    return map.view;
  };
  const scale = () => plot / (2 * shown().half);

  /** @type {ServerRayWish | TracedRay | null} */
  let rayWish = null;
  // Whether a drawing of the map waits for the next animation frame (map.draw).
  let drawQueued = false;
  // When the observer last moved (map.update), and whether a fetched map waits for its next
  // move to be drawn with it (at most FOLLOW_MS).
  let movedAt = -Infinity;
  let fetchedWaits = false;
  const wantMap = latest(
    /** @param {ObserverEvent} e */
    (e) => /** @type {Promise<ExploreMap>} */ (getJson(`/api/explore/map?t=${e.t}&x=${e.x}`
      + `&y=${e.y}&z=${e.z}`)),
    (e, answer, error) => {
      if (error) {
        hooks.status(`map: ${error.message}`);
        return;
      }
      map.fetched = answer;
      // While the observer moves, the fetched map is drawn with its next move, in the
      // picture's animation frame (fly.js), not in one of its own: on a software renderer
      // each animation frame that changes the page costs the browser a whole composition.
      if (performance.now() - movedAt < FOLLOW_MS) {
        fetchedWaits = true;
        setTimeout(() => {
          if (fetchedWaits) map.draw();
        }, FOLLOW_MS);
      } else {
        map.draw();
      }
    }, MAP_GAP_MS);
  const wantRay = latest(
    /**
     * @param {ServerRayWish | TracedRay} w
     * @returns {Promise<SampleRay | null>}
     */
    (w) => ('load' in w ? w.load() : /** @type {Promise<SampleRay>} */ (getJson(
      `/api/explore/ray?generation=${w.generation}&level=${w.level}&col=${w.col}&row=${w.row}`))),
    (w, answer, error) => {
      if (w !== rayWish) return; // the mouse left the picture meanwhile, or moved on
      if (error) {
        if (error.status !== 410) hooks.status(`ray: ${error.message}`);
        return;
      }
      if (answer === null) return; // a traced frame replaced meanwhile
      map.ray = answer;
      map.draw();
    });

  /** @type {MapPanel} */
  const map = {
    canvas: top.id,
    side: side.id,
    fetched: null,
    ray: null,
    event: null,
    dragging: false,
    drawTimes: [],
    view: null,
    toScreen: (x, y) => ({
      px: TOP.left + plot / 2 + (x - shown().cx) * scale(),
      py: TOP.top + plot / 2 - (y - shown().cy) * scale(),
    }),
    fromScreen: (px, py) => ({
      x: shown().cx + (px - TOP.left - plot / 2) / scale(),
      y: shown().cy - (py - TOP.top - plot / 2) / scale(),
    }),
    // The observer moved: fetch its map (the marker follows at once; `now`: drawn now, in
    // the caller's animation frame).
    update: (event, now = false) => {
      map.event = { ...event };
      movedAt = performance.now();
      wantMap.want({ ...event });
      map.draw(now);
    },
    // The pixel (col, row) of frame {generation, level} is hovered: fetch its light ray.
    hover: (frame, col, row) => {
      const w = { generation: frame.generation, level: frame.level, col, row };
      if (rayWish && JSON.stringify(rayWish) === JSON.stringify(w)) return;
      rayWish = w;
      wantRay.want(w);
    },
    // A pixel of a frame traced in the page is hovered: `ray` is fly.js's {key, load}.
    hoverTraced: (ray) => {
      if (rayWish && 'key' in rayWish && rayWish.key === ray.key) return;
      rayWish = ray;
      wantRay.want(ray);
    },
    clearRay: () => {
      rayWish = null;
      map.ray = null;
      map.draw();
    },
    // Nothing to fetch or draw (for tests).
    idle: () => !wantMap.busy() && !wantRay.busy() && !drawQueued && !fetchedWaits,
    // Drawn once in the next animation frame, however often asked for before it (while
    // flying, each move and each fetched map asks), or `now` (a drawing queued before is
    // then dropped).
    draw: (now = false) => {
      const drawNow = () => {
        drawQueued = false;
        fetchedWaits = false;
        const m = map.fetched;
        const event = map.event || (m && m.event);
        if (!m || !event) return;
        if (!map.dragging || map.view === null) map.view = topWindow(m, event);
        drawTop(m, event);
        drawSide(m, event);
        drawLegend(m);
        map.drawTimes.push(Number(document.timeline.currentTime ?? performance.now()));
        if (map.drawTimes.length > 600) map.drawTimes.shift();
      };
      if (now) {
        drawNow();
        return;
      }
      if (drawQueued) return;
      drawQueued = true;
      requestAnimationFrame(() => {
        if (drawQueued) drawNow();
      });
    },
  };

  /**
   * @param {ExploreMap} m
   * @param {ObserverEvent} event
   */
  function drawTop(m, event) {
    const g = prepare(top, TOP);
    const v = shown();
    /** @type {(x: number, y: number) => [number, number]} */
    const at = (x, y) => { const p = map.toScreen(x, y); return [p.px, p.py]; };
    const n = ticks(v.cx - v.half, v.cx + v.half, 6);
    const sy = ticks(v.cy - v.half, v.cy + v.half, 6);
    const [xName, yName] = m.member ? ['x', 'y'] : ['x / a', 'y / a'];
    axes(g, TOP, n, sy, (x) => at(x, 0)[0], (y) => at(0, y)[1], xName, yName);
    text(g, `top view: the x–y plane (r–φ) at z = ${label(event.z)}`, TOP.width / 2, 15,
      COLOURS.text, 'center');
    g.save();
    g.beginPath();
    g.rect(TOP.left, TOP.top, plot, plot);
    g.clip();
    // The origin of the coordinates.
    const [ox, oy] = at(0, 0);
    g.strokeStyle = COLOURS.dim;
    g.lineWidth = 1.5;
    g.beginPath();
    g.moveTo(ox - 5, oy - 5); g.lineTo(ox + 5, oy + 5);
    g.moveTo(ox - 5, oy + 5); g.lineTo(ox + 5, oy - 5);
    g.stroke();
    text(g, 'O', ox + 6, oy + 14, COLOURS.dim);
    if (m.horizon.length > 1) {
      const curve = m.horizon.map(([x, y]) => at(x, y));
      polyline(g, [...curve, curve[0]], COLOURS.horizon, 1.5, [6, 5]);
      const lowest = curve.reduce((a, b) => (b[1] > a[1] ? b : a));
      const radius = m.horizon_radius ?? 0;
      const words = m.member
        ? `${horizonText(m, radius)} (closed timelike curves beyond)`
        : `horizon of the observer (${horizonText(m, radius)})`;
      tag(g, words, lowest[0] - 95, lowest[1] + 16, COLOURS.horizon, TOP);
    }
    for (const o of m.objects) {
      const colour = objectColour(o.index);
      g.globalAlpha = 0.7;
      polyline(g, o.track.map((p) => at(p.x, p.y)), colour, 1);
      g.globalAlpha = 1;
      if (o.at) {
        const [x, y] = at(o.at.x, o.at.y);
        disc(g, x, y, Math.max(3, o.radius * scale()), colour);
        tag(g, o.name, x + Math.max(3, o.radius * scale()) + 4, y + 4, colour, TOP);
      }
    }
    const ray = map.ray;
    if (ray && ray.points.length > 1) {
      const path = ray.points.map((p) => at(p.x, p.y));
      polyline(g, path, COLOURS.ray, 2);
      arrows(g, path, COLOURS.ray);
      const end = path[path.length - 1];
      ring(g, end[0], end[1], 7, COLOURS.ray, 2);
      tag(g, emittedText(ray), end[0] + 10, end[1] - 10, COLOURS.ray, TOP);
    }
    const [ex, ey] = at(event.x, event.y);
    observerMark(g, ex, ey);
    tag(g, 'observer', ex + 12, ey - 8, COLOURS.observer, TOP);
    g.restore();
  }

  /** @param {SampleRay} ray */
  function emittedText(ray) {
    const e = ray.emission;
    if (!e) return `no hit: traced back to t = ${ray.points[ray.points.length - 1].t.toFixed(2)}`;
    const unit = map.fetched?.member ? '' : ' a';
    return `emitted t = ${e.t.toFixed(2)}, travel time ${Number(ray.travel_time).toFixed(2)}${unit}`;
  }

  /**
   * @param {ExploreMap} m
   * @param {ObserverEvent} event
   */
  function drawSide(m, event) {
    const g = prepare(side, SIDE);
    // Room for the horizon and a tenth beyond it (2.2a in Gödel's universe).
    let rMax = m.member && m.horizon_radius ? 1.1 * m.horizon_radius : 2.2 * lengthUnit(m);
    let [t0, t1] = [Math.min(m.time_range[0], event.t), Math.max(m.time_range[1], event.t)];
    for (const o of m.objects) for (const p of o.track) rMax = Math.max(rMax, p.r + o.radius);
    const ray = map.ray;
    if (ray) for (const p of ray.points) { t0 = Math.min(t0, p.t); t1 = Math.max(t1, p.t); }
    rMax *= 1.04;
    if (t1 - t0 < 1e-9) t1 = t0 + 1;
    const w = SIDE.width - SIDE.left - SIDE.right;
    const h = SIDE.height - SIDE.top - SIDE.bottom;
    /** @param {number} r */
    const sx = (r) => SIDE.left + (r / rMax) * w;
    /** @param {number} t */
    const sy = (t) => SIDE.top + (1 - (t - t0) / (t1 - t0)) * h;
    const [rName, tName, distance] = m.member
      ? ['ρ', 't', 'proper distance ρ'] : ['r / a', 't / a', 'distance r'];
    axes(g, SIDE, ticks(0, rMax, 6), ticks(t0, t1, 5), sx, sy, rName, tName);
    text(g, `side view: t against ${distance} from the observer\u2019s axis`, SIDE.width / 2, 15,
      COLOURS.text, 'center');
    g.save();
    g.beginPath();
    g.rect(SIDE.left, SIDE.top, w, h);
    g.clip();
    if (m.horizon_radius) {
      const x = sx(m.horizon_radius);
      polyline(g, [[x, SIDE.top], [x, SIDE.top + h]], COLOURS.horizon, 1.5, [6, 5]);
      tag(g, horizonText(m, m.horizon_radius), x + 4, SIDE.top + 16, COLOURS.horizon, SIDE);
    }
    for (const o of m.objects) {
      const colour = objectColour(o.index);
      polyline(g, o.track.map((p) => [sx(p.r), sy(p.t)]), colour, 1.5);
      if (o.at) disc(g, sx(o.at.r), sy(o.at.t), 4, colour);
    }
    if (ray && ray.points.length > 1) {
      const path = ray.points.map((p) => [sx(p.r), sy(p.t)]);
      polyline(g, path, COLOURS.ray, 2);
      arrows(g, path, COLOURS.ray, 50);
      const end = path[path.length - 1];
      ring(g, end[0], end[1], 6, COLOURS.ray, 2);
    }
    observerMark(g, sx(0), sy(event.t));
    g.restore();
  }

  /** @type {string | null} */
  let legendKey = null;
  /** @param {ExploreMap} m */
  function drawLegend(m) {
    const key = JSON.stringify([m.horizon.length > 1, m.horizon_radius, Boolean(m.member),
      ...m.objects.map((o) => [o.index, o.name, o.moving])]);
    if (key === legendKey) return;
    legendKey = key;
    /**
     * @param {string} colour
     * @param {string} style
     * @param {string} words
     */
    const line = (colour, style, words) => {
      const row = document.createElement('div');
      const swatch = document.createElement('span');
      swatch.className = 'swatch';
      swatch.style.borderTop = `3px ${style} ${colour}`;
      row.append(swatch, document.createTextNode(words));
      return row;
    };
    legend.replaceChildren(
      line(COLOURS.observer, 'solid', 'the observer (drag it on the top view)'),
      ...(m.horizon.length > 1
        ? [line(COLOURS.horizon, 'dashed', m.member
          ? `its horizon, ${horizonText(m, m.horizon_radius ?? 0)}: closed timelike curves `
            + 'beyond, no light from beyond'
          : 'its optical horizon, r = 2a: no light from beyond')]
        : []),
      ...m.objects.map((o) => line(objectColour(o.index), 'solid',
        `${o.name}: worldline track${o.moving ? ' (free fall)' : ''}; disc: at the observer\u2019s t`)),
      line(COLOURS.ray, 'solid', 'light ray of the hovered pixel: from its emission (ring) to '
        + 'the observer (arrows)'),
    );
  }

  // Dragging the observer on the top view (the window stays put while dragging).
  /** @param {PointerEvent} event */
  const local = (event) => {
    const rect = top.getBoundingClientRect();
    return [event.clientX - rect.left, event.clientY - rect.top];
  };
  /** @param {PointerEvent} event */
  const nearObserver = (event) => {
    if (!map.view || !map.event) return false;
    const [px, py] = local(event);
    const o = map.toScreen(map.event.x, map.event.y);
    return Math.hypot(px - o.px, py - o.py) <= PICK_PX;
  };
  top.addEventListener('pointerdown', (event) => {
    if (!nearObserver(event)) return;
    map.dragging = true;
    top.setPointerCapture(event.pointerId);
    event.preventDefault();
  });
  top.addEventListener('pointermove', (event) => {
    if (!map.dragging) {
      top.style.cursor = nearObserver(event) ? 'grab' : 'default';
      return;
    }
    const [px, py] = local(event);
    const p = map.fromScreen(px, py);
    /** @param {number} v */
    const round = (v) => Math.round(v * 1000) / 1000;
    hooks.dragTo(round(p.x), round(p.y));
  });
  const stop = () => {
    if (!map.dragging) return;
    map.dragging = false;
    map.draw();
  };
  top.addEventListener('pointerup', stop);
  top.addEventListener('pointercancel', stop);
  return map;
}
