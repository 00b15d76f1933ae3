// At rest in explore mode (fly.js), for the Rust test crates/godel/tests/viewer_browser/fly.rs,
// on a scene of several samples a pixel: after a wheel turn (zooming in), the page
// first shows the full size at one sample a pixel, then the full samples. Saves the slots of
// both frames as they are shown.
//
// usage: node fly-rest.mjs URL OUT_DIR
// Writes OUT_DIR/rest-LEVEL-slot-S.f32 (LEVEL size or full; RGBA32F, grid row 0 first) and
// prints {view, shown: [{level, width, height, slots}], log (the frames of the final view),
// header, console_errors, error}.
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { launch, open, atRest } from './launch.mjs';

const [url, outDir] = process.argv.slice(2);
if (!url || !outDir) {
  console.error('usage: node fly-rest.mjs URL OUT_DIR');
  process.exit(2);
}
const { context, page, consoleErrors } = await launch(outDir, { width: 1200, height: 900 });
const rest = () => atRest(page, 180000);

const result = {};
try {
  await open(page, url);
  await rest();
  // Every frame at rest from now on, its slots read while they are the ones shown.
  await page.evaluate(() => {
    const e = window.godelViewer.explore;
    e.testShown = [];
    e.onShown = (level) => {
      if (level !== 'moving') e.testShown.push({ level, ...e.readSlots() });
    };
  });
  const box = await page.evaluate(() => {
    const r = document.getElementById('image').getBoundingClientRect();
    return { x: r.left + r.width / 2, y: r.top + r.height / 2 };
  });
  const before = await page.evaluate(() => window.godelViewer.explore.fly.version);
  await page.mouse.move(box.x, box.y);
  await page.mouse.wheel(0, -300); // zooms in (e^-0.3): the ball grows
  await page.waitForFunction((v) => window.godelViewer.explore.fly.version > v, before,
    { timeout: 60000 });
  await rest();
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
  result.header = await page.evaluate(() => document.getElementById('file').textContent);
  result.error = await page.evaluate(() => window.godelViewer.error
    || window.godelViewer.explore.fly.error);
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
