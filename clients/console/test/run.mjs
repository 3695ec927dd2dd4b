// Bundles the unit tests with esbuild and runs them with node's test runner:
//   node test/run.mjs        (ctest: console_unit)
import { spawnSync } from "node:child_process";
import { mkdtempSync, readdirSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

import { requireFile } from "../e2e/prereq.mjs";

const here = dirname(fileURLToPath(import.meta.url));
requireFile(join(here, "../node_modules/esbuild/package.json"), "clients/console/node_modules (npm ci in clients/console)");
const { build } = await import("esbuild");
const out = mkdtempSync(join(tmpdir(), "seaplan-console-test-"));
const tests = readdirSync(here).filter((f) => f.endsWith(".test.ts"));
await build({
  entryPoints: tests.map((f) => join(here, f)),
  bundle: true, platform: "node", format: "esm", target: "node18", outdir: out,
  outExtension: { ".js": ".mjs" }, logLevel: "warning",
});
const files = readdirSync(out).map((f) => join(out, f));
const run = spawnSync(process.execPath, ["--test", ...files], { stdio: "inherit" });
rmSync(out, { recursive: true, force: true });
process.exit(run.status ?? 1);
