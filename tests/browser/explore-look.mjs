// Explore mode with `--sphere`: the page looks around in the traced sphere as `godel view`
// does (a drag turns the view without asking the server for anything), and a new event keeps
// the view turned; for the Rust test crates/godel/tests/integration/browser/explore.rs.
//
// usage: node explore-look.mjs URL OUT_DIR T
// Prints {look, drag: {yaw, pixels_changed, requests}, after: {event, level, yaw, look},
// pixels_changed_by_t, console_errors, error}.
import { join } from 'node:path';
import { argsOr, launch, open, savePicture, differing, fullFrame, dragLeft } from './launch.mjs';

const [url, outDir, t] = argsOr('node explore-look.mjs URL OUT_DIR T', 3);
const { context, page, requests, consoleErrors } = await launch(outDir);

const result = {};
try {
  await open(page, url);
  const first = await fullFrame(page, 0);
  result.look = await page.evaluate(() => window.godelViewer.look);
  const before = await savePicture(page, join(outDir, 'look-before.rgba'), {}, 'canvas');
  const requestsBefore = requests.length;
  await dragLeft(page);
  const dragged = await savePicture(page, join(outDir, 'look-dragged.rgba'), {}, 'canvas');
  result.drag = {
    yaw: await page.evaluate(() => window.godelViewer.look.yaw),
    pixels_changed: differing(before.bytes, dragged.bytes),
    requests: requests.slice(requestsBefore).filter((r) => !r.includes('/api/pixel?')
      && !r.includes('/api/explore/frame') && !r.includes('/api/explore/ray')),
  };
  // A new time: the frame traced for it, seen in the same turned view.
  await page.locator('#explore-t').fill(t);
  const after = await fullFrame(page, first.generation);
  const moved = await savePicture(page, join(outDir, 'look-after.rgba'), {}, 'canvas');
  result.after = { ...after, yaw: await page.evaluate(() => window.godelViewer.look.yaw),
    look: await page.evaluate(() => window.godelViewer.look !== null) };
  result.pixels_changed_by_t = differing(dragged.bytes, moved.bytes);
  result.error = await page.evaluate(() => window.godelViewer.error);
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
