// Benchmark of the page's GPU tracer (page/trace.js, the `gpu` crate's kernel in WebGL2) in
// headless chromium, for BENCHMARKS.md: traces the served data file's scene RUNS times
// (the first run also compiles the kernel) and prints one JSON object with each run's time.
//
// usage: node bench-trace.mjs URL OUT_DIR [RUNS]
import { argsOr, launch, idle } from './launch.mjs';

const [url, outDir, runsText] = argsOr('node bench-trace.mjs URL OUT_DIR [RUNS]', 2);
const runs = Number(runsText || 2);
const { context, page } = await launch(outDir);

// Waits for the trace under way to end; throws the page's error.
async function traced() {
  await page.waitForFunction(() => {
    const v = window.godelViewer;
    if (v.error !== null) return true;
    const t = v.traced;
    return t && !t.tracing && (t.traced !== null || t.error !== null);
  }, null, { timeout: 0, polling: 200 });
  await idle(page);
  const error = await page.evaluate(() => window.godelViewer.traced?.error
    ?? window.godelViewer.error);
  if (error !== null) throw new Error(error);
  return page.evaluate(() => {
    const t = window.godelViewer.traced.traced;
    return { width: t.width, height: t.height, compile_ms: t.compileMs, trace_ms: t.traceMs };
  });
}

const result = { runs: [] };
try {
  await page.goto(`${url}?trace=gpu`);
  await page.waitForFunction(() => window.godelViewer && window.godelViewer.traced !== undefined,
    null, { timeout: 60000 });
  result.runs.push(await traced());
  for (let k = 1; k < runs; k += 1) {
    await page.uncheck('#trace-gpu');
    await idle(page);
    await page.check('#trace-gpu');
    result.runs.push(await traced());
  }
  const last = result.runs[result.runs.length - 1];
  result.samples = last.width * last.height;
  result.rays_per_s = result.runs.map((r) => Math.round(result.samples / r.trace_ms * 1e3));
  result.renderer = await page.evaluate(() => {
    const gl = window.godelViewer.gpu().gl;
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  });
} finally {
  await context.close();
}
console.log(JSON.stringify(result));
