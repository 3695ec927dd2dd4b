#!/usr/bin/env bash
# Seeded runs of the simulation scenarios against a real seaplan-server:
# starts the server on loopback (free ports, a temporary database), runs
# seaplan-sim on each scenario with seeds 1..RUNS (the traffic's timing
# shifted by up to +-60 s and the wind varied per seed, see
# clients/sim/core/scenario.h) and prints per scenario: runs completed, the
# smallest and largest minimum CPA per vessel, the runs with a CPA below the
# safety distance, the runs aground and the smallest land clearance, then
# the seed of each vessel's lowest CPA and of the smallest land clearance.
#
#   bench/colav/scenario_seeds.sh [--colav sbmpc|vo] [--runs N] [scenario ...]
# Default: sbmpc, 20 runs, every examples/scenarios/*.scenario (trondheim
# needs SEAPLAN_SHARED, default ../shared). Needs build/bin and jq. SIM_ARGS
# adds seaplan-sim flags (e.g. SIM_ARGS=--former-autopilot); REPORT_DIR keeps
# each run's report and log there (NAME-SEED/, NAME-SEED.log).
set -euo pipefail
cd "$(dirname "$0")/../.."
COLAV=sbmpc
RUNS=20
SCENARIOS=()
while [ $# -gt 0 ]; do
  case "$1" in
    --colav) COLAV=$2; shift 2 ;;
    --runs) RUNS=$2; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) SCENARIOS+=("$1"); shift ;;
  esac
done
[ ${#SCENARIOS[@]} -gt 0 ] || SCENARIOS=(examples/scenarios/*.scenario)
[ -z "${REPORT_DIR:-}" ] || mkdir -p "$REPORT_DIR"
export SEAPLAN_SHARED=${SEAPLAN_SHARED:-$(cd .. && pwd)/shared}
command -v jq >/dev/null || { echo "scenario_seeds: needs jq (apt-get install jq)" >&2; exit 1; }

WORK=$(mktemp -d)
PORT_FILE=$WORK/ports
. scripts/server_lib.sh
cleanup() {
  stop_seaplan_server
  rm -rf "$WORK"
}
trap cleanup EXIT
start_seaplan_server build/bin "$PORT_FILE" --grpc-addr 127.0.0.1:0 --http-addr "" \
  --data-dir "$WORK/data" --log-level warn || { echo "scenario_seeds: seaplan-server exited" >&2; exit 1; }
SERVER=127.0.0.1:$(server_port grpc "$PORT_FILE")

printf '%-16s %-5s %9s %-34s %8s %7s %9s %s\n' scenario colav completed \
  "min CPA per vessel, lowest-highest (m)" "<safety" aground "land (m)" "mission time (s)"
for scenario in "${SCENARIOS[@]}"; do
  name=$(basename "$scenario" .scenario)
  if grep -q 'shared:' "$scenario" && [ ! -d "$SEAPLAN_SHARED" ]; then
    echo "$name: skipped, SEAPLAN_SHARED ($SEAPLAN_SHARED) is absent"
    continue
  fi
  : > "$WORK/rows"
  for seed in $(seq 1 "$RUNS"); do
    out=${REPORT_DIR:-$WORK}/$name-$seed
    if ! build/bin/seaplan-sim --server "$SERVER" --token-file "$WORK/data/admin.token" --scenario "$scenario" --report-dir "$out" \
      --colav "$COLAV" --seed "$seed" --log-level error ${SIM_ARGS:-} >"$out.log" 2>&1; then
      echo "$name seed $seed: seaplan-sim failed ($(tail -1 "$out.log"))" >&2
    fi
    [ -f "$out/report.json" ] || continue
    jq -c --argjson seed "$seed" '{seed: $seed, completed, end_time_s, safety: .safety_distance_m,
            land: (.min_land_clearance_m // null), aground: (.aground_s // 0),
            cpa: [.cpa[] | {vessel, d: .min_distance_m}]}' "$out/report.json" >>"$WORK/rows"
  done
  jq -s -r --arg name "$name" --arg colav "$COLAV" --argjson runs "$RUNS" '
    (map(select(.completed)) | length) as $done
    | ([.[] | select((.cpa | map(.d) | min) < .safety)] | length) as $below
    | ([.[] | select(.aground > 0)] | length) as $aground
    | ((map(.land) | map(select(. != null)) | min) // "-") as $land
    | ([.[0].cpa[]?.vessel]) as $names
    | ([$names[] as $n | [.[] | .cpa[] | select(.vessel == $n) | .d] as $ds
        | "\($n) \($ds | min | floor)-\($ds | max | floor)"] | join(", ")) as $cpas
    | "\($name)\t\($colav)\t\($done)/\($runs)\t\($cpas)\t\($below)\t\($aground)\t\($land | if type == "number" then floor else . end)\t\((map(.end_time_s) | min // 0 | floor))-\((map(.end_time_s) | max // 0 | floor))"
  ' "$WORK/rows" | awk -F'\t' '{printf "%-16s %-5s %9s %-34s %8s %7s %9s %s\n", $1, $2, $3, $4, $5, $6, $7, $8}'
  # The seed of each vessel's lowest CPA and of the smallest land clearance,
  # to replay with seaplan-sim --seed.
  jq -s -r '
    ([.[0].cpa[]?.vessel]) as $names
    | ([$names[] as $n | [.[] | {seed, d: (.cpa[] | select(.vessel == $n) | .d)}] | min_by(.d)
        | "\($n) \(.d | floor) m (seed \(.seed))"] | join(", ")) as $low
    | ([.[] | select(.land != null)] | min_by(.land)) as $l
    | "  lowest: \($low)" + (if $l then "; land \($l.land | floor) m (seed \($l.seed))" else "" end)
  ' "$WORK/rows"
done
