// The page checks what it shows (fly.js, crates/viewer/src/page_check.rs), for the Rust test
// crates/godel/tests/integration/browser/page_check.rs: explore serves a kernel with a fault; the
// page's first traced frame is checked against the server's CPU exact tracer, refused, and
// the server's frames (coarse, then full) are shown from then on, the header saying why.
//
// usage: node fly-check.mjs URL OUT_DIR
// prints {refused (explore's note), check (fly.js's last check), header, shown (the server's
// frame shown: generation, level), size [width, height], requests_after (the requests since
// the refusal), requests (all), console_errors, error}.
import { argsOr, launch, idle } from './launch.mjs';

const [url, outDir] = argsOr('node fly-check.mjs URL OUT_DIR', 2);
const { context, page, requests, consoleErrors } = await launch(outDir, { width: 1200, height: 900 });
const result = {};
try {
  await page.goto(url);
  await page.waitForFunction(() => window.godelViewer?.explore?.refused, null,
    { timeout: 240000 });
  const at = requests.length;
  // The server's full frame of the event, asked for after the refusal.
  await page.waitForFunction(() => {
    const e = window.godelViewer.explore;
    return e.shown && e.shown.generation === e.requested && e.shown.level === 'full';
  }, null, { timeout: 120000 });
  await idle(page);
  Object.assign(result, await page.evaluate(() => {
    const v = window.godelViewer;
    const e = v.explore;
    return { refused: e.refused, check: e.refusedCheck, shown: e.shown, fly: e.fly ?? null,
      size: [v.info.width, v.info.height], header: document.getElementById('file').textContent,
      error: v.error };
  }));
  result.requests_after = requests.slice(at);
  result.requests = requests;
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
