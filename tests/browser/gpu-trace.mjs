// Traces the frame of each served data file in the page, on the GPU (WebGL2 on SwiftShader,
// page/trace.js running crates/gpu/src/kernel/), and saves what it traced, for the Rust
// test crates/godel/tests/integration/browser/gpu_trace.rs to compare with the data file.
//
// usage: node gpu-trace.mjs URL OUT_DIR [URL…] [--shade]
//   For the K-th URL (`godel view` of a data file) writes OUT_DIR/trace-K.json ({width,
//   height, slots, traceMs, compileMs, source (the kernel as compiled), defines and
//   drawBuffers (as the server sent them), header}) and trace-K-slot-S.f32 (RGBA32F, grid
//   row 0 first). With --shade, for the first URL also the picture shaded from the traced frame
//   (trace-0-gpu.rgba), from the file's frame (trace-0-file.rgba), and the canvas showing the
//   traced frame (trace-0-canvas.rgba), with every layer on. Prints {requests,
//   console_errors, without_float_targets}: the latter what the page shows for the first URL
//   where WebGL2 cannot draw into float textures (EXT_color_buffer_float withheld).
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { launch, idle, savePicture, traced, waitFor } from './launch.mjs';

const args = process.argv.slice(2);
const shade = args.includes('--shade');
const [first, outDir, ...more] = args.filter((a) => a !== '--shade');
if (!first || !outDir) {
  console.error('usage: node gpu-trace.mjs URL OUT_DIR [URL…] [--shade]');
  process.exit(2);
}
const urls = [first, ...more];

const { context, page, requests, consoleErrors } = await launch(outDir, { width: 1200, height: 800 });
const result = {};
try {
  for (const [k, url] of urls.entries()) {
    await page.goto(`${url}?trace=gpu`);
    await traced(page);
    const slots = await page.evaluate(() => window.godelViewer.traced.readSlots());
    slots.slots.forEach((b64, s) => writeFileSync(join(outDir, `trace-${k}-slot-${s}.f32`),
      Buffer.from(b64, 'base64')));
    const header = await page.evaluate(() => document.getElementById('file').textContent);
    writeFileSync(join(outDir, `trace-${k}.json`), JSON.stringify({ width: slots.width,
      height: slots.height, slots: slots.slots.length, traceMs: slots.traceMs,
      compileMs: slots.compileMs, source: slots.source, defines: slots.defines,
      drawBuffers: slots.drawBuffers, header }));
    if (shade && k === 0) {
      await page.evaluate(() => {
        const v = window.godelViewer;
        v.settings.shaders = ['texture', 'frequency', 'time', 'light']
          .filter((s) => s !== 'light' || v.info.lights > 0);
        v.changed();
      });
      await idle(page);
      await savePicture(page, join(outDir, `trace-${k}-gpu.rgba`),
        { settings: await page.evaluate(() => window.godelViewer.settings) });
      await savePicture(page, join(outDir, `trace-${k}-canvas.rgba`), {}, 'canvas');
      await page.uncheck('#trace-gpu');
      await idle(page);
      await savePicture(page, join(outDir, `trace-${k}-file.rgba`), {
        header: await page.evaluate(() => document.getElementById('file').textContent) });
    }
  }
  // A WebGL2 that cannot draw into float textures: the page says so, and shows the file's frame.
  const bare = await context.newPage();
  await bare.addInitScript(() => {
    const get = WebGL2RenderingContext.prototype.getExtension;
    WebGL2RenderingContext.prototype.getExtension = function (name) {
      return name === 'EXT_color_buffer_float' ? null : get.call(this, name);
    };
  });
  await bare.goto(`${first}?trace=gpu`);
  await waitFor(bare, 'without float targets, the page did not say why it cannot trace',
    () => window.godelViewer && window.godelViewer.traced
      && window.godelViewer.traced.error !== null);
  await idle(bare);
  result.without_float_targets = await bare.evaluate(() => ({
    error: document.getElementById('trace-status').textContent,
    checked: document.getElementById('trace-gpu').checked,
    header: document.getElementById('file').textContent,
    frames: window.godelViewer.frames,
  }));
  result.requests = requests;
  result.console_errors = consoleErrors;
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
