#!/usr/bin/env bash
# Bytes per search state of two `seaplan` executables on the same problems,
# whole processes, one at a time, and their ratio.
#
# Each problem is planned (first plan) under a small memory budget that the
# search outgrows, so both runs end in a memory-out (or a plan / timeout,
# then the row says so); bytes per state is the process's peak resident
# memory divided by the states it generated (every successor put on the open
# lists: the lazy search registers a state only when it is expanded, so
# generated states are what fills memory). Both executables count the same
# states, so the ratio is the packing's gain, grounding and heuristic
# tables included (they are the same in both).
#
# usage: state_memory.sh BEFORE_SEAPLAN AFTER_SEAPLAN [--memory-limit MB] [--time-limit S]
#            [--bench DIR] PROBLEM...    (PROBLEM: domain/pNN, e.g. storage-2011/p01)
set -euo pipefail
before=$1 after=$2
shift 2
memory_mb=400 time_s=120 bench=${SEAPLAN_SHARED:-../shared}/bench
source "$(dirname "$0")/problem_args.sh"

# Prints: status generated peak_rss_kb
run_one() {
  local exe=$1 domain=$2 problem=$3
  nice /usr/bin/time -f '%M' -o "$work/time" "$exe" plan "$domain" "$problem" --no-anytime \
    --time-limit "$time_s" --memory-limit "$memory_mb" >"$work/out" 2>/dev/null || true
  local status generated
  status=$(sed -n 's/^; status: //p' "$work/out" | head -1)
  generated=$(sed -n 's/^; search: [0-9]* expanded, \([0-9]*\) generated.*/\1/p' "$work/out" | head -1)
  echo "${status:-none} ${generated:-0} $(tail -1 "$work/time")"
}

printf '%-26s %-22s %10s %7s %9s | %-22s %10s %7s %9s | %s\n' problem before-status generated rss_MB B/state \
  after-status generated rss_MB B/state ratio
ratios=()
for p in "${problems[@]}"; do
  dir=$bench/${p%/*} name=${p#*/}
  domain=$(domain_of "$dir" "$name")
  read -r s1 g1 k1 < <(run_one "$before" "$domain" "$dir/$name.pddl")
  read -r s2 g2 k2 < <(run_one "$after" "$domain" "$dir/$name.pddl")
  b1=$(( g1 > 0 ? k1 * 1024 / g1 : 0 )) b2=$(( g2 > 0 ? k2 * 1024 / g2 : 0 ))
  ratio=$(awk -v a="$b2" -v b="$b1" 'BEGIN { if (b > 0) printf "%.3f", a / b; else print "-" }')
  ratios+=("$ratio")
  printf '%-26s %-22s %10d %7d %9d | %-22s %10d %7d %9d | %s\n' "$p" "$s1" "$g1" $((k1 / 1024)) "$b1" \
    "$s2" "$g2" $((k2 / 1024)) "$b2" "$ratio"
done
printf '%s\n' "${ratios[@]}" | grep -v -- - | sort -g |
  awk '{ r[NR] = $1 } END { if (NR) printf "median ratio after/before (bytes per generated state): %.3f over %d problems\n", (NR % 2 ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2), NR }'
