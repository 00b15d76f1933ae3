// Flying in explore mode (fly.js), for the Rust test crates/godel/tests/integration/browser/fly.rs:
// waits for the full frame at rest; compares the page's kernel uniforms with the server's for
// the view (POST /api/explore/input); with "fall freely" on, holds R (up) until the observer has moved a while,
// counting animation frames (its own requestAnimationFrame loop) and the pictures the page
// draws meanwhile; lets go, waits for the full frame at rest and saves its slots and view;
// hovers a hit pixel and one that hit nothing and keeps the map's light rays and the
// record panel's records; drags the picture by touch and zooms with the wheel.
//
// usage: node fly.mjs URL OUT_DIR
// Writes OUT_DIR/fly-slot-S.f32 (RGBA32F, grid row 0 first) and prints {start, moved, tau,
// speed, uniforms_page, uniforms_server, rafs, drawn, traced_moving, moving_sizes, rest,
// header, keyframe, hovered, ray, record, hovered_miss, ray_miss, record_miss, before_touch,
// touch {dx, width, after}, wheel, requests, console_errors, error}.
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { argsOr, launch, open, atRest } from './launch.mjs';

const [url, outDir] = argsOr('node fly.mjs URL OUT_DIR', 2);
const { context, page, requests, consoleErrors } = await launch(outDir, { width: 1200, height: 900 });
// The full frame of the view as it is now, at rest (at most 3 minutes).
const rest = () => atRest(page, 180000);

const result = {};
try {
  await open(page, url);
  await rest();
  result.start = await page.evaluate(() => window.godelViewer.explore.view());
  const compare = await page.evaluate(async () => {
    const e = window.godelViewer.explore;
    const v = e.view();
    const response = await fetch('/api/explore/input', { method: 'POST',
      headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(v) });
    const server = await response.json();
    const ss = server.supersample;
    return { page: e.uniforms(v.camera.width * ss, v.camera.height * ss),
      server: server.uniforms };
  });
  result.uniforms_page = compare.page;
  result.uniforms_server = compare.server;
  // Hold R, counting animation frames and pictures drawn from the first moving frame on.
  await page.evaluate(() => {
    const v = window.godelViewer;
    v.testRafs = 0;
    v.counting = false;
    const count = () => {
      if (v.counting) v.testRafs += 1;
      if (v.counting !== null) requestAnimationFrame(count);
    };
    requestAnimationFrame(count);
  });
  // Falling freely: the velocity R gives stays once it is let go (the geodesic's).
  await page.check('#fly-fall');
  // A fifth of a second of proper time per second: the observer stays near the ball however
  // slowly this machine draws the 40 frames counted.
  await page.locator('#fly-rate').fill('0.2');
  await page.locator('#fly-rate').dispatchEvent('change');
  // A tenth of c: the ball stays within the panorama's 25° band (aberration of the motion).
  await page.evaluate(() => {
    const speed = document.getElementById('fly-speed');
    speed.value = '0.1';
    speed.dispatchEvent(new Event('input'));
  });
  await page.locator('#fly-rate').blur(); // the keys go to the page, not the field
  result.speed = await page.evaluate(() => window.godelViewer.explore.fly.speed);
  await page.keyboard.down('KeyR');
  await page.waitForFunction(() => window.godelViewer.explore.fly.tauMoved > 0, null,
    { timeout: 180000 });
  const before = await page.evaluate(() => {
    const v = window.godelViewer;
    v.counting = true;
    return { frames: v.frames, drawn: v.explore.fly.drawn };
  });
  await page.waitForFunction(() => window.godelViewer.testRafs >= 40, null, { timeout: 180000 });
  const after = await page.evaluate(() => {
    const v = window.godelViewer;
    v.counting = null;
    return { frames: v.frames, drawn: v.explore.fly.drawn, rafs: v.testRafs,
      header: document.getElementById('file').textContent,
      sizes: v.explore.fly.log.slice(-10).map((l) => [l.width, l.height, l.level]) };
  });
  await page.keyboard.up('KeyR');
  result.rafs = after.rafs;
  result.drawn = after.frames - before.frames;
  result.traced_moving = after.drawn - before.drawn;
  result.moving_sizes = after.sizes;
  result.moving_header = after.header;
  await page.waitForFunction(() => !window.godelViewer.explore.fly.moving, null, { timeout: 180000 });
  await rest();
  result.moved = await page.evaluate(() => window.godelViewer.explore.view());
  result.tau = await page.evaluate(() => window.godelViewer.explore.fly.tauMoved);
  const slots = await page.evaluate(() => window.godelViewer.explore.readSlots());
  slots.slots.forEach((b64, s) => writeFileSync(join(outDir, `fly-slot-${s}.f32`),
    Buffer.from(b64, 'base64')));
  result.rest = { width: slots.width, height: slots.height, slots: slots.slots.length,
    traced: await page.evaluate(() => window.godelViewer.explore.fly.traced) };
  result.header = await page.evaluate(() => document.getElementById('file').textContent);
  // Hover the first pixel of status `code` (rows from the top, as the slots): the map shows
  // its light ray, the record read from the frame traced here, its path traced by the kernel.
  const pick = (code) => page.evaluate((code) => {
    const v = window.godelViewer;
    const slots = v.explore.readSlots();
    const bytes = Uint8Array.from(atob(slots.slots[0]), (c) => c.charCodeAt(0));
    const s0 = new Float32Array(bytes.buffer);
    for (let i = 0; i < slots.width * slots.height; i += 1) {
      if (s0[4 * i + 1] !== code) continue;
      const [col, row] = [i % slots.width, Math.floor(i / slots.width)];
      const rect = document.getElementById('image').getBoundingClientRect();
      const point = { clientX: rect.left + (col + 0.5) * rect.width / slots.width,
        clientY: rect.top + (row + 0.5) * rect.height / slots.height };
      return { col, row, x: point.clientX, y: point.clientY, at: v.pixelAt(point) };
    }
    return null;
  }, code);
  // The map's light ray and the record panel's record of the hovered pixel.
  const hover = async (target) => {
    if (!target) return [null, null];
    await page.mouse.move(target.x, target.y);
    await page.waitForFunction(([col, row]) => {
      const v = window.godelViewer;
      const ray = v.explore.map.ray;
      return ray !== null && ray.col === col && ray.row === row
        && v.record && v.record.col === col && v.record.row === row;
    }, target.at, { timeout: 60000 });
    return page.evaluate(() => [window.godelViewer.explore.map.ray, window.godelViewer.record]);
  };
  // Save observer keyframe: the view flown (its velocity from falling freely).
  await page.click('#explore-save-keyframe');
  await page.waitForFunction(() => !document.getElementById('explore-keyframe').hidden, null,
    { timeout: 60000 });
  result.keyframe = await page.evaluate(() =>
    document.getElementById('explore-keyframe').textContent);
  // A hit (status 0), then a ray that hit nothing (status 1, escaped).
  result.hovered = await pick(0);
  [result.ray, result.record] = await hover(result.hovered);
  result.hovered_miss = await pick(1);
  [result.ray_miss, result.record_miss] = await hover(result.hovered_miss);
  // A touch drag across the picture (real touch input: pointer events of type touch), then
  // one wheel step: the view turns about its up axis by the drag's share of the field of
  // view, and the wheel zooms.
  const box = await page.evaluate(() => {
    const r = document.getElementById('image').getBoundingClientRect();
    return { x: r.left + r.width / 2, y: r.top + r.height / 2, width: r.width };
  });
  result.before_touch = await page.evaluate(() => window.godelViewer.explore.view());
  const cdp = await context.newCDPSession(page);
  const touch = (type, x) => cdp.send('Input.dispatchTouchEvent', { type,
    touchPoints: type === 'touchEnd' ? [] : [{ x, y: box.y }] });
  const DRAG_PX = 40;
  await touch('touchStart', box.x);
  for (let k = 1; k <= 4; k += 1) await touch('touchMove', box.x + (DRAG_PX * k) / 4);
  await touch('touchEnd', box.x + DRAG_PX);
  result.touch = { dx: DRAG_PX, width: box.width,
    after: await page.evaluate(() => window.godelViewer.explore.view()) };
  await page.mouse.move(box.x, box.y);
  await page.mouse.wheel(0, 100);
  await page.waitForFunction((h) => window.godelViewer.explore.view().camera.h_fov_deg !== h,
    result.touch.after.camera.h_fov_deg, { timeout: 60000 });
  result.wheel = await page.evaluate(() => window.godelViewer.explore.view());
  await page.screenshot({ path: join(outDir, 'fly.png') });
  result.error = await page.evaluate(() => window.godelViewer.error
    || window.godelViewer.explore.fly.error);
  result.requests = requests;
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
