// The operator console end to end in a real browser (Debian's Chromium,
// headless): start seaplan-server with the console, upload the fjord chart,
// create case B through the form, run seaplan-sim against it, and check what
// an operator sees: the route on the map, the ship moving, version 2 after
// the GNSS jump with its reason, both versions in the Gantt chart, no
// console errors, no serious accessibility violations (axe-core), and
// screenshots that are not blank (saved under $ARTIFACT_DIR).
//
//   node e2e/console_e2e.mjs   (env: SEAPLAN_SERVER_BIN, SEAPLAN_SIM_BIN,
//                               CONSOLE_DIR, EXAMPLES_DIR, ARTIFACT_DIR)
// Exit 0 passed, 1 failed, 77 skipped (prerequisite missing, outside CI).
import { spawn } from "node:child_process";
import { mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { createRequire } from "node:module";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { requireFile } from "./prereq.mjs";

const here = dirname(fileURLToPath(import.meta.url));
const repo = resolve(here, "../../..");
const serverBin = process.env.SEAPLAN_SERVER_BIN || join(repo, "build/bin/seaplan-server");
const simBin = process.env.SEAPLAN_SIM_BIN || join(repo, "build/bin/seaplan-sim");
const consoleDir = process.env.CONSOLE_DIR || join(repo, "build/bin/console");
const examples = process.env.EXAMPLES_DIR || join(repo, "examples");
const artifacts = process.env.ARTIFACT_DIR || join(repo, "build/test-artifacts/console");
requireFile(serverBin, "seaplan-server");
requireFile(simBin, "seaplan-sim");
requireFile(join(consoleDir, "index.html"), "the built console");
requireFile(process.env.CHROMIUM_PATH || "/usr/bin/chromium", "Chromium (apt-get install chromium)");
requireFile(join(here, "../node_modules/playwright-core/package.json"),
            "clients/console/node_modules (npm ci in clients/console)");
const { distinctColours, launchBrowser, readScenario, signIn, startServer } = await import("./support.mjs");
mkdirSync(artifacts, { recursive: true });

const failures = [];
let passed = 0;
function check(ok, what) {
  if (ok) {
    passed++;
    console.log(`ok   ${what}`);
  } else {
    failures.push(what);
    console.log(`FAIL ${what}`);
  }
}

async function waitFor(what, fn, timeoutMs) {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const v = await fn();
    if (v) return v;
    if (Date.now() > end) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 250));
  }
}

process.env.SEAPLAN_BYPASS_CSP = "1";  // to inject axe-core
const scenarioPath = join(examples, "scenarios/case-b.scenario");
const scenario = readScenario(scenarioPath);
const server = await startServer({ serverBin, consoleDir });
const browser = await launchBrowser();
let sim;
try {
  const page = await browser.context.newPage();
  const consoleErrors = [];
  page.on("console", (m) => { if (m.type() === "error") consoleErrors.push(m.text()); });
  page.on("pageerror", (e) => consoleErrors.push(String(e)));
  const external = [];
  page.on("request", (r) => { if (!r.url().startsWith(server.url) && !r.url().startsWith("data:")) external.push(r.url()); });
  const scriptCodings = [];
  page.on("response", (r) => { if (r.url().endsWith("/app.js")) scriptCodings.push(r.headers()["content-encoding"] ?? "identity"); });

  // 0. Sign-in: the console asks for a token, a wrong one is refused, the
  // admin token the server wrote at its first start opens the session; the
  // cookie alone (without the CSRF header) is refused.
  await page.goto(server.url);
  await page.waitForSelector("#sign-in #token");
  await page.fill("#token", "seaplan_0000000000000000_wrong");
  await page.click("#sign-in button[type=submit]");
  await page.waitForFunction(() => (document.querySelector("#sign-in-error")?.textContent ?? "") !== "");
  check(true, `a wrong token is refused (${await page.$eval("#sign-in-error", (e) => e.textContent)})`);
  await signIn(page, server);
  check(/^admin /.test(await page.$eval("#signed-in-as", (e) => e.textContent ?? "")), "signed in as admin");
  // Compressed, but not with brotli: the server's library brotli-compresses
  // at its slowest setting (1.5 s for the script on every load).
  check(scriptCodings.length > 0 && scriptCodings.every((c) => c === "gzip"),
        `the script comes gzip-compressed (${scriptCodings.join(", ")})`);
  const cookieOnly = await page.evaluate(async () =>
    (await fetch("/v1/MissionService/ListMissions", { method: "POST", body: "{}" })).status);
  check(cookieOnly === 403, `the session cookie without the CSRF header gets 403 (${cookieOnly})`);
  const cookies = await browser.context.cookies();
  const sessionCookie = cookies.find((c) => c.name === "seaplan_session");
  check(!!sessionCookie && sessionCookie.httpOnly && sessionCookie.sameSite === "Strict",
        "session cookie is HttpOnly and SameSite=Strict");
  // The browser logs those refusals (and the signed-out session probe) as
  // failed loads; what follows must log nothing.
  consoleErrors.length = 0;

  // 1. Charts: upload the scenario's chart through the form.
  const t0 = Date.now();
  await page.goto(`${server.url}#/charts`);
  await page.waitForSelector("#c-upload");
  console.log(`first load: ${Date.now() - t0} ms`);
  await page.fill("#c-name", "fjord entrance");
  await page.setInputFiles("#c-files", join(dirname(scenarioPath), scenario.chart));
  await page.selectOption("#c-format", "CHART_FORMAT_GEOJSON");
  await page.fill("#c-depth", "5");
  await page.click("#c-upload");
  await page.waitForFunction(() => /^Stored /.test(document.querySelector("#c-message")?.textContent ?? ""), null, { timeout: 60000 });
  await page.waitForSelector("#charts-body tr td:nth-child(2)");
  const chartId = await page.$eval("#charts-body tr td:nth-child(2)", (e) => e.textContent);
  check(/^c-/.test(chartId ?? ""), `chart uploaded and listed (${chartId})`);
  await page.selectOption("#p-chart", chartId);
  await page.fill("#p-depth", "2");
  await page.click("#p-show");
  await page.waitForFunction(() => /obstacles at 2 m$/.test(document.querySelector("#p-status")?.textContent ?? ""), null, { timeout: 60000 });
  const previewed = await page.evaluate(() => window.seaplanMap.obstacleCount());
  check(previewed > 0, `chart preview at 2 m draws ${previewed} obstacles`);
  // The scale bars' labels (NM line, metric steps) at several zoom levels:
  // each label's text box inside the map, none overlapping another, the
  // metric steps left to right.
  for (const dz of [0, 1.3, -2.6, 3.7, 1.9]) {
    const labels = await page.evaluate((d) => {
      const m = window.seaplanMap.map;
      m.getView().setZoom(m.getView().getZoom() + d);
      m.renderSync();
      const mapBox = document.querySelector("#preview-map").getBoundingClientRect();
      return [...document.querySelectorAll("#preview-map .ol-scale-line-inner, #preview-map .ol-scale-step-text")].map((el) => {
        const range = document.createRange();
        range.selectNodeContents(el);
        const b = range.getBoundingClientRect();
        return { text: el.textContent, step: el.classList.contains("ol-scale-step-text"),
                 left: b.left, right: b.right, top: b.top, bottom: b.bottom,
                 inside: b.left >= mapBox.left && b.right <= mapBox.right && b.top >= mapBox.top && b.bottom <= mapBox.bottom };
      });
    }, dz);
    const overlaps = [];
    labels.forEach((a, i) => labels.slice(i + 1).forEach((b) => {
      if (a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom) overlaps.push(`"${a.text}"/"${b.text}"`);
    }));
    const steps = labels.filter((l) => l.step);
    const inRow = steps.every((l, i) => i === 0 || l.left > steps[i - 1].right);
    check(labels.length >= 4 && steps.length >= 3 && overlaps.length === 0 && inRow && labels.every((l) => l.inside),
          `scale labels apart and inside the map (${labels.map((l) => l.text).join(", ")}` +
          `${overlaps.length ? `; overlapping: ${overlaps.join(" ")}` : ""})`);
  }
  await page.screenshot({ path: join(artifacts, "charts.png"), fullPage: true });

  // 2. New mission: case B typed into the form.
  await page.goto(`${server.url}#/new`);
  await page.waitForSelector("#m-submit");
  await page.waitForFunction((id) => !!document.querySelector(`#m-chart option[value="${id}"]`), chartId);
  const sdir = dirname(scenarioPath);
  await page.fill("#m-name", scenario.name);
  await page.fill("#m-vessel", scenario.vessel_id);
  await page.fill("#m-ship-object", scenario.ship_object);
  await page.selectOption("#m-chart", chartId);
  await page.fill("#m-locations", scenario.locations.join("\n"));
  await page.fill("#m-speed", scenario.service_speed_mps);
  await page.fill("#m-heading", scenario.start_heading_deg);
  await page.fill("#m-fuel", scenario.initial_fuel);
  await page.fill("#m-fuel-threshold", scenario.fuel_threshold);
  await page.fill("#m-deviation", scenario.position_deviation_m);
  await page.fill("#m-delay", scenario.delay_tolerance_s);
  await page.fill("#m-time-limit", scenario.planner_time_limit_s);
  const [windSpeed, windFrom] = scenario.wind.split(/\s+/);
  const [currentSpeed, currentFrom] = scenario.current.split(/\s+/);
  await page.fill("#m-wind-speed", windSpeed);
  await page.fill("#m-wind-from", windFrom);
  await page.fill("#m-current-speed", currentSpeed);
  await page.fill("#m-current-from", currentFrom);
  await page.fill("#m-port-ops", scenario.portOperations.join("\n"));
  await page.setInputFiles("#domain-file", join(sdir, scenario.domain));
  await page.setInputFiles("#problem-file", join(sdir, scenario.problem));
  await page.waitForFunction(() => (document.querySelector("#problem-text")?.value ?? "").includes("define"));

  // A broken problem first: the server's diagnostic lands at its line.
  const problemText = readFileSync(join(sdir, scenario.problem), "utf8");
  await page.fill("#problem-text", problemText.replace("(at ship0 port-a)", "(at ship0 port-zz)"));
  await page.click("#m-submit");
  await page.waitForSelector("#problem-diags li", { timeout: 30000 });
  const diag = await page.$eval("#problem-diags li", (e) => e.textContent ?? "");
  check(/^problem:\d+:\d+: /.test(diag), `PDDL diagnostic shown at line:column (${diag.slice(0, 80)})`);
  await page.screenshot({ path: join(artifacts, "new-mission-diagnostic.png"), fullPage: true });
  // The refused request is the one error the browser logs here (its 400).
  const refused = consoleErrors.splice(0);
  check(refused.length <= 1 && refused.every((e) => /status of 400/.test(e)),
        `only the refused request logged (${refused.join(" | ") || "nothing"})`);
  await page.fill("#problem-text", problemText);
  await page.click("#m-submit");
  await page.waitForURL(/#\/mission\//, { timeout: 120000 });
  const missionId = /#\/mission\/([\w-]+)/.exec(page.url())[1];
  check(!!missionId, `mission created through the form (${missionId})`);

  // 3. The mission view: route on the map before the ship sails.
  await page.waitForFunction(() => window.seaplanMap && window.seaplanMap.routeSegmentCount() > 0 &&
                             window.seaplanMap.obstacleCount() > 0, null, { timeout: 30000 });
  check(true, "route and obstacles drawn on the map");

  // The chart pans from the keyboard.
  const centre = () => page.evaluate(() => window.seaplanMap.map.getView().getCenter().join(","));
  const before = await centre();
  await page.focus("#mission-map");
  await page.keyboard.press("ArrowRight");
  await page.waitForTimeout(400);  // the pan animates
  check((await centre()) !== before, "chart pans with the arrow keys");

  // 4. seaplan-sim executes it.
  const simOut = [];
  sim = spawn(simBin, ["--server", server.grpcAddress, "--scenario", scenarioPath, "--mission-id", missionId,
                       "--time-factor", process.env.SIM_TIME_FACTOR || "25", "--report-dir", join(server.dir, "report")],
              { stdio: ["ignore", "pipe", "pipe"] });
  sim.stdout.on("data", (d) => simOut.push(String(d)));
  sim.stderr.on("data", (d) => simOut.push(String(d)));
  const simExit = new Promise((r) => sim.on("exit", (code) => r(code)));

  const firstPos = await waitFor("a position update", () => page.evaluate(() => {
    const el = document.querySelector("#ship-panel dd");
    return el?.textContent && el.textContent !== "-" ? el.textContent : null;
  }), 60000);
  const moved = await waitFor("the ship to move", () => page.evaluate((first) => {
    const now = document.querySelector("#ship-panel dd")?.textContent;
    return now && now !== first ? now : null;
  }, firstPos), 60000);
  check(moved !== firstPos, `ship moving (${firstPos} -> ${moved})`);
  const trackPoints = await page.evaluate(() => window.seaplanMap.trackPointCount());
  check(trackPoints >= 2, `ship track drawn (${trackPoints} points)`);
  await page.screenshot({ path: join(artifacts, "mission-underway.png") });

  // A broken connection: the watch resumes after the last version and
  // event it delivered (checked below: no duplicate, no gap in the log).
  await page.evaluate(() => window.seaplanWatch.dropConnection());
  await page.waitForFunction(() => /^stream: live \(resumed/.test(document.querySelector("#watch-status")?.textContent ?? ""), null, { timeout: 30000 });
  check(true, "watch stream resumed after a dropped connection");

  // 4b. A second operator opens the mission part-way through: the track and
  // fuel from the start (the stored feedback reports), then live, with no
  // stored report missing and no mission time drawn twice.
  await waitFor("mission time past 0:03:00", () => page.evaluate(() => {
    const t = window.seaplanHistory?.series.all.at(-1)?.missionTimeS ?? 0;
    return t >= 180 ? t : null;
  }), 120000);
  const late = await browser.context.newPage();
  late.on("console", (m) => { if (m.type() === "error") consoleErrors.push(`late page: ${m.text()}`); });
  late.on("pageerror", (e) => consoleErrors.push(`late page: ${e}`));
  await late.goto(`${server.url}#/mission/${missionId}`);
  await late.waitForFunction(() => window.seaplanHistory && window.seaplanHistory.storedReports() > 0 &&
                             window.seaplanHistory.firstLiveS() !== undefined, null, { timeout: 60000 });
  const seriesOf = () => late.evaluate(() => window.seaplanHistory.series.all.map((s) => ({
    t: s.missionTimeS, lat: s.position?.latitudeDeg, fuel: s.fuelFraction })));
  const opened = await seriesOf();
  const firstLiveS = await late.evaluate(() => window.seaplanHistory.firstLiveS());
  const storedReports = (missionId) => late.evaluate(async (missionId) => {
    const out = [];
    let after = "0";
    const { csrfToken } = await (await fetch("/auth/session")).json();
    for (;;) {
      const res = await fetch("/v1/MissionService/ListFeedback", { method: "POST",
        headers: { "X-CSRF-Token": csrfToken },
        body: JSON.stringify({ missionId, afterSequence: after, pageSize: 100 }) });
      const page = await res.json();
      for (const r of page.feedback ?? []) {
        if (r.feedback?.state) out.push({ t: r.feedback.missionTimeS ?? 0, lat: r.feedback.state.position?.latitudeDeg,
                                           lon: r.feedback.state.position?.longitudeDeg, seq: Number(r.sequence) });
        after = r.sequence;
      }
      if (!page.nextAfterSequence || page.nextAfterSequence === "0") return out;
    }
  }, missionId);
  const stored = await storedReports(missionId);
  const lateTrack = await late.evaluate(() => window.seaplanMap.trackPointCount());
  const firstDrawn = await late.evaluate(() => window.seaplanMap.trackStart());
  check(stored.length > 2 && opened[0].t === stored[0].t && firstLiveS > stored[0].t + 60 &&
        Math.abs(firstDrawn.latitudeDeg - stored[0].lat) < 1e-7 && Math.abs(firstDrawn.longitudeDeg - stored[0].lon) < 1e-7,
        `opened at T+${Math.round(firstLiveS)} s, the track (${lateTrack} points) and fuel (${opened.length} samples) ` +
        `start at the first stored report (T+${Math.round(stored[0].t)} s, ${stored.length} stored)`);
  await waitFor("a live update after opening", async () =>
    (await seriesOf()).at(-1).t > opened.at(-1).t, 60000);
  // Every report stored since is fetched as its log event arrives.
  const storedSince = await storedReports(missionId);
  await waitFor("the reports stored since opening", () => late.evaluate((seq) =>
    Number(window.seaplanHistory.cursor()) >= seq, storedSince.at(-1).seq), 30000);
  const later = await seriesOf();
  const times = later.map((s) => s.t);
  const strictlyIncreasing = times.every((t, i) => i === 0 || t > times[i - 1]);
  const lastT = times.at(-1);
  const missed = storedSince.filter((r) => r.t <= lastT && !times.includes(r.t));
  check(strictlyIncreasing && missed.length === 0 && later.length > opened.length,
        `history then live: ${later.length} samples, each mission time once, none of the ${storedSince.length} stored reports missing ` +
        `(missing ${missed.map((r) => r.t).join(",") || "none"})`);
  const caption = await late.textContent("#fuel-caption");
  check(/^T\+0:00:\d\d .*from stored reports\)$/.test(caption ?? ""), `fuel over time from the start (${caption})`);
  await late.screenshot({ path: join(artifacts, "mission-opened-late.png") });
  await late.close();

  // 5. Version 2 after the GNSS jump, with its reason, and both in the Gantt.
  await page.waitForFunction(() => document.querySelectorAll("#gantt .gantt-version").length >= 2, null, { timeout: 180000 });
  const versionLabel = await page.$eval("#mission-version", (e) => e.textContent ?? "");
  check(/^version 2: .+/.test(versionLabel) && !/initial plan/.test(versionLabel), `version 2 with its reason (${versionLabel})`);
  const heads = await page.$$eval("#gantt .gantt-head", (es) => es.map((e) => e.textContent));
  check(heads.length >= 2 && /^version 1: /.test(heads[0]) && /^version 2: /.test(heads[1]), `Gantt shows both versions (${heads.join(" | ")})`);
  const ids = await page.$$eval("#navlog li", (lis) => lis.map((li) => Number(li.dataset.event)).reverse());
  const inOrder = ids.every((id, i) => i === 0 || id > ids[i - 1]);
  const fresh = await page.evaluate(async (missionId) => {
    // The same events fetched afresh: the live log has every one of them.
    const { csrfToken } = await (await fetch("/auth/session")).json();
    const res = await fetch("/v1/MissionService/WatchMission", { method: "POST", body: JSON.stringify({ missionId }),
                                                                   headers: { "X-CSRF-Token": csrfToken },
                                                                   signal: AbortSignal.timeout(3000) }).catch(() => null);
    if (!res) return null;
    const reader = res.body.getReader();
    let text = "";
    const until = Date.now() + 2000;
    while (Date.now() < until) {
      const { value, done } = await Promise.race([reader.read(), new Promise((r) => setTimeout(() => r({ done: true }), 500))]);
      if (value) text += new TextDecoder().decode(value);
      if (done) break;
    }
    reader.cancel().catch(() => undefined);
    return text.split("\n").filter(Boolean).map((l) => JSON.parse(l)).filter((e) => e.log).map((e) => Number(e.log.eventId));
  }, missionId);
  const missing = (fresh ?? []).filter((id) => id <= ids[ids.length - 1] && !ids.includes(id));
  check(ids.length > 0 && inOrder && fresh !== null && missing.length === 0,
        `navigation log without duplicate or gap across the reconnect (${ids.length} events, missing ${missing.join(",") || "none"})`);
  const targets = await page.$$eval("#traffic-body tr", (rows) => rows.length);
  check(targets > 0, `traffic listed (${targets} targets)`);

  // Hover read-outs: a route leg's grounding risk, a target's CPA/TCPA. The
  // ship or a label may lie over a feature: up to five features are tried.
  const hover = async (layerName, wanted) => {
    let text = "";
    for (let k = 0; k < 5 && !wanted.test(text); k++) {
      const at = await page.evaluate(({ name, k }) => {
        const m = window.seaplanMap.map;
        const features = m.getAllLayers().find((l) => l.get("name") === name)?.getSource().getFeatures() ?? [];
        const f = features[Math.floor((k * features.length) / 5)];
        if (!f) return null;
        const g = f.getGeometry();
        const c = g.getType() === "Point" ? g.getCoordinates() : g.getCoordinateAt(0.5);
        m.getView().setCenter(c);
        m.renderSync();
        const px = m.getPixelFromCoordinate(c);
        const box = m.getTargetElement().getBoundingClientRect();
        return { x: box.left + px[0], y: box.top + px[1] };
      }, { name: layerName, k });
      if (!at) break;
      await page.mouse.move(at.x - 20, at.y - 20);
      await page.mouse.move(at.x, at.y);
      await page.waitForTimeout(200);
      text = await page.$eval("#mission-map .map-tip", (e) => (e.offsetParent ? e.textContent : "")).catch(() => "");
      text = (text ?? "").replace(/\s+/g, " ").trim();
    }
    await page.mouse.move(0, 0);
    return text;
  };
  const routeTip = await hover("routes", /time to grounding/);
  check(/time to grounding/.test(routeTip) && /P\(grounding\) \d/.test(routeTip) && /mode (PTO|MEC|PTI)/.test(routeTip),
        `route leg on hover: ${routeTip.slice(0, 120)}`);
  const targetTip = await hover("traffic", /CPA/);
  check(/CPA .+ in -?\d+ s/.test(targetTip), `traffic on hover: ${targetTip.slice(0, 120)}`);

  // 6. Screenshot of the map: not blank, land and route colours present.
  await page.waitForTimeout(500);
  const mapPng = await page.locator("#mission-map").screenshot({ path: join(artifacts, "mission-map.png") });
  const colours = await distinctColours(page, mapPng);
  check(colours > 20, `map screenshot not blank (${colours} distinct colours)`);
  const layerPixels = await page.evaluate(() => {
    const want = { land: [0xd6, 0xc7, 0x9a], pto: [0x2f, 0x7f, 0xd8], mec: [0x1f, 0xa3, 0x7a], pti: [0xe0, 0x8a, 0x1e] };
    const count = { land: 0, route: 0 };
    for (const c of document.querySelectorAll("#mission-map canvas")) {
      const d = c.getContext("2d")?.getImageData(0, 0, c.width, c.height).data;
      if (!d) continue;
      for (let i = 0; i < d.length; i += 4) {
        const near = (rgb) => Math.abs(d[i] - rgb[0]) + Math.abs(d[i + 1] - rgb[1]) + Math.abs(d[i + 2] - rgb[2]) < 24;
        if (near(want.land)) count.land++;
        else if (near(want.pto) || near(want.mec) || near(want.pti)) count.route++;
      }
    }
    return count;
  });
  check(layerPixels.land > 1000 && layerPixels.route > 50, `map layers present (land ${layerPixels.land} px, route ${layerPixels.route} px)`);

  // 7. Accessibility (axe-core, WCAG 2 A/AA): no serious or critical violations.
  const require = createRequire(import.meta.url);
  await page.addScriptTag({ path: require.resolve("axe-core/axe.min.js") });
  for (const view of ["mission", "missions", "new", "charts", "workbench"]) {
    if (view !== "mission") {
      await page.goto(`${server.url}#/${view}`);
      await page.waitForSelector("main h1");
      await page.addScriptTag({ path: require.resolve("axe-core/axe.min.js") });
    }
    const result = await page.evaluate(() => window.axe.run(document, { runOnly: ["wcag2a", "wcag2aa"] }));
    const serious = result.violations.filter((v) => v.impact === "serious" || v.impact === "critical");
    check(serious.length === 0, `axe: no serious violations on ${view}` +
          (serious.length ? ` (${serious.map((v) => `${v.id}: ${v.nodes.length}`).join(", ")})` : ""));
  }
  // 8. Workbench: plan case A streamed, see it as a Gantt chart, validate it
  // and a broken copy.
  await page.goto(`${server.url}#/workbench`);
  await page.fill("#wb-domain-text", readFileSync(join(sdir, scenario.domain), "utf8"));
  await page.fill("#wb-problem-text", problemText);
  await page.fill("#wb-limit", "3");
  await page.click("#wb-run");
  await page.waitForFunction(() => /^SOLVED/.test(document.querySelector("#wb-status")?.textContent ?? ""), null, { timeout: 60000 });
  const bars = await page.$$eval("#wb-gantt .gantt-bar", (b) => b.length);
  const improved = await page.$$eval("#wb-improvements li", (l) => l.length);
  check(bars > 0 && improved > 0, `workbench: plan streamed (${improved} improvements) and drawn (${bars} actions)`);
  await page.click("#wb-validate");
  await page.waitForFunction(() => /^Valid:/.test(document.querySelector("#wb-status")?.textContent ?? ""), null, { timeout: 30000 });
  const planText = await page.inputValue("#wb-plan-text");
  await page.fill("#wb-plan-text", planText.split("\n").filter((l) => !/unload-cont/.test(l)).join("\n"));
  await page.click("#wb-validate");
  await page.waitForFunction(() => /^Invalid/.test(document.querySelector("#wb-status")?.textContent ?? ""), null, { timeout: 30000 });
  const why = await page.textContent("#wb-status");
  check(true, `workbench: valid plan accepted, broken plan refused (${why.slice(0, 100)})`);
  await page.screenshot({ path: join(artifacts, "workbench.png"), fullPage: true });

  await page.goto(`${server.url}#/mission/${missionId}`);
  await page.waitForFunction(() => window.seaplanMap && window.seaplanMap.routeSegmentCount() > 0 &&
                             window.seaplanMap.obstacleCount() > 0, null, { timeout: 30000 });
  await page.selectOption("#palette", "night");
  await page.waitForTimeout(500);
  await page.screenshot({ path: join(artifacts, "mission-night.png") });
  for (const palette of ["dusk", "night"]) {
    await page.goto(`${server.url}#/missions`);
    await page.selectOption("#palette", palette);
    await page.screenshot({ path: join(artifacts, `missions-${palette}.png`) });
  }
  await page.selectOption("#palette", "day");

  const code = await Promise.race([simExit, new Promise((r) => setTimeout(() => r("timeout"), 240000))]);
  check(code === 0, `seaplan-sim completed the mission (exit ${code})`);
  if (code !== 0) console.log(simOut.join("").slice(-3000));

  // 9. The finished mission: its state shown, replan and cancel refused
  // with the server's reason.
  const errorsBefore = consoleErrors.length;
  await page.goto(`${server.url}#/mission/${missionId}`);
  await page.waitForFunction(() => document.querySelector("#mission-state")?.textContent === "completed", null, { timeout: 30000 });
  await page.click("#replan");
  await page.waitForFunction(() => /^Replan refused: /.test(document.querySelector(".mission .status")?.textContent ?? ""), null, { timeout: 30000 });
  const refusedReplan = await page.textContent(".mission .status");
  page.once("dialog", (d) => d.accept());
  await page.click("#cancel");
  await page.waitForFunction(() => /^Cancel refused: /.test(document.querySelector(".mission .status")?.textContent ?? ""), null, { timeout: 30000 });
  const refusedCancel = await page.textContent(".mission .status");
  check(true, `completed mission: ${refusedReplan.slice(0, 90)}; ${refusedCancel.slice(0, 90)}`);
  // Those refusals are the browser's logged 4xx responses; nothing else.
  const refusals = consoleErrors.splice(errorsBefore);
  check(refusals.length === 2 && refusals.every((e) => /status of 412/.test(e)),
        `only the two refusals logged (${refusals.join(" | ")})`);
  check(consoleErrors.length === 0, `no console errors${consoleErrors.length ? `: ${consoleErrors.join(" | ")}` : ""}`);
  check(external.length === 0, `nothing loaded from elsewhere${external.length ? `: ${external.join(", ")}` : ""}`);

  // 9b. The admin deletes the chart the finished mission used: it leaves the list.
  await page.goto(`${server.url}#/charts`);
  await page.waitForSelector(`button.delete-chart[data-chart-id="${chartId}"]`);
  page.once("dialog", (d) => d.accept());
  await page.click(`button.delete-chart[data-chart-id="${chartId}"]`);
  await page.waitForFunction(() => /^Deleted /.test(document.querySelector("#charts-status")?.textContent ?? ""), null, { timeout: 30000 });
  const listedAfter = await page.$$eval("#charts-body tr td:nth-child(2)", (cells) => cells.map((c) => c.textContent));
  check(!listedAfter.includes(chartId), `chart ${chartId} deleted from the console (${listedAfter.length} left)`);

  // 10. Sign-out ends the session: the form again, and the cookie is refused.
  await page.click("#sign-out");
  await page.waitForSelector("#sign-in #token");
  const afterSignOut = await page.evaluate(async () =>
    (await fetch("/v1/MissionService/ListMissions", { method: "POST", body: "{}" })).status);
  check(afterSignOut === 401, `after sign-out the API answers 401 (${afterSignOut})`);
} catch (e) {
  failures.push(String(e?.stack ?? e));
  console.log(`FAIL ${e?.stack ?? e}`);
} finally {
  if (sim && sim.exitCode === null) sim.kill("SIGTERM");
  await browser.close();
  await server.stop();
}
writeFileSync(join(artifacts, "result.txt"), `${passed} passed, ${failures.length} failed\n${failures.join("\n")}\n`);
console.log(`screenshots: ${artifacts}`);
console.log(`${passed} passed, ${failures.length} failed`);
process.exit(failures.length ? 1 : 0);
