// Frames per second while flying (scripts/bench-fly.sh): waits for the first traced frame
// (at 640×360 and less, for the full frame at rest, which also measures the kernel's speed
// there), holds W for FRAMES animation frames, then lets go and waits for the full frame,
// at most FULL_BOUND_S.
// usage: [BENCH_HOVER=1] node bench-fly.mjs URL OUT_DIR FRAMES
// Prints {size, frames, seconds, frames_per_s, moving_sizes (median, smallest, largest
// width×height), full_ms (from letting go to the full frame shown; null past the bound),
// half_ms and size_ms (from letting go to the frame of half the size, and to the full size
// at one sample a pixel, where the page traces them: fly.js traceFull), hover_ms (the centre
// pixel's light ray made in the page: first, then again), start_half_ms, start_size_ms and
// start_full_ms (up to 640×360: the same for the scene's own view, before flying, from its
// coming to rest), tracers {moving_gpu, moving_cpu (moving frames each traced), full (who
// traced the full frame), cpu_rays_per_ms, gpu_rays_per_ms (the speeds fly.js measured)}}.
import { argsOr, launch, open, atRest } from './launch.mjs';

const [url, outDir, frames] = argsOr('node bench-fly.mjs URL OUT_DIR FRAMES', 3);
const n = Number(frames);
const { context, page } = await launch(outDir, { width: 1400, height: 900 });
const FULL_BOUND_S = 90;
const rest = (timeout = 600000) => atRest(page, timeout);
try {
  await open(page, url);
  const size = await page.evaluate(() => window.godelViewer.explore.view().camera);
  let startFull = null;
  if (size.width * size.height <= 640 * 360) {
    await rest();
    // The frames at rest of the scene's own view, before flying (fly.js's log).
    startFull = await page.evaluate(() => {
      const f = window.godelViewer.explore.fly;
      const log = f.log.filter((l) => l.version === f.traced.version);
      const ms = (level) => (log.find((l) => l.level === level) || {}).ms ?? null;
      return { half: ms('half'), size: ms('size'), full: ms('full') };
    });
  } else {
    await page.waitForFunction(() => window.godelViewer.explore?.fly?.drawn > 0, null,
      { timeout: 600000 });
  }
  // BENCH_HOVER=1: the pointer rests on the picture's centre while flying, so that every
  // frame also reads the hovered record back and traces its light ray (hovered.js).
  if (process.env.BENCH_HOVER === '1') {
    const c = await page.evaluate(() => {
      const r = document.getElementById('image').getBoundingClientRect();
      return [r.left + r.width / 2, r.top + r.height / 2];
    });
    await page.mouse.move(c[0], c[1]);
  }
  await page.keyboard.down('KeyW');
  await page.waitForFunction(() => window.godelViewer.explore.fly.tauMoved > 0, null,
    { timeout: 600000 });
  const start = await page.evaluate(() => [performance.now(), window.godelViewer.frames,
    window.godelViewer.explore.fly.log.length]);
  await page.waitForFunction((k) => window.godelViewer.frames >= k, start[1] + n,
    { timeout: 600000 });
  const end = await page.evaluate((s) => [performance.now(), window.godelViewer.frames,
    window.godelViewer.explore.fly.log.slice(-(window.godelViewer.explore.fly.log.length - s))
      .map((l) => [l.width, l.height, l.by])], start[2]);
  await page.keyboard.up('KeyW');
  const let_go = await page.evaluate(() => performance.now());
  const full = await rest(FULL_BOUND_S * 1000).then(
    () => page.evaluate(() => performance.now()), () => null);
  // The frames at rest after letting go.
  const atRestLog = await page.evaluate(() => {
    const f = window.godelViewer.explore.fly;
    return f.log.filter((l) => l.version === f.version);
  });
  const shownAt = (level) => {
    const l = atRestLog.find((e) => e.level === level);
    return l ? Math.round(l.at - let_go) : null;
  };
  // The hovered pixel's light ray in the page (hovered.js): the centre pixel of the frame
  // shown, the first time (compiling the kernel's RAY_PATH variant) and the next.
  const hoverMs = await page.evaluate(async () => {
    const e = window.godelViewer.explore;
    const t = e.fly.traced;
    const times = [];
    try {
      for (let i = 0; i < 2; i += 1) {
        const started = performance.now();
        const ray = e.hoverRay(t.width >> 1, t.height >> 1);
        if (ray) await ray.load();
        times.push(Math.round(performance.now() - started));
      }
    } catch (error) {
      times.push(`failed: ${error.message || error}`);
    }
    return times;
  });
  const sizes = end[2].sort((a, b) => a[0] - b[0]);
  // Which tracer made the moving frames and the full one (fly.js: the faster one measured).
  const tracers = await page.evaluate((moving) => {
    const f = window.godelViewer.explore.fly;
    const count = (by) => moving.filter((m) => m[2] === by).length;
    return { moving_gpu: count('gpu'), moving_cpu: count('cpu'), full: f.traced.by,
      cpu_rays_per_ms: f.cpuRaysPerMs && Math.round(f.cpuRaysPerMs),
      gpu_rays_per_ms: f.raysPerMs && Number(f.raysPerMs.toFixed(1)) };
  }, end[2]);
  const seconds = (end[0] - start[0]) / 1000;
  const s = (p) => (p ? `${p[0]}×${p[1]}` : null);
  console.log(JSON.stringify({ size: `${size.width}×${size.height}`, frames: end[1] - start[1],
    seconds: Number(seconds.toFixed(2)),
    frames_per_s: Number(((end[1] - start[1]) / seconds).toFixed(1)),
    moving_sizes: { median: s(sizes[sizes.length >> 1]), smallest: s(sizes[0]),
      largest: s(sizes[sizes.length - 1]) },
    full_ms: full === null ? null : Math.round(full - let_go), half_ms: shownAt('half'),
    size_ms: shownAt('size'), hover_ms: hoverMs, start_half_ms: startFull && startFull.half,
    start_size_ms: startFull && startFull.size, start_full_ms: startFull && startFull.full,
    tracers }));
} finally {
  await context.close();
}
