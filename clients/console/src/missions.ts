// Missions: the list (filter by state) and the create form, which shows the
// server's PDDL diagnostics at their line and column.
import { ApiError, call, type Chart, type Diagnostic, type Mission, type MissionSpec,
         type NamedLocation } from "./api";
import { field, h, readFileText } from "./dom";
import { shortState, utc } from "./units";

const STATES = ["", "MISSION_STATE_PLANNING", "MISSION_STATE_ACTIVE", "MISSION_STATE_REPLANNING",
                "MISSION_STATE_COMPLETED", "MISSION_STATE_FAILED", "MISSION_STATE_CANCELLED"];

export function missionsView(root: HTMLElement): () => void {
  const filter = h("select", { id: "mission-filter" },
                   ...STATES.map((s) => h("option", { value: s, text: s ? shortState(s) : "all" })));
  const body = h("tbody");
  const status = h("p", { class: "status", role: "status" });
  root.append(h("section", { "aria-labelledby": "missions-title" },
    h("div", { class: "toolbar" }, h("h1", { id: "missions-title", text: "Missions" }),
      field("State", filter), h("a", { href: "#/new", class: "button", text: "New mission" })),
    h("table", { class: "grid", "aria-label": "Missions" },
      h("thead", {}, h("tr", {}, ...["Mission", "State", "Vessel", "Version", "Last update"]
        .map((t) => h("th", { scope: "col", text: t })))), body),
    status));
  let timer = 0;
  const load = async () => {
    try {
      const res = await call<{ missions: Mission[] }>("MissionService/ListMissions",
        { pageSize: 200, state: filter.value || undefined });
      const missions = (res.missions ?? []).slice().reverse();
      body.replaceChildren(...missions.map((m) => h("tr", { "data-state": m.state },
        h("td", {}, h("a", { href: `#/mission/${m.missionId}`, text: m.spec?.name || m.missionId })),
        h("td", {}, h("span", { class: `badge ${shortState(m.state)}`, text: shortState(m.state) })),
        h("td", { text: m.spec?.vesselId ?? "" }),
        h("td", { text: String(m.currentVersion ?? 0) }),
        h("td", { text: utc(m.updatedAt) }))));
      status.textContent = missions.length ? "" : "No missions.";
    } catch (e) {
      status.textContent = `Cannot list missions: ${(e as Error).message}`;
    }
  };
  filter.addEventListener("change", load);
  void load();
  timer = window.setInterval(load, 3000);
  return () => window.clearInterval(timer);
}

// "(at ship0 port-a)" in the problem: where the ship starts.
function shipLocation(problem: string, ship: string): string | undefined {
  const m = new RegExp(`\\(\\s*at\\s+${ship.replace(/[^\w-]/g, "")}\\s+([\\w-]+)\\s*\\)`, "i").exec(problem);
  return m?.[1];
}

export function parseLocations(text: string): NamedLocation[] {
  const out: NamedLocation[] = [];
  text.split("\n").forEach((line, i) => {
    const t = line.replace(/#.*/, "").trim();
    if (!t) return;
    const parts = t.split(/[\s,]+/);
    const lat = Number(parts[1]);
    const lon = Number(parts[2]);
    if (parts.length !== 3 || !Number.isFinite(lat) || !Number.isFinite(lon)) {
      throw new Error(`locations line ${i + 1}: expected "name latitude longitude", got "${t}"`);
    }
    out.push({ name: parts[0], position: { latitudeDeg: lat, longitudeDeg: lon } });
  });
  return out;
}

function pddlEditor(name: string, label: string): { box: HTMLElement; text: HTMLTextAreaElement;
                                                    file: HTMLInputElement; gutter: HTMLElement } {
  const text = h("textarea", { id: `${name}-text`, rows: 14, spellcheck: "false", class: "code",
                               "aria-describedby": `${name}-diags` });
  const file = h("input", { id: `${name}-file`, type: "file", accept: ".pddl,.txt" });
  file.addEventListener("change", async () => {
    const t = await readFileText(file);
    if (t !== undefined) text.value = t;
  });
  const gutter = h("ul", { id: `${name}-diags`, class: "diagnostics", "aria-live": "polite" });
  const box = h("fieldset", { class: "pddl" }, h("legend", { text: label }),
                field(`${label} file`, file), field(`${label} text`, text), gutter);
  return { box, text, file, gutter };
}

// Lists diagnostics under their editor; each one selects its line and
// column in the text.
export function showDiagnostics(diags: Diagnostic[],
                                editors: Record<string, { text: HTMLTextAreaElement; gutter: HTMLElement }>,
                                fallback: HTMLElement): void {
  for (const ed of Object.values(editors)) {
    ed.gutter.replaceChildren();
    ed.text.removeAttribute("aria-invalid");
  }
  for (const d of diags) {
    const ed = editors[d.file ?? ""] ?? undefined;
    const where = `${d.file ?? "?"}:${d.line ?? 0}:${d.column ?? 0}`;
    const text = `${where}: ${d.message ?? ""}${d.symbol ? ` ('${d.symbol}')` : ""}` +
                 `${d.expected ? `; expected ${d.expected}` : ""}`;
    const button = h("button", { type: "button", class: "diag", text });
    const item = h("li", { class: `diag-${(d.severity ?? "ERROR").toLowerCase()}` }, button);
    if (ed) {
      ed.text.setAttribute("aria-invalid", "true");
      button.addEventListener("click", () => selectLineColumn(ed.text, d.line ?? 1, d.column ?? 1));
      ed.gutter.append(item);
      if (ed.gutter.children.length === 1) selectLineColumn(ed.text, d.line ?? 1, d.column ?? 1, false);
    } else {
      fallback.append(item);
    }
  }
}

export function selectLineColumn(area: HTMLTextAreaElement, line: number, column: number,
                                 focus = true): void {
  const lines = area.value.split("\n");
  let offset = 0;
  for (let i = 0; i < Math.min(line - 1, lines.length); i++) offset += lines[i].length + 1;
  const lineText = lines[Math.max(0, line - 1)] ?? "";
  const start = offset + Math.max(0, Math.min(column - 1, lineText.length));
  const tokenEnd = /^[^\s()]*/.exec(lineText.slice(start - offset))?.[0].length ?? 0;
  if (focus) area.focus();
  area.setSelectionRange(start, start + Math.max(1, tokenEnd));
  const lineHeight = parseFloat(getComputedStyle(area).lineHeight) || 16;
  area.scrollTop = Math.max(0, (line - 3) * lineHeight);
}

export function newMissionView(root: HTMLElement): () => void {
  const num = (id: string, value: string, step = "any") =>
    h("input", { id, type: "number", step, value, inputmode: "decimal" });
  const name = h("input", { id: "m-name", value: "", required: true, autocomplete: "off" });
  const vessel = h("input", { id: "m-vessel", value: "mass-1" });
  const shipObject = h("input", { id: "m-ship-object", value: "" });
  const domain = pddlEditor("domain", "Domain");
  const problem = pddlEditor("problem", "Problem");
  const chart = h("select", { id: "m-chart" }, h("option", { value: "", text: "(none: straight legs)" }));
  const locations = h("textarea", { id: "m-locations", rows: 5, class: "code", spellcheck: "false",
                                    placeholder: "port-a 63.441795 10.327122" });
  const speed = num("m-speed", "9");
  const draft = num("m-draft", "5");
  const heading = num("m-heading", "0");
  const fuel = num("m-fuel", "1");
  const fuelThreshold = num("m-fuel-threshold", "0.3");
  const deviation = num("m-deviation", "200");
  const delay = num("m-delay", "120");
  const timeLimit = num("m-time-limit", "10");
  const windSpeed = num("m-wind-speed", "0");
  const windFrom = num("m-wind-from", "0");
  const currentSpeed = num("m-current-speed", "0");
  const currentFrom = num("m-current-from", "0");
  const portOps = h("textarea", { id: "m-port-ops", rows: 4, class: "code", spellcheck: "false",
                                  placeholder: "load-cont 60" });
  const errors = h("ul", { class: "diagnostics", id: "m-errors", role: "alert" });
  const submit = h("button", { type: "submit", id: "m-submit", text: "Create mission" });
  const form = h("form", { class: "mission-form", "aria-labelledby": "new-title", novalidate: true },
    h("h1", { id: "new-title", text: "New mission" }),
    h("div", { class: "cols" },
      h("fieldset", {}, h("legend", { text: "Mission" }), field("Name", name), field("Vessel id", vessel),
        field("Ship object in the problem", shipObject, "default: the first ship"),
        field("Chart", chart), field("Named locations", locations, "one per line: name latitude longitude")),
      h("fieldset", {}, h("legend", { text: "Ship" }),
        field("Service speed (m/s)", speed, "9 m/s = 17.5 kn"), field("Draft (m)", draft),
        field("Initial heading (°)", heading), field("Initial fuel (0..1)", fuel),
        field("Wind speed (m/s)", windSpeed), field("Wind from (°)", windFrom),
        field("Current speed (m/s)", currentSpeed), field("Current from (°)", currentFrom),
        field("Port operations", portOps, "one per line: action duration_s")),
      h("fieldset", {}, h("legend", { text: "Replan policy" }),
        field("Fuel threshold (fraction)", fuelThreshold), field("Position deviation (m)", deviation),
        field("Delay tolerance (s)", delay), field("Planner time limit (s)", timeLimit))),
    h("div", { class: "cols" }, domain.box, problem.box),
    errors, submit);
  root.append(form);
  const editors = { domain, problem };
  void call<{ charts: Chart[] }>("ChartService/ListCharts", { pageSize: 200 }).then((r) => {
    for (const c of r.charts ?? []) chart.append(h("option", { value: c.chartId, text: `${c.name} (${c.chartId})` }));
  }).catch(() => undefined);

  form.addEventListener("submit", async (ev) => {
    ev.preventDefault();
    errors.replaceChildren();
    showDiagnostics([], editors, errors);
    let spec: MissionSpec;
    try {
      const locs = parseLocations(locations.value);
      const ops = portOps.value.split("\n").map((l) => l.trim()).filter(Boolean).map((l, i) => {
        const [action, d] = l.split(/\s+/);
        if (!action || !Number.isFinite(Number(d))) throw new Error(`port operations line ${i + 1}: expected "action duration_s"`);
        return { action, durationS: Number(d) };
      });
      const startName = shipLocation(problem.text.value, shipObject.value || "ship0");
      const start = locs.find((l) => l.name === startName)?.position;
      spec = {
        name: name.value || "mission", domain: domain.text.value, problem: problem.text.value,
        chartId: chart.value || undefined, locations: locs, vesselId: vessel.value || undefined,
        shipObject: shipObject.value || undefined,
        ship: { name: vessel.value, draftM: Number(draft.value), serviceSpeedMps: Number(speed.value) },
        initialState: { position: start, headingDeg: Number(heading.value),
                        fuelFraction: Number(fuel.value), mode: "MSO_MODE_PTO" },
        replanPolicy: { fuelThresholdFraction: Number(fuelThreshold.value),
                        positionDeviationM: Number(deviation.value), delayToleranceS: Number(delay.value) },
        plannerOptions: { timeLimit: `${Number(timeLimit.value)}s` },
        portOperations: ops,
        environment: {
          windSpeedMps: Number(windSpeed.value), windFromDeg: Number(windFrom.value),
          currentSpeedMps: Number(currentSpeed.value), currentFromDeg: Number(currentFrom.value) },
      };
    } catch (e) {
      errors.append(h("li", { text: (e as Error).message }));
      return;
    }
    submit.disabled = true;
    submit.textContent = "Planning…";
    try {
      const m = await call<Mission>("MissionService/CreateMission", { spec });
      location.hash = `#/mission/${m.missionId}`;
    } catch (e) {
      if (e instanceof ApiError) {
        errors.append(h("li", { text: e.message }));
        showDiagnostics(e.diagnostics, editors, errors);
      } else {
        errors.append(h("li", { text: `Cannot reach the server: ${(e as Error).message}` }));
      }
    } finally {
      submit.disabled = false;
      submit.textContent = "Create mission";
    }
  });
  return () => undefined;
}
