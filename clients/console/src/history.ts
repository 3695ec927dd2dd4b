// The ship's track and fuel over mission time, from two sources: the stored
// feedback reports (ListFeedback: everything before the page opened, and
// whatever a broken watch missed) and the live vessel updates on the watch.
// Both carry the ship's state at a mission time; a series keeps one sample
// per mission time, in time order, so overlapping sources neither leave a
// hole nor draw a point twice.
import { call, type LatLon, type ShipState } from "./api";

export interface ShipSample {
  missionTimeS: number;
  position?: LatLon;
  fuelFraction: number;
}

export interface StoredFeedback {
  sequence: string;  // int64 as a JSON string: the paging cursor
  vesselId?: string;
  sequenceNumber?: string;
  receivedAt?: string;
  feedback?: { kind?: string; taskId?: string; planVersion?: number; missionTimeS?: number;
               state?: ShipState; detail?: string };
}

interface ListFeedbackResponse { feedback?: StoredFeedback[]; nextAfterSequence?: string; }

// Samples closer than this in mission time are the same instant.
const SAME_TIME_S = 1e-6;

export class ShipSeries {
  private readonly samples: ShipSample[] = [];

  get length(): number { return this.samples.length; }
  get all(): readonly ShipSample[] { return this.samples; }

  // Adds `s` at its mission time. Returns "append" when it is the newest,
  // "insert" when it went before the end, "duplicate" when a sample of that
  // time is already held (nothing changes).
  add(s: ShipSample): "append" | "insert" | "duplicate" {
    const n = this.samples.length;
    if (n === 0 || s.missionTimeS > this.samples[n - 1].missionTimeS + SAME_TIME_S) {
      this.samples.push(s);
      return "append";
    }
    let lo = 0, hi = n;  // first sample not earlier than s
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (this.samples[mid].missionTimeS < s.missionTimeS - SAME_TIME_S) lo = mid + 1;
      else hi = mid;
    }
    if (lo < n && Math.abs(this.samples[lo].missionTimeS - s.missionTimeS) <= SAME_TIME_S) {
      return "duplicate";
    }
    this.samples.splice(lo, 0, s);
    return "insert";
  }

  track(): LatLon[] {
    return this.samples.flatMap((s) => (s.position ? [s.position] : []));
  }

  fuel(): [number, number][] {
    return this.samples.map((s) => [s.missionTimeS, s.fuelFraction]);
  }
}

export function sampleOf(missionTimeS: number | undefined, state: ShipState | undefined): ShipSample {
  // Protobuf JSON leaves zero values out.
  return { missionTimeS: missionTimeS ?? 0, position: state?.position,
           fuelFraction: state?.fuelFraction ?? 0 };
}

// Feedback reports of a mission after `afterSequence`, page by page until
// the last; `onPage` gets each page as it arrives. Resolves with the last
// report's sequence (the cursor for what arrives later).
export async function loadFeedback(missionId: string, afterSequence: string,
                                   onPage: (reports: StoredFeedback[]) => void,
                                   pageSize = 1000): Promise<string> {
  let after = afterSequence;
  for (;;) {
    const page = await call<ListFeedbackResponse>("MissionService/ListFeedback",
                                                  { missionId, afterSequence: after, pageSize });
    const reports = page.feedback ?? [];
    if (reports.length) {
      onPage(reports);
      after = reports[reports.length - 1].sequence;
    }
    const next = page.nextAfterSequence ?? "0";
    if (next === "0" || reports.length === 0) return after;
  }
}
