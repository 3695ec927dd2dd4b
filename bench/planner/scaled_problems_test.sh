#!/usr/bin/env bash
# scaled_problems_test.sh SEAPLAN BENCH: the generator's problems load with
# the shared domains and get valid plans (small sizes), the same arguments
# give the same file and another seed another, bad sizes are refused.
set -euo pipefail
seaplan=$1 bench=$2
gen=$(dirname "$0")/scaled_problems.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "scaled_problems_test: $*" >&2
  exit 1
}
solve() {
  local domain=$bench/$1/domain.pddl
  shift
  "$gen" "$@" >"$work/p.pddl"
  "$gen" "$@" | cmp -s - "$work/p.pddl" || fail "$*: two runs differ"
  "$seaplan" plan "$domain" "$work/p.pddl" --no-anytime --time-limit 60 -o "$work/plan" \
    >"$work/out" 2>&1 || fail "$*: seaplan plan failed: $(cat "$work/out")"
  grep -q '^; status: SOLVED' "$work/out" || fail "$*: no plan: $(cat "$work/out")"
  "$seaplan" validate "$domain" "$work/p.pddl" "$work/plan" >/dev/null ||
    fail "$*: the plan does not validate"
  echo "ok: $* ($(sed -n 's/^; makespan: //p' "$work/out"))"
}
solve floortile-2011 floortile 2 3 2 1
solve driverlog-2014 driverlog 3 3 5 1
"$gen" driverlog 3 3 5 2 | cmp -s - <("$gen" driverlog 3 3 5 1) && fail "seeds 1 and 2 give the same problem"
if "$gen" floortile 0 3 2 1 >/dev/null 2>&1; then fail "0 rows accepted"; fi
if "$gen" driverlog 3 0 5 1 >/dev/null 2>&1; then fail "0 trucks accepted"; fi
echo "scaled_problems_test: passed"
