// Makes the README's picture of the viewer (docs/viewer.png) with Debian's chromium:
// the frequency layer at the scene's temperatures, the mouse on pixel COL ROW.
// usage: node screenshot.mjs URL OUT.png COL ROW   (with `godel view` serving URL)
import { chromium } from 'playwright-core';
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const [url, out, col, row] = process.argv.slice(2);
const args = ['--headless', '--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];
const context = await chromium.launchPersistentContext(mkdtempSync(join(tmpdir(), 'godel-shot-')), {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args,
  viewport: { width: 1500, height: 820 },
});
try {
  const page = context.pages()[0] || await context.newPage();
  const idle = () => page.waitForFunction(() => window.godelViewer?.frames > 0
    && window.godelViewer.idle());
  await page.goto(url);
  await idle();
  await page.check('#layer-frequency');
  await page.uncheck('#layer-texture');
  await idle();
  const box = await page.locator('#image').boundingBox();
  const [w, h] = await page.evaluate(() => [window.godelViewer.info.width,
    window.godelViewer.info.height]);
  await page.mouse.move(box.x + (Number(col) + 0.5) * box.width / w,
    box.y + (Number(row) + 0.5) * box.height / h);
  await page.waitForFunction(() => window.godelViewer.record !== null);
  await page.screenshot({ path: out });
} finally {
  await context.close();
}
