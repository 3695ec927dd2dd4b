// Shared by the browser tests and the render benchmark: a seaplan-server on
// free loopback ports with the console, and Debian's Chromium driven by
// playwright-core (no browser download). The server writes its admin token
// to its data folder at the first start: startServer returns it (and sets
// SEAPLAN_TOKEN_FILE, so the clients a test starts present it), and
// signIn() signs the console in with it.
import { spawn } from "node:child_process";
import { existsSync, mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { chromium } from "playwright-core";

export { requireFile, skipOrFail } from "./prereq.mjs";

export const CHROMIUM = process.env.CHROMIUM_PATH || "/usr/bin/chromium";

export async function startServer({ serverBin, consoleDir }) {
  const dir = mkdtempSync(join(tmpdir(), "seaplan-console-"));
  const portFile = join(dir, "ports");
  const child = spawn(serverBin, ["--grpc-addr", "127.0.0.1:0", "--http-addr", "127.0.0.1:0",
                                  "--data-dir", join(dir, "data"), "--port-file", portFile,
                                  "--console-dir", consoleDir, "--log-level", "warn"],
                      { stdio: ["ignore", "inherit", "inherit"] });
  let exited = false;
  child.on("exit", () => { exited = true; });
  for (let i = 0; i < 300; i++) {
    if (existsSync(portFile)) {
      const text = readFileSync(portFile, "utf8");
      const grpc = /grpc=(\d+)/.exec(text);
      const http = /http=(\d+)/.exec(text);
      if (grpc && http) {
        const adminTokenFile = join(dir, "data", "admin.token");
        process.env.SEAPLAN_TOKEN_FILE = adminTokenFile;
        return {
          dir, grpcAddress: `127.0.0.1:${grpc[1]}`, url: `http://127.0.0.1:${http[1]}/`,
          adminTokenFile, adminToken: readFileSync(adminTokenFile, "utf8").trim(),
          async stop() {
            if (!exited) {
              child.kill("SIGTERM");
              await new Promise((r) => { if (exited) r(); else child.on("exit", r); });
            }
            rmSync(dir, { recursive: true, force: true });
          },
        };
      }
    }
    if (exited) throw new Error("seaplan-server exited before listening");
    await new Promise((r) => setTimeout(r, 100));
  }
  child.kill("SIGKILL");
  throw new Error("seaplan-server did not write its port file in 30 s");
}

// Signs the console in through its form with the server's admin token; the
// session cookie then serves every page of the browser context.
export async function signIn(page, server) {
  await page.goto(server.url);
  await page.waitForSelector("#sign-in #token");
  await page.fill("#token", server.adminToken);
  await page.click("#sign-in button[type=submit]");
  await page.waitForSelector("#sign-out:not([hidden])");
}

export async function launchBrowser() {
  const userDataDir = mkdtempSync(join(tmpdir(), "seaplan-chromium-"));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    // axe-core is injected as a script; the console itself runs under its CSP elsewhere.
    bypassCSP: process.env.SEAPLAN_BYPASS_CSP === "1",
    viewport: { width: 1400, height: 1000 },
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
  return {
    context,
    async close() {
      await context.close();
      rmSync(userDataDir, { recursive: true, force: true });
    },
  };
}

// Reads a scenario file (examples/scenarios/*.scenario): "key = value" lines.
export function readScenario(path) {
  const out = { locations: [], portOperations: [], path };
  for (const raw of readFileSync(path, "utf8").split("\n")) {
    const line = raw.replace(/#.*/, "").trim();
    const m = /^([\w.]+)\s*=\s*(.*)$/.exec(line);
    if (!m) continue;
    const [, key, value] = m;
    if (key === "location") out.locations.push(value);
    else if (key === "port_operation") out.portOperations.push(value);
    else out[key] = value;
  }
  return out;
}

// Distinct colours in a PNG (decoded by the browser): a blank picture has one.
export async function distinctColours(page, png) {
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement("canvas");
    c.width = img.width;
    c.height = img.height;
    const g = c.getContext("2d");
    g.drawImage(img, 0, 0);
    const data = g.getImageData(0, 0, c.width, c.height).data;
    const seen = new Set();
    for (let i = 0; i < data.length; i += 4 * 7) seen.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
    return seen.size;
  }, png.toString("base64"));
}
