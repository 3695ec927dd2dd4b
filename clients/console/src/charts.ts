// Charts: upload (S-57 cell with updates, zipped FileGDB / shapefiles,
// GeoJSON) with progress and the server's errors, list, a preview of the
// obstacles at a chosen minimum depth, and (admins only) deletion.
import { ApiError, call, currentSession, headers, type ApiErrorBody, type Chart } from "./api";
import { field, fileToBase64, h } from "./dom";
import { ChartMap } from "./map";
import { utc } from "./units";

// XMLHttpRequest, not fetch: it reports upload progress.
function post(method: string, body: string, onProgress: (fraction: number) => void): Promise<unknown> {
  return new Promise((resolve, reject) => {
    const xhr = new XMLHttpRequest();
    xhr.open("POST", `/v1/${method}`);
    for (const [name, value] of Object.entries(headers())) xhr.setRequestHeader(name, value);
    xhr.upload.onprogress = (e) => { if (e.lengthComputable) onProgress(e.loaded / e.total); };
    xhr.onerror = () => reject(new Error("network error"));
    xhr.onload = () => {
      let parsed: unknown;
      try { parsed = JSON.parse(xhr.responseText); } catch { parsed = { code: `HTTP ${xhr.status}`, message: xhr.responseText }; }
      if (xhr.status >= 200 && xhr.status < 300) resolve(parsed);
      else reject(new ApiError(xhr.status, parsed as ApiErrorBody));
    };
    xhr.send(body);
  });
}

export function chartsView(root: HTMLElement): () => void {
  const name = h("input", { id: "c-name", required: true });
  const files = h("input", { id: "c-files", type: "file", multiple: true,
                             accept: ".000,.001,.002,.003,.zip,.geojson,.json" });
  const format = h("select", { id: "c-format" },
    ...[["CHART_FORMAT_UNSPECIFIED", "detect"], ["CHART_FORMAT_S57", "S-57"],
        ["CHART_FORMAT_GEOJSON", "GeoJSON"], ["CHART_FORMAT_ZIP", "zip (FileGDB / shapefiles)"]]
      .map(([v, t]) => h("option", { value: v, text: t })));
  const depth = h("input", { id: "c-depth", type: "number", step: "any", value: "10" });
  const buffer = h("input", { id: "c-buffer", type: "number", step: "any", value: "10" });
  const progress = h("progress", { id: "c-progress", max: 1, value: 0, "aria-label": "Upload progress" });
  const message = h("p", { id: "c-message", class: "status", role: "status" });
  const upload = h("button", { type: "submit", id: "c-upload", text: "Upload chart" });
  const body = h("tbody", { id: "charts-body" });
  const previewDepth = h("input", { id: "p-depth", type: "number", step: "any", value: "" });
  const previewChart = h("select", { id: "p-chart" });
  const previewButton = h("button", { type: "button", id: "p-show", text: "Show obstacles" });
  const previewStatus = h("p", { class: "status", role: "status", id: "p-status" });
  const mapBox = h("div", { class: "map small", id: "preview-map" });
  // Only admins may delete (the server checks too); others see no button.
  const admin = currentSession()?.role === "admin";
  const listStatus = h("p", { id: "charts-status", class: "status", role: "status" });
  const form = h("form", { "aria-labelledby": "upload-title", class: "upload" },
    h("h2", { id: "upload-title", text: "Upload" }), field("Name", name), field("Files", files),
    field("Format", format), field("Minimum depth (m)", depth, "shallower water is an obstacle"),
    field("Safety buffer (m)", buffer), upload, progress, message);
  root.append(h("section", { "aria-labelledby": "charts-title" },
    h("h1", { id: "charts-title", text: "Charts" }), form,
    h("h2", { text: "Stored charts" }),
    h("table", { class: "grid", "aria-label": "Charts" }, h("thead", {}, h("tr", {},
      ...["Name", "Id", "Format", "Min depth", "Obstacles", "Uploaded", ...(admin ? ["Delete"] : [])]
        .map((t) => h("th", { scope: "col", text: t })))), body),
    listStatus,
    h("h2", { text: "Preview" }),
    h("div", { class: "toolbar" }, field("Chart", previewChart),
      field("Minimum depth (m)", previewDepth, "empty: the chart's own"), previewButton, previewStatus),
    mapBox));
  const map = new ChartMap(mapBox);
  (window as unknown as Record<string, unknown>).seaplanMap = map;  // for the render benchmark

  const load = async () => {
    const r = await call<{ charts: Chart[] }>("ChartService/ListCharts", { pageSize: 200 });
    const charts = r.charts ?? [];
    body.replaceChildren(...charts.map((c) => h("tr", {},
      h("td", { text: c.name }), h("td", { text: c.chartId }), h("td", { text: c.format.replace("CHART_FORMAT_", "") }),
      h("td", { text: `${c.minimumDepthM} m` }), h("td", { text: String(c.summary?.obstacleCount ?? 0) }),
      h("td", { text: utc(c.createdAt) }),
      admin ? h("td", {}, deleteButton(c)) : null)));
    const selected = previewChart.value;
    previewChart.replaceChildren(...charts.map((c) => h("option", { value: c.chartId, text: c.name })));
    if (selected) previewChart.value = selected;
  };
  // The server refuses (412, naming them) while unfinished missions use the chart.
  const deleteButton = (c: Chart) => {
    const button = h("button", { type: "button", class: "delete-chart", "data-chart-id": c.chartId,
                                 text: "Delete", "aria-label": `Delete chart ${c.name} (${c.chartId})` });
    button.addEventListener("click", async () => {
      if (!window.confirm(`Delete chart ${c.name} (${c.chartId})? This cannot be undone.`)) return;
      button.disabled = true;
      try {
        await call("ChartService/DeleteChart", { chartId: c.chartId });
        await load();
        listStatus.textContent = `Deleted ${c.name} (${c.chartId}).`;
      } catch (e) {
        listStatus.textContent = `Delete refused: ${(e as Error).message}`;
        button.disabled = false;
      }
    });
    return button;
  };
  void load().catch((e) => { message.textContent = `Cannot list charts: ${(e as Error).message}`; });

  form.addEventListener("submit", async (ev) => {
    ev.preventDefault();
    const list = Array.from(files.files ?? []);
    if (!name.value || !list.length) {
      message.textContent = "A chart needs a name and at least one file.";
      return;
    }
    upload.disabled = true;
    message.textContent = "Uploading…";
    try {
      const request = {
        name: name.value, format: format.value, minimumDepthM: Number(depth.value),
        safetyBufferM: Number(buffer.value),
        files: await Promise.all(list.map(async (f) => ({ name: f.name, content: await fileToBase64(f) }))),
      };
      const r = await post("ChartService/UploadChart", JSON.stringify(request), (f) => {
        progress.value = f;
        if (f >= 1) message.textContent = "Loading the chart on the server…";
      }) as { chart: Chart; warnings?: string[] };
      message.textContent = `Stored ${r.chart.name} (${r.chart.chartId}): ${r.chart.summary?.obstacleCount ?? 0} obstacles` +
        (r.warnings?.length ? `; warnings: ${r.warnings.join("; ")}` : "");
      await load();
      previewChart.value = r.chart.chartId;
    } catch (e) {
      message.textContent = `Upload failed: ${(e as Error).message}`;
    } finally {
      upload.disabled = false;
    }
  });
  previewButton.addEventListener("click", async () => {
    previewStatus.textContent = "Loading…";
    try {
      const r = await call<{ geojson: string; obstacleCount: number; minimumDepthM: number }>(
        "ChartService/GetObstacles", { chartId: previewChart.value, minimumDepthM: Number(previewDepth.value) || 0 });
      map.setObstacles(r.geojson);
      map.fitOnce(true);
      previewStatus.textContent = `${r.obstacleCount} obstacles at ${r.minimumDepthM} m`;
    } catch (e) {
      previewStatus.textContent = `Cannot load obstacles: ${(e as Error).message}`;
    }
  });
  return () => map.dispose();
}
