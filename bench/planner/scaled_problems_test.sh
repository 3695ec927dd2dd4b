#!/usr/bin/env bash
# scaled_problems_test.sh SEAPLAN BENCH [PYTHON3]: the generator's problems
# load with the shared domains and get valid plans (small sizes), the same
# arguments give the same file and another seed another, bad sizes are
# refused. Without python3: skipped (exit 77), or failed under CI.
set -euo pipefail
seaplan=$1 bench=$2 python=${3:-python3}
gen=$(dirname "$0")/scaled_problems.py
if ! command -v "$python" >/dev/null; then
  echo "scaled_problems_test: $python not found" >&2
  if [[ -n "${CI:-}" ]]; then exit 1; fi
  echo "skipped: needs python3"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "scaled_problems_test: $*" >&2
  exit 1
}
generate() {  # generate FILE ARGS...
  local out=$1
  shift
  "$python" "$gen" "$@" >"$out" || fail "$*: the generator failed"
}
solve() {  # solve SHARED_DOMAIN_FOLDER[/FILE.pddl] GENERATOR_ARGS...
  local domain=$bench/$1/domain.pddl
  [[ $1 == *.pddl ]] && domain=$bench/$1
  shift
  generate "$work/p.pddl" "$@"
  generate "$work/again.pddl" "$@"
  cmp -s "$work/p.pddl" "$work/again.pddl" || fail "$*: two runs differ"
  "$seaplan" plan "$domain" "$work/p.pddl" --no-anytime --time-limit 60 -o "$work/plan" \
    >"$work/out" 2>&1 || fail "$*: seaplan plan failed: $(cat "$work/out")"
  grep -q '^; status: SOLVED' "$work/out" || fail "$*: no plan: $(cat "$work/out")"
  "$seaplan" validate "$domain" "$work/p.pddl" "$work/plan" >/dev/null ||
    fail "$*: the plan does not validate"
  echo "ok: $* ($(sed -n 's/^; makespan: //p' "$work/out"))"
}
solve floortile-2011 floortile 2 3 2 1
solve driverlog-2014 driverlog 3 3 5 1
solve driverlog-2014 driverlog 1 1 2 1  # the smallest map: two sites, one road
solve elevators-2011 elevators 8 3 1
solve trucks-time-til trucks 2 3 6 2 2
solve satellite-tw-til satellite-tw 2 6 4 2 1
solve satellite-2014 satellite 2 2 3 6 5 1
solve satellite-2014 satellite 1 1 1 2 1 1  # one observed direction, one mode
solve depots-time depots 1 1 1 2 2 3 1
solve depots-time depots 1 0 1 2 1 3 1  # no distributor: one place
solve driverlogshift-upf driverlogshift 2 2 2 2 1
solve turnandopen-2011 turnandopen 1 3 3 1
solve turnandopen-2011 turnandopen 2 1 2 1  # one room: no door
solve parcprinter-2011/domain-1.pddl parcprinter upp 3 1
solve parcprinter-2011/domain-4.pddl parcprinter eTipp 2 2
generate "$work/seed1.pddl" floortile 2 3 2 1
generate "$work/seed2.pddl" floortile 2 3 2 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "floortile: seeds 1 and 2 give the same problem"
generate "$work/seed1.pddl" driverlog 3 3 5 1
generate "$work/seed2.pddl" driverlog 3 3 5 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "driverlog: seeds 1 and 2 give the same problem"
generate "$work/seed1.pddl" elevators 8 3 1
generate "$work/seed2.pddl" elevators 8 3 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "elevators: seeds 1 and 2 give the same problem"
generate "$work/seed1.pddl" trucks 2 3 6 2 1
generate "$work/seed2.pddl" trucks 2 3 6 2 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "trucks: seeds 1 and 2 give the same problem"
generate "$work/seed1.pddl" satellite-tw 2 6 4 2 1
generate "$work/seed2.pddl" satellite-tw 2 6 4 2 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "satellite-tw: seeds 1 and 2 give the same problem"
generate "$work/seed1.pddl" satellite 2 2 3 6 5 1
generate "$work/seed2.pddl" satellite 2 2 3 6 5 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "satellite: seeds 1 and 2 give the same problem"
generate "$work/seed1.pddl" depots 1 1 1 2 2 3 1
generate "$work/seed2.pddl" depots 1 1 1 2 2 3 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "depots: seeds 1 and 2 give the same problem"
generate "$work/seed1.pddl" driverlogshift 3 2 3 3 1
generate "$work/seed2.pddl" driverlogshift 3 2 3 3 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "driverlogshift: seeds 1 and 2 give the same problem"
generate "$work/seed1.pddl" parcprinter upp 6 1
generate "$work/seed2.pddl" parcprinter upp 6 2
cmp -s "$work/seed1.pddl" "$work/seed2.pddl" && fail "parcprinter: seeds 1 and 2 give the same problem"
for bad in "floortile 0 3 2 1" "floortile 1 1 2 1" "driverlog 3 0 5 1" "elevators 12 3 1" \
  "elevators 16 0 1" "trucks 1 1 3 2 1" "trucks 0 3 3 2 1" \
  "satellite-tw 0 6 4 2 1" "satellite-tw 2 1 4 2 1" "satellite-tw 2 6 4 0 1" \
  "satellite-tw 2 6 16 2 1" "satellite 0 2 3 6 5 1" "satellite 2 0 3 6 5 1" \
  "satellite 2 2 3 2 5 1" "satellite 2 2 1 6 5 1" "depots 0 1 1 2 2 3 1" "depots 1 1 1 1 2 3 1" \
  "depots 1 1 0 2 2 3 1" "depots 1 1 1 2 1 3 1" "driverlogshift 2 2 2 1 1" \
  "driverlogshift 0 2 2 2 1" "turnandopen 0 3 3 1" "parcprinter upp 0 1" "parcprinter ipp 3 1"; do
  # shellcheck disable=SC2086  # the arguments split on purpose
  if "$python" "$gen" $bad >/dev/null 2>&1; then fail "accepted: $bad"; fi
done
echo "scaled_problems_test: passed"
