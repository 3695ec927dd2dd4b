// seaplan operator console: a hash-routed single page over the server's
// HTTP/JSON API (same origin; nothing loaded from elsewhere).
import "ol/ol.css";
import "./styles.css";
import { chartsView } from "./charts";
import { h } from "./dom";
import { missionView } from "./mission";
import { missionsView, newMissionView } from "./missions";
import { workbenchView } from "./workbench";

type Palette = "day" | "dusk" | "night";

function applyPalette(p: Palette): void {
  document.documentElement.dataset.palette = p;
  localStorage.setItem("seaplan.palette", p);
  window.dispatchEvent(new Event("seaplan-palette"));
}

const main = h("main", { id: "main", tabindex: "-1" });
const palette = h("select", { id: "palette", "aria-label": "Palette" },
  ...(["day", "dusk", "night"] as Palette[]).map((p) => h("option", { value: p, text: p })));
const utcClock = h("time", { id: "utc-clock", class: "clock" });
const links: [string, string][] = [["#/missions", "Missions"], ["#/new", "New mission"],
                                   ["#/charts", "Charts"], ["#/workbench", "Workbench"]];
const nav = h("nav", { "aria-label": "Views" },
  ...links.map(([href, text]) => h("a", { href, text, "data-view": href })));
document.body.append(
  h("a", { href: "#main", class: "skip", text: "Skip to content" }),
  h("header", { class: "top" }, h("span", { class: "brand", text: "seaplan" }), nav,
    h("div", { class: "spacer" }), palette, utcClock),
  main);

const saved = localStorage.getItem("seaplan.palette") as Palette | null;
palette.value = saved ?? "day";
applyPalette(palette.value as Palette);
palette.addEventListener("change", () => applyPalette(palette.value as Palette));
const tick = () => { utcClock.textContent = `${new Date().toISOString().slice(11, 19)} UTC`; };
tick();
window.setInterval(tick, 1000);

let teardown: () => void = () => undefined;
function route(): void {
  teardown();
  main.replaceChildren();
  const hash = location.hash || "#/missions";
  for (const a of nav.querySelectorAll("a")) {
    if (hash.startsWith(a.getAttribute("data-view") ?? "-")) a.setAttribute("aria-current", "page");
    else a.removeAttribute("aria-current");
  }
  const mission = /^#\/mission\/([\w-]+)/.exec(hash);
  if (mission) teardown = missionView(main, mission[1]);
  else if (hash.startsWith("#/new")) teardown = newMissionView(main);
  else if (hash.startsWith("#/charts")) teardown = chartsView(main);
  else if (hash.startsWith("#/workbench")) teardown = workbenchView(main);
  else teardown = missionsView(main);
  document.title = `seaplan · ${main.querySelector("h1")?.textContent ?? "console"}`;
}
window.addEventListener("hashchange", route);
route();
