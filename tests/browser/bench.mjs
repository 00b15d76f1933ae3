// Benchmarks of the GPU viewer in headless chromium (SwiftShader: software WebGL2), for
// BENCHMARKS.md. Prints one JSON object.
//
// usage: node bench.mjs URL OUT_DIR load     time from navigation to the first picture
//        node bench.mjs URL OUT_DIR drag     frames per second while dragging a
//                                            1920×1080 look-around view (a sphere file)
import { launch, idle } from './launch.mjs';

const [url, outDir, mode] = process.argv.slice(2);
if (!url || !outDir || !['load', 'drag'].includes(mode)) {
  console.error('usage: node bench.mjs URL OUT_DIR load|drag');
  process.exit(2);
}
const { context, page, requests } = await launch(outDir, { width: 1960, height: 1300 });
const result = { mode };
try {
  await page.goto(url);
  await page.waitForFunction(() => window.godelViewer && (window.godelViewer.firstPicture !== null
    || window.godelViewer.error !== null), null, { timeout: 600000 });
  await idle(page);
  result.error = await page.evaluate(() => window.godelViewer.error);
  result.first_picture_ms = await page.evaluate(() => window.godelViewer.firstPicture);
  result.timeline_ms = await page.evaluate(() => window.godelViewer.timeline);
  result.fetched = await page.evaluate(() => window.godelViewer.fetched());
  result.picture = await page.evaluate(() => {
    const p = window.godelViewer.readPicture();
    return [p.width, p.height];
  });
  if (mode === 'drag') {
    await page.evaluate(() => window.godelViewer.setViewSize(1920, 1080));
    await idle(page);
    const box = await page.locator('#image').boundingBox();
    const y = box.y + box.height / 2;
    const before = await page.evaluate(() => [window.godelViewer.shadings, performance.now()]);
    const started = Date.now();
    // Drag across most of the picture and back, 100 mouse moves each way.
    await page.mouse.move(box.x + box.width * 0.9, y);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * 0.1, y, { steps: 100 });
    await page.mouse.move(box.x + box.width * 0.9, y, { steps: 100 });
    await page.mouse.up();
    await idle(page);
    const after = await page.evaluate(() => {
      window.godelViewer.finish();
      return [window.godelViewer.shadings, performance.now()];
    });
    result.view = await page.evaluate(() => {
      const p = window.godelViewer.readPicture();
      return [p.width, p.height];
    });
    result.frames = after[0] - before[0];
    result.page_seconds = (after[1] - before[1]) / 1000;
    result.seconds = (Date.now() - started) / 1000;
    result.frames_per_second = result.frames / result.seconds;
  }
  result.requests = requests.length;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
