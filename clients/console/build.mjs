// Bundles the console into static files: index.html, app.js (with its source
// map), app.css. Output folder: $CONSOLE_OUT_DIR or dist/. Prints the sizes.
import { build } from "esbuild";
import { copyFileSync, mkdirSync, readdirSync, statSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const outdir = resolve(process.env.CONSOLE_OUT_DIR || join(here, "dist"));
mkdirSync(outdir, { recursive: true });
await build({
  entryPoints: { app: join(here, "src/main.ts") },
  bundle: true,
  minify: true,
  sourcemap: true,
  format: "esm",
  target: ["es2020"],
  outdir,
  logLevel: "warning",
  legalComments: "linked",
});
copyFileSync(join(here, "src/index.html"), join(outdir, "index.html"));
let total = 0;
for (const name of readdirSync(outdir)) {
  if (name.endsWith(".map")) continue;
  const size = statSync(join(outdir, name)).size;
  total += size;
  console.log(`${name.padEnd(24)} ${(size / 1024).toFixed(1).padStart(8)} KiB`);
}
console.log(`${"bundle total".padEnd(24)} ${(total / 1024).toFixed(1).padStart(8)} KiB -> ${outdir}`);
