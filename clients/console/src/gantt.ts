// Plan versions as a Gantt chart (SVG): one block per version headed by its
// replan reason, one row per task on a shared mission-time axis. Tasks new
// in a version (not in the one before) are marked; the task under way is
// outlined.
import type { PlanVersion, Task } from "./api";
import { missionTime } from "./units";

const SVG = "http://www.w3.org/2000/svg";
const KIND_COLOURS: Record<string, string> = {
  KIND_MOVE: "#4a90d9", KIND_LOAD: "#7bc043", KIND_UNLOAD: "#f6a623",
  KIND_REPAIR: "#d0021b", KIND_REFUEL: "#9b59b6",
};

function el<K extends keyof SVGElementTagNameMap>(name: K, attrs: Record<string, string | number>,
                                                   text?: string): SVGElementTagNameMap[K] {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

export function taskLabel(t: Task): string {
  const a = t.action;
  return a ? `(${[a.name ?? "", ...(a.arguments ?? [])].join(" ")})` : t.taskId;
}

export interface GanttOptions {
  nowS?: number;             // mission time now (a vertical line)
  runningTaskIds?: Set<string>;
  completedTaskIds?: Set<string>;
}

export function renderGantt(container: HTMLElement, versions: PlanVersion[],
                            options: GanttOptions = {}): void {
  container.replaceChildren();
  if (!versions.length) {
    container.textContent = "No plan yet.";
    return;
  }
  const left = 300, right = 16, rowH = 18, width = Math.max(640, container.clientWidth || 900);
  let end = 1;
  let rows = 0;
  for (const v of versions) {
    rows += v.tasks.length + 1;
    for (const t of v.tasks) end = Math.max(end, (t.startS ?? 0) + (t.durationS ?? 0));
  }
  const scale = (width - left - right) / end;
  const height = rows * rowH + 40;
  const svg = el("svg", { width, height, viewBox: `0 0 ${width} ${height}`, role: "img",
                          "aria-label": `Gantt chart of ${versions.length} plan versions`,
                          class: "gantt-svg" });
  let y = 6;
  let previous = new Set<string>();
  for (const v of versions) {
    const g = el("g", { class: "gantt-version", "data-version": v.version });
    const names = new Set(v.tasks.map(taskLabel));
    // What changed against the version before: tasks added and dropped.
    let change = "";
    if (v.version > 1 && previous.size) {
      const added = [...names].filter((n) => !previous.has(n)).length;
      const dropped = [...previous].filter((n) => !names.has(n)).length;
      change = ` (${added} task${added === 1 ? "" : "s"} new, ${dropped} dropped)`;
    }
    g.append(el("text", { x: 4, y: y + 13, class: "gantt-head" },
                `version ${v.version}: ${v.reason}${change}`));
    y += rowH;
    for (const t of v.tasks) {
      const label = taskLabel(t);
      const isNew = v.version > 1 && !previous.has(label);
      g.append(el("text", { x: 12, y: y + 13, class: "gantt-task" }, `${isNew ? "+ " : ""}${label}`));
      const bar = el("rect", {
        x: left + (t.startS ?? 0) * scale, y: y + 3, width: Math.max(2, (t.durationS ?? 0) * scale),
        height: rowH - 6, rx: 2, fill: KIND_COLOURS[t.kind] ?? "#999",
        class: options.runningTaskIds?.has(t.taskId) ? "gantt-bar running" :
               options.completedTaskIds?.has(t.taskId) ? "gantt-bar done" : "gantt-bar",
      });
      bar.append(el("title", {}, `${label}\nstart ${missionTime(t.startS)}, ${Math.round(t.durationS ?? 0)} s`));
      g.append(bar);
      y += rowH;
    }
    previous = names;
    svg.append(g);
  }
  const step = Math.max(60, Math.round(end / 8 / 60) * 60);
  for (let t = 0; t <= end; t += step) {
    svg.append(el("line", { x1: left + t * scale, x2: left + t * scale, y1: 0, y2: y, class: "gantt-grid" }));
    svg.append(el("text", { x: left + t * scale + 2, y: y + 14, class: "gantt-axis" }, missionTime(t)));
  }
  if (options.nowS !== undefined) {
    svg.append(el("line", { x1: left + options.nowS * scale, x2: left + options.nowS * scale, y1: 0,
                            y2: y, class: "gantt-now" }));
  }
  container.append(svg);
}
