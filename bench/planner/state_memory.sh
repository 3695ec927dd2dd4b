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
# tables included (they are the same in both). Beside it, generated states
# per second of CPU time (user + system) of each run: a speed figure that
# the machine's load moves much less than wall time.
#
# usage: state_memory.sh BEFORE_SEAPLAN AFTER_SEAPLAN [--memory-limit MB] [--time-limit S]
#            [--bench DIR] PROBLEM...    (PROBLEM: domain/pNN, e.g. storage-2011/p01)
set -euo pipefail
before=$1 after=$2
shift 2
memory_mb=400 time_s=120 bench=${SEAPLAN_SHARED:-../shared}/bench
source "$(dirname "$0")/problem_args.sh"

# Prints: status generated peak_rss_kb cpu_s
run_one() {
  local exe=$1 domain=$2 problem=$3
  nice /usr/bin/time -f '%M %U %S' -o "$work/time" "$exe" plan "$domain" "$problem" --no-anytime \
    --time-limit "$time_s" --memory-limit "$memory_mb" >"$work/out" 2>/dev/null || true
  local status generated
  status=$(sed -n 's/^; status: //p' "$work/out" | head -1)
  generated=$(sed -n 's/^; search: [0-9]* expanded, \([0-9]*\) generated.*/\1/p' "$work/out" | head -1)
  local rss_kb user_s system_s
  read -r rss_kb user_s system_s < <(tail -1 "$work/time")
  echo "${status:-none} ${generated:-0} $rss_kb $(awk -v u="$user_s" -v s="$system_s" 'BEGIN { print u + s }')"
}

printf '%-22s %-14s %9s %6s %6s %8s | %-14s %9s %6s %6s %8s | %s\n' problem before generated rss_MB B/st gen/cpu_s \
  after generated rss_MB B/st gen/cpu_s ratio
ratios=()
for p in "${problems[@]}"; do
  dir=$bench/${p%/*} name=${p#*/}
  domain=$(domain_of "$dir" "$name")
  read -r s1 g1 k1 c1 < <(run_one "$before" "$domain" "$dir/$name.pddl")
  read -r s2 g2 k2 c2 < <(run_one "$after" "$domain" "$dir/$name.pddl")
  b1=$(( g1 > 0 ? k1 * 1024 / g1 : 0 )) b2=$(( g2 > 0 ? k2 * 1024 / g2 : 0 ))
  r1=$(awk -v g="$g1" -v c="$c1" 'BEGIN { printf "%d", (c > 0 ? g / c : 0) }')
  r2=$(awk -v g="$g2" -v c="$c2" 'BEGIN { printf "%d", (c > 0 ? g / c : 0) }')
  ratio=$(awk -v a="$b2" -v b="$b1" 'BEGIN { if (b > 0) printf "%.3f", a / b; else print "-" }')
  ratios+=("$ratio")
  printf '%-22s %-14s %9d %6d %6d %8d | %-14s %9d %6d %6d %8d | %s\n' "$p" "$s1" "$g1" $((k1 / 1024)) \
    "$b1" "$r1" "$s2" "$g2" $((k2 / 1024)) "$b2" "$r2" "$ratio"
done
known=$(printf '%s\n' "${ratios[@]}" | grep -cv -- - || true)
if [[ $known -gt 0 ]]; then
  printf 'median ratio after/before (bytes per generated state): %.3f over %d problems\n' \
    "$(printf '%s\n' "${ratios[@]}" | grep -v -- - | median)" "$known"
fi
