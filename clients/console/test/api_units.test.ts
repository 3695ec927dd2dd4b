// Unit tests of the console's logic that needs no browser: the watch's
// resume (no gap, no duplicate across a broken stream) and the maritime
// units. Run by test/run.mjs (esbuild bundles, node:test runs).
import assert from "node:assert/strict";
import { test } from "node:test";
import { MissionWatch, type MissionEvent } from "../src/api";
import { cpa, distance, missionTime, speed } from "../src/units";

function ndjson(lines: unknown[], breakAfter?: number): ReadableStream<Uint8Array> {
  const enc = new TextEncoder();
  let i = 0;
  return new ReadableStream({
    pull(controller) {
      if (breakAfter !== undefined && i === breakAfter) {
        controller.error(new TypeError("network error"));
        return;
      }
      if (i >= lines.length) {
        controller.close();
        return;
      }
      controller.enqueue(enc.encode(`${JSON.stringify(lines[i++])}\n`));
    },
  });
}

test("MissionWatch resumes after the last version and event it delivered", async () => {
  const v1 = { planVersion: { version: 1, reason: "initial plan", tasks: [] } };
  const v2 = { planVersion: { version: 2, reason: "fuel 28% <= 30%", tasks: [] } };
  const log = (id: number) => ({ log: { eventId: String(id), message: `e${id}` } });
  const done = { mission: { state: "MISSION_STATE_COMPLETED" } };
  const requests: { afterVersion: number; afterEventId: string }[] = [];
  const responses = [
    // First stream breaks after three messages.
    () => ndjson([v1, log(1), log(2), log(3)], 3),
    // The server resends from where the request said (here it also repeats
    // one of each, which must not be delivered twice).
    () => ndjson([v1, log(2), log(3), v2, log(4), done]),
  ];
  (globalThis as { fetch: unknown }).fetch = async (_url: string, init: { body: string }) => {
    requests.push(JSON.parse(init.body));
    const body = responses[requests.length - 1]();
    return new Response(body, { status: 200, headers: { "Content-Type": "application/x-ndjson" } });
  };
  const got: MissionEvent[] = [];
  const statuses: string[] = [];
  const watch = new MissionWatch("m-1", (e) => got.push(e), (s) => statuses.push(s));
  await watch.run();
  assert.equal(requests.length, 2);
  assert.deepEqual([requests[0].afterVersion, requests[0].afterEventId], [0, "0"]);
  assert.deepEqual([requests[1].afterVersion, requests[1].afterEventId], [1, "2"]);
  const versions = got.filter((e) => e.planVersion).map((e) => e.planVersion!.version);
  const events = got.filter((e) => e.log).map((e) => Number(e.log!.eventId));
  assert.deepEqual(versions, [1, 2]);
  assert.deepEqual(events, [1, 2, 3, 4]);
  assert.equal(got[got.length - 1].mission?.state, "MISSION_STATE_COMPLETED");
  assert.equal(watch.reconnects, 1);
  assert.equal(statuses[statuses.length - 1], "ended");
});

test("MissionWatch stops on a client error instead of retrying", async () => {
  let calls = 0;
  (globalThis as { fetch: unknown }).fetch = async () => {
    calls++;
    return new Response(JSON.stringify({ code: "NOT_FOUND", message: "mission m-x not found" }), { status: 404 });
  };
  const statuses: string[] = [];
  await new MissionWatch("m-x", () => undefined, (s) => statuses.push(s)).run();
  assert.equal(calls, 1);
  assert.match(statuses[statuses.length - 1], /^error: NOT_FOUND: mission m-x not found/);
});

test("units: knots and nautical miles beside SI, mission time", () => {
  assert.equal(speed(1852 / 3600 * 10), "10.0 kn (5.1 m/s)");
  assert.equal(distance(1852), "1.00 NM (1.85 km)");
  assert.equal(distance(500), "0.27 NM (500 m)");
  assert.equal(missionTime(3725), "T+1:02:05");
});

test("cpa: head-on, crossing behind and diverging", () => {
  // Target 1000 m north closing at 10 m/s: meets in 100 s at 0 m.
  let c = cpa(0, 1000, 0, -10);
  assert.equal(Math.round(c.tcpaS), 100);
  assert.equal(Math.round(c.dcpaM), 0);
  // Passing 300 m east, closing from the north.
  c = cpa(300, 1000, 0, -10);
  assert.equal(Math.round(c.dcpaM), 300);
  // Moving away: the closest point is now.
  c = cpa(0, 1000, 0, 5);
  assert.equal(c.tcpaS, 0);
  assert.equal(Math.round(c.dcpaM), 1000);
});
