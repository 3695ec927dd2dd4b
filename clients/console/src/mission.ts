// One mission, live: the map (obstacles, routes by MSO mode, ship, track,
// traffic), the plan versions as a Gantt chart, the navigation log, fuel
// over time and the machinery mode, over the WatchMission NDJSON stream
// (resumed after a broken connection). The track and fuel before the page
// opened come from the stored feedback reports (ListFeedback).
import { call, MissionWatch, type Mission, type PlanVersion, type VesselUpdate } from "./api";
import { field, h } from "./dom";
import { renderGantt } from "./gantt";
import { loadFeedback, sampleOf, ShipSeries, type StoredFeedback } from "./history";
import { ChartMap } from "./map";
import { cpa, degrees, distance, missionTime, percent, shortMode, shortState, speed,
         utc } from "./units";

export function missionView(root: HTMLElement, missionId: string): () => void {
  const title = h("h1", { id: "mission-title", text: `Mission ${missionId}` });
  const stateBadge = h("span", { class: "badge", id: "mission-state" });
  const versionLabel = h("span", { id: "mission-version" });
  const clock = h("span", { id: "mission-clock" });
  const link = h("span", { id: "watch-status", class: "watch-status", role: "status" });
  const reason = h("input", { id: "replan-reason", value: "operator request" });
  const replan = h("button", { type: "button", id: "replan", text: "Request replan" });
  const cancel = h("button", { type: "button", id: "cancel", class: "danger", text: "Cancel mission" });
  const actionStatus = h("p", { class: "status", role: "status" });
  const mapBox = h("div", { class: "map", id: "mission-map" });
  const shipPanel = h("dl", { class: "ship-panel", id: "ship-panel" });
  const trafficBody = h("tbody", { id: "traffic-body" });
  const gantt = h("div", { class: "gantt", id: "gantt", tabindex: 0, role: "region", "aria-label": "Plan versions" });
  const log = h("ol", { class: "navlog", id: "navlog", "aria-live": "polite", tabindex: 0, "aria-label": "Navigation log" });
  const fuelBox = h("div", { class: "fuel", id: "fuel-chart" });
  const fuelCaption = h("p", { class: "fuel-caption", id: "fuel-caption" });
  root.append(h("section", { class: "mission", "aria-labelledby": "mission-title" },
    h("div", { class: "toolbar" }, title, stateBadge, versionLabel, clock, link),
    h("div", { class: "toolbar" }, field("Replan reason", reason), replan, cancel, actionStatus),
    h("div", { class: "mission-grid" }, mapBox,
      h("aside", { "aria-label": "Ship and traffic" },
        h("h2", { text: "Own ship" }), shipPanel,
        h("h2", { text: "Fuel" }), fuelBox, fuelCaption,
        h("h2", { text: "Traffic" }),
        h("table", { class: "grid", "aria-label": "Traffic" }, h("thead", {}, h("tr", {},
          ...["Target", "Course", "Speed", "CPA", "TCPA"].map((t) => h("th", { scope: "col", text: t })))),
          trafficBody))),
    h("h2", { text: "Plan versions" }), gantt,
    h("h2", { text: "Navigation log" }), log));

  const map = new ChartMap(mapBox);
  const versions: PlanVersion[] = [];
  let mission: Mission | undefined;
  let vessel: VesselUpdate | undefined;
  // Track and fuel over mission time: stored reports and live updates merged.
  const series = new ShipSeries();
  let timedTrack = false;  // the map's track is drawn from `series`
  let feedbackCursor = "0";
  let storedReports = 0;
  let history: Promise<void> = Promise.resolve();
  let firstLiveS: number | undefined;  // mission time of the first live update
  (window as unknown as Record<string, unknown>).seaplanMap = map;  // for tests and the benchmark
  (window as unknown as Record<string, unknown>).seaplanHistory = {  // for tests
    series, storedReports: () => storedReports, cursor: () => feedbackCursor,
    firstLiveS: () => firstLiveS };

  const redrawFuel = () => {
    const points = series.fuel();
    fuelBox.replaceChildren(fuelChart(points, mission?.spec?.replanPolicy?.fuelThresholdFraction || 0.3));
    const [first, last] = [points[0], points[points.length - 1]];
    fuelCaption.textContent = first
      ? `${missionTime(first[0])} ${percent(first[1])} → ${missionTime(last[0])} ${percent(last[1])}` +
        ` (${points.length} samples, ${storedReports} from stored reports)`
      : "no report yet";
  };
  // Reports stored after the cursor: before the page opened, while a broken
  // watch was reconnecting (its live picture resends only the latest), and
  // each one as it arrives (every report is logged in the same transaction,
  // so its log event on the watch says there is one to fetch). Requests that
  // come while one is queued join it.
  let historyQueued = false;
  const fetchHistory = () => {
    if (historyQueued) return;
    historyQueued = true;
    history = history.then(async () => {
      historyQueued = false;
      try {
        feedbackCursor = await loadFeedback(missionId, feedbackCursor, (reports: StoredFeedback[]) => {
          let positions = 0;
          for (const r of reports) {
            if (!r.feedback?.state) continue;
            const sample = sampleOf(r.feedback.missionTimeS, r.feedback.state);
            if (series.add(sample) !== "duplicate") storedReports++;
            if (sample.position) positions++;
          }
          if (positions || timedTrack) {
            timedTrack = true;
            map.setTrack(series.track());
          }
          redrawFuel();
        });
      } catch (e) {
        actionStatus.textContent = `Cannot load the track and fuel history: ${(e as Error).message}`;
      }
    });
  };

  const redrawPlan = () => {
    const current = versions[versions.length - 1];
    versionLabel.textContent = current ? `version ${current.version}: ${current.reason}` : "no plan yet";
    if (current) map.setRoutes(current.tasks);
    map.fitOnce();
    const done = new Set(mission?.completedTasks ?? []);
    const now = vessel?.missionTimeS;
    const running = new Set(current?.tasks.filter((t) => !done.has(t.taskId) && now !== undefined &&
      t.startS <= now && now < t.startS + t.durationS).map((t) => t.taskId));
    renderGantt(gantt, versions, { nowS: now, completedTaskIds: done, runningTaskIds: running });
  };
  const redrawShip = () => {
    if (!vessel) return;
    const s = vessel.state;
    shipPanel.replaceChildren(
      ...[["Position", s.position ? `${s.position.latitudeDeg.toFixed(5)}°N ${s.position.longitudeDeg.toFixed(5)}°E` : "-"],
          ["Heading", degrees(s.headingDeg)], ["Speed", speed(s.speedMps)],
          ["Machinery mode", shortMode(s.mode)], ["Fuel", percent(s.fuelFraction)],
          ["Mission time", missionTime(vessel.missionTimeS)]]
        .flatMap(([k, v]) => [h("dt", { text: k }), h("dd", { text: v })]));
    clock.textContent = `${missionTime(vessel.missionTimeS)} · ${utc(new Date().toISOString())}`;
    trafficBody.replaceChildren(...vessel.targets.map((t) => {
      const lat0 = ((s.position?.latitudeDeg ?? 0) * Math.PI) / 180;
      const east = ((t.position.longitudeDeg - (s.position?.longitudeDeg ?? 0)) * Math.PI / 180) * 6371000 * Math.cos(lat0);
      const north = ((t.position.latitudeDeg - (s.position?.latitudeDeg ?? 0)) * Math.PI / 180) * 6371000;
      const hs = ((s.headingDeg ?? 0) * Math.PI) / 180;
      const ht = (t.courseDeg * Math.PI) / 180;
      const c = cpa(east, north, t.speedMps * Math.sin(ht) - (s.speedMps ?? 0) * Math.sin(hs),
                    t.speedMps * Math.cos(ht) - (s.speedMps ?? 0) * Math.cos(hs));
      return h("tr", {}, h("th", { scope: "row", text: `${t.targetId} (${t.kind})` }),
               h("td", { text: degrees(t.courseDeg) }), h("td", { text: speed(t.speedMps) }),
               h("td", { text: distance(c.dcpaM) }), h("td", { text: `${Math.round(c.tcpaS)} s` }));
    }));
  };

  const watch = new MissionWatch(missionId, (e) => {
    if (e.planVersion) {
      versions.push(e.planVersion);
      redrawPlan();
    }
    if (e.log) {
      if (e.log.source !== "server") fetchHistory();  // a vessel's report was stored
      log.prepend(h("li", { "data-event": e.log.eventId },
        h("time", { datetime: e.log.time ?? "", text: `${missionTime(e.log.missionTimeS)} · ${utc(e.log.time)}` }),
        h("span", { class: "source", text: e.log.source }), h("span", { text: e.log.message })));
    }
    if (e.mission) {
      mission = e.mission;
      stateBadge.textContent = shortState(e.mission.state);
      stateBadge.className = `badge ${shortState(e.mission.state)}`;
    }
    if (e.vessel) {
      const sample = sampleOf(e.vessel.missionTimeS, e.vessel.state);
      firstLiveS ??= sample.missionTimeS;
      const added = series.add(sample);
      if (timedTrack) {
        if (added === "append" && sample.position) map.appendTrack(sample.position);
        else if (added === "insert") map.setTrack(series.track());
      } else if (e.vessel.track?.length) {
        // No stored report yet: the positions this server has seen, untimed.
        map.setTrack([...e.vessel.track, e.vessel.state.position!]);
      } else if (sample.position) {
        map.appendTrack(sample.position);
      }
      vessel = e.vessel;
      map.setShip(e.vessel.state);
      map.setTraffic(e.vessel.targets ?? []);
      redrawShip();
      redrawFuel();
      redrawPlan();
    }
  }, (s) => { link.textContent = `stream: ${s}`; }, fetchHistory);

  void (async () => {
    try {
      mission = await call<Mission>("MissionService/GetMission", { missionId });
      title.textContent = `Mission ${mission.spec?.name ?? ""} (${missionId})`;
      stateBadge.textContent = shortState(mission.state);
      stateBadge.className = `badge ${shortState(mission.state)}`;
      map.setLocations(mission.spec?.locations ?? []);
      map.fitOnce();
      if (mission.spec?.chartId) {
        // Obstacles at the ship's draft when the chart was loaded for
        // shallower water than the ship needs; else the stored ones.
        const chart = await call<{ chart: { minimumDepthM: number } }>(
          "ChartService/GetChart", { chartId: mission.spec.chartId });
        const draft = mission.spec.ship?.draftM ?? 0;
        const obstacles = await call<{ geojson: string }>("ChartService/GetObstacles", {
          chartId: mission.spec.chartId,
          minimumDepthM: draft > chart.chart.minimumDepthM ? draft : 0,
        });
        map.setObstacles(obstacles.geojson);
      }
    } catch (e) {
      actionStatus.textContent = `Cannot load the mission: ${(e as Error).message}`;
    }
  })();
  (window as unknown as Record<string, unknown>).seaplanWatch = watch;  // for tests
  void watch.run();

  replan.addEventListener("click", async () => {
    actionStatus.textContent = "Replanning…";
    try {
      const r = await call<{ version: PlanVersion }>("MissionService/RequestReplan",
                                                     { missionId, reason: reason.value });
      actionStatus.textContent = `Version ${r.version?.version} planned.`;
    } catch (e) {
      actionStatus.textContent = `Replan refused: ${(e as Error).message}`;
    }
  });
  cancel.addEventListener("click", async () => {
    if (!window.confirm("Cancel this mission?")) return;
    try {
      await call<Mission>("MissionService/CancelMission", { missionId, reason: reason.value });
      actionStatus.textContent = "Cancelled.";
    } catch (e) {
      actionStatus.textContent = `Cancel refused: ${(e as Error).message}`;
    }
  });
  return () => {
    watch.stop();
    map.dispose();
  };
}

// Fuel over mission time. The fraction axis spans the data to the next
// tenth (a 2 % burn over an hour would be a flat line on 0-100 %), labelled
// at both ends, with the replan threshold dashed when it falls inside.
function fuelChart(points: [number, number][], thresholdFraction: number): SVGElement {
  const w = 260, hgt = 60, left = 30;
  const ns = "http://www.w3.org/2000/svg";
  const svg = document.createElementNS(ns, "svg");
  svg.setAttribute("viewBox", `0 0 ${w} ${hgt}`);
  svg.setAttribute("role", "img");
  const last = points[points.length - 1];
  svg.setAttribute("aria-label", last ? `Fuel ${percent(last[1])} at ${missionTime(last[0])}` : "No fuel data yet");
  if (points.length < 2) return svg;
  const fractions = points.map(([, f]) => f);
  const lo = Math.max(0, Math.floor(Math.min(...fractions) * 10 - 1e-9) / 10);
  const hi = Math.min(1, Math.max(lo + 0.1, Math.ceil(Math.max(...fractions) * 10 - 1e-9) / 10));
  const t0 = points[0][0], t1 = Math.max(t0 + 1, last[0]);
  const x = (t: number) => left + ((t - t0) / (t1 - t0)) * (w - left - 2);
  const y = (f: number) => 2 + (1 - (f - lo) / (hi - lo)) * (hgt - 4);
  const el = (name: string, attrs: Record<string, string | number>, text?: string) => {
    const e = document.createElementNS(ns, name);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
    if (text) e.textContent = text;
    svg.append(e);
  };
  el("text", { x: 2, y: 10, class: "fuel-axis" }, percent(hi));
  el("text", { x: 2, y: hgt - 2, class: "fuel-axis" }, percent(lo));
  if (thresholdFraction > lo && thresholdFraction < hi) {
    el("line", { x1: left, x2: w, y1: y(thresholdFraction), y2: y(thresholdFraction), class: "fuel-threshold" });
  }
  el("polyline", { points: points.map(([t, f]) => `${x(t).toFixed(1)},${y(f).toFixed(1)}`).join(" "),
                   class: "fuel-line" });
  return svg;
}
