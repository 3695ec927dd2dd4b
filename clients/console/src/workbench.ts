// Planning workbench: a domain and problem in, the plan streamed as it
// improves (PlanStream) and drawn as a Gantt chart, and a plan validated
// with the reason it fails.
import { ApiError, call, stream, type Task } from "./api";
import { field, h, readFileText } from "./dom";
import { renderGantt } from "./gantt";
import { showDiagnostics } from "./missions";

interface TimedAction { startS: number; durationS: number; name: string; arguments?: string[]; }
interface PlanResponse { status: string; plan?: TimedAction[]; makespanS?: number; planText?: string; message?: string; }
interface PlanStreamEvent { progress?: { elapsedS: number }; improvedPlan?: PlanResponse; finalResult?: PlanResponse; }

// The Gantt colour of a plain PDDL action, from its name as the mission
// engine reads it.
function kindOf(action: string): string {
  for (const [prefix, kind] of [["move", "KIND_MOVE"], ["unload", "KIND_UNLOAD"], ["load", "KIND_LOAD"],
                                ["repair", "KIND_REPAIR"], ["refuel", "KIND_REFUEL"]]) {
    if (action.startsWith(prefix)) return kind;
  }
  return "KIND_OTHER";
}

function editor(id: string, label: string, rows = 12) {
  const text = h("textarea", { id: `${id}-text`, rows, class: "code", spellcheck: "false" });
  const file = h("input", { id: `${id}-file`, type: "file" });
  file.addEventListener("change", async () => { const t = await readFileText(file); if (t !== undefined) text.value = t; });
  const gutter = h("ul", { class: "diagnostics", id: `${id}-diags`, "aria-live": "polite" });
  return { box: h("fieldset", {}, h("legend", { text: label }), field(`${label} file`, file), field(`${label} text`, text), gutter), text, gutter };
}

export function workbenchView(root: HTMLElement): () => void {
  const domain = editor("wb-domain", "Domain");
  const problem = editor("wb-problem", "Problem");
  const plan = editor("wb-plan", "Plan", 8);
  const limit = h("input", { id: "wb-limit", type: "number", value: "10", step: "any" });
  const planButton = h("button", { type: "button", id: "wb-run", text: "Plan (streamed)" });
  const stopButton = h("button", { type: "button", id: "wb-stop", text: "Stop", disabled: true });
  const validateButton = h("button", { type: "button", id: "wb-validate", text: "Validate plan" });
  const status = h("p", { class: "status", role: "status", id: "wb-status" });
  const improvements = h("ol", { id: "wb-improvements" });
  const gantt = h("div", { class: "gantt", id: "wb-gantt", tabindex: 0, role: "region", "aria-label": "Plan" });
  const errors = h("ul", { class: "diagnostics", role: "alert" });
  root.append(h("section", { "aria-labelledby": "wb-title" }, h("h1", { id: "wb-title", text: "Planning workbench" }),
    h("div", { class: "cols" }, domain.box, problem.box),
    h("div", { class: "toolbar" }, field("Time limit (s)", limit), planButton, stopButton, status),
    errors, h("h2", { text: "Improvements" }), improvements, h("h2", { text: "Plan" }), gantt,
    plan.box, validateButton));
  const editors = { domain, problem, plan };
  let abort: AbortController | undefined;

  const show = (r: PlanResponse) => {
    const tasks: Task[] = (r.plan ?? []).map((a, i) => ({
      taskId: `a${i}`, kind: kindOf(a.name), startS: a.startS,
      durationS: a.durationS, action: { name: a.name, arguments: a.arguments ?? [] } }));
    renderGantt(gantt, [{ missionId: "", version: 1, reason: `${r.status}, makespan ${(r.makespanS ?? 0).toFixed(1)} s`,
                          makespanS: r.makespanS ?? 0, tasks, missionTimeOriginS: 0 }]);
    if (r.planText) plan.text.value = r.planText;
  };
  planButton.addEventListener("click", async () => {
    errors.replaceChildren();
    showDiagnostics([], editors, errors);
    improvements.replaceChildren();
    abort = new AbortController();
    planButton.disabled = true;
    stopButton.disabled = false;
    status.textContent = "Planning…";
    try {
      await stream<PlanStreamEvent>("PlanningService/PlanStream", {
        domain: domain.text.value, problem: problem.text.value, options: { timeLimit: `${Number(limit.value)}s` },
      }, (e) => {
        if (e.progress) status.textContent = `Planning… ${e.progress.elapsedS.toFixed(1)} s`;
        if (e.improvedPlan) {
          improvements.append(h("li", { text: `makespan ${(e.improvedPlan.makespanS ?? 0).toFixed(1)} s (${e.improvedPlan.plan?.length ?? 0} actions)` }));
          show(e.improvedPlan);
        }
        if (e.finalResult) {
          status.textContent = `${e.finalResult.status}${e.finalResult.message ? `: ${e.finalResult.message}` : ""}`;
          if (e.finalResult.plan?.length) show(e.finalResult);
        }
      }, abort.signal);
    } catch (e) {
      if (e instanceof ApiError) { errors.append(h("li", { text: e.message })); showDiagnostics(e.diagnostics, editors, errors); }
      else if ((e as Error).name !== "AbortError") errors.append(h("li", { text: (e as Error).message }));
      status.textContent = "Stopped.";
    } finally {
      planButton.disabled = false;
      stopButton.disabled = true;
    }
  });
  stopButton.addEventListener("click", () => abort?.abort());
  validateButton.addEventListener("click", async () => {
    errors.replaceChildren();
    showDiagnostics([], editors, errors);
    try {
      const r = await call<{ valid: boolean; makespanS: number; actionCount: number;
                             firstFailure?: { timeS: number; action: string; condition: string; reason: string } }>(
        "PlanningService/Validate", { domain: domain.text.value, problem: problem.text.value, plan: plan.text.value });
      status.textContent = r.valid ? `Valid: ${r.actionCount} actions, makespan ${r.makespanS.toFixed(1)} s`
        : `Invalid at ${(r.firstFailure?.timeS ?? 0).toFixed(1)} s: ${r.firstFailure?.action ?? ""} ${r.firstFailure?.condition ?? ""} — ${r.firstFailure?.reason ?? ""}`;
    } catch (e) {
      if (e instanceof ApiError) { errors.append(h("li", { text: e.message })); showDiagnostics(e.diagnostics, editors, errors); }
      else errors.append(h("li", { text: (e as Error).message }));
    }
  });
  return () => abort?.abort();
}
