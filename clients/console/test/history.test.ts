// The track and fuel history: stored reports and live updates merged by
// mission time (no duplicate, no hole), and ListFeedback paged to the end.
import assert from "node:assert/strict";
import { test } from "node:test";
import { loadFeedback, sampleOf, ShipSeries, type StoredFeedback } from "../src/history";

const at = (t: number, fuel: number) =>
  sampleOf(t, { position: { latitudeDeg: 63 + t / 1000, longitudeDeg: 10 }, fuelFraction: fuel });

test("ShipSeries merges stored reports into live updates by mission time, each time once", () => {
  const series = new ShipSeries();
  // Live updates arrive first (the page opened mid-mission)...
  assert.equal(series.add(at(95, 0.8)), "append");
  assert.equal(series.add(at(100, 0.79)), "append");
  // ...then the stored reports from the start, overlapping the live ones.
  const stored = [at(0, 0.9), at(30, 0.87), at(60, 0.84), at(90, 0.81), at(100, 0.79)];
  assert.deepEqual(stored.map((s) => series.add(s)),
                   ["insert", "insert", "insert", "insert", "duplicate"]);
  assert.equal(series.add(at(130, 0.76)), "append");
  assert.deepEqual(series.fuel().map(([t]) => t), [0, 30, 60, 90, 95, 100, 130]);
  assert.deepEqual(series.fuel()[0], [0, 0.9]);
  assert.equal(series.track().length, 7);
  assert.equal(series.track()[0].latitudeDeg, 63);
  // A report without a position still counts for fuel, not for the track.
  series.add(sampleOf(140, { fuelFraction: 0.75 }));
  assert.equal(series.fuel().length, 8);
  assert.equal(series.track().length, 7);
  // Protobuf JSON leaves zeros out: mission time 0 and an empty tank.
  assert.deepEqual(sampleOf(undefined, {}), { missionTimeS: 0, position: undefined, fuelFraction: 0 });
});

test("loadFeedback pages through ListFeedback and returns the last sequence", async () => {
  const report = (seq: number): StoredFeedback => ({
    sequence: String(seq), feedback: { missionTimeS: seq * 30, state: { fuelFraction: 1 - seq / 100 } } });
  const pages: Record<string, { feedback?: StoredFeedback[]; nextAfterSequence?: string }> = {
    "0": { feedback: [report(1), report(2)], nextAfterSequence: "2" },
    "2": { feedback: [report(3)] },  // the last page: no cursor (0 is left out)
    "3": {},
  };
  const requests: { missionId: string; afterSequence: string; pageSize: number }[] = [];
  (globalThis as { fetch: unknown }).fetch = async (url: string, init: { body: string }) => {
    assert.equal(url, "/v1/MissionService/ListFeedback");
    const req = JSON.parse(init.body);
    requests.push(req);
    return new Response(JSON.stringify(pages[req.afterSequence]), { status: 200 });
  };
  const got: string[] = [];
  const cursor = await loadFeedback("m-1", "0", (rs) => got.push(...rs.map((r) => r.sequence)), 2);
  assert.deepEqual(got, ["1", "2", "3"]);
  assert.equal(cursor, "3");
  assert.deepEqual(requests.map((r) => r.afterSequence), ["0", "2"]);
  assert.ok(requests.every((r) => r.missionId === "m-1" && r.pageSize === 2));
  // Later: only what arrived since; nothing new keeps the cursor.
  assert.equal(await loadFeedback("m-1", cursor, () => assert.fail("no page expected")), "3");
  // An error (unknown mission) rejects rather than looping.
  (globalThis as { fetch: unknown }).fetch = async () =>
    new Response(JSON.stringify({ code: "NOT_FOUND", message: "mission 'm-x' not found" }), { status: 404 });
  await assert.rejects(loadFeedback("m-x", "0", () => undefined), /NOT_FOUND/);
});
