// The seaplan HTTP/JSON API: every RPC is POST /v1/<Service>/<Method> with the
// Protobuf JSON mapping; streams answer newline-delimited JSON.

export interface LatLon { latitudeDeg: number; longitudeDeg: number; }
export interface Diagnostic {
  severity?: string; kind?: string; file?: string; line?: number; column?: number;
  symbol?: string; message?: string; expected?: string;
}
export interface ShipState {
  position?: LatLon; headingDeg?: number; speedMps?: number; fuelFraction?: number;
  mode?: string; time?: string;
}
export interface RouteWaypoint {
  position: LatLon; mode: string; timeToGroundingS: number; groundsWithinHorizon: boolean;
  groundingProbability: number; expectedGroundingCost: number; fuelKg: number;
  distanceFromStartM: number; etaS: number;
}
export interface TimedAction { name?: string; arguments?: string[]; startS?: number; durationS?: number; }
export interface Task {
  taskId: string; kind: string; startS: number; durationS: number; action?: TimedAction;
  fromLocation?: string; toLocation?: string;
  route?: { waypoints: RouteWaypoint[]; lengthM?: number; maxGroundingProbability?: number };
}
export interface PlanVersion {
  missionId: string; version: number; reason: string; createdAt?: string; makespanS: number;
  tasks: Task[]; plannerStatus?: string; missionTimeOriginS: number;
}
export interface LogEvent {
  eventId: string; missionId: string; time?: string; missionTimeS: number; source: string;
  message: string;
}
export interface TrackedTarget {
  targetId: string; kind: string; position: LatLon; courseDeg: number; speedMps: number;
}
export interface VesselUpdate {
  missionId: string; vesselId: string; missionTimeS: number; state: ShipState;
  targets: TrackedTarget[]; track: LatLon[]; sequence: string;
}
export interface NamedLocation { name: string; position: LatLon; }
export interface MissionSpec {
  name?: string; domain?: string; problem?: string; chartId?: string;
  locations?: NamedLocation[]; vesselId?: string; shipObject?: string;
  ship?: { name?: string; draftM?: number; serviceSpeedMps?: number };
  initialState?: ShipState;
  replanPolicy?: { fuelThresholdFraction?: number; positionDeviationM?: number; delayToleranceS?: number };
  plannerOptions?: { timeLimit?: string };
  portOperations?: { action: string; durationS: number }[];
  environment?: { windSpeedMps?: number; windFromDeg?: number; currentSpeedMps?: number;
                  currentFromDeg?: number };
}
export interface Mission {
  missionId: string; spec: MissionSpec; state: string; currentVersion: number;
  createdAt?: string; updatedAt?: string; lastState?: ShipState; completedTasks?: string[];
  failureReason?: string;
}
export interface MissionEvent {
  planVersion?: PlanVersion; log?: LogEvent; mission?: Mission; vessel?: VesselUpdate;
  error?: ApiErrorBody;
}
export interface Chart {
  chartId: string; name: string; format: string; minimumDepthM: number; safetyBufferM: number;
  createdAt?: string;
  summary?: { obstacleCount?: number; southWest?: LatLon; northEast?: LatLon; frame?: string };
}
export interface ApiErrorBody {
  code: string; message: string; details?: { diagnostics?: Diagnostic[] }[];
}

export class ApiError extends Error {
  constructor(public readonly status: number, public readonly body: ApiErrorBody) {
    super(`${body.code}: ${body.message}`);
  }
  get diagnostics(): Diagnostic[] {
    return (this.body.details ?? []).flatMap((d) => d.diagnostics ?? []);
  }
}

async function errorOf(res: Response): Promise<ApiError> {
  const text = await res.text();
  try {
    return new ApiError(res.status, JSON.parse(text) as ApiErrorBody);
  } catch {
    return new ApiError(res.status, { code: `HTTP ${res.status}`, message: text });
  }
}

// The console's session: the server keeps the token behind an HttpOnly,
// SameSite=Strict cookie; every API call sends the session's CSRF token in a
// header, without which the server refuses the cookie (403).
export interface Session { csrfToken: string; tokenId: string; role: string; vesselId: string; }
let session: Session | null = null;

export function currentSession(): Session | null { return session; }

// Fired when the server no longer knows the caller (401): sign in again.
export const SIGNED_OUT_EVENT = "seaplan-signed-out";

// The headers of an API call: JSON, and the session's CSRF token (also for
// requests not made through call(), such as the chart upload's XHR).
export function headers(): Record<string, string> {
  const h: Record<string, string> = { "Content-Type": "application/json" };
  if (session) h["X-CSRF-Token"] = session.csrfToken;
  return h;
}

async function checked(res: Response): Promise<Response> {
  if (res.status === 401 && session) {
    session = null;
    window.dispatchEvent(new Event(SIGNED_OUT_EVENT));
  }
  if (!res.ok) throw await errorOf(res);
  return res;
}

// Resumes the session of the cookie (after a reload); null when signed out.
export async function resumeSession(): Promise<Session | null> {
  const res = await fetch("/auth/session", { cache: "no-store" });
  session = res.ok ? (await res.json()) as Session : null;
  return session;
}

export async function signIn(token: string): Promise<Session> {
  const res = await fetch("/auth/login", {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ token }),
  });
  if (!res.ok) throw await errorOf(res);
  session = (await res.json()) as Session;
  return session;
}

export async function signOut(): Promise<void> {
  const res = await fetch("/auth/logout", { method: "POST", headers: headers() });
  session = null;
  if (!res.ok) throw await errorOf(res);
}

export async function call<T>(method: string, request: unknown, signal?: AbortSignal): Promise<T> {
  const res = await checked(await fetch(`/v1/${method}`, {
    method: "POST",
    headers: headers(),
    body: JSON.stringify(request ?? {}),
    signal,
  }));
  return (await res.json()) as T;
}

// Reads an NDJSON stream, calling onMessage per line; resolves when the
// server ends the stream. A last {"error": ...} line rejects.
export async function stream<T>(method: string, request: unknown, onMessage: (m: T) => void,
                                signal?: AbortSignal): Promise<void> {
  const res = await checked(await fetch(`/v1/${method}`, {
    method: "POST",
    headers: headers(),
    body: JSON.stringify(request ?? {}),
    signal,
  }));
  if (!res.body) throw await errorOf(res);
  const reader = res.body.getReader();
  const decoder = new TextDecoder();
  let buffered = "";
  for (;;) {
    const { value, done } = await reader.read();
    if (value) buffered += decoder.decode(value, { stream: true });
    let newline: number;
    while ((newline = buffered.indexOf("\n")) >= 0) {
      const line = buffered.slice(0, newline).trim();
      buffered = buffered.slice(newline + 1);
      if (!line) continue;
      const message = JSON.parse(line) as T & { error?: ApiErrorBody };
      if (message.error) throw new ApiError(200, message.error);
      onMessage(message);
    }
    if (done) return;
  }
}

// WatchMission that reconnects after a broken stream and resumes after the
// last version and event id it delivered: no gap, no duplicate. `onConnected`
// runs at the first message of each stream (the server is then following
// the mission), e.g. to fetch what the live picture does not resend.
export class MissionWatch {
  private lastVersion = 0;
  private lastEventId = 0;
  private abort = new AbortController();
  private stopped = false;
  reconnects = 0;

  constructor(private readonly missionId: string,
              private readonly onEvent: (e: MissionEvent) => void,
              private readonly onStatus: (status: string) => void,
              private readonly onConnected?: () => void) {}

  async run(): Promise<void> {
    let backoffMs = 250;
    while (!this.stopped) {
      this.abort = new AbortController();
      try {
        this.onStatus(this.reconnects ? `live (resumed after version ${this.lastVersion}, event ${this.lastEventId})` : "live");
        let connected = false;
        await stream<MissionEvent>("MissionService/WatchMission", {
          missionId: this.missionId,
          afterVersion: this.lastVersion,
          afterEventId: String(this.lastEventId),
        }, (e) => {
          if (!connected) {
            connected = true;
            this.onConnected?.();
          }
          this.deliver(e);
        }, this.abort.signal);
        this.onStatus("ended");
        return;  // the mission reached a final state and everything was sent
      } catch (err) {
        if (this.stopped) return;
        if (err instanceof ApiError && err.status >= 400 && err.status < 500) {
          this.onStatus(`error: ${err.message}`);
          return;
        }
        this.reconnects++;
        this.onStatus(`reconnecting (${this.reconnects})`);
        await new Promise((r) => setTimeout(r, backoffMs));
        backoffMs = Math.min(backoffMs * 2, 5000);
      }
    }
  }

  private deliver(e: MissionEvent): void {
    if (e.planVersion) {
      if (e.planVersion.version <= this.lastVersion) return;
      this.lastVersion = e.planVersion.version;
    }
    if (e.log) {
      const id = Number(e.log.eventId);
      if (id <= this.lastEventId) return;
      this.lastEventId = id;
    }
    this.onEvent(e);
  }

  stop(): void {
    this.stopped = true;
    this.abort.abort();
  }

  // Breaks the connection as a network fault would (the watch resumes).
  dropConnection(): void {
    this.abort.abort();
  }
}
