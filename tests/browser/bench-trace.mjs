// Benchmark of the page's GPU tracer (page/trace.js, the `gpu` crate's kernel in WebGL2) in
// headless chromium, for BENCHMARKS.md: traces the served data file's scene RUNS times
// (the first run also compiles the kernel) and prints one JSON object with each run's time.
//
// usage: node bench-trace.mjs URL OUT_DIR [RUNS]
import { argsOr, launch, idle, traced } from './launch.mjs';

const [url, outDir, runsText] = argsOr('node bench-trace.mjs URL OUT_DIR [RUNS]', 2);
const runs = Number(runsText || 2);
const { context, page } = await launch(outDir);

// Waits for the trace under way to end (launch.mjs: throws the page's error); its size and
// times.
async function run() {
  await traced(page);
  return page.evaluate(() => {
    const t = window.godelViewer.traced.traced;
    return { width: t.width, height: t.height, compile_ms: t.compileMs, trace_ms: t.traceMs };
  });
}

const result = { runs: [] };
try {
  await page.goto(`${url}?trace=gpu`);
  result.runs.push(await run());
  for (let k = 1; k < runs; k += 1) {
    await page.uncheck('#trace-gpu');
    await idle(page);
    await page.check('#trace-gpu');
    result.runs.push(await run());
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
