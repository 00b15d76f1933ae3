// Explore mode in the browser: waits for the full frame of the scene's own event, moves the
// time slider to T, waits for the full frame of the new event, and saves both pictures; then
// plays time for four frames and pauses, for the Rust test
// crates/godel/tests/integration/browser/explore.rs.
//
// usage: node explore.mjs URL OUT_DIR T
// Writes OUT_DIR/before.rgba and OUT_DIR/after.rgba (+ .json), and prints {before, after,
// saved (the size of the PNG "Save PNG" downloads after the move), panel_hidden, status,
// play_log, paused, paused_t, requests, console_errors, error}.
import { readFile } from 'node:fs/promises';
import { join } from 'node:path';
import { argsOr, launch, pageReport, open, savePicture, fullFrame } from './launch.mjs';

const [url, outDir, t] = argsOr('node explore.mjs URL OUT_DIR T', 3);
const { context, page, requests, consoleErrors } = await launch(outDir);

const result = {};
try {
  await open(page, url);
  result.panel_hidden = await page.evaluate(() => document.getElementById('explore-panel').hidden);
  result.before = await fullFrame(page, 0);
  await savePicture(page, join(outDir, 'before.rgba'));
  await page.locator('#explore-t').fill(t);
  result.after = await fullFrame(page, result.before.generation);
  await savePicture(page, join(outDir, 'after.rgba'));
  // "Save PNG" of the frame on screen (issue 24: it gave the first coarse frame).
  const [download] = await Promise.all([page.waitForEvent('download'),
    page.locator('#save-png').click()]);
  const png = await readFile(await download.path());
  result.saved = { width: png.readUInt32BE(16), height: png.readUInt32BE(20) };
  result.status = await page.evaluate(() => document.getElementById('explore-status').textContent);
  // Play (rate 2 t per second) until four frames are taken, logging the shading passes run
  // when each is taken; then Pause, which asks for the full frame of where time stopped.
  await page.evaluate(() => {
    const v = window.godelViewer;
    v.playLog = [];
    const show = v.showFrame;
    v.showFrame = (frame, channelUrl) => {
      const taken = show(frame, channelUrl);
      if (taken) v.playLog.push({ generation: frame.generation, level: frame.level,
        t: frame.event.t, shadings: v.shadings });
      return taken;
    };
    // The log as it was when Pause was clicked: the frames of the Pause's own request (the
    // same t, traced again) may come before the test reads it.
    v.playLogAtPause = null;
    document.getElementById('explore-play').addEventListener('click', () => {
      if (v.playLog.length >= 4 && v.playLogAtPause === null) v.playLogAtPause = v.playLog.slice();
    }, { capture: true });
  });
  await page.locator('#explore-rate').fill('2');
  await page.locator('#explore-play').click();
  await page.waitForFunction(() => window.godelViewer.playLog.length >= 4, null,
    { timeout: 120000 });
  await page.locator('#explore-play').click();
  const pausedAt = await page.evaluate(() => ({ t: window.godelViewer.explore.event.t,
    generation: window.godelViewer.explore.requested,
    log: window.godelViewer.playLogAtPause }));
  result.paused = await fullFrame(page, pausedAt.generation - 1);
  result.paused_t = pausedAt.t;
  result.play_log = pausedAt.log;
  Object.assign(result, await pageReport(page, requests, consoleErrors));
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
