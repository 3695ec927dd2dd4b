// Render benchmark of the operator console in headless Chromium:
//   - the Trondheim chart (trondheim_landareal_wgs84.geojson, ~55k land
//     vertices) uploaded through the API and drawn by the chart view, plus a
//     ship track of 10,000 points; frame times while panning (renderSync per
//     frame), against the same pan over an empty map in the same page
//     (baseline ratio);
//   - the console's first load on loopback (navigation to the first view
//     drawn), median of several cold loads, against a GET /healthz round
//     trip in the same page (baseline ratio);
//   - the bundle size;
//   - main-thread CPU per frame of the pans and drags, from a Chromium trace
//     (thread time, which a loaded machine does not stretch), and each frame
//     over 50 ms with its CPU and garbage-collection time.
//
//   node bench/console/render_bench.mjs [--frames 120] [--loads 5]
//   env: SEAPLAN_SERVER_BIN, CONSOLE_DIR (default build/bin/...),
//        SEAPLAN_SHARED (default ../shared beside the clone)
import { existsSync, readdirSync, readFileSync, statSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { cpus } from "node:os";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const repo = resolve(here, "../..");
const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? Number(process.argv[i + 1]) : fallback;
};
const frames = arg("frames", 120);
const loads = arg("loads", 5);
const trackPoints = arg("track-points", 10000);
const serverBin = process.env.SEAPLAN_SERVER_BIN || join(repo, "build/bin/seaplan-server");
const consoleDir = process.env.CONSOLE_DIR || join(repo, "build/bin/console");
const shared = process.env.SEAPLAN_SHARED || resolve(repo, "../shared");
const chartFile = join(shared, "enc/trondheim/trondheim_landareal_wgs84.geojson");
for (const [path, what] of [[serverBin, "seaplan-server"], [join(consoleDir, "index.html"), "the built console"],
                            [chartFile, "the Trondheim chart (SEAPLAN_SHARED)"]]) {
  if (!existsSync(path)) {
    console.log(`SKIP: ${what} not found (${path})`);
    process.exit(process.env.CI ? 1 : 0);
  }
}
const { launchBrowser, signIn, startServer } = await import("../../clients/console/e2e/support.mjs");

const stats = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const q = (p) => s[Math.min(s.length - 1, Math.floor(p * s.length))];
  return { median: q(0.5), p95: q(0.95), max: s[s.length - 1], mean: s.reduce((a, b) => a + b, 0) / s.length };
};
const fmt = (x) => x.toFixed(2);
const loadAverage = () => readFileSync("/proc/loadavg", "utf8").split(" ").slice(0, 3).join(" ");

const loadBefore = loadAverage();
const server = await startServer({ serverBin, consoleDir });
const browser = await launchBrowser();
try {
  // The chart through the API, as the console's upload form sends it.
  const upload = await fetch(`${server.url}v1/ChartService/UploadChart`, {
    method: "POST",
    headers: { "Content-Type": "application/json", Authorization: `Bearer ${server.adminToken}` },
    body: JSON.stringify({ name: "trondheim", format: "CHART_FORMAT_GEOJSON", files: [
      { name: "trondheim_landareal_wgs84.geojson", content: readFileSync(chartFile).toString("base64") }] }),
  });
  if (!upload.ok) throw new Error(`upload: ${upload.status} ${await upload.text()}`);
  const chart = (await upload.json()).chart;

  const page = await browser.context.newPage();
  await signIn(page, server);
  // First load: cold navigations (cache disabled) to the first view drawn.
  const cdp = await browser.context.newCDPSession(page);
  await cdp.send("Network.setCacheDisabled", { cacheDisabled: true });
  const loadMs = [];
  const healthMs = [];
  const documents = new Set();
  for (let i = 0; i < loads; i++) {
    // From a blank page: going to the console's own URL again with only the
    // hash changed would stay in the same document and load nothing.
    await page.goto("about:blank");
    const t0 = Date.now();
    await page.goto(`${server.url}#/missions`);
    await page.waitForSelector("main h1");
    loadMs.push(Date.now() - t0);
    documents.add(await page.evaluate(() => performance.timeOrigin));
    healthMs.push(await page.evaluate(async () => {
      const t = performance.now();
      await (await fetch("/healthz", { cache: "no-store" })).text();
      return performance.now() - t;
    }));
  }

  if (documents.size !== loads) throw new Error(`${loads} loads made ${documents.size} documents`);

  // The chart view with the obstacles and a 10,000-point track.
  await page.goto(`${server.url}#/charts`);
  await page.waitForFunction((id) => !!document.querySelector(`#p-chart option[value="${id}"]`), chart.chartId);
  await page.selectOption("#p-chart", chart.chartId);
  const tLoad = Date.now();
  await page.click("#p-show");
  await page.waitForFunction(() => /obstacles at/.test(document.querySelector("#p-status")?.textContent ?? ""), null, { timeout: 120000 });
  const obstaclesMs = Date.now() - tLoad;
  // Main-thread long tasks (over 50 ms) from here on. Installed in the page
  // as it is: the views are one document (hash routes), so a script run at
  // each new document would never run again.
  const observing = await page.evaluate(() => {
    window.__long = [];
    if (!PerformanceObserver.supportedEntryTypes.includes("longtask")) return false;
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) window.__long?.push([e.startTime, e.duration]);
    }).observe({ type: "longtask" });
    return true;
  });
  if (!observing) throw new Error("this Chromium reports no main-thread long tasks");
  const vertices = await page.evaluate((n) => {
    const m = window.seaplanMap;
    // A track wandering over the chart's extent.
    const pts = [];
    for (let i = 0; i < n; i++) {
      const t = i / n;
      pts.push({ latitudeDeg: 63.43 + 0.03 * Math.sin(t * 20) * t, longitudeDeg: 10.3 + 0.25 * t });
    }
    m.setTrack(pts);
    let count = 0;
    m.map.getAllLayers()[0].getSource().forEachFeature((f) => {
      const g = f.getGeometry();
      count += g.getFlatCoordinates().length / g.getStride();
    });
    return count;
  }, trackPoints);

  // The map has drawn what it shows (the state an operator pans from: the
  // chart on screen, nothing else rehearsed).
  const drawn = () => page.evaluate(() => new Promise((resolve) => {
    const m = window.seaplanMap.map;
    m.once("rendercomplete", () => resolve());
    m.render();
  }));
  // Frame times from requestAnimationFrame's timestamps (each frame's begin
  // time). A callback that runs in a frame begun before a long task (a frame
  // the compositor asked for while the main thread was busy) gets that old
  // begin time: the interval that ends at the next frame then holds the whole
  // task, not a frame. The recorded frames therefore start one frame later,
  // at a fresh begin time; that frame moves and draws nothing. Each frame is
  // marked in the trace by its index, and each callback's delay behind its
  // begin time is kept.
  await page.evaluate(() => {
    window.__frameLoop = () => {
      const f = { frames: [], ends: [], lag: [] };
      f.record = (now, i) => {
        console.timeStamp(`frame ${i}`);
        const at = performance.now();
        if (f.ends.length) f.frames.push(now - f.ends[f.ends.length - 1]);
        f.ends.push(now);
        f.lag.push(at - now);
      };
      return f;
    };
  });
  // Pan three ways: (a) frame intervals: move the centre in each
  // requestAnimationFrame callback and time the frames (a full redraw each
  // frame, the worst case; 16.7 ms at 60 Hz when the drawing keeps up);
  // (b) work per frame: move the centre and renderSync(), timed in the page
  // (one long task, after the frames, in a task of its own, so that it
  // delays none of them and is in no frame of the trace).
  const pan = async (n) => {
    const framed = await page.evaluate((count) => {
      const m = window.seaplanMap.map;
      const view = m.getView();
      const c = view.getCenter();
      const res = view.getResolution();
      const move = (i) => [c[0] + Math.sin(i / 10) * 200 * res, c[1] + Math.cos(i / 10) * 120 * res];
      const f = window.__frameLoop();
      window.__long = [];  // main-thread long tasks from here on
      return new Promise((resolve) => {
        let i = 0;
        const step = (now) => {
          f.record(now, i);
          if (++i >= count) {
            view.setCenter(c);
            resolve({ ...f, record: undefined, long: window.__long });
            return;
          }
          view.setCenter(move(i));
          requestAnimationFrame(step);
        };
        requestAnimationFrame(() => requestAnimationFrame(step));
      });
    }, n);
    const work = await page.evaluate((count) => {
      const m = window.seaplanMap.map;
      const view = m.getView();
      const c = view.getCenter();
      const res = view.getResolution();
      const move = (i) => [c[0] + Math.sin(i / 10) * 200 * res, c[1] + Math.cos(i / 10) * 120 * res];
      const times = [];
      for (let i = 0; i < count; i++) {
        view.setCenter(move(i));
        const t = performance.now();
        m.renderSync();
        times.push(performance.now() - t);
      }
      view.setCenter(c);
      return times;
    }, n);
    return { ...framed, work };
  };
  // (c) a real drag with the mouse (OpenLayers' DragPan), frames recorded
  // by a requestAnimationFrame loop while Playwright moves the mouse.
  const box = await page.locator("#preview-map").boundingBox();
  const drag = async (n) => {
    await page.evaluate(() => new Promise((resolve) => {
      window.__long = [];
      const f = window.__frameLoop();
      window.__drag = f;
      let i = 0;
      const tick = (now) => {
        if (i === 0) resolve();
        f.record(now, i++);
        if (window.__drag === f) window.__raf = requestAnimationFrame(tick);
      };
      requestAnimationFrame(() => { window.__raf = requestAnimationFrame(tick); });
    }));
    const x0 = box.x + box.width / 2, y0 = box.y + box.height / 2;
    await page.mouse.move(x0, y0);
    await page.mouse.down();
    for (let i = 1; i <= n; i++) {
      await page.mouse.move(x0 + Math.sin(i / 10) * 150, y0 + Math.cos(i / 10) * 90 - 90);
    }
    await page.mouse.up();
    await page.waitForTimeout(300);  // the redraw after the drag
    return page.evaluate(() => {
      cancelAnimationFrame(window.__raf);
      const f = window.__drag;
      window.__drag = undefined;
      return { ...f, record: undefined, long: window.__long };
    });
  };
  // Frames over 50 ms, and how many of them overlap a main-thread long task
  // (the page's own script, layout or drawing); the others waited for
  // something outside the page (the compositor, the GPU process, the
  // machine's scheduler).
  const slowFrames = ({ frames: f, ends, long }) => {
    const slow = f.map((d, i) => [ends[i + 1] - d, ends[i + 1]]).filter(([a, b]) => b - a > 50);
    const inPage = slow.filter(([a, b]) => long.some(([s, d]) => s < b && s + d > a));
    return { slow: slow.length, inPage: inPage.length };
  };
  // Main-thread CPU per frame from a Chromium trace: the thread time (CPU
  // time, not wall time) of the renderer main thread's top-level tasks that
  // start between the marks of two frames. A loaded machine stretches wall
  // times (a descheduled thread waits for a core), not thread times: this is
  // the figure to compare across runs. Each frame the page counts over 50 ms
  // is looked up in the trace by its index (the same frame, not a recount):
  // the main thread's CPU and its longest task, the CPU of the renderer's
  // compositor thread and of the GPU process's display compositor, and the
  // garbage collections in it.
  const cdpTrace = await browser.context.newCDPSession(page);
  const traced = async (fn) => {
    const events = [];
    const onData = (e) => { for (const x of e.value) events.push(x); };
    cdpTrace.on("Tracing.dataCollected", onData);
    await cdpTrace.send("Tracing.start", { transferMode: "ReportEvents",
      traceConfig: { recordMode: "recordAsMuchAsPossible", bufferSizeInKb: 400 * 1024,
                     includedCategories: ["toplevel", "devtools.timeline"], excludedCategories: ["*"] } });
    // Starting a trace stalls the renderer for a moment (a 350 ms frame was
    // seen right after it): the measured frames begin once it has settled.
    await page.waitForTimeout(300);
    const result = await fn();
    const complete = new Promise((r) => cdpTrace.once("Tracing.tracingComplete", r));
    await cdpTrace.send("Tracing.end");
    await complete;
    cdpTrace.off("Tracing.dataCollected", onData);
    const marks = new Map();
    let main;
    for (const e of events) {
      const m = e.name === "TimeStamp" && /^frame (\d+)$/.exec(e.args?.data?.message ?? "");
      if (m) {
        marks.set(Number(m[1]), e.ts);
        main = e;
      }
    }
    if (!main) return { result, cpu: [], slow: [], heaviest: { cpu: 0, index: 0 }, marks: 0 };
    const threadNames = new Map();
    for (const e of events) if (e.ph === "M" && e.name === "thread_name") threadNames.set(`${e.pid}/${e.tid}`, e.args.name);
    const topLevel = (accept) => {
      const tasks = [];
      for (const e of events.filter((e) => e.ph === "X" && e.dur !== undefined && e.cat.split(",").includes("toplevel") &&
                                           accept(e)).sort((a, b) => a.ts - b.ts)) {
        const last = tasks[tasks.length - 1];
        if (!last || e.ts >= last.ts + last.dur || e.tid !== last.tid) tasks.push(e);  // not nested
      }
      return tasks;
    };
    const mainTasks = topLevel((e) => e.pid === main.pid && e.tid === main.tid);
    const compositor = topLevel((e) => e.pid === main.pid && threadNames.get(`${e.pid}/${e.tid}`) === "Compositor");
    const display = topLevel((e) => threadNames.get(`${e.pid}/${e.tid}`) === "VizCompositorThread");
    const gcs = events.filter((e) => e.pid === main.pid && e.tid === main.tid && e.ph === "X" &&
                                     (e.name === "MinorGC" || e.name === "MajorGC"));
    const within = (xs, a, b) => xs.filter((e) => e.ts < b && e.ts + e.dur > a);
    const cpuOf = (xs) => xs.reduce((t, e) => t + (e.tdur ?? e.dur), 0) / 1000;
    const cpu = [];
    const slow = [];
    let heaviest = { cpu: 0, index: 0 };
    const frames = result.frames;
    for (let i = 1; i <= frames.length; i++) {
      const [a, b] = [marks.get(i - 1), marks.get(i)];
      if (a === undefined || b === undefined) continue;
      const tasks = mainTasks.filter((e) => e.ts >= a && e.ts < b);
      cpu.push(cpuOf(tasks));
      if (cpu[cpu.length - 1] > heaviest.cpu) heaviest = { cpu: cpu[cpu.length - 1], index: i };
      if (frames[i - 1] > 50) {
        const longest = tasks.reduce((x, e) => (!x || e.dur > x.dur ? e : x), undefined);
        const gc = within(gcs, a, b);
        slow.push({ index: i, wall: frames[i - 1], marks: (b - a) / 1000, lag: [result.lag[i - 1], result.lag[i]], cpu: cpuOf(tasks),
                    longestWall: (longest?.dur ?? 0) / 1000, longestCpu: (longest?.tdur ?? 0) / 1000,
                    compositor: cpuOf(within(compositor, a, b)), display: cpuOf(within(display, a, b)),
                    gcCpu: cpuOf(gc), gcWall: gc.reduce((t, g) => t + g.dur, 0) / 1000 });
      }
    }
    return { result, cpu, slow, heaviest, marks: marks.size };
  };
  const measure = async (name) => {
    await drawn();
    // The drag first: an operator's first pan of what is on screen.
    const dragged = await traced(() => drag(frames));
    const r = await traced(() => pan(frames));
    const [a, b] = [slowFrames(r.result), slowFrames(dragged.result)];
    // Every frame of the page's own count is between two marks of the trace.
    for (const [t, n] of [[r, r.result.frames.length], [dragged, dragged.result.frames.length]]) {
      if (t.marks < n + 1) console.log(`note: the trace holds ${t.marks} frame marks for ${n} frames`);
    }
    return { work: stats(r.result.work), frame: stats(r.result.frames), drag: stats(dragged.result.frames),
             cpuFrame: stats(r.cpu.length ? r.cpu : [0]), cpuDrag: stats(dragged.cpu.length ? dragged.cpu : [0]),
             slowDetail: [...r.slow.map((d) => ({ ...d, where: `${name}, frame` })),
                          ...dragged.slow.map((d) => ({ ...d, where: `${name}, drag` }))],
             heaviest: [{ ...r.heaviest, where: `${name}, frame` }, { ...dragged.heaviest, where: `${name}, drag` }]
               .reduce((x, y) => (y.cpu > x.cpu ? y : x)),
             slow: a.slow + b.slow, slowInPage: a.inPage + b.inPage,
             count: r.result.frames.length + dragged.result.frames.length };
  };
  const runs = {};
  await page.evaluate(() => window.seaplanMap.fitOnce(true));
  runs["server obstacles, whole chart"] = await measure("server obstacles, whole chart");
  await page.evaluate(() => window.seaplanMap.map.getView().setZoom(window.seaplanMap.map.getView().getZoom() + 2));
  runs["server obstacles, zoomed x4"] = await measure("server obstacles, zoomed x4");
  // The raw land file (every vertex, unsimplified, unbuffered) as the worst
  // case: parsed, fitted and drawn (until the map's rendercomplete).
  const raw = readFileSync(chartFile, "utf8");
  const rawLoad = await page.evaluate((text) => new Promise((resolve) => {
    const m = window.seaplanMap;
    const t = performance.now();
    m.map.once("rendercomplete", () => {
      let count = 0;
      m.map.getAllLayers()[0].getSource().forEachFeature((f) => {
        const g = f.getGeometry();
        count += g.getFlatCoordinates().length / g.getStride();
      });
      resolve({ count, ms: performance.now() - t });
    });
    m.setObstacles(text);
    m.fitOnce(true);
  }), raw);
  const rawVertices = rawLoad.count;
  runs["raw land file, whole chart"] = await measure("raw land file, whole chart");
  await page.evaluate(() => window.seaplanMap.map.getView().setZoom(window.seaplanMap.map.getView().getZoom() + 2));
  runs["raw land file, zoomed x4"] = await measure("raw land file, zoomed x4");
  // Baseline: the same page and pans with nothing drawn.
  await page.evaluate(() => {
    const m = window.seaplanMap;
    m.map.getAllLayers().forEach((l) => l.setVisible(false));
    m.fitOnce(true);
  });
  const empty = await measure("empty map");

  let bundle = 0;
  for (const name of readdirSync(consoleDir)) if (!name.endsWith(".map") && !name.endsWith(".txt")) bundle += statSync(join(consoleDir, name)).size;
  const ld = stats(loadMs);
  const hl = stats(healthMs);
  console.log(`load average (1, 5, 15 min): ${loadBefore} before, ${loadAverage()} after (${cpus().length} cores)`);
  console.log(`chart: server obstacles ${vertices} vertices (fetched and drawn in ${obstaclesMs} ms), raw land file ${rawVertices} vertices ` +
              `(parsed and drawn in ${Math.round(rawLoad.ms)} ms); ` +
              `ship track ${trackPoints} points`);
  console.log(`pan, ${frames} frames each: work = renderSync ms; frame = requestAnimationFrame interval ms while the centre moves each frame; ` +
              `drag = the same while the mouse drags the map (p50 / p95 / max); ratio = mean work / empty map's`);
  const worst = { work: 0, frame: 0, cpu: 0, cpuWhere: "" };
  const slowDetail = [];
  const slow = { over: 0, inPage: 0, of: 0 };
  for (const [name, r] of Object.entries(runs)) {
    worst.work = Math.max(worst.work, r.work.max);
    worst.frame = Math.max(worst.frame, r.frame.max, r.drag.max);
    slow.over += r.slow;
    slow.inPage += r.slowInPage;
    slow.of += r.count;
    if (r.heaviest.cpu > worst.cpu) [worst.cpu, worst.cpuWhere] = [r.heaviest.cpu, `${r.heaviest.where} #${r.heaviest.index}`];
    slowDetail.push(...r.slowDetail);
    console.log(`  ${name.padEnd(32)} work ${fmt(r.work.median)} / ${fmt(r.work.p95)} / ${fmt(r.work.max)}   ` +
                `frame ${fmt(r.frame.median)} / ${fmt(r.frame.p95)} / ${fmt(r.frame.max)}   ` +
                `drag ${fmt(r.drag.median)} / ${fmt(r.drag.p95)} / ${fmt(r.drag.max)}   ` +
                `ratio ${fmt(r.work.mean / Math.max(empty.work.mean, 0.001))}x`);
  }
  console.log(`  ${"empty map (baseline)".padEnd(32)} work ${fmt(empty.work.median)} / ${fmt(empty.work.p95)} / ${fmt(empty.work.max)}   ` +
              `frame ${fmt(empty.frame.median)} / ${fmt(empty.frame.p95)} / ${fmt(empty.frame.max)}   ` +
              `drag ${fmt(empty.drag.median)} / ${fmt(empty.drag.p95)} / ${fmt(empty.drag.max)}   ` +
              `(${empty.slow} of ${empty.count} frames over 50 ms)`);
  slowDetail.push(...empty.slowDetail);
  console.log(`main-thread CPU per frame, ms (thread time from a Chromium trace; p50 / p95 / max):`);
  for (const [name, r] of [...Object.entries(runs), ["empty map (baseline)", empty]]) {
    console.log(`  ${name.padEnd(32)} frame ${fmt(r.cpuFrame.median)} / ${fmt(r.cpuFrame.p95)} / ${fmt(r.cpuFrame.max)}   ` +
                `drag ${fmt(r.cpuDrag.median)} / ${fmt(r.cpuDrag.p95)} / ${fmt(r.cpuDrag.max)}`);
  }
  // The slowest of them: on a loaded machine there can be hundreds.
  const shown = [...slowDetail].sort((a, b) => b.wall - a.wall).slice(0, 12);
  const n = slowDetail.length;
  console.log(`frames over 50 ms (empty map too), each looked up in the trace by its index: ` +
              `${n === 0 ? "none" : n > shown.length ? `${n}, the ${shown.length} slowest:` : `${n}:`}`);
  for (const d of shown) {
    console.log(`  ${d.where} #${d.index}: ${fmt(d.wall)} ms (trace marks ${fmt(d.marks)} ms apart; the callbacks at its ends ran ${fmt(d.lag[0])} and ${fmt(d.lag[1])} ms after their frames began); ` +
                `main thread ${fmt(d.cpu)} ms CPU (longest task ${fmt(d.longestWall)} ms wall, ${fmt(d.longestCpu)} CPU; ` +
                `GC ${fmt(d.gcCpu)} CPU, ${fmt(d.gcWall)} wall); compositor ${fmt(d.compositor)} ms CPU; display compositor (GPU process) ${fmt(d.display)} ms CPU`);
  }
  console.log(`first load ms (cold cache, ${loads} loads): ${loadMs.join(", ")}; median ${ld.median}; /healthz round trip median ${fmt(hl.median)} ms (ratio ${fmt(ld.median / Math.max(hl.median, 0.01))}x)`);
  console.log(`bundle: ${(bundle / 1024).toFixed(1)} KiB (index.html, app.js, app.css)`);
  console.log(`targets: frames under 50 ms: ${worst.frame < 50 ? "yes" : "NO"} (${slow.over} of ${slow.of} frames over 50 ms, ` +
              `${slow.inPage} of them during a main-thread long task; worst frame ${fmt(worst.frame)} ms, worst renderSync ${fmt(worst.work)} ms, ` +
              `worst main-thread CPU in a frame ${fmt(worst.cpu)} ms, ${worst.cpuWhere}); ` +
              `first load under 1 s: ${ld.median < 1000 ? "yes" : "NO"} (median); ` +
              `main-thread CPU of every frame under 50 ms: ${worst.cpu < 50 ? "yes" : "NO"}`);
} finally {
  await browser.close();
  await server.stop();
}
