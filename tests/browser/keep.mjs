// Explore's "Render exactly" and "Record" in the browser, for the Rust test
// crates/godel/tests/integration/browser/keep.rs.
//
// usage: node keep.mjs URL OUT_DIR X T
// Waits for the full frame of the scene's own event, then moves the observer with the Explore
// panel's x field to X (and waits for its full frame); "Render exactly" of that view at the
// size and samples already in the panel, downloading OUT_DIR/exact.png and OUT_DIR/exact.exr.
// Then records a flight: Record, t set to T, x back to 0, Stop, and downloads the script as
// OUT_DIR/flight.toml. Prints {view (the view rendered exactly), exact (its state and status
// line), keyframes (the recorded {seconds, view}), record_status, requests, console_errors,
// error}.
import { copyFile } from 'node:fs/promises';
import { join } from 'node:path';
import { argsOr, launch, pageReport, open, fullFrame } from './launch.mjs';

const [url, outDir, x, t] = argsOr('node keep.mjs URL OUT_DIR X T', 4);
const { context, page, requests, consoleErrors } = await launch(outDir);

const download = async (selector, path) => {
  const [file] = await Promise.all([page.waitForEvent('download'), page.locator(selector).click()]);
  await copyFile(await file.path(), path);
};
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

const result = {};
try {
  await open(page, url);
  const first = await fullFrame(page, 0);
  await page.locator('#explore-x').fill(x);
  await page.locator('#explore-x').dispatchEvent('change');
  await fullFrame(page, first.generation);
  // Render exactly the view on screen.
  await page.locator('#keep-render').click();
  await page.waitForFunction(() => window.godelViewer.keep.state
    && window.godelViewer.keep.state !== 'rendering', null, { timeout: 120000 });
  result.view = await page.evaluate(() => window.godelViewer.keep.view);
  result.exact = await page.evaluate(() => ({ state: window.godelViewer.keep.state,
    status: document.getElementById('keep-status').textContent }));
  await download('#keep-png', join(outDir, 'exact.png'));
  await download('#keep-exr', join(outDir, 'exact.exr'));
  // Record a flight: the time moves, then x, each change kept as a keyframe.
  await page.locator('#keep-record').click();
  await sleep(400);
  await page.locator('#explore-t-value').fill(t);
  await page.locator('#explore-t-value').dispatchEvent('change');
  await sleep(400);
  await page.locator('#explore-x').fill('0');
  await page.locator('#explore-x').dispatchEvent('change');
  await sleep(400);
  await page.locator('#keep-record').click();
  // The script, or the server's refusal in the status line (named in the error).
  await page.waitForFunction(() => window.godelViewer.keep.script !== null
    || !document.getElementById('keep-record-status').textContent.startsWith('recording'),
  null, { timeout: 60000 }).catch(async (e) => {
    const line = await page.evaluate(() => document.getElementById('keep-record-status')
      .textContent);
    throw new Error(`no script after Stop (${e.message}); the record status: ${line}`);
  });
  const script = await page.evaluate(() => window.godelViewer.keep.script);
  if (script === null) {
    throw new Error(`Stop gave no script: ${await page.evaluate(
      () => document.getElementById('keep-record-status').textContent)}`);
  }
  await download('#keep-script', join(outDir, 'flight.toml'));
  result.keyframes = await page.evaluate(() => window.godelViewer.keep.keyframes);
  result.record_status = await page.evaluate(
    () => document.getElementById('keep-record-status').textContent);
  Object.assign(result, await pageReport(page, requests, consoleErrors));
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
