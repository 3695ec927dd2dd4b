// seaplan operator console: a hash-routed single page over the server's
// HTTP/JSON API (same origin; nothing loaded from elsewhere).
import "ol/ol.css";
import "./styles.css";
import { SIGNED_OUT_EVENT, ApiError, currentSession, resumeSession, signIn, signOut } from "./api";
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
const who = h("span", { id: "signed-in-as", class: "who" });
const signOutButton = h("button", { id: "sign-out", type: "button", text: "Sign out", hidden: "" });
const links: [string, string][] = [["#/missions", "Missions"], ["#/new", "New mission"],
                                   ["#/charts", "Charts"], ["#/workbench", "Workbench"]];
const nav = h("nav", { "aria-label": "Views" },
  ...links.map(([href, text]) => h("a", { href, text, "data-view": href })));
document.body.append(
  h("a", { href: "#main", class: "skip", text: "Skip to content" }),
  h("header", { class: "top" }, h("span", { class: "brand", text: "seaplan" }), nav,
    h("div", { class: "spacer" }), who, signOutButton, palette, utcClock),
  main);

const saved = localStorage.getItem("seaplan.palette") as Palette | null;
palette.value = saved ?? "day";
applyPalette(palette.value as Palette);
palette.addEventListener("change", () => applyPalette(palette.value as Palette));
const tick = () => { utcClock.textContent = `${new Date().toISOString().slice(11, 19)} UTC`; };
tick();
window.setInterval(tick, 1000);

// Sign-in: a token (the admin token the server wrote at its first start,
// or one an admin created), exchanged once for the session cookie.
function signInView(message = ""): void {
  teardown();
  teardown = () => undefined;
  who.textContent = "";
  signOutButton.hidden = true;
  const input = h("input", { id: "token", type: "password", autocomplete: "off", required: "",
                             spellcheck: "false" }) as HTMLInputElement;
  const error = h("p", { id: "sign-in-error", role: "alert", text: message });
  const form = h("form", { id: "sign-in", class: "sign-in" },
    h("h1", { text: "Sign in" }),
    h("p", { text: "Paste an API token (seaplan_…). The first admin token is in admin.token in the " +
                   "server's data folder." }),
    h("label", { for: "token", text: "Token" }), input,
    h("button", { type: "submit", text: "Sign in" }), error) as HTMLFormElement;
  form.addEventListener("submit", (event) => {
    event.preventDefault();
    signIn(input.value.trim()).then(() => { input.value = ""; signedIn(); }, (err: unknown) => {
      error.textContent = err instanceof ApiError ? err.body.message : String(err);
    });
  });
  main.replaceChildren(form);
  document.title = "seaplan · sign in";
  input.focus();
}

function signedIn(): void {
  const s = currentSession();
  if (!s) { signInView(); return; }
  who.textContent = `${s.role}${s.vesselId ? ` ${s.vesselId}` : ""} · ${s.tokenId}`;
  signOutButton.hidden = false;
  route();
}

signOutButton.addEventListener("click", () => {
  signOut().finally(() => signInView());
});
window.addEventListener(SIGNED_OUT_EVENT, () => signInView("The session has ended: sign in again."));

let teardown: () => void = () => undefined;
function route(): void {
  if (!currentSession()) { signInView(); return; }
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
resumeSession().then(signedIn, () => signInView());
