// Shades a data file on the GPU with several settings and saves each picture, for the Rust
// test crates/godel/tests/integration/browser.rs to compare with the `shade` crate's.
//
// usage: node layers.mjs URL OUT_DIR CASES.json
//   CASES.json: a list of complete settings (ShadeSettings as JSON).
// Writes OUT_DIR/case-K.rgba (+ .json) for each, and prints {requests, console_errors, errors}.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { argsOr, launch, open, idle, savePicture } from './launch.mjs';

const [url, outDir, casesFile] = argsOr('node layers.mjs URL OUT_DIR CASES.json', 3);
const cases = JSON.parse(readFileSync(casesFile, 'utf8'));
const { context, page, requests, consoleErrors } = await launch(outDir);
const result = { errors: [] };
try {
  await open(page, url);
  for (const [k, settings] of cases.entries()) {
    await page.evaluate((s) => {
      const v = window.godelViewer;
      for (const key of Object.keys(v.settings)) delete v.settings[key];
      Object.assign(v.settings, s);
      v.changed();
    }, settings);
    await idle(page);
    result.errors.push(await page.evaluate(() => window.godelViewer.error));
    await savePicture(page, join(outDir, `case-${k}.rgba`));
  }
  result.requests = requests;
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
