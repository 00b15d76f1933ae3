// At rest in explore mode (fly.js), for the Rust test crates/godel/tests/integration/browser/fly.rs,
// on a scene of several samples a pixel: saves the first full frame (the scene's own view and
// velocity), stops the observer (X), then after a wheel turn (zooming in), the page shows
// the full size at one sample a pixel (after half the size, where the kernel's speed asks for
// it), then the full samples. Saves the slots of the frames at rest as they are shown, and
// compares the canvas as shown while the full samples are traced (the one-sample frame drawn
// between their draws) with the canvas before the wheel and after the full samples. The
// server's own first frame is held back, so that the page's frames replace it while its
// channels load.
//
// usage: node fly-rest.mjs URL OUT_DIR
// Writes OUT_DIR/rest-LEVEL-slot-S.f32 (LEVEL half, size or full; RGBA32F, grid row 0 first),
// OUT_DIR/start-full-slot-S.f32 (the first full frame, of the scene's own view) and
// prints {view, start_view, start {width, height, slots} (the first full frame),
// stopped_view (the view once X, Stop, was pressed: then the wheel turns), check {done, last,
// refused} (the page's checks of its tracer),
// start_log (the frames at rest of the scene's own view), rays_per_ms (the
// kernel's speed the page measured before the wheel, once stopped), shown: [{level, width, height, slots}],
// log (the frames at rest of the final view),
// canvas {drawn_while_refining, pixels, size_to_full, size_to_before, full_to_before}
// (pixels of the canvas differing by more than 40 in a channel), header, console_errors,
// error}.
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { argsOr, launch, open, atRest } from './launch.mjs';

// Pixels whose RGB differ by more than 40 in a channel between two canvases (RGBA, base64).
function apart(a, b) {
  const [x, y] = [Buffer.from(a, 'base64'), Buffer.from(b, 'base64')];
  let n = 0;
  for (let i = 0; i < Math.min(x.length, y.length); i += 4) {
    if ([0, 1, 2].some((c) => Math.abs(x[i + c] - y[i + c]) > 40)) n += 1;
  }
  return n;
}

const [url, outDir] = argsOr('node fly-rest.mjs URL OUT_DIR', 2);
const { context, page, consoleErrors } = await launch(outDir, { width: 1200, height: 900 });
const rest = () => atRest(page, 180000);

const result = {};
try {
  // The server's own first frame comes late (its channels held back 12 s): the page's traced
  // frames are shown while they load, and must win without an error (data.js ensure).
  await page.route('**/api/explore/channels?**', async (route) => {
    if (route.request().url().includes('generation=1&')) {
      await new Promise((resolve) => { setTimeout(resolve, 12000); });
    }
    await route.continue();
  });
  await open(page, url);
  await rest();
  let start;
  [result.start_log, result.start_view, start] = await page.evaluate(() => {
    const e = window.godelViewer.explore;
    const f = e.fly;
    return [f.log.filter((l) => l.version === f.version && l.level !== 'moving'), e.view(),
      e.readSlots()];
  });
  // The first full frame, of the scene's own view.
  start.slots.forEach((b64, k) => writeFileSync(join(outDir, `start-full-slot-${k}.f32`),
    Buffer.from(b64, 'base64')));
  result.start = { width: start.width, height: start.height, slots: start.slots.length };
  // Stop (X): the observer at rest, the rest of the script as on a scene at rest.
  const stopped = await page.evaluate(() => window.godelViewer.explore.fly.version);
  await page.keyboard.press('KeyX');
  await page.waitForFunction((v) => window.godelViewer.explore.fly.version > v, stopped,
    { timeout: 60000 });
  await rest();
  [result.stopped_view, result.rays_per_ms] = await page.evaluate(() => [
    window.godelViewer.explore.view(), window.godelViewer.explore.fly.raysPerMs]);
  // Every frame at rest from now on, its slots read while they are the ones shown.
  const before = await page.evaluate(() => {
    const v = window.godelViewer;
    const e = v.explore;
    e.testShown = [];
    e.onShown = (level) => {
      if (level !== 'moving') e.testShown.push({ level, ...e.readSlots() });
      if (level === 'size') e.testSizeFrames = v.frames;
    };
    return v.readCanvas();
  });
  const box = await page.evaluate(() => {
    const r = document.getElementById('image').getBoundingClientRect();
    return { x: r.left + r.width / 2, y: r.top + r.height / 2 };
  });
  const version = await page.evaluate(() => window.godelViewer.explore.fly.version);
  await page.mouse.move(box.x, box.y);
  await page.mouse.wheel(0, -300); // zooms in (e^-0.3): the ball grows
  await page.waitForFunction((v) => window.godelViewer.explore.fly.version > v, version,
    { timeout: 60000 });
  // The canvas once the one-sample frame is drawn, while the full samples are traced.
  await page.waitForFunction(() => {
    const v = window.godelViewer;
    const e = v.explore;
    if (e.fly.traced?.level === 'full') return true;
    if (e.testSizeFrames === undefined || v.frames <= e.testSizeFrames) return false;
    e.testSizeCanvas = { refining: e.fly.refining, ...v.readCanvas() };
    return true;
  }, null, { timeout: 180000, polling: 'raf' });
  await rest();
  const [sized, full] = await page.evaluate(() => [window.godelViewer.explore.testSizeCanvas,
    window.godelViewer.readCanvas()]);
  result.canvas = { drawn_while_refining: sized?.refining ?? false,
    pixels: full.width * full.height,
    size_to_full: sized ? apart(sized.bytes, full.bytes) : null,
    size_to_before: sized ? apart(sized.bytes, before.bytes) : null,
    full_to_before: apart(full.bytes, before.bytes) };
  const seen = await page.evaluate(() => {
    const e = window.godelViewer.explore;
    e.onShown = null;
    const f = e.fly;
    return { view: e.view(), shown: e.testShown, version: f.version,
      log: f.log.filter((l) => l.version === f.version && l.level !== 'moving') };
  });
  result.view = seen.view;
  result.log = seen.log;
  // The frames of the final view, in the order shown.
  const last = seen.shown.slice(-seen.log.length);
  result.shown = last.map((s) => {
    s.slots.forEach((b64, k) => writeFileSync(join(outDir, `rest-${s.level}-slot-${k}.f32`),
      Buffer.from(b64, 'base64')));
    return { level: s.level, width: s.width, height: s.height, slots: s.slots.length };
  });
  // The page's checks of its tracer against the server's CPU tracer (the first frame's, and
  // one at most every few seconds after).
  await page.waitForFunction(() => !window.godelViewer.explore.fly.check.busy, null,
    { timeout: 60000 });
  result.check = await page.evaluate(() => {
    const f = window.godelViewer.explore.fly;
    return { done: f.check.done, last: f.check.last, refused: f.refused };
  });
  result.header = await page.evaluate(() => document.getElementById('file').textContent);
  result.error = await page.evaluate(() => window.godelViewer.error
    || window.godelViewer.explore.fly.error);
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
