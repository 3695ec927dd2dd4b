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

  // Pan two ways: (a) work per frame: move the centre and renderSync(),
  // timed in the page; (b) frame intervals: move the centre in each
  // requestAnimationFrame callback and time the callbacks (what an operator
  // sees; 16.7 ms at 60 Hz when the drawing keeps up).
  const pan = (n) => page.evaluate((count) => {
    const m = window.seaplanMap.map;
    const view = m.getView();
    const c = view.getCenter();
    const res = view.getResolution();
    const work = [];
    for (let i = 0; i < count; i++) {
      view.setCenter([c[0] + Math.sin(i / 10) * 200 * res, c[1] + Math.cos(i / 10) * 120 * res]);
      const t = performance.now();
      m.renderSync();
      work.push(performance.now() - t);
    }
    window.__long = [];  // main-thread long tasks from here on (the work loop above is one)
    return new Promise((resolve) => {
      const frames = [];
      const ends = [];
      let last = performance.now();
      let i = 0;
      const step = (now) => {
        console.timeStamp("frame");  // frame boundary in the trace
        frames.push(now - last);
        ends.push(now);
        last = now;
        if (++i >= count) {
          view.setCenter(c);
          resolve({ work, frames: frames.slice(1), ends: ends.slice(1), long: window.__long });
          return;
        }
        view.setCenter([c[0] + Math.sin(i / 10) * 200 * res, c[1] + Math.cos(i / 10) * 120 * res]);
        requestAnimationFrame(step);
      };
      requestAnimationFrame(step);
    });
  }, n);
  // (c) a real drag with the mouse (OpenLayers' DragPan), frames recorded
  // by a requestAnimationFrame loop while Playwright moves the mouse.
  const box = await page.locator("#preview-map").boundingBox();
  const drag = async (n) => {
    await page.evaluate(() => {
      window.__frames = [];
      window.__ends = [];
      window.__long = [];
      let last = performance.now();
      const tick = (now) => {
        console.timeStamp("frame");
        window.__frames.push(now - last);
        window.__ends.push(now);
        last = now;
        if (window.__frames) window.__raf = requestAnimationFrame(tick);
      };
      window.__raf = requestAnimationFrame(tick);
    });
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
      const f = { frames: window.__frames.slice(1), ends: window.__ends.slice(1), long: window.__long };
      window.__frames = undefined;
      return f;
    });
  };
  // Frames over 50 ms, and how many of them overlap a main-thread long task
  // (the page's own script, layout or drawing); the others waited for
  // something outside the page (the compositor, the GPU process, the
  // machine's scheduler).
  const slowFrames = ({ frames: f, ends, long }) => {
    const slow = f.map((d, i) => [ends[i] - d, ends[i]]).filter(([a, b]) => b - a > 50);
    const inPage = slow.filter(([a, b]) => long.some(([s, d]) => s < b && s + d > a));
    return { slow: slow.length, inPage: inPage.length };
  };
  // Main-thread CPU per frame from a Chromium trace: the thread time (CPU
  // time, not wall time) of the renderer main thread's top-level tasks that
  // start between two frame marks. A loaded machine stretches wall times
  // (a descheduled thread waits for a core), not thread times: this is the
  // figure to compare across runs. For each frame over 50 ms it also gives
  // that CPU time and the GC's, so what the rest was is plain.
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
    const marks = events.filter((e) => e.name === "TimeStamp" && e.args?.data?.message === "frame")
      .sort((a, b) => a.ts - b.ts);
    if (marks.length < 2) return { result, cpu: [], slow: [], marks: marks.length };
    const { pid, tid } = marks[0];
    const onMain = (e) => e.pid === pid && e.tid === tid && e.ph === "X" && e.dur !== undefined;
    const tasks = [];
    for (const e of events.filter((e) => onMain(e) && e.cat.split(",").includes("toplevel")).sort((a, b) => a.ts - b.ts)) {
      const last = tasks[tasks.length - 1];
      if (!last || e.ts >= last.ts + last.dur) tasks.push(e);  // top-level only, not nested
    }
    const gcs = events.filter((e) => onMain(e) && (e.name === "MinorGC" || e.name === "MajorGC"));
    const cpu = [];
    const slow = [];
    for (let i = 1, k = 0; i < marks.length; i++) {
      const [a, b] = [marks[i - 1].ts, marks[i].ts];
      while (k < tasks.length && tasks[k].ts < a) k++;
      let ms = 0;
      for (let j = k; j < tasks.length && tasks[j].ts < b; j++) ms += (tasks[j].tdur ?? tasks[j].dur) / 1000;
      cpu.push(ms);
      if ((b - a) / 1000 > 50) {
        const gc = gcs.filter((g) => g.ts < b && g.ts + g.dur > a);
        slow.push({ wall: (b - a) / 1000, cpu: ms, gcCpu: gc.reduce((t, g) => t + (g.tdur ?? g.dur), 0) / 1000,
                    gcWall: gc.reduce((t, g) => t + g.dur, 0) / 1000 });
      }
    }
    return { result, cpu, slow, marks: marks.length };
  };
  const measure = async () => {
    await pan(10);  // warm-up
    const r = await traced(() => pan(frames));
    const dragged = await traced(() => drag(frames));
    const [a, b] = [slowFrames(r.result), slowFrames(dragged.result)];
    // Every frame of the page's own count is between two marks of the trace.
    for (const [t, n] of [[r, r.result.frames.length], [dragged, dragged.result.frames.length]]) {
      if (t.marks < n + 1) console.log(`note: the trace holds ${t.marks} frame marks for ${n} frames`);
    }
    return { work: stats(r.result.work), frame: stats(r.result.frames), drag: stats(dragged.result.frames),
             cpuFrame: stats(r.cpu.length ? r.cpu : [0]), cpuDrag: stats(dragged.cpu.length ? dragged.cpu : [0]),
             slowDetail: [...r.slow, ...dragged.slow],
             slow: a.slow + b.slow, slowInPage: a.inPage + b.inPage,
             count: r.result.frames.length + dragged.result.frames.length };
  };
  const runs = {};
  await page.evaluate(() => window.seaplanMap.fitOnce(true));
  runs["server obstacles, whole chart"] = await measure();
  await page.evaluate(() => window.seaplanMap.map.getView().setZoom(window.seaplanMap.map.getView().getZoom() + 2));
  runs["server obstacles, zoomed x4"] = await measure();
  // The raw land file (every vertex, unsimplified, unbuffered) as the worst case.
  const raw = readFileSync(chartFile, "utf8");
  const rawVertices = await page.evaluate((text) => {
    const m = window.seaplanMap;
    m.setObstacles(text);
    m.fitOnce(true);
    let count = 0;
    m.map.getAllLayers()[0].getSource().forEachFeature((f) => {
      const g = f.getGeometry();
      count += g.getFlatCoordinates().length / g.getStride();
    });
    return count;
  }, raw);
  runs["raw land file, whole chart"] = await measure();
  await page.evaluate(() => window.seaplanMap.map.getView().setZoom(window.seaplanMap.map.getView().getZoom() + 2));
  runs["raw land file, zoomed x4"] = await measure();
  // Baseline: the same page and pans with nothing drawn.
  await page.evaluate(() => {
    const m = window.seaplanMap;
    m.map.getAllLayers().forEach((l) => l.setVisible(false));
    m.fitOnce(true);
  });
  const empty = await measure();

  let bundle = 0;
  for (const name of readdirSync(consoleDir)) if (!name.endsWith(".map") && !name.endsWith(".txt")) bundle += statSync(join(consoleDir, name)).size;
  const ld = stats(loadMs);
  const hl = stats(healthMs);
  console.log(`load average (1, 5, 15 min): ${loadBefore} before, ${loadAverage()} after (${cpus().length} cores)`);
  console.log(`chart: server obstacles ${vertices} vertices (fetched and drawn in ${obstaclesMs} ms), raw land file ${rawVertices} vertices; ` +
              `ship track ${trackPoints} points`);
  console.log(`pan, ${frames} frames each: work = renderSync ms; frame = requestAnimationFrame interval ms while the centre moves each frame; ` +
              `drag = the same while the mouse drags the map (p50 / p95 / max); ratio = mean work / empty map's`);
  const worst = { work: 0, frame: 0, cpu: 0 };
  const slowDetail = [];
  const slow = { over: 0, inPage: 0, of: 0 };
  for (const [name, r] of Object.entries(runs)) {
    worst.work = Math.max(worst.work, r.work.max);
    worst.frame = Math.max(worst.frame, r.frame.max, r.drag.max);
    slow.over += r.slow;
    slow.inPage += r.slowInPage;
    slow.of += r.count;
    worst.cpu = Math.max(worst.cpu, r.cpuFrame.max, r.cpuDrag.max);
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
  console.log(`frames over 50 ms (traced, empty map too): ${slowDetail.length ? slowDetail.map((d) =>
    `${fmt(d.wall)} ms wall, ${fmt(d.cpu)} ms main-thread CPU (GC ${fmt(d.gcCpu)} CPU, ${fmt(d.gcWall)} wall)`).join("; ") : "none"}`);
  console.log(`first load ms (cold cache, ${loads} loads): ${loadMs.join(", ")}; median ${ld.median}; /healthz round trip median ${fmt(hl.median)} ms (ratio ${fmt(ld.median / Math.max(hl.median, 0.01))}x)`);
  console.log(`bundle: ${(bundle / 1024).toFixed(1)} KiB (index.html, app.js, app.css)`);
  console.log(`targets: frames under 50 ms: ${worst.frame < 50 ? "yes" : "NO"} (${slow.over} of ${slow.of} frames over 50 ms, ` +
              `${slow.inPage} of them during a main-thread long task; worst frame ${fmt(worst.frame)} ms, worst renderSync ${fmt(worst.work)} ms, ` +
              `worst main-thread CPU in a frame ${fmt(worst.cpu)} ms); ` +
              `first load under 1 s: ${ld.median < 1000 ? "yes" : "NO"} (median); ` +
              `main-thread CPU of every frame under 50 ms: ${worst.cpu < 50 ? "yes" : "NO"}`);
} finally {
  await browser.close();
  await server.stop();
}
