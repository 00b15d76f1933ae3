// Makes the guide's pictures of the viewer with Debian's chromium (WebGL2 on SwiftShader):
// the mouse on pixel COL ROW of the picture, after applying SETTINGS (JSON: "shaders", and for
// a full-sphere file "look": projection, fov, yaw, pitch, speed, preset).
// With "explore": true in SETTINGS (`godel explore` serving URL) it first waits for the full
// frame of the scene's event and its map, and then also for the map's light ray of the pixel.
// usage: node screenshot.mjs URL OUT.png COL ROW [SETTINGS]   (with `godel view` serving URL)
//   e.g. node screenshot.mjs URL docs/guide/src/pictures/viewer.png 700 125 '{"shaders": ["frequency"]}'
//        node screenshot.mjs URL docs/guide/src/pictures/explore.png 300 50 '{"explore": true}'
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { argsOr, launch, open, idle } from './launch.mjs';

const [url, out, col, row, settingsText] = argsOr('node screenshot.mjs URL OUT.png COL ROW [SETTINGS]', 4);
const settings = JSON.parse(settingsText || '{"shaders": ["frequency"]}');
const { context, page } = await launch(mkdtempSync(join(tmpdir(), 'godel-shot-')),
  settings.explore ? { width: 1400, height: 900 } : { width: 1500, height: 960 });
try {
  await open(page, url);
  if (settings.explore) {
    await page.waitForFunction(() => {
      const e = window.godelViewer.explore;
      return e && e.shown && e.shown.level === 'full' && e.map.fetched !== null && e.map.idle();
    }, null, { timeout: 600000 });
  }
  await page.evaluate((s) => {
    const v = window.godelViewer;
    if (s.shaders) v.settings.shaders = s.shaders;
    if (s.look && v.look) Object.assign(v.look, s.look);
    v.changed();
  }, settings);
  await idle(page);
  const box = await page.locator('#image').boundingBox();
  const [w, h] = await page.evaluate(() => {
    const p = window.godelViewer.readPicture();
    return [p.width, p.height];
  });
  // The picture is centred on the canvas (look) or fills it (a file's own pixels).
  const canvas = await page.evaluate(() => [document.getElementById('image').width,
    document.getElementById('image').height]);
  const scale = box.width / canvas[0];
  const zoom = await page.evaluate(() => (window.godelViewer.look ? 1 : null));
  const [sx, sy] = zoom ? [scale, scale] : [box.width / w, box.height / h];
  const [ox, oy] = zoom ? [Math.floor((canvas[0] - w) / 2) * scale,
    Math.floor((canvas[1] - h) / 2) * scale] : [0, 0];
  await page.mouse.move(box.x + ox + (Number(col) + 0.5) * sx, box.y + oy + (Number(row) + 0.5) * sy);
  await page.waitForFunction(() => window.godelViewer.record !== null);
  if (settings.explore) {
    await page.waitForFunction(([c, r]) => {
      const ray = window.godelViewer.explore.map.ray;
      return ray !== null && ray.col === c && ray.row === r;
    }, [Number(col), Number(row)]);
  }
  await page.screenshot({ path: out });
} finally {
  await context.close();
}
