// Render benchmark of the operator console in headless Chromium:
//   - the Trondheim chart (trondheim_landareal_wgs84.geojson, ~55k land
//     vertices) uploaded through the API and drawn by the chart view, plus a
//     ship track of 10,000 points; frame times while panning (renderSync per
//     frame), against the same pan over an empty map in the same page
//     (baseline ratio);
//   - the console's first load on loopback (navigation to the first view
//     drawn), median of several cold loads, against a GET /healthz round
//     trip in the same page (baseline ratio);
//   - the bundle size.
//
//   node bench/console/render_bench.mjs [--frames 120] [--loads 5]
//   env: SEAPLAN_SERVER_BIN, CONSOLE_DIR (default build/bin/...),
//        SEAPLAN_SHARED (default ../shared beside the clone)
import { existsSync, readdirSync, readFileSync, statSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
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
const { launchBrowser, startServer } = await import("../../clients/console/e2e/support.mjs");

const stats = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const q = (p) => s[Math.min(s.length - 1, Math.floor(p * s.length))];
  return { median: q(0.5), p95: q(0.95), max: s[s.length - 1] };
};
const fmt = (x) => x.toFixed(2);

const server = await startServer({ serverBin, consoleDir });
const browser = await launchBrowser();
try {
  // The chart through the API, as the console's upload form sends it.
  const upload = await fetch(`${server.url}v1/ChartService/UploadChart`, {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ name: "trondheim", format: "CHART_FORMAT_GEOJSON", files: [
      { name: "trondheim_landareal_wgs84.geojson", content: readFileSync(chartFile).toString("base64") }] }),
  });
  if (!upload.ok) throw new Error(`upload: ${upload.status} ${await upload.text()}`);
  const chart = (await upload.json()).chart;

  const page = await browser.context.newPage();
  // First load: cold navigations (cache disabled) to the first view drawn.
  const cdp = await browser.context.newCDPSession(page);
  await cdp.send("Network.setCacheDisabled", { cacheDisabled: true });
  const loadMs = [];
  const healthMs = [];
  for (let i = 0; i < loads; i++) {
    const t0 = Date.now();
    await page.goto(`${server.url}#/missions`);
    await page.waitForSelector("main h1");
    loadMs.push(Date.now() - t0);
    healthMs.push(await page.evaluate(async () => {
      const t = performance.now();
      await (await fetch("/healthz", { cache: "no-store" })).text();
      return performance.now() - t;
    }));
  }

  // The chart view with the obstacles and a 10,000-point track.
  await page.goto(`${server.url}#/charts`);
  await page.waitForFunction((id) => !!document.querySelector(`#p-chart option[value="${id}"]`), chart.chartId);
  await page.selectOption("#p-chart", chart.chartId);
  const tLoad = Date.now();
  await page.click("#p-show");
  await page.waitForFunction(() => /obstacles at/.test(document.querySelector("#p-status")?.textContent ?? ""), null, { timeout: 120000 });
  const obstaclesMs = Date.now() - tLoad;
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

  // Pan: each frame moves the centre and renders synchronously.
  const pan = (n) => page.evaluate((count) => {
    const m = window.seaplanMap.map;
    const view = m.getView();
    const c = view.getCenter();
    const res = view.getResolution();
    const times = [];
    for (let i = 0; i < count; i++) {
      view.setCenter([c[0] + Math.sin(i / 10) * 200 * res, c[1] + Math.cos(i / 10) * 120 * res]);
      const t = performance.now();
      m.renderSync();
      times.push(performance.now() - t);
    }
    view.setCenter(c);
    return times;
  }, n);
  await page.evaluate(() => window.seaplanMap.fitOnce(true));
  await pan(10);  // warm-up
  const full = stats(await pan(frames));
  await page.evaluate(() => window.seaplanMap.map.getView().setZoom(window.seaplanMap.map.getView().getZoom() + 2));
  const zoomed = stats(await pan(frames));
  // Baseline: the same page and pan with nothing drawn.
  await page.evaluate(() => {
    const m = window.seaplanMap;
    m.map.getAllLayers().forEach((l) => l.setVisible(false));
    m.fitOnce(true);
  });
  await pan(10);
  const empty = stats(await pan(frames));

  let bundle = 0;
  for (const name of readdirSync(consoleDir)) if (!name.endsWith(".map") && !name.endsWith(".txt")) bundle += statSync(join(consoleDir, name)).size;
  const ld = stats(loadMs);
  const hl = stats(healthMs);
  console.log(`chart: ${vertices} obstacle vertices, ${trackPoints} track points; obstacles fetched and drawn in ${obstaclesMs} ms`);
  console.log(`frame ms (renderSync while panning, ${frames} frames): whole chart median ${fmt(full.median)} p95 ${fmt(full.p95)} max ${fmt(full.max)}; ` +
              `zoomed x4 median ${fmt(zoomed.median)} p95 ${fmt(zoomed.p95)} max ${fmt(zoomed.max)}; empty map median ${fmt(empty.median)}`);
  console.log(`frame ratio to the empty map (median): ${fmt(full.median / Math.max(empty.median, 0.01))}x whole chart, ${fmt(zoomed.median / Math.max(empty.median, 0.01))}x zoomed`);
  console.log(`first load ms (cold, ${loads} loads): median ${ld.median} max ${ld.max}; /healthz round trip median ${fmt(hl.median)} ms (ratio ${fmt(ld.median / Math.max(hl.median, 0.01))}x)`);
  console.log(`bundle: ${(bundle / 1024).toFixed(1)} KiB (index.html, app.js, app.css)`);
  console.log(`targets: frames under 50 ms: ${full.max < 50 && zoomed.max < 50 ? "yes" : "NO"} (worst ${fmt(Math.max(full.max, zoomed.max))} ms); first load under 1 s: ${ld.median < 1000 ? "yes" : "NO"}`);
} finally {
  await browser.close();
  await server.stop();
}
