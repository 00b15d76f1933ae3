// Benchmarks of `godel explore` (issue 15), for BENCHMARKS.md "Explore". Prints one JSON object.
// Run through scripts/bench-explore.sh, which starts the server.
//
// usage: node bench-explore.mjs URL OUT_DIR event [N]
//          After the first full frame, posts N (default 10) events one after the other and,
//          for each, times from the POST to /api/explore/frame reporting that generation's
//          coarse frame and its full frame, polling every 5 ms (the server's times, not the
//          page's 100 ms poll). Then N times: posts an event, and as soon as its coarse frame
//          is reported (its full frame under way) posts another: the time to that one's coarse
//          frame, cancelling included. Plain fetch, no browser.
//        node bench-explore.mjs URL OUT_DIR play [SECONDS] [RATE]
//          In headless chromium: waits for the page's first full frame, sets the play rate
//          (default: the page's own), clicks Play, and for SECONDS (default 10) records every
//          frame the page accepts for the GPU (window.godelViewer.explore.shown changes) and
//          every shading pass (the frame drawn): frames per second while playing time, their
//          levels, and where a frame's time goes.
const [url, outDir, mode, arg1, arg2] = process.argv.slice(2);
if (!url || !outDir || !['event', 'play'].includes(mode)) {
  console.error('usage: node bench-explore.mjs URL OUT_DIR event [N] | play [SECONDS] [RATE]');
  process.exit(2);
}

const POLL_MS = 5;
// The longest wait for one frame (a full frame of the reference scene takes ~15 s on 2 idle
// cores); every wait below is bounded by it.
const FRAME_TIMEOUT_MS = 600000;
const sleep = (ms) => new Promise((done) => setTimeout(done, ms));
const base = url.endsWith('/') ? url : `${url}/`;

async function getJson(path) {
  const response = await fetch(base + path);
  const body = await response.json();
  if (!response.ok) throw new Error(`${path}: ${response.status} ${JSON.stringify(body)}`);
  return body;
}

// Polls /api/explore/frame until `generation` has its frame at level `until` ('coarse' or
// 'full'); calls `seen(level, ms, frame)` the first time each level of it is reported (ms
// from `t0`).
async function waitFor(generation, t0, until, seen = () => {}) {
  const got = new Set();
  while (performance.now() - t0 < FRAME_TIMEOUT_MS) {
    const answer = await getJson('api/explore/frame');
    if (answer.error && answer.generation === generation) {
      throw new Error(`generation ${generation}: ${answer.error}`);
    }
    const frame = answer.frame;
    if (frame && frame.generation === generation && !got.has(frame.level)) {
      got.add(frame.level);
      seen(frame.level, performance.now() - t0, frame);
    }
    if (got.has(until) || got.has('full')) return;
    await sleep(POLL_MS);
  }
  throw new Error(`generation ${generation}: no ${until} frame within ${FRAME_TIMEOUT_MS} ms`);
}

async function post(event) {
  const response = await fetch(`${base}api/explore/event`, { method: 'POST',
    headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(event) });
  const answer = await response.json();
  if (!response.ok) throw new Error(`POST ${JSON.stringify(event)}: ${JSON.stringify(answer)}`);
  return answer.generation;
}

const stats = (values) => {
  const v = values.filter((x) => x !== null).sort((a, b) => a - b);
  if (v.length === 0) return null;
  const mid = Math.floor(v.length / 2);
  const median = v.length % 2 ? v[mid] : (v[mid - 1] + v[mid]) / 2;
  return { median: Math.round(median), min: Math.round(v[0]), max: Math.round(v[v.length - 1]),
    n: v.length };
};

async function eventMode(n) {
  const info = await getJson('api/explore/info');
  const t0 = performance.now();
  await waitFor(info.generation, t0, 'full');
  const result = { mode: 'event', start: info.start,
    first_full_wait_ms: Math.round(performance.now() - t0) };
  // t steps by 0.37; x by a few hundredths: the observer stays near the axis, well inside
  // the optical horizon (r = 2a), where the scene is valid.
  const eventAt = (i) => ({ t: info.start.t + 0.37 * i, x: info.start.x + 0.02 * (i % 4),
    y: info.start.y, z: info.start.z });
  // Idle server: each event posted once the previous one has its full frame.
  const runs = [];
  for (let i = 1; i <= n; i += 1) {
    const event = eventAt(i);
    const posted = performance.now();
    const generation = await post(event);
    const run = { event, generation, post_ms: Math.round(performance.now() - posted),
      coarse_ms: null, full_ms: null };
    await waitFor(generation, posted, 'full', (level, ms, frame) => {
      run[`${level}_ms`] = Math.round(ms);
      run[`${level}_size`] = [frame.width, frame.height];
    });
    runs.push(run);
  }
  result.coarse_ms = stats(runs.map((r) => r.coarse_ms));
  result.full_ms = stats(runs.map((r) => r.full_ms));
  result.full_after_coarse_ms = stats(runs.map((r) => (r.coarse_ms === null ? null
    : r.full_ms - r.coarse_ms)));
  result.coarse_missed = runs.filter((r) => r.coarse_ms === null).length;
  result.runs = runs;
  // Busy server: an event posted as soon as the previous one has its coarse frame, while its
  // full frame is being traced (what playing time does): the coarse frame waits for the
  // cancelled work's tiles under way.
  const busy = [];
  for (let i = 1; i <= n; i += 1) {
    const first = await post(eventAt(n + 2 * i - 1));
    await waitFor(first, performance.now(), 'coarse');
    const posted = performance.now();
    const generation = await post(eventAt(n + 2 * i));
    let coarse = null;
    await waitFor(generation, posted, 'coarse', (level, ms) => {
      if (level === 'coarse') coarse = ms;
    });
    busy.push(coarse === null ? null : Math.round(coarse));
  }
  result.busy_coarse_ms = stats(busy);
  result.busy_runs = busy;
  return result;
}

async function playMode(seconds, rate) {
  const { launch, open } = await import('./launch.mjs');
  const { context, page, consoleErrors } = await launch(outDir);
  const result = { mode: 'play', seconds };
  try {
    await open(page, `${base}?trace=server`);
    await page.waitForFunction(() => {
      const e = window.godelViewer.explore;
      return e && e.shown && e.shown.level === 'full';
    }, null, { timeout: FRAME_TIMEOUT_MS });
    if (rate !== undefined) await page.locator('#explore-rate').fill(String(rate));
    result.rate = Number(await page.locator('#explore-rate').inputValue());
    // Records, every animation frame, each change of the frame on the GPU and of the shading
    // passes, with the page's clock.
    await page.evaluate(() => {
      const v = window.godelViewer;
      const log = { shown: [], shadings: [], requested: {}, t0: performance.now(), stop: false };
      window.benchLog = log;
      let last = null;
      let shadings = v.shadings;
      const watch = (now) => {
        const s = v.explore.shown;
        const key = s && `${s.generation}/${s.level}`;
        if (key !== last) {
          last = key;
          log.shown.push({ ms: now - log.t0, at: Date.now(), generation: s.generation,
            level: s.level, t: v.explore.event.t });
        }
        if (v.shadings !== shadings) {
          shadings = v.shadings;
          log.shadings.push(now - log.t0);
        }
        if (!log.stop) requestAnimationFrame(watch);
      };
      requestAnimationFrame(watch);
      // When each event was sent, by the generation the server answered.
      const send = window.fetch;
      window.fetch = (resource, options) => {
        const sent = Date.now();
        const answer = send(resource, options);
        if (String(resource).includes('/api/explore/event')) {
          answer.then((r) => r.clone().json()).then((j) => {
            log.requested[j.generation] = sent;
          }).catch(() => {});
        }
        return answer;
      };
    });
    const t0 = await page.evaluate(() => window.godelViewer.explore.event.t);
    const g0 = await page.evaluate(() => window.godelViewer.explore.requested);
    // Meanwhile this script notes when the server has each frame (wall clock, as the page's
    // Date.now()), polling every 5 ms: server time vs the page's poll. A frame was made after
    // the previous poll was sent and before the poll that reports it was answered: the
    // middle of that interval is taken (its width, under load, is reported).
    const ready = new Map();
    const widths = [];
    let watching = true;
    const watcher = (async () => {
      let previous = Date.now();
      while (watching) {
        const sent = Date.now();
        const frame = (await getJson('api/explore/frame')).frame;
        const answered = Date.now();
        const key = frame && `${frame.generation}/${frame.level}`;
        if (key && !ready.has(key)) {
          ready.set(key, (previous + answered) / 2);
          widths.push(answered - previous);
        }
        previous = sent;
        await sleep(POLL_MS);
      }
    })();
    await page.locator('#explore-play').click();
    await page.waitForTimeout(seconds * 1000);
    await page.locator('#explore-play').click();
    watching = false;
    await watcher;
    const log = await page.evaluate(() => {
      window.benchLog.stop = true;
      return { ...window.benchLog, now: performance.now() - window.benchLog.t0 };
    });
    // Frames put on the GPU after Play (the first entry is the full frame already shown).
    const frames = log.shown.slice(1);
    const gaps = frames.slice(1).map((f, i) => f.ms - frames[i].ms);
    result.page_seconds = log.now / 1000;
    result.frames = frames.length;
    result.frames_per_second = frames.length / seconds;
    result.levels = { coarse: frames.filter((f) => f.level === 'coarse').length,
      full: frames.filter((f) => f.level === 'full').length };
    result.gap_ms = stats(gaps);
    // Per frame: from the page sending its event to the server having the frame, and from there to the page showing it (its 100 ms poll); from a frame
    // shown to the next event sent (the page's animation frame).
    const trace = [];
    const poll = [];
    const next = [];
    for (const f of frames) {
      const asked = log.requested[f.generation];
      const had = ready.get(`${f.generation}/${f.level}`);
      if (asked !== undefined && had !== undefined) {
        trace.push(had - asked);
        poll.push(f.at - had);
      }
      const after = log.requested[f.generation + 1];
      if (after !== undefined) next.push(after - f.at);
    }
    result.server_ms = stats(trace);
    result.poll_wait_ms = stats(poll);
    result.server_uncertainty_ms = stats(widths);
    result.shown_to_next_send_ms = stats(next);
    // A frame accepted by the page counts as drawn only with its shading pass: one whose
    // channels the server no longer serves (410) is never drawn.
    result.shading_passes = log.shadings.length;
    result.drawn_per_second = log.shadings.length / seconds;
    result.requests_sent = (await page.evaluate(() => window.godelViewer.explore.requested)) - g0;
    result.t_from_to = [t0, await page.evaluate(() => window.godelViewer.explore.event.t)];
    result.frames_log = frames.map((f) => [Math.round(f.ms), f.generation, f.level]);
    result.error = await page.evaluate(() => window.godelViewer.error);
    result.explore_error = await page.evaluate(() => window.godelViewer.explore.error);
    result.console_errors = consoleErrors;
  } finally {
    await context.close();
  }
  return result;
}

const result = mode === 'event'
  ? await eventMode(Number(arg1 || 10))
  : await playMode(Number(arg1 || 10), arg2 === undefined ? undefined : Number(arg2));
console.log(JSON.stringify(result));
