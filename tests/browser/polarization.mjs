// The page's polarization layer and its emitter-axis control (issue 25), for the Rust test
// crates/godel/tests/integration/browser/polarization.rs: turns the layer on with its checkbox
// (texture and polarization) and saves the file's frame (file.rgba); traces the frame on the
// GPU and saves its slots (trace-0-slot-S.f32, trace-0.json) and its picture (traced.rgba);
// then turns the first object's polarization axis with the azimuth slider, as a user drags
// it, and saves the picture again (turned.rgba). Each picture's .json holds the settings it
// was shaded with.
//
// usage: node polarization.mjs URL OUT_DIR AZIMUTH
// Prints {requests, console_errors, requests_while_turning, traces_before, traces_after}.
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { argsOr, launch, open, idle, savePicture, traced } from './launch.mjs';

const [url, outDir, azimuth] = argsOr('node polarization.mjs URL OUT_DIR AZIMUTH', 3);
const settings = (page) => page.evaluate(() => window.godelViewer.settings);
// The traced frame the page holds (a new object with each trace).
const traceMark = (page) => page.evaluate(() => {
  const t = window.godelViewer.traced;
  if (!t.traced) return null;
  t.traced.mark = t.traced.mark || Math.random();
  return t.traced.mark;
});

const { context, page, requests, consoleErrors } = await launch(outDir);
const result = {};
try {
  await open(page, url);
  await page.check('#layer-texture');
  await page.uncheck('#layer-frequency');
  await page.check('#layer-polarization');
  await idle(page);
  await savePicture(page, join(outDir, 'file.rgba'), { settings: await settings(page) });

  await page.check('#trace-gpu');
  await traced(page);
  const slots = await page.evaluate(() => window.godelViewer.traced.readSlots());
  slots.slots.forEach((b64, s) => writeFileSync(join(outDir, `trace-0-slot-${s}.f32`),
    Buffer.from(b64, 'base64')));
  writeFileSync(join(outDir, 'trace-0.json'), JSON.stringify({ width: slots.width,
    height: slots.height, slots: slots.slots.length }));
  await savePicture(page, join(outDir, 'traced.rgba'), { settings: await settings(page) });

  // The slider dragged: input events, as the browser sends them while it moves.
  result.traces_before = await traceMark(page);
  const asked = requests.length;
  await page.$eval('#axis-azimuth-0', (input, value) => {
    input.value = value;
    input.dispatchEvent(new Event('input', { bubbles: true }));
  }, azimuth);
  await idle(page);
  result.requests_while_turning = requests.slice(asked);
  result.traces_after = await traceMark(page);
  await savePicture(page, join(outDir, 'turned.rgba'), { settings: await settings(page) });
  result.requests = requests;
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
