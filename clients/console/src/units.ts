// Maritime units beside SI, and mission time beside UTC.
export const MPS_PER_KNOT = 1852 / 3600;
export const M_PER_NM = 1852;

export function speed(mps: number | undefined): string {
  const v = mps ?? 0;
  return `${(v / MPS_PER_KNOT).toFixed(1)} kn (${v.toFixed(1)} m/s)`;
}

export function distance(m: number | undefined): string {
  const v = m ?? 0;
  return `${(v / M_PER_NM).toFixed(2)} NM (${v >= 1000 ? `${(v / 1000).toFixed(2)} km` : `${v.toFixed(0)} m`})`;
}

export function missionTime(s: number | undefined): string {
  const v = Math.max(0, s ?? 0);
  const h = Math.floor(v / 3600);
  const m = Math.floor((v % 3600) / 60);
  const sec = Math.floor(v % 60);
  return `T+${h}:${String(m).padStart(2, "0")}:${String(sec).padStart(2, "0")}`;
}

export function utc(iso: string | undefined): string {
  if (!iso) return "-";
  const d = new Date(iso);
  if (Number.isNaN(d.getTime())) return "-";
  return `${d.toISOString().slice(0, 19).replace("T", " ")} UTC`;
}

export function degrees(deg: number | undefined): string {
  return `${String(Math.round(((deg ?? 0) % 360 + 360) % 360)).padStart(3, "0")}°`;
}

export function percent(fraction: number | undefined): string {
  return `${Math.round((fraction ?? 0) * 100)}%`;
}

export function shortState(state: string | undefined): string {
  return (state ?? "").replace(/^MISSION_STATE_/, "").toLowerCase();
}

export function shortMode(mode: string | undefined): string {
  return (mode ?? "").replace(/^MSO_MODE_/, "") || "-";
}

// Closest point of approach of two vessels on straight courses (east/north
// metres and m/s relative to the own ship): distance (m) and time (s).
export function cpa(relEastM: number, relNorthM: number, relVe: number, relVn: number):
    { dcpaM: number; tcpaS: number } {
  const v2 = relVe * relVe + relVn * relVn;
  const t = v2 < 1e-9 ? 0 : Math.max(0, -(relEastM * relVe + relNorthM * relVn) / v2);
  const e = relEastM + relVe * t;
  const n = relNorthM + relVn * t;
  return { dcpaM: Math.hypot(e, n), tcpaS: t };
}
