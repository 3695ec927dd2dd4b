#!/usr/bin/env bash
# CPU time per expanded state of two `seaplan` executables doing the same
# search: whole processes, one at a time, alternating BEFORE and AFTER
# --runs times per problem, each `seaplan plan --no-anytime --max-expansions
# N --time-limit 600`. An expansion limit, not a time limit, so that both do
# the same work whatever the machine's load; the time limit is the most
# `seaplan plan` takes, since the switch to the third first-plan search
# comes after a quarter of it and would make the work depend on the clock
# (keep each run below 150 s). The script checks that they did the same
# work: the same status, states expanded and generated and plan makespan
# in every run, or the row says "DIFFERENT WORK" and gives no ratio. Per
# problem: each executable's median CPU seconds (user + system) and
# expansions per CPU second, and the ratio of the medians, AFTER / BEFORE
# (below 1: faster).
#
# usage: state_speed.sh BEFORE_SEAPLAN AFTER_SEAPLAN [--runs 5] [--max-expansions 5000]
#            [--bench DIR] PROBLEM...
#   PROBLEM: domain/pNN of $SEAPLAN_SHARED/bench (default ../shared/bench), or
#            DOMAIN_FILE:PROBLEM_FILE (generated problems, scaled_problems.py)
set -euo pipefail
[[ $# -ge 3 ]] || {
  sed -n '/^# usage:/,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
  exit 2
}
before=$1 after=$2
shift 2
runs=5 expansions=5000 bench=${SEAPLAN_SHARED:-$(dirname "$0")/../../../shared}/bench
args=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --runs) runs=${2:?--runs needs a count}; shift 2 ;;
    --max-expansions) expansions=${2:?--max-expansions needs a count}; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
set -- "${args[@]}"
source "$(dirname "$0")/problem_args.sh"
for exe in "$before" "$after"; do
  [[ -x $exe ]] || { echo "state_speed: $exe is not an executable" >&2; exit 2; }
done

# Prints the run's work (status, expanded, generated, makespan: one word)
# and its CPU seconds.
run_one() {
  local exe=$1 domain=$2 problem=$3
  /usr/bin/time -f '%U %S' -o "$work/time" "$exe" plan "$domain" "$problem" --no-anytime \
    --max-expansions "$expansions" --time-limit 600 >"$work/out" 2>/dev/null || true
  local status counts makespan
  status=$(sed -n 's/^; status: //p' "$work/out" | head -1)
  counts=$(sed -n 's/^; search: \([0-9]*\) expanded, \([0-9]*\) generated.*/\1,\2/p' "$work/out" | head -1)
  makespan=$(sed -n 's/^; makespan: \([0-9.e+-]*\) s.*/\1/p' "$work/out" | head -1)
  echo "${status:-none},${counts:-0,0},${makespan:--} $(awk '{ print $1 + $2 }' "$work/time" | tail -1)"
}

printf '%-34s %9s %8s %9s | %8s %9s | %s\n' problem expanded cpu_s exp/cpu_s cpu_s exp/cpu_s \
  'after/before'
ratios=()
for p in "${problems[@]}"; do
  if [[ $p == *:* ]]; then
    domain=${p%%:*} problem=${p#*:}
    label=$(basename "$problem" .pddl)
  else
    dir=$bench/${p%/*} name=${p#*/}
    domain=$(domain_of "$dir" "$name") problem=$dir/$name.pddl label=$p
  fi
  works=() cpu_before=() cpu_after=()
  for ((i = 0; i < runs; ++i)); do
    read -r w c < <(run_one "$before" "$domain" "$problem")
    works+=("$w") cpu_before+=("$c")
    read -r w c < <(run_one "$after" "$domain" "$problem")
    works+=("$w") cpu_after+=("$c")
  done
  if [[ $(printf '%s\n' "${works[@]}" | sort -u | wc -l) -ne 1 ]]; then
    printf '%-34s DIFFERENT WORK: %s\n' "$label" "$(printf '%s\n' "${works[@]}" | sort -u | tr '\n' ' ')"
    continue
  fi
  expanded=$(cut -d, -f2 <<<"${works[0]}")
  mb=$(printf '%s\n' "${cpu_before[@]}" | median) ma=$(printf '%s\n' "${cpu_after[@]}" | median)
  ratio=$(awk -v a="$ma" -v b="$mb" 'BEGIN { if (b > 0) printf "%.3f", a / b; else print "-" }')
  [[ $ratio == - ]] || ratios+=("$ratio")
  printf '%-34s %9d %8.2f %9.0f | %8.2f %9.0f | %s\n' "$label" "$expanded" "$mb" \
    "$(awk -v e="$expanded" -v c="$mb" 'BEGIN { print (c > 0 ? e / c : 0) }')" "$ma" \
    "$(awk -v e="$expanded" -v c="$ma" 'BEGIN { print (c > 0 ? e / c : 0) }')" "$ratio"
done
if [[ ${#ratios[@]} -gt 0 ]]; then
  echo "median ratio after/before (CPU s of the same search): $(printf '%s\n' "${ratios[@]}" | median)" \
    "over ${#ratios[@]} problems, $runs runs each"
fi
