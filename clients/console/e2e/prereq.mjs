// Prerequisite checks without dependencies (run before playwright-core is
// imported, so a missing node_modules is reported, not a stack trace).
import { existsSync } from "node:fs";

// Exit code ctest reads as "skipped" (SKIP_RETURN_CODE 77); under CI a
// missing prerequisite fails instead.
export function skipOrFail(reason) {
  if (process.env.CI) {
    console.error(`FAIL: ${reason} (CI is set: prerequisites must be present)`);
    process.exit(1);
  }
  console.log(`SKIP: ${reason}`);
  process.exit(77);
}

export function requireFile(path, what) {
  if (!path || !existsSync(path)) skipOrFail(`${what} not found (${path || "unset"})`);
}
