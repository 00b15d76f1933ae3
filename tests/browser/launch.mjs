// Shared by the browser scripts: starts Debian's chromium through playwright-core with WebGL2
// on SwiftShader (software rendering: the tests need no graphics card), records every request
// the page makes and every console error, and reads pictures back from the page.
import { chromium } from 'playwright-core';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

// The closed network refuses chromium's own connections: switch them all off. WebGL2 runs on
// ANGLE over SwiftShader (software Vulkan), which headless chromium allows only when asked.
export const ARGS = ['--headless', '--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// The script's arguments (after `node SCRIPT`); fewer than `required` print `usage: USAGE`
// and exit with status 2.
export function argsOr(usage, required) {
  const args = process.argv.slice(2);
  if (args.length < required || args.slice(0, required).some((a) => a === '')) {
    console.error(`usage: ${usage}`);
    process.exit(2);
  }
  return args;
}

// What a script reports of the page at its end: the page's own error line, the requests it
// made and the console's errors.
export async function pageReport(page, requests, consoleErrors) {
  const error = await page.evaluate(() => window.godelViewer.error);
  return { error, requests, console_errors: consoleErrors };
}

export async function launch(dir, viewport = { width: 1400, height: 900 }) {
  const context = await chromium.launchPersistentContext(mkdtempSync(join(dir, 'profile-')), {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: ARGS,
    acceptDownloads: true, viewport,
  });
  const page = context.pages()[0] || await context.newPage();
  const requests = [];
  const consoleErrors = [];
  context.on('request', (r) => requests.push(r.url()));
  // Not an error: explore answers 410 Gone for a frame replaced while the page loaded it
  // (the page drops that frame and takes the newer one, viewer.js), and chromium logs the
  // response itself; under load the race happens (seen once in a full test run).
  const gone = /the server responded with a status of 410 \(Gone\)/;
  page.on('console', (m) => {
    if (m.type() === 'error' && !gone.test(m.text())) consoleErrors.push(m.text());
  });
  page.on('pageerror', (e) => consoleErrors.push(String(e)));
  return { context, page, requests, consoleErrors };
}

// Waits until the page has drawn a picture and has nothing left to draw or fetch.
export const idle = (page) => page.waitForFunction(() => {
  const v = window.godelViewer;
  return v && (v.error !== null || (v.frames > 0 && v.idle()));
}, null, { timeout: 120000 });

// Opens the viewer and waits for its first picture; throws the page's error (e.g. no WebGL2)
// if it shows one instead.
export async function open(page, url) {
  await page.goto(url);
  await idle(page);
  const error = await page.evaluate(() => window.godelViewer.error);
  if (error !== null) throw new Error(`the viewer shows an error: ${error}`);
}

// How long a script waits for the page's trace on the GPU: SwiftShader compiles the kernel in
// 20–80 s on the 2-core machine, and the machine sometimes runs at half pace. A bound against
// a hung page, not a timing.
export const TRACE_TIMEOUT_MS = 600000;

// Waits until `predicate` holds in the page, polled every 100 ms (whether or not the page
// draws frames meanwhile), at most `timeout` ms; when it does not hold by then, throws with
// `what` and the page's state: where it stopped.
export async function waitFor(page, what, predicate, arg = null, timeout = TRACE_TIMEOUT_MS) {
  try {
    await page.waitForFunction(predicate, arg, { timeout, polling: 100 });
  } catch (e) {
    const state = await Promise.race([
      page.evaluate(() => ({ url: window.location.href, ready: document.readyState,
        viewer: window.godelViewer !== undefined, frames: window.godelViewer?.frames,
        error: window.godelViewer?.error, traced: window.godelViewer?.traced !== undefined,
        status: document.getElementById('trace-status')?.textContent })),
      new Promise((resolve) => { setTimeout(() => resolve('the page does not answer'), 10000); }),
    ]).catch((err) => `the page cannot be read: ${err}`);
    throw new Error(`${what}: ${e.message}; the page: ${JSON.stringify(state)}`);
  }
}

// Waits until the page has traced (or failed to trace) on the GPU (traced.js); throws its
// error.
export async function traced(page) {
  await waitFor(page, 'the page did not start its trace on the GPU', () => window.godelViewer
    && (window.godelViewer.error !== null || window.godelViewer.traced !== undefined));
  const shown = await page.evaluate(() => window.godelViewer.error);
  if (shown !== null) throw new Error(`the viewer shows an error: ${shown}`);
  await waitFor(page, 'the page did not finish its trace on the GPU', () => {
    const t = window.godelViewer.traced;
    return t && !t.tracing && (t.traced !== null || t.error !== null);
  });
  await idle(page);
  const error = await page.evaluate(() => window.godelViewer.traced.error);
  if (error !== null) throw new Error(`the page could not trace on the GPU: ${error}`);
}

// Writes the page's shaded picture (or the canvas: which = 'canvas') to PATH (raw RGBA, top row
// first) and its size and `extra` to PATH with .json; returns the size and the bytes.
export async function savePicture(page, path, extra = {}, which = 'picture') {
  const p = await page.evaluate((w) => (w === 'canvas' ? window.godelViewer.readCanvas()
    : window.godelViewer.readPicture()), which);
  const bytes = Buffer.from(p.bytes, 'base64');
  writeFileSync(path, bytes);
  writeFileSync(path.replace(/\.rgba$/, '.json'), JSON.stringify({ width: p.width,
    height: p.height, ...extra }));
  return { width: p.width, height: p.height, bytes };
}

// Pixels (RGB) that differ between two RGBA buffers.
export function differing(a, b) {
  let n = 0;
  for (let i = 0; i < Math.min(a.length, b.length); i += 4) {
    if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2]) n += 1;
  }
  return n + Math.abs(a.length - b.length) / 4;
}

// Explore: waits until the frame on the GPU is the full one of a generation after `after`;
// returns it with the page's event and picture size.
export async function fullFrame(page, after) {
  await page.waitForFunction((g) => {
    const e = window.godelViewer.explore;
    return e && e.shown && e.shown.level === 'full' && e.shown.generation > g;
  }, after, { timeout: 120000 });
  await idle(page);
  return page.evaluate(() => ({ ...window.godelViewer.explore.shown,
    event: { ...window.godelViewer.explore.event },
    width: window.godelViewer.info.width, height: window.godelViewer.info.height }));
}

// Drags the picture to the left by a quarter of its width, as a user does.
export async function dragLeft(page) {
  const box = await page.locator('#image').boundingBox();
  await page.mouse.move(box.x + box.width * 0.6, box.y + box.height * 0.5);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.35, box.y + box.height * 0.5, { steps: 10 });
  await page.mouse.up();
  await idle(page);
}

// Flying (fly.js): waits until the page shows the full frame of the view as it is now, at
// rest (no move of the observer under way), drawn on the canvas with its header and event
// (a server frame's are written with its picture: viewer.js), at most `timeout` ms.
export const atRest = (page, timeout) => page.waitForFunction(() => {
  const v = window.godelViewer;
  const f = v.explore?.fly;
  return f && f.traced && f.traced.level === 'full' && f.traced.version === f.version && !f.moving
    && v.idle();
}, null, { timeout });
