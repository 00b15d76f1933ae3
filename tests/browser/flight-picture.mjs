// The picture of a flight in the README and the guide (scripts/flight-picture.sh): in explore
// mode, with "Fall freely" on, holds W at SPEED (fraction of c) until the observer's time
// passes UNTIL, lets go, waits for the full frame traced in the browser at rest, hovers the
// middle of the leftmost image on the picture's middle row (made by light that looped round
// the observer's axis) until the map shows its light ray, and saves the page as OUT.png.
// usage: node flight-picture.mjs URL OUT_DIR OUT.png SPEED UNTIL
// Prints {view, hovered, full_ms}.
import { argsOr, launch, open, atRest } from './launch.mjs';

const [url, outDir, out, speed, until] = argsOr('node flight-picture.mjs URL OUT_DIR OUT.png SPEED UNTIL', 5);
// Bounds on each wait: the full frame of the reference scene takes about 40 s here.
const WAIT_MS = 600000;
const { context, page } = await launch(outDir, { width: 1400, height: 790 });
const rest = () => atRest(page, WAIT_MS);
try {
  await open(page, url);
  await page.waitForFunction(() => window.godelViewer.explore?.fly?.drawn > 0, null,
    { timeout: WAIT_MS });
  await page.$eval('#fly-speed', (e, v) => {
    e.value = v;
    e.dispatchEvent(new Event('input', { bubbles: true }));
  }, speed);
  await page.check('#fly-fall');
  await page.keyboard.down('KeyW');
  await page.waitForFunction((t) => window.godelViewer.explore.view().time >= t, Number(until),
    { timeout: WAIT_MS });
  await page.keyboard.up('KeyW');
  const letGo = Date.now();
  await page.waitForFunction(() => !window.godelViewer.explore.fly.moving, null,
    { timeout: WAIT_MS });
  await rest();
  const fullMs = Date.now() - letGo;
  const target = await page.evaluate(() => {
    const v = window.godelViewer;
    const slots = v.explore.readSlots();
    const bytes = Uint8Array.from(atob(slots.slots[0]), (c) => c.charCodeAt(0));
    const s0 = new Float32Array(bytes.buffer);
    const row = slots.height >> 1;
    const hit = (col) => s0[4 * (row * slots.width + col) + 1] === 0; // the status
    let first = 0;
    while (first < slots.width && !hit(first)) first += 1;
    if (first === slots.width) return null;
    let end = first;
    while (end < slots.width && hit(end)) end += 1;
    // The middle of that image's run of samples, well within it.
    const c = (first + end) >> 1;
    const rect = document.getElementById('image').getBoundingClientRect();
    return { x: rect.left + (c + 0.5) * rect.width / slots.width,
      y: rect.top + (row + 0.5) * rect.height / slots.height };
  });
  if (target === null) throw new Error('no pixel of the middle row sees an object');
  await page.mouse.move(target.x, target.y);
  await page.waitForFunction(() => window.godelViewer.explore.map.ray !== null
    && window.godelViewer.explore.map.idle(), null, { timeout: WAIT_MS });
  await page.screenshot({ path: out });
  console.log(JSON.stringify({ view: await page.evaluate(() => window.godelViewer.explore.view()),
    hovered: await page.evaluate(() => {
      const r = window.godelViewer.explore.map.ray;
      return { col: r.col, row: r.row, status: r.status, travel_time: r.travel_time };
    }),
    full_ms: fullMs }));
} finally {
  await context.close();
}
