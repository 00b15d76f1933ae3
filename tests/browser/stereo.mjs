// The page's Stereo panel (issue 37), for the Rust test
// crates/godel/tests/integration/browser/stereo.rs: viewing one eye of a stereo pair,
// waits for the panel's picture of both eyes in the pair's layout and saves it
// (pair.png, its size and the page's settings in pair.json); then chooses the anaglyph and
// saves that picture (anaglyph.png, anaglyph.json).
//
// usage: node stereo.mjs URL OUT_DIR
// Prints {panel_shown, layout_selected, error, requests, console_errors}.
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { argsOr, launch, open, pageReport } from './launch.mjs';

const [url, outDir] = argsOr('node stereo.mjs URL OUT_DIR', 2);

// Waits until the panel has shown `n` pictures and wants no other (or the page shows an
// error).
const shown = (page, n) => page.waitForFunction((count) => {
  const v = window.godelViewer;
  return v.error !== null || (v.stereo !== undefined && v.stereo.shown >= count
    && !v.stereo.busy);
}, n);

// Saves the panel's picture as NAME.png (the bytes the server sent) and NAME.json.
async function save(page, name) {
  const p = await page.evaluate(async () => {
    const img = /** @type {HTMLImageElement} */ (document.getElementById('stereo-image'));
    const bytes = new Uint8Array(await (await fetch(img.src)).arrayBuffer());
    return { width: img.naturalWidth, height: img.naturalHeight,
      png: window.godelViewer.base64(bytes), settings: window.godelViewer.settings };
  });
  writeFileSync(join(outDir, `${name}.png`), Buffer.from(p.png, 'base64'));
  writeFileSync(join(outDir, `${name}.json`), JSON.stringify({ width: p.width,
    height: p.height, settings: p.settings }));
}

const { context, page, requests, consoleErrors } = await launch(outDir);
let result = {};
try {
  await open(page, url);
  await shown(page, 1);
  const panelShown = await page.isVisible('#stereo-panel');
  const layoutSelected = await page.inputValue('#stereo-layout');
  await save(page, 'pair');
  await page.selectOption('#stereo-layout', 'anaglyph');
  await shown(page, 2);
  await save(page, 'anaglyph');
  result = { panel_shown: panelShown, layout_selected: layoutSelected,
    ...await pageReport(page, requests, consoleErrors) };
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
