// The faster tracer in explore mode (fly.js), for the Rust test
// crates/godel/tests/integration/browser/faster.rs: opens the page as a user does (no
// `?trace=`), waits for the full frame at rest (a quarter-size frame at rest, of at most 2,048 rays,
// measures the kernel's speed, then each frame is traced by whichever tracer was faster), hovers pixel (COL, ROW)
// of it and keeps its record and the map's light ray; then holds W (forward, at 0.1 c) until
// ten frames have been shown while moving, lets go, and waits for the full frame at rest
// again.
//
// usage: node fly-faster.mjs URL OUT_DIR COL ROW
// Prints {rest {traced, cpu, gpu, header, shown, view, canvas}, rest_log, record, ray,
// moving_log, moving_header, moving_canvas, moving_map {requests, ms}, again {traced, header,
// view, canvas}, again_log, requests, console_errors, error}; each log holds the frames shown
// (level, size, `by`: gpu or cpu); a canvas is {level (of the frame shown), width, height
// (its pixels), box (its box in device pixels)}; moving_map counts the map's requests while W
// was held, over `ms`, and `alone`: the animation frames in which the map was drawn and no
// picture; moving_moves: the least time (ms) between two moves of the observer sent while
// a moving frame of the server's was under way (from its view-frame request to the answer
// that it was kept: that request's or a further wait's), null where no two were.
import { argsOr, launch, open, atRest } from './launch.mjs';

const [url, outDir, col, row] = argsOr('node fly-faster.mjs URL OUT_DIR COL ROW', 4);
const { page, context, requests, consoleErrors } = await launch(outDir,
  { width: 1200, height: 900 });
const rest = () => atRest(page, 180000);
// The frame shown at rest now: its tracer, the speeds measured, the header, the view.
const state = () => page.evaluate(() => {
  const e = window.godelViewer.explore;
  return { traced: e.fly.traced, cpu: e.fly.cpuRaysPerMs, gpu: e.fly.raysPerMs,
    header: document.getElementById('file').textContent, shown: e.shown, view: e.view() };
});
// The frames shown since log entry `from`: level, size and tracer.
const logFrom = (from) => page.evaluate((k) => window.godelViewer.explore.fly.log.slice(k)
  .map((l) => ({ level: l.level, width: l.width, height: l.height, by: l.by })), from);
const logLength = () => page.evaluate(() => window.godelViewer.explore.fly.log.length);
// The canvas's pixels and its box's, with the level of the frame shown.
const canvas = () => page.evaluate(() => {
  const c = document.getElementById('image');
  const dpr = window.devicePixelRatio || 1;
  return { level: window.godelViewer.explore.fly.traced?.level ?? null, width: c.width,
    height: c.height, box: [Math.round(c.clientWidth * dpr), Math.round(c.clientHeight * dpr)] };
});
const mapRequests = () => requests.filter((u) => u.includes('/api/explore/map')).length;

const result = {};
try {
  await open(page, url);
  await rest();
  result.rest = { ...await state(), canvas: await canvas() };
  result.rest_log = await logFrom(0);
  // Hover pixel (COL, ROW): the record panel and the map follow the frame shown.
  const target = await page.evaluate(([c, r]) => {
    const v = window.godelViewer;
    const rect = document.getElementById('image').getBoundingClientRect();
    const point = { clientX: rect.left + (c + 0.5) * rect.width / v.info.width,
      clientY: rect.top + (r + 0.5) * rect.height / v.info.height };
    return { x: point.clientX, y: point.clientY, at: v.pixelAt(point) };
  }, [Number(col), Number(row)]);
  await page.mouse.move(target.x, target.y);
  await page.waitForFunction(([c, r]) => {
    const v = window.godelViewer;
    const ray = v.explore.map.ray;
    return ray !== null && ray.col === c && ray.row === r && v.record
      && v.record.col === c && v.record.row === r;
  }, target.at, { timeout: 60000 });
  [result.ray, result.record] = await page.evaluate(() => [window.godelViewer.explore.map.ray,
    window.godelViewer.record]);
  result.hovered = target.at;
  await page.mouse.move(0, 0);
  // Hold W at a tenth of c until ten frames were shown while moving.
  await page.evaluate(() => {
    const speed = document.getElementById('fly-speed');
    speed.value = '0.1';
    speed.dispatchEvent(new Event('input'));
  });
  const pressed = await logLength();
  const [mapsBefore, pressedAt] = [mapRequests(), await page.evaluate(() => performance.now())];
  await page.evaluate(() => {
    performance.clearResourceTimings();
    performance.setResourceTimingBufferSize(100000);
  });
  await page.keyboard.down('KeyW');
  await page.waitForFunction((k) => window.godelViewer.explore.fly.log.slice(k)
    .filter((l) => l.level === 'moving').length >= 10, pressed, { timeout: 180000 });
  result.moving_header = await page.evaluate(() => document.getElementById('file').textContent);
  result.moving_canvas = await canvas();
  await page.keyboard.up('KeyW');
  result.moving_map = { requests: mapRequests() - mapsBefore,
    ms: await page.evaluate(() => performance.now()) - pressedAt,
    alone: await page.evaluate((from) => {
      const v = window.godelViewer;
      const pictures = new Set(v.frameTimes);
      return new Set(v.explore.map.drawTimes.filter((t) => t >= from && !pictures.has(t))).size;
    }, pressedAt) };
  result.moving_log = await logFrom(pressed);
  result.moving_moves = await page.evaluate(() => {
    const all = performance.getEntriesByType('resource');
    const named = (part) => all.filter((e) => e.name.includes(part));
    const [asks, answers] = [named('/api/explore/view-frame'), named('/api/explore/frame?after=')];
    // Each view-frame request (which waits for its frame) to its answer or to the last
    // answer to a further wait that ended before the next.
    const spans = asks.map((a, i) => {
      const next = asks[i + 1]?.startTime ?? Infinity;
      const ends = answers.filter((w) => w.startTime > a.startTime && w.responseEnd < next);
      return [a.startTime, Math.max(a.responseEnd, ...ends.map((w) => w.responseEnd))];
    });
    const moves = named('/api/explore/move').map((e) => e.startTime);
    let least = null;
    for (const [from, to] of spans) {
      const inside = moves.filter((t) => t > from && t < to);
      for (let k = 1; k < inside.length; k += 1) {
        const gap = inside[k] - inside[k - 1];
        if (least === null || gap < least) least = gap;
      }
    }
    return least;
  });
  const released = await logLength();
  await page.waitForFunction(() => !window.godelViewer.explore.fly.moving, null,
    { timeout: 180000 });
  await rest();
  result.again = { ...await state(), canvas: await canvas() };
  result.again_log = await logFrom(released);
  result.error = await page.evaluate(() => window.godelViewer.error
    || window.godelViewer.explore.fly.error);
  result.requests = requests;
  result.console_errors = consoleErrors;
} catch (e) {
  result.error = String(e);
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
