// The explore map in the browser, for crates/godel/tests/integration/browser/explore.rs: waits for
// the full frame of the scene's own event and its map, hovers the picture pixel COL ROW (the
// map then shows its light ray; the script reads the map canvas back along the ray), leaves
// the picture, drags the observer's marker on the map by (DX, DY) CSS pixels, waits for the
// full frame of the new event, and clicks "Save observer keyframe".
//
// usage: node map.mjs URL OUT_DIR COL ROW DX DY
// Writes OUT_DIR/before.rgba, OUT_DIR/after.rgba (+ .json) and OUT_DIR/keyframe.toml, and
// prints one JSON object (see `result` below).
import { join } from 'node:path';
import { argsOr, launch, pageReport, open, idle, savePicture } from './launch.mjs';

const [url, outDir, colText, rowText, dxText, dyText] = argsOr('node map.mjs URL OUT_DIR COL ROW DX DY', 6);
const [col, row, dx, dy] = [colText, rowText, dxText, dyText].map(Number);
const { context, page, requests, consoleErrors } = await launch(outDir);

// The full frame of a generation after `after` is on the GPU and the map is of its event.
async function settled(after) {
  await page.waitForFunction((g) => {
    const e = window.godelViewer.explore;
    return e && e.shown && e.shown.level === 'full' && e.shown.generation > g
      && e.shown.generation === e.requested && !e.inFlight && !e.again && e.map.fetched !== null
      && e.map.idle() && ['t', 'x', 'y', 'z'].every((k) => e.map.fetched.event[k] === e.event[k]);
  }, after, { timeout: 120000 });
  await idle(page);
  const frame = (await page.evaluate(() => fetch('/api/explore/frame').then((r) => r.json()))).frame;
  return page.evaluate((f) => {
    const e = window.godelViewer.explore;
    return { ...e.shown, frame_event: f.event, event: { ...e.event },
      fields: ['x', 'y', 'z'].map((k) => Number(document.getElementById(`explore-${k}`).value)),
      width: window.godelViewer.info.width, height: window.godelViewer.info.height };
  }, frame);
}

// Ray-coloured pixels of the map's top view: in all, and near each point of the ray (within
// 2 CSS pixels) that lies inside the plot.
const rayPixels = () => page.evaluate(() => {
  const m = window.godelViewer.explore.map;
  const canvas = document.getElementById(m.canvas);
  const dpr = canvas.width / canvas.getBoundingClientRect().width;
  const pixels = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  const [r, g, b] = [0xff, 0xd2, 0x3f];
  const isRay = (i) => Math.abs(pixels[i] - r) <= 24 && Math.abs(pixels[i + 1] - g) <= 24
    && Math.abs(pixels[i + 2] - b) <= 24;
  let total = 0;
  for (let i = 0; i < pixels.length; i += 4) if (isRay(i)) total += 1;
  let inside = 0;
  let near = 0;
  for (const p of m.ray ? m.ray.points : []) {
    const s = m.toScreen(p.x, p.y);
    const [x, y] = [Math.round(s.px * dpr), Math.round(s.py * dpr)];
    if (x < 50 * dpr || y < 45 * dpr || x >= canvas.width - 15 * dpr || y >= canvas.height - 40 * dpr) continue;
    inside += 1;
    let found = false;
    for (let v = -2 * dpr; v <= 2 * dpr && !found; v += 1) {
      for (let u = -2 * dpr; u <= 2 * dpr && !found; u += 1) {
        found = isRay(((y + v) * canvas.width + (x + u)) * 4);
      }
    }
    if (found) near += 1;
  }
  return { total, inside, near };
});

// Hovers pixel (col, row) of the frame shown, then leaves the picture: the pixel's record,
// the map's ray, and the ray-coloured pixels of the map before, during and after.
async function hover(frame) {
  const seen = {};
  // The record of the frame on screen, named as the page names it.
  seen.record = await page.evaluate(([c, r]) => {
    const shown = window.godelViewer.frameQuery();
    return fetch(`/api/pixel${shown ? `${shown}&` : '?'}col=${c}&row=${r}`).then((x) => x.json());
  }, [col, row]);
  seen.ray_pixels_before = await rayPixels();
  // The picture fills the canvas (fitted).
  const box = await page.locator('#image').boundingBox();
  await page.mouse.move(box.x + (col + 0.5) * box.width / frame.width,
    box.y + (row + 0.5) * box.height / frame.height);
  await page.waitForFunction(([c, r]) => {
    const m = window.godelViewer.explore.map;
    return m.ray !== null && m.ray.col === c && m.ray.row === r;
  }, [col, row]);
  seen.ray = await page.evaluate(() => window.godelViewer.explore.map.ray);
  // The Pixel panel shows the same pixel, with its direction in the frame's camera.
  await page.waitForFunction(([c, r]) => {
    const record = window.godelViewer.record;
    return record !== null && record.col === c && record.row === r;
  }, [col, row]);
  seen.direction = await page.evaluate(() => document
    .querySelector('#record [data-field="direction"]').textContent);
  seen.ray_pixels = await rayPixels();
  // Leaving the picture clears the ray.
  await page.mouse.move(box.x + box.width - 4, box.y + box.height + 6);
  await page.waitForFunction(() => window.godelViewer.explore.map.ray === null);
  seen.ray_pixels_after = await rayPixels();
  return seen;
}

const result = {};
try {
  await open(page, url);
  result.map_hidden = await page.evaluate(() => document.getElementById('map-panel').hidden);
  result.before = await settled(0);
  result.map = await page.evaluate(() => {
    const m = window.godelViewer.explore.map.fetched;
    return { horizon_points: m.horizon.length, objects: m.objects.map((o) => o.name) };
  });
  result.hover_before = await hover(result.before);
  await savePicture(page, join(outDir, 'before.rgba'));

  result.console_errors_before_drag = [...consoleErrors];

  // Drag the observer: the map's window stays put while dragging, so the drop point's map
  // coordinates follow from two points of toScreen taken before.
  const mapBox = await page.locator('#map-top').boundingBox();
  const [from, o, one] = await page.evaluate(() => {
    const m = window.godelViewer.explore.map;
    return [m.toScreen(m.event.x, m.event.y), m.toScreen(0, 0), m.toScreen(1, 1)];
  });
  const [sx, sy] = [one.px - o.px, one.py - o.py];
  const drop = { px: from.px + dx, py: from.py + dy };
  result.drop = { x: (drop.px - o.px) / sx, y: (drop.py - o.py) / sy, pixel: 1 / Math.abs(sx) };
  await page.mouse.move(mapBox.x + from.px, mapBox.y + from.py);
  await page.mouse.down();
  for (let k = 1; k <= 10; k += 1) {
    await page.mouse.move(mapBox.x + from.px + dx * k / 10, mapBox.y + from.py + dy * k / 10);
  }
  await page.mouse.up();
  result.after = await settled(result.before.generation);
  await savePicture(page, join(outDir, 'after.rgba'));
  result.map_after = await page.evaluate(() => window.godelViewer.explore.map.fetched.event);
  result.hover_after = await hover(result.after);

  // Save observer keyframe: shown on the page and downloaded.
  const [download] = await Promise.all([page.waitForEvent('download'),
    page.locator('#explore-save-keyframe').click()]);
  result.keyframe_name = download.suggestedFilename();
  await download.saveAs(join(outDir, 'keyframe.toml'));
  await page.waitForFunction(() => !document.getElementById('explore-keyframe').hidden);
  result.keyframe_shown = await page.evaluate(() => document.getElementById('explore-keyframe').textContent);
  Object.assign(result, await pageReport(page, requests, consoleErrors));
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
