#!/usr/bin/env bash
# Runs one `seaplan` executable on named problems of the benchmark set, whole
# processes, one at a time (under nice), first plan, and checks every plan
# with `seaplan validate` of the same executable. One line per problem, then
# the coverage.
#
# cpu_s is the run's user + system time: expanded or generated states per
# CPU second compare executables fairly on a loaded machine, where a wall
# limit gives each process whatever share of a core it gets.
# --cpu-limit S interrupts each run (SIGINT) once it has used S s of CPU time
# (read from /proc every 0.1 s), so that two executables get the same work
# budget for coverage; give a --time-limit well above it. An interrupted run
# prints no status or counters (the row says `none`), and no plan: so a run
# that has reported its first plan (`--stream`) is not interrupted but left
# to finish the bounded searches that may shorten it (its cpu_s can then
# exceed S; the first plan came within S). S is also passed to `seaplan plan
# --cpu-limit`, so that its switch to the second first-plan search comes at
# S/2 of CPU time, as in a run of S s on a core of its own, not at half the
# wall limit.
#
# usage: run_problems.sh SEAPLAN [--time-limit 60] [--memory-limit 2048] [--cpu-limit S]
#            [--bench DIR] PROBLEM...    (PROBLEM: domain/pNN, e.g. storage-2011/p01)
set -euo pipefail
exe=$1
shift
time_s=60 memory_mb=2048 cpu_s=0 bench=${SEAPLAN_SHARED:-../shared}/bench
source "$(dirname "$0")/problem_args.sh"
ticks_per_s=$(getconf CLK_TCK)

# Interrupts the `seaplan` child of process $1 once it has used cpu_s of CPU.
stop_at_cpu_limit() {
  local parent=$1 child= stat interrupted=0
  while kill -0 "$parent" 2>/dev/null; do
    [[ -n $child ]] || child=$(pgrep -P "$parent" | head -1) || true
    if [[ -n $child && $interrupted == 0 ]] && ! grep -q '^improved plan:' "$work/err" &&
      read -r -a stat 2>/dev/null <"/proc/$child/stat"; then
      # Fields 14 and 15: user and system time in clock ticks.
      if ((stat[13] + stat[14] >= cpu_s * ticks_per_s)); then
        kill -INT "$child" 2>/dev/null || true
        interrupted=1
      fi
    fi
    sleep 0.1
  done
}

printf '%-24s %-22s %8s %8s %8s %10s %10s %s\n' problem status wall_s cpu_s rss_MB expanded generated \
  valid
solved=0
for p in "${problems[@]}"; do
  dir=$bench/${p%/*} name=${p#*/}
  domain=$(domain_of "$dir" "$name")
  rm -f "$work/plan"
  : >"$work/err"
  nice /usr/bin/time -f '%e %M %U %S' -o "$work/time" "$exe" plan "$domain" "$dir/$name.pddl" \
    --no-anytime --stream --time-limit "$time_s" --memory-limit "$memory_mb" --cpu-limit "$cpu_s" \
    -o "$work/plan" \
    >"$work/out" 2>"$work/err" &
  runner=$!
  if [[ $cpu_s != 0 ]]; then stop_at_cpu_limit "$runner"; fi
  wait "$runner" || true
  status=$(sed -n 's/^; status: //p' "$work/out" | head -1)
  # No search line (a load error, or stopped while grounding): read fails, the row says "-".
  read -r expanded generated < <(sed -n 's/^; search: \([0-9]*\) expanded, \([0-9]*\) generated.*/\1 \2/p' \
    "$work/out" | head -1) || true
  read -r wall_s rss_kb user_s system_s < <(tail -1 "$work/time")
  valid=$(plan_validity "$exe" "$domain" "$dir/$name.pddl")
  [[ $valid != yes ]] || solved=$((solved + 1))
  printf '%-24s %-22s %8s %8.2f %8d %10s %10s %s\n' "$p" "${status:-none}" "$wall_s" \
    "$(echo "$user_s + $system_s" | bc)" $((rss_kb / 1024)) "${expanded:--}" "${generated:--}" "$valid"
done
limits="${time_s} s / ${memory_mb} MB"
[[ $cpu_s == 0 ]] || limits+=" / ${cpu_s} CPU s"
echo "coverage (valid plans): $solved/${#problems[@]} at $limits"
