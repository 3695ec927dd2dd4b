// The chart view: OpenLayers vector layers in Web Mercator, no tiles. Land
// and shallow water from the chart's obstacles, each move's route coloured
// by machinery mode (risk on hover), named locations, the ship with its
// heading and track, and the traffic it reports (CPA/TCPA on hover).
import Feature from "ol/Feature";
import Map from "ol/Map";
import Overlay from "ol/Overlay";
import View from "ol/View";
import { Control, ScaleLine, Zoom } from "ol/control";
import { extend as extendExtent, createEmpty, isEmpty, type Extent } from "ol/extent";
import GeoJSON from "ol/format/GeoJSON";
import { LineString, Point } from "ol/geom";
import VectorLayer from "ol/layer/Vector";
import { fromLonLat, toLonLat } from "ol/proj";
import VectorSource from "ol/source/Vector";
import { Circle, Fill, Icon, RegularShape, Stroke, Style, Text } from "ol/style";
import type { LatLon, NamedLocation, ShipState, Task, TrackedTarget } from "./api";
import { cpa, degrees, distance, missionTime, percent, shortMode, speed } from "./units";

// Route colours per MSO mode: CSS variables of the palette (dimmed at
// night), with the day values as fallbacks.
const MODE_VARS: Record<string, [string, string]> = {
  PTO: ["--pto", "#2f7fd8"], MEC: ["--mec", "#1fa37a"], PTI: ["--pti", "#e08a1e"],
  "-": ["--muted", "#888888"],
};

function css(name: string, fallback: string): string {
  const v = getComputedStyle(document.documentElement).getPropertyValue(name).trim();
  return v || fallback;
}

function xy(p: LatLon): number[] {
  return fromLonLat([p.longitudeDeg, p.latitudeDeg]);
}

function escapeHtml(s: string): string {
  return s.replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);
}

// A hull outline pointing up (bow at the top), rotated to the heading.
function shipIcon(fill: string, outline: string): string {
  const svg = `<svg xmlns="http://www.w3.org/2000/svg" width="16" height="30" viewBox="0 0 16 30">
    <path d="M8 1 C12 6 14 11 14 16 L14 28 L2 28 L2 16 C2 11 4 6 8 1 Z" fill="${fill}"
          stroke="${outline}" stroke-width="1.5"/></svg>`;
  return `data:image/svg+xml;utf8,${encodeURIComponent(svg)}`;
}

class NorthArrow extends Control {
  constructor() {
    const el = document.createElement("div");
    el.className = "north-arrow ol-unselectable ol-control";
    el.setAttribute("role", "img");
    el.setAttribute("aria-label", "North is up");
    el.innerHTML = `<svg viewBox="0 0 24 36" width="24" height="36" aria-hidden="true">
      <polygon points="12,2 19,24 12,19 5,24" fill="currentColor"/>
      <text x="12" y="34" text-anchor="middle" font-size="10" fill="currentColor">N</text></svg>`;
    super({ element: el });
  }
}

class Legend extends Control {
  constructor() {
    const el = document.createElement("div");
    el.className = "map-legend ol-unselectable ol-control";
    el.setAttribute("aria-label", "Legend");
    const swatch = (colour: string, label: string, dash = false) =>
      `<li><span class="swatch${dash ? " dash" : ""}" style="background:${colour}"></span>${label}</li>`;
    el.innerHTML = `<ul>
      ${swatch("var(--pto)", "route, PTO")}
      ${swatch("var(--mec)", "route, MEC")}
      ${swatch("var(--pti)", "route, PTI")}
      ${swatch("var(--track)", "ship track")}
      ${swatch("var(--land)", "land / shallower than the depth")}
      <li><span class="glyph ship">⬆</span>own ship (heading)</li>
      <li><span class="glyph target">◆</span>traffic</li></ul>`;
    super({ element: el });
  }
}

export class ChartMap {
  readonly map: Map;
  private readonly obstacles = new VectorSource();
  private readonly routes = new VectorSource();
  private readonly places = new VectorSource();
  private readonly traffic = new VectorSource();
  private readonly trackFeature = new Feature(new LineString([]));
  private readonly shipFeature = new Feature(new Point([0, 0]));
  private readonly tip: HTMLElement;
  private readonly tipOverlay: Overlay;
  private ship: ShipState | undefined;
  private fitted = false;
  // The layers whose features have a read-out on hover: hit detection
  // leaves out the chart's polygons and the track (thousands of vertices,
  // nothing to say), which made the first hover over a large chart take
  // 180 ms.
  private readonly hoverLayers: Set<unknown>;

  constructor(target: HTMLElement) {
    this.shipFeature.set("kind", "ship");
    this.trackFeature.set("kind", "track");
    this.tip = document.createElement("div");
    this.tip.className = "map-tip";
    this.tip.setAttribute("role", "tooltip");
    this.tipOverlay = new Overlay({ element: this.tip, offset: [12, 12], stopEvent: false });
    this.map = new Map({
      target,
      // The focusable chart element itself takes the arrow keys and +/-.
      keyboardEventTarget: target,
      controls: [new Zoom(), new ScaleLine({ units: "nautical", bar: false, minWidth: 90 }),
                 // OpenLayers names the bar's inner element after the class name
                 // ("ol-scale-bar-inner" lays the steps out in a row): keep its own.
                 new ScaleLine({ units: "metric", bar: true, steps: 2, text: false, minWidth: 140 }),
                 new NorthArrow(), new Legend()],
      layers: [
        new VectorLayer({ source: this.obstacles, style: () => this.obstacleStyle(),
                          properties: { name: "obstacles" } }),
        new VectorLayer({ source: this.routes, style: (f) => this.routeStyle(f as Feature),
                          properties: { name: "routes", hover: true } }),
        new VectorLayer({ source: this.places, style: (f) => this.placeStyle(f as Feature),
                          properties: { name: "locations", hover: true } }),
        new VectorLayer({ source: this.traffic, style: (f) => this.trafficStyle(f as Feature),
                          properties: { name: "traffic", hover: true } }),
        new VectorLayer({ source: new VectorSource({ features: [this.trackFeature] }),
                          style: () => this.trackStyle(), properties: { name: "track" } }),
        new VectorLayer({ source: new VectorSource({ features: [this.shipFeature] }),
                          style: () => this.shipStyle(), properties: { name: "ship", hover: true } }),
      ],
      overlays: [this.tipOverlay],
      // North-up: no rotation.
      view: new View({ center: fromLonLat([10.4, 63.44]), zoom: 11, enableRotation: false }),
    });
    this.hoverLayers = new Set(this.map.getAllLayers().filter((l) => l.get("hover")));
    // OpenLayers times canvas reads for 150 ms (3 x 50 ms) at the first hit
    // detection of the page, to choose how to read pixels: an operator's
    // first hover, or the first frames of a drag, would stall that long.
    // Done once the map has drawn, when the page is idle instead.
    this.map.once("rendercomplete", () => {
      const warm = () => this.map.forEachFeatureAtPixel([0, 0], () => true, {
        layerFilter: (l) => this.hoverLayers.has(l) });
      if ("requestIdleCallback" in window) window.requestIdleCallback(warm, { timeout: 2000 });
      else setTimeout(warm, 0);
    });
    // Styles read the palette's CSS variables: redraw when it changes.
    window.addEventListener("seaplan-palette", this.onPalette);
    target.setAttribute("tabindex", "0");
    target.setAttribute("role", "application");
    target.setAttribute("aria-label", "Chart: arrow keys pan, + and - zoom");
    this.map.on("pointermove", (e) => {
      if (e.dragging) return;
      const f = this.map.forEachFeatureAtPixel(e.pixel, (feature) => feature as Feature,
                                               { hitTolerance: 5,
                                                 layerFilter: (l) => this.hoverLayers.has(l) });
      const html = f ? this.describe(f) : "";
      if (!html) {
        this.tipOverlay.setPosition(undefined);
        return;
      }
      this.tip.innerHTML = html;
      this.tipOverlay.setPosition(e.coordinate);
    });
  }

  private readonly onPalette = () => {
    this.styles.clear();
    this.map.getAllLayers().forEach((l) => l.changed());
  };

  dispose(): void {
    window.removeEventListener("seaplan-palette", this.onPalette);
    this.map.setTarget(undefined);
  }

  setObstacles(geojson: string): void {
    this.obstacles.clear();
    const features = new GeoJSON().readFeatures(geojson, { featureProjection: "EPSG:3857" });
    this.obstacles.addFeatures(features as Feature[]);
  }

  obstacleCount(): number { return this.obstacles.getFeatures().length; }
  routeSegmentCount(): number { return this.routes.getFeatures().length; }
  trackPointCount(): number { return (this.trackFeature.getGeometry() as LineString).getCoordinates().length; }
  trackStart(): LatLon | undefined {
    const c = (this.trackFeature.getGeometry() as LineString).getFirstCoordinate();
    if (!c || c.length < 2) return undefined;
    const [lon, lat] = toLonLat(c);
    return { latitudeDeg: lat, longitudeDeg: lon };
  }

  setLocations(locations: NamedLocation[]): void {
    this.places.clear();
    for (const l of locations) {
      if (!l.position) continue;
      const f = new Feature(new Point(xy(l.position)));
      f.setProperties({ kind: "location", name: l.name });
      this.places.addFeature(f);
    }
  }

  // One feature per route leg (waypoint to waypoint), styled by its mode.
  setRoutes(tasks: Task[], current?: string): void {
    this.routes.clear();
    for (const task of tasks) {
      const wps = task.route?.waypoints ?? [];
      for (let i = 0; i + 1 < wps.length; i++) {
        const f = new Feature(new LineString([xy(wps[i].position), xy(wps[i + 1].position)]));
        f.setProperties({ kind: "route", task: task.taskId, current: task.taskId === current,
                          mode: shortMode(wps[i].mode), waypoint: wps[i], index: i,
                          from: task.fromLocation, to: task.toLocation });
        this.routes.addFeature(f);
      }
    }
  }

  setTrack(points: LatLon[]): void {
    (this.trackFeature.getGeometry() as LineString).setCoordinates(points.map(xy));
  }

  appendTrack(p: LatLon): void {
    (this.trackFeature.getGeometry() as LineString).appendCoordinate(xy(p));
  }

  setShip(state: ShipState | undefined): void {
    this.ship = state;
    if (state?.position) (this.shipFeature.getGeometry() as Point).setCoordinates(xy(state.position));
    this.shipFeature.changed();
  }

  setTraffic(targets: TrackedTarget[]): void {
    const seen = new Set<string>();
    for (const t of targets) {
      seen.add(t.targetId);
      let f = this.traffic.getFeatureById(t.targetId) as Feature | null;
      if (!f) {
        f = new Feature(new Point(xy(t.position)));
        f.setId(t.targetId);
        this.traffic.addFeature(f);
      }
      (f.getGeometry() as Point).setCoordinates(xy(t.position));
      f.setProperties({ kind: "target", target: t });
    }
    for (const f of this.traffic.getFeatures()) {
      if (!seen.has(String(f.getId()))) this.traffic.removeFeature(f);
    }
  }

  // Fits the view to what is drawn once (routes, else the chart), not again
  // while the operator pans.
  fitOnce(force = false): void {
    if (this.fitted && !force) return;
    const extent: Extent = createEmpty();
    for (const s of [this.routes, this.places]) {
      const e = s.getExtent();
      if (s.getFeatures().length && e) extendExtent(extent, e);
    }
    const chartExtent = this.obstacles.getExtent();
    if (isEmpty(extent) && this.obstacles.getFeatures().length && chartExtent) {
      extendExtent(extent, chartExtent);
    }
    if (isEmpty(extent)) return;
    this.map.getView().fit(extent, { padding: [40, 40, 40, 40], maxZoom: 16 });
    this.fitted = true;
  }

  // Styles are made once per palette and kept by what they show: a layer
  // asks for a feature's style every time it rebuilds its drawing (on zoom,
  // and on pans beyond the drawn margin; thousands of obstacle polygons),
  // and a new Style, or a CSS variable read through getComputedStyle
  // (which may force a style recalculation), per call was most of that.
  private readonly styles = new globalThis.Map<string, Style>();
  private cached(key: string, make: () => Style): Style {
    let style = this.styles.get(key);
    if (!style) {
      style = make();
      this.styles.set(key, style);
    }
    return style;
  }

  private obstacleStyle(): Style {
    return this.cached("land", () => new Style({
      fill: new Fill({ color: css("--land", "#c8b88a") }),
      stroke: new Stroke({ color: css("--land-edge", "#8a7a50"), width: 0.5 }) }));
  }

  private routeStyle(f: Feature): Style {
    const mode = MODE_VARS[f.get("mode") as string] ? (f.get("mode") as string) : "-";
    const current = !!f.get("current");
    return this.cached(`route ${mode} ${current}`, () => {
      const [name, fallback] = MODE_VARS[mode];
      return new Style({ stroke: new Stroke({ color: css(name, fallback), width: current ? 5 : 3 }) });
    });
  }

  private placeStyle(f: Feature): Style {
    const name = f.get("name") as string;
    return this.cached(`place ${name}`, () => new Style({
      image: new Circle({ radius: 5, fill: new Fill({ color: css("--fg", "#222") }) }),
      text: new Text({ text: name, offsetY: -14, font: "12px sans-serif",
                       fill: new Fill({ color: css("--fg", "#222") }),
                       stroke: new Stroke({ color: css("--bg", "#fff"), width: 3 }) }),
    }));
  }

  private trafficStyle(f: Feature): Style {
    const id = (f.get("target") as TrackedTarget).targetId;
    return this.cached(`target ${id}`, () => new Style({
      image: new RegularShape({ points: 4, radius: 7, fill: new Fill({ color: css("--target", "#c03") }),
                                stroke: new Stroke({ color: css("--bg", "#fff"), width: 1 }) }),
      text: new Text({ text: id, offsetY: -15, font: "11px sans-serif",
                       fill: new Fill({ color: css("--target", "#c03") }),
                       stroke: new Stroke({ color: css("--bg", "#fff"), width: 3 }) }),
    }));
  }

  private trackStyle(): Style {
    return this.cached("track", () => new Style({
      stroke: new Stroke({ color: css("--track", "#1f3a93"), width: 2, lineDash: [6, 4] }) }));
  }

  private shipStyle(): Style | undefined {
    if (!this.ship?.position) return undefined;
    // One icon per palette, turned to the heading (a new Icon would load its image again).
    const style = this.cached("ship", () => new Style({
      image: new Icon({ src: shipIcon(css("--ship", "#111"), css("--bg", "#fff")), rotateWithView: true }) }));
    style.getImage()?.setRotation(((this.ship.headingDeg ?? 0) * Math.PI) / 180);
    return style;
  }

  private describe(f: Feature): string {
    const kind = f.get("kind");
    if (kind === "route") {
      const w = f.get("waypoint") as RouteWaypoint;
      return `<b>${escapeHtml(String(f.get("from") ?? ""))} → ${escapeHtml(String(f.get("to") ?? ""))}</b>
        <br>leg ${Number(f.get("index")) + 1}, mode ${escapeHtml(shortMode(w.mode))}
        <br>time to grounding ${w.groundsWithinHorizon ? `${Math.round(w.timeToGroundingS)} s` : "beyond the horizon"}
        <br>P(grounding) ${(w.groundingProbability ?? 0).toExponential(2)}
        <br>expected cost ${(w.expectedGroundingCost ?? 0).toFixed(1)}
        <br>ETA ${missionTime(w.etaS)}, ${distance(w.distanceFromStartM)} from the start`;
    }
    if (kind === "target") {
      const t = f.get("target") as TrackedTarget;
      let line = "";
      if (this.ship?.position) {
        const [se, sn] = xy(this.ship.position);
        const [te, tn] = xy(t.position);
        const k = Math.cos((this.ship.position.latitudeDeg * Math.PI) / 180);  // Mercator scale
        const hs = ((this.ship.headingDeg ?? 0) * Math.PI) / 180;
        const ht = (t.courseDeg * Math.PI) / 180;
        const vs = this.ship.speedMps ?? 0;
        const c = cpa((te - se) * k, (tn - sn) * k, t.speedMps * Math.sin(ht) - vs * Math.sin(hs),
                      t.speedMps * Math.cos(ht) - vs * Math.cos(hs));
        line = `<br>CPA ${distance(c.dcpaM)} in ${Math.round(c.tcpaS)} s`;
      }
      return `<b>${escapeHtml(t.targetId)}</b> (${escapeHtml(t.kind)})
        <br>course ${degrees(t.courseDeg)}, ${speed(t.speedMps)}${line}`;
    }
    if (kind === "ship" && this.ship) {
      const [lon, lat] = toLonLat((f.getGeometry() as Point).getCoordinates());
      return `<b>own ship</b><br>${lat.toFixed(5)}°N ${lon.toFixed(5)}°E
        <br>heading ${degrees(this.ship.headingDeg)}, ${speed(this.ship.speedMps)}
        <br>mode ${escapeHtml(shortMode(this.ship.mode))}, fuel ${percent(this.ship.fuelFraction)}`;
    }
    if (kind === "location") return `<b>${escapeHtml(String(f.get("name")))}</b>`;
    return "";
  }
}

type RouteWaypoint = import("./api").RouteWaypoint;
