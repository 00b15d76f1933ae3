// Drives a real browser (Debian's chromium, through playwright-core) against a running
// `godel view`, and prints what it saw as one JSON object on stdout, for the Rust test
// crates/godel/tests/integration/browser.rs to check.
//
// usage: node viewer.mjs URL OUT_DIR COL ROW
//   COL ROW: a pixel that the caller knows to be a hit; its record is read on hover.
// Writes into OUT_DIR: screenshot.png, saved.png (the "Save PNG" download),
// keyframe.toml (the "Save keyframe" download), slider.rgba/.json (the picture after the
// slider moved), textured.rgba and zoomed.rgba (the picture with the texture layer, and the
// canvas zoomed in on it) and a fresh chromium profile.
import { join } from 'node:path';
import { argsOr, launch, open, idle, savePicture, differing } from './launch.mjs';

const [url, outDir, colText, rowText] = argsOr('node viewer.mjs URL OUT_DIR COL ROW', 4);
const col = Number(colText);
const row = Number(rowText);

const { context, page, requests, consoleErrors } = await launch(outDir);
const result = {};
try {
  await open(page, url);
  result.title = await page.title();
  const first = await savePicture(page, join(outDir, 'first.rgba'));
  result.canvas = [first.width, first.height];

  // The temperature matters to the frequency layer: switch to it alone first.
  await page.check('#layer-frequency');
  await page.uncheck('#layer-texture');
  await page.waitForFunction(() => window.godelViewer.settings.shaders.join() === 'frequency');
  await idle(page);
  const before = await savePicture(page, join(outDir, 'before.rgba'));
  const temperatureBefore = await page.inputValue('#temperature-0');

  // Move the temperature slider with the mouse, as a user does: press near its right
  // end and drag to near its left end (a stream of input events).
  const shadingsBefore = await page.evaluate(() => window.godelViewer.shadings);
  const requestsBefore = requests.length;
  const slider = page.locator('#temperature-0');
  await slider.scrollIntoViewIfNeeded();
  const box = await slider.boundingBox();
  const y = box.y + box.height / 2;
  await page.mouse.move(box.x + box.width * 0.8, y);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.1, y, { steps: 20 });
  await page.mouse.up();
  await idle(page);
  const after = await savePicture(page, join(outDir, 'slider.rgba'),
    { settings: await page.evaluate(() => window.godelViewer.settings) });
  result.temperature = [Number(temperatureBefore), Number(await page.inputValue('#temperature-0'))];
  result.pixels_changed = differing(before.bytes, after.bytes);
  result.shadings_for_drag = await page.evaluate((n) => window.godelViewer.shadings - n,
    shadingsBefore);
  // Slider changes are shaded on the GPU: the page asks the server nothing.
  result.requests_for_drag = requests.slice(requestsBefore);

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
    'direction', 'doppler']) {
    result.record_shown[field] = await page.textContent(`#record [data-field="${field}"]`);
  }
  result.record = await page.evaluate(() => window.godelViewer.record);

  // The two save buttons download files.
  const save = async (button, name) => {
    const [download] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
    await download.saveAs(join(outDir, name));
    return download.suggestedFilename();
  };
  result.png_name = await save('#save-png', 'saved.png');
  result.keyframe_name = await save('#save-keyframe', 'keyframe.toml');
  result.settings = await page.evaluate(() => window.godelViewer.settings);

  // Zoom in with the wheel over the textured ball: the picture is enlarged smoothly
  // (filtered), not in blocks, and the server is not asked.
  await page.check('#layer-texture');
  await idle(page);
  await savePicture(page, join(outDir, 'textured.rgba'));
  const requestsBeforeZoom = requests.length;
  await page.mouse.move(
    canvasBox.x + (col + 0.5) * canvasBox.width / result.canvas[0],
    canvasBox.y + (row + 0.5) * canvasBox.height / result.canvas[1],
  );
  await page.mouse.wheel(0, -2000);
  await page.waitForFunction(() => window.godelViewer.zoom() > 6);
  await idle(page);
  await savePicture(page, join(outDir, 'zoomed.rgba'), {}, 'canvas');
  result.zoom = await page.evaluate(() => window.godelViewer.zoom());
  result.requests_for_zoom = requests.slice(requestsBeforeZoom)
    .filter((r) => !r.includes('/api/pixel?'));

  await page.screenshot({ path: join(outDir, 'screenshot.png'), fullPage: true });

  // Bad settings sent to the server: its message shows on the page.
  await page.evaluate(() => window.godelViewer.sendRaw('{"shaders": ["sepia"]}'));
  result.error_shown = await page.isVisible('#error');
  result.error_text = await page.textContent('#error');
  result.console_errors = consoleErrors;
  result.requests = requests;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
