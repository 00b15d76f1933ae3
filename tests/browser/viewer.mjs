// Drives a real browser (Debian's chromium, through playwright-core) against a running
// `godel view`, and prints what it saw as one JSON object on stdout, for the Rust test
// crates/godel/tests/viewer_browser.rs to check.
//
// usage: node viewer.mjs URL OUT_DIR COL ROW
//   COL ROW: a pixel that the caller knows to be a hit; its record is read on hover.
// Writes into OUT_DIR: screenshot.png, saved.png (the "Save PNG" download),
// keyframe.toml (the "Save keyframe" download) and a fresh chromium profile.
import { chromium } from 'playwright-core';
import { mkdtempSync } from 'node:fs';
import { join } from 'node:path';

const [url, outDir, colText, rowText] = process.argv.slice(2);
if (!url || !outDir || colText === undefined || rowText === undefined) {
  console.error('usage: node viewer.mjs URL OUT_DIR COL ROW');
  process.exit(2);
}
const col = Number(colText);
const row = Number(rowText);
const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';

// The closed network refuses chromium's own connections: switch them all off.
const args = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];

const context = await chromium.launchPersistentContext(mkdtempSync(join(outDir, 'profile-')), {
  executablePath, headless: true, args, acceptDownloads: true,
  viewport: { width: 1400, height: 900 },
});
const result = {};
try {
  const page = context.pages()[0] || await context.newPage();
  const consoleErrors = [];
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(String(e)));

  const idle = () => page.waitForFunction(() => {
    const v = window.godelViewer;
    return v && v.frames > 0 && v.idle();
  });
  // The canvas's pixels as base64 RGBA, read back from the browser.
  const pixels = () => page.evaluate(() => {
    const c = document.getElementById('image');
    const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let s = '';
    for (let i = 0; i < data.length; i += 8192) {
      s += String.fromCharCode(...data.subarray(i, i + 8192));
    }
    return btoa(s);
  });
  const differing = (a, b) => {
    const x = Buffer.from(a, 'base64');
    const y = Buffer.from(b, 'base64');
    let n = 0;
    for (let i = 0; i < Math.min(x.length, y.length); i += 4) {
      if (x[i] !== y[i] || x[i + 1] !== y[i + 1] || x[i + 2] !== y[i + 2]) n += 1;
    }
    return n + Math.abs(x.length - y.length) / 4;
  };

  await page.goto(url);
  await idle();
  result.title = await page.title();
  result.canvas = await page.evaluate(() => {
    const c = document.getElementById('image');
    return [c.width, c.height];
  });

  // The temperature matters to the frequency layer: switch to it alone first.
  await page.check('#layer-frequency');
  await page.uncheck('#layer-texture');
  await page.waitForFunction(() => window.godelViewer.settings.shaders.join() === 'frequency');
  await idle();
  const before = await pixels();
  const temperatureBefore = await page.inputValue('#temperature-0');

  // Move the temperature slider with the mouse, as a user does: press near its right
  // end and drag to near its left end (a stream of input events).
  const framesBefore = await page.evaluate(() => window.godelViewer.frames);
  const slider = page.locator('#temperature-0');
  await slider.scrollIntoViewIfNeeded();
  const box = await slider.boundingBox();
  const y = box.y + box.height / 2;
  await page.mouse.move(box.x + box.width * 0.8, y);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.1, y, { steps: 20 });
  await page.mouse.up();
  await idle();
  const after = await pixels();
  result.temperature = [Number(temperatureBefore), Number(await page.inputValue('#temperature-0'))];
  result.pixels_changed = differing(before, after);
  result.pixel_count = Buffer.from(after, 'base64').length / 4;
  result.frames_for_drag = await page.evaluate((n) => window.godelViewer.frames - n, framesBefore);
  result.round_trips_ms = await page.evaluate(() => window.godelViewer.roundTrips);
  result.server_timings_ms = await page.evaluate(() => window.godelViewer.serverTimings);

  // Hover the pixel given and read the record the page shows.
  await page.locator('#image').scrollIntoViewIfNeeded();
  const canvasBox = await page.locator('#image').boundingBox();
  await page.mouse.move(
    canvasBox.x + (col + 0.5) * canvasBox.width / result.canvas[0],
    canvasBox.y + (row + 0.5) * canvasBox.height / result.canvas[1],
  );
  // The browser rounds mouse positions to whole CSS pixels: when the picture is shown
  // smaller than its size, the pixel under the mouse may be a neighbour of the one aimed at.
  await page.waitForFunction(([c, r]) => {
    const rec = window.godelViewer.record;
    return rec && Math.abs(rec.col - c) <= 1 && Math.abs(rec.row - r) <= 1;
  }, [col, row]);
  result.record_shown = {};
  for (const field of ['pixel', 'object', 'status', 'u', 'v', 'g', 't_emit', 'travel_time',
    'direction']) {
    result.record_shown[field] = await page.textContent(`#record [data-field="${field}"]`);
  }

  // The two save buttons download files.
  const save = async (button, name) => {
    const [download] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
    await download.saveAs(join(outDir, name));
    return download.suggestedFilename();
  };
  result.png_name = await save('#save-png', 'saved.png');
  result.keyframe_name = await save('#save-keyframe', 'keyframe.toml');
  result.settings = await page.evaluate(() => window.godelViewer.settings);

  await page.screenshot({ path: join(outDir, 'screenshot.png'), fullPage: true });

  // Bad settings, sent the way the page sends them: the server's message shows on the page.
  await page.evaluate(() => window.godelViewer.sendRaw('{"shaders": ["sepia"]}'));
  result.error_shown = await page.isVisible('#error');
  result.error_text = await page.textContent('#error');
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
