#!/usr/bin/env bash
# What a user can observe, from two builds side by side: the first plan of
# every fjord example (seaplan plan --no-anytime --seed 1), the routes between
# the fjord scenarios' consecutive ports on their chart (seaplan route, seed 1)
# and the outcome of missions A, B and C (seaplan-server + seaplan-sim, the
# traffic as scripted, as fast as possible). Writes one summary per build into
# OUT_DIR (before.txt, after.txt), prints their diff and exits 1 when they
# differ.
#
#   scripts/compare_outcomes.sh BEFORE_BIN AFTER_BIN [OUT_DIR]
#   SIM=<seaplan-sim>   one simulation client for both servers (by default each
#                       build's own), so that only the server side is compared
#
# Plans and routes are deterministic. Missions A and B plan with an anytime
# search under a wall-clock budget (the scenario's planner_time_limit_s), so
# under load they can end differently from one run to the next: compare
# mission lines of two runs of the same build before reading a difference as
# a change. Mission C's searches are bounded by expansions
# (planner_max_expansions) and end the same on any machine (a seaplan-sim
# older than that key refuses the scenario: give SIM the newer one). Needs jq
# (scripts/install-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ $# -lt 2 ]]; then
  sed -n '2,18p' "$0" >&2
  exit 2
fi
before=$(cd "$1" && pwd)
after=$(cd "$2" && pwd)
out=${3:-$(mktemp -d)}
mkdir -p "$out"
examples=$PWD/examples

# <ports>: every "location = name lat lon" line of the case A scenario, in order.
mapfile -t ports < <(sed -n 's/^location = \([^ ]*\) \([^ ]*\) \([^ ]*\)$/\1 \2,\3/p' \
  "$examples/scenarios/case-a.scenario")

plans() {  # bin
  local p
  for p in "domain case-a" "domain case-b" "domain-fuel case-c" "domain-numeric case-c-numeric"; do
    set -- $p
    local plan="$work/$2.plan"
    if "$bin/seaplan" plan --no-anytime --seed 1 --time-limit 120 \
      "$examples/fjord/$1.pddl" "$examples/fjord/$2.pddl" -o "$plan" >/dev/null 2>&1; then
      echo "plan $2: $(grep -c . "$plan") actions, last ends $(awk -F'[][ :]+' \
        'NF>2 {e=$1+$(NF-1); if (e>m) m=e} END {printf "%.3f", m}' "$plan") s," \
        "sha256 $(sha256sum <"$plan" | cut -c1-16)"
    else
      echo "plan $2: no plan (exit $?)"
    fi
  done
}

routes() {  # bin
  local i
  for ((i = 0; i + 1 < ${#ports[@]}; i++)); do
    local from=(${ports[i]}) to=(${ports[i + 1]})
    local json
    json=$("$bin/seaplan" --json route --chart-file "$examples/scenarios/fjord-entrance.geojson" \
      --from "${from[1]}" --to "${to[1]}" --seed 1 2>&1) || {
      echo "route ${from[0]}->${to[0]}: failed: $json"
      continue
    }
    # Per alternative: waypoints, length, cost, the mode per waypoint and
    # the positions (1e-6 degrees, about 0.1 m).
    echo "route ${from[0]}->${to[0]}: $(jq -c '[.alternatives[] | {n: (.waypoints | length),
      length_m: ((.lengthM // 0) * 10 | round / 10), cost: ((.totalCost // 0) * 1000 | round / 1000),
      modes: ([.waypoints[].mode] | map(.[9:]) | join(",")),
      at: ([.waypoints[].position | [.latitudeDeg, .longitudeDeg] | map(. * 1e6 | round)] | tostring
           | @base64 | .[0:12])}]' <<<"$json")"
  done
}

missions() {  # bin sim
  local sim=$2 ports_file="$work/ports"
  "$bin/seaplan-server" --grpc-addr 127.0.0.1:0 --http-addr "" --data-dir "$work/data" \
    --port-file "$ports_file" --log-level error &
  local server_pid=$!
  for _ in $(seq 1 200); do
    grep -q '^grpc=' "$ports_file" 2>/dev/null && break
    sleep 0.1
  done
  local address=127.0.0.1:$(sed -n 's/^grpc=//p' "$ports_file")
  local c code
  for c in case-a case-b case-c; do
    code=0
    "$sim" --server "$address" --scenario "$examples/scenarios/$c.scenario" --time-factor 0 \
      --report-dir "$work/$c" --log-level off >/dev/null 2>&1 || code=$?
    if [[ ! -f "$work/$c/report.json" ]]; then
      echo "mission $c: exit $code, no report"
      continue
    fi
    echo "mission $c: exit $code $(jq -c '{completed, end_s: (.end_time_s | round),
      aground_s, fuel_replans: .fuel_triggered_replans,
      versions: [.plan_versions[] | {v: .version, reason, makespan_s: (.makespan_s | round),
        tasks: [.tasks[] | .action + (if .route_length_m then "@\(.route_length_m | round)m" else "" end)]}]}' \
      "$work/$c/report.json")"
  done
  kill -TERM "$server_pid"
  wait "$server_pid" || true
}

for side in before after; do
  bin=${!side}
  work=$(mktemp -d)
  {
    plans
    routes
    missions "$bin" "${SIM:-$bin/seaplan-sim}"
  } >"$out/$side.txt"
  rm -rf "$work"
  echo "compare_outcomes: $side ($bin) -> $out/$side.txt"
done
if diff "$out/before.txt" "$out/after.txt"; then
  echo "compare_outcomes: same plans, routes and mission outcomes"
else
  echo "compare_outcomes: the outcomes differ (above)"
  exit 1
fi
