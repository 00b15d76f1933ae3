// Looks around a full-sphere data file on the GPU, as a user does (drag, velocity), and saves
// the pictures with the view the server would make them of, for the Rust test
// crates/godel/tests/integration/browser.rs to compare with `godel look` then `godel shade`.
//
// usage: node look.mjs URL OUT_DIR CASES.json
//   CASES.json: a list of {look: {projection, fov, yaw, pitch, speed, preset}, settings}.
// Writes into OUT_DIR: case-K.rgba (+ .json holding "body", the settings and view that "Save
// PNG" sends), drag-before/after.rgba (the canvas around a drag), saved-look.png (the "Save
// PNG" download of the last case), and prints what it saw as one JSON object.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { argsOr, launch, open, idle, savePicture, differing, dragLeft } from './launch.mjs';

const [url, outDir, casesFile] = argsOr('node look.mjs URL OUT_DIR CASES.json', 3);
const cases = JSON.parse(readFileSync(casesFile, 'utf8'));
const { context, page, requests, consoleErrors } = await launch(outDir);
const result = { errors: [] };
try {
  await open(page, url);
  result.look = await page.evaluate(() => window.godelViewer.look);
  await page.evaluate(() => window.godelViewer.setViewSize(160, 120));
  await idle(page);

  const before = await savePicture(page, join(outDir, 'drag-before.rgba'), {}, 'canvas');
  const framesBefore = await page.evaluate(() => window.godelViewer.frames);
  const requestsBefore = requests.length;
  await dragLeft(page);
  const after = await savePicture(page, join(outDir, 'drag-after.rgba'),
    { body: JSON.parse(await page.evaluate(() => window.godelViewer.saveBody())) }, 'canvas');
  result.drag = {
    yaw: await page.evaluate(() => window.godelViewer.look.yaw),
    pixels_changed: differing(before.bytes, after.bytes),
    frames: await page.evaluate((n) => window.godelViewer.frames - n, framesBefore),
    // Hovering asks the server for records; turning asks nothing else.
    requests: requests.slice(requestsBefore).filter((r) => !r.includes('/api/pixel?')),
  };

  for (const [k, c] of cases.entries()) {
    await page.evaluate((c) => {
      const v = window.godelViewer;
      Object.assign(v.look, c.look);
      for (const key of Object.keys(v.settings)) delete v.settings[key];
      Object.assign(v.settings, c.settings);
      v.changed();
    }, c);
    await idle(page);
    result.errors.push(await page.evaluate(() => window.godelViewer.error));
    await savePicture(page, join(outDir, `case-${k}.rgba`),
      { body: JSON.parse(await page.evaluate(() => window.godelViewer.saveBody())) });
  }

  // Hover the centre of the last view: the record of the sphere pixel it shows, its direction.
  // The record of an earlier hover (the drag above ended over the picture) must not be read
  // as this one's: forget it, then wait for the answer to this move.
  const centre = await page.locator('#image').boundingBox();
  await page.evaluate(() => { window.godelViewer.record = null; });
  await page.mouse.move(centre.x + centre.width / 2, centre.y + centre.height / 2);
  await page.waitForFunction(() => window.godelViewer.record !== null);
  result.record = await page.evaluate(() => window.godelViewer.record);
  result.record_shown = {};
  for (const field of ['pixel', 'g', 'direction', 'static_direction', 'doppler']) {
    result.record_shown[field] = await page.textContent(`#record [data-field="${field}"]`);
  }

  const [download] = await Promise.all([page.waitForEvent('download'),
    page.click('#save-png')]);
  await download.saveAs(join(outDir, 'saved-look.png'));
  result.png_name = download.suggestedFilename();
  result.requests = requests;
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
