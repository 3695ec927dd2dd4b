#!/usr/bin/env bash
# Runs one `seaplan` executable on named problems of the benchmark set, whole
# processes, one at a time (under nice), first plan, and checks every plan
# with `seaplan validate` of the same executable. One line per problem, then
# the coverage.
#
# usage: run_problems.sh SEAPLAN [--time-limit 60] [--memory-limit 2048] [--bench DIR]
#            PROBLEM...    (PROBLEM: domain/pNN, e.g. storage-2011/p01)
set -euo pipefail
exe=$1
shift
time_s=60 memory_mb=2048 bench=${SEAPLAN_SHARED:-../shared}/bench
source "$(dirname "$0")/problem_args.sh"
printf '%-24s %-22s %8s %8s %10s %10s %s\n' problem status wall_s rss_MB expanded generated valid
solved=0
for p in "${problems[@]}"; do
  dir=$bench/${p%/*} name=${p#*/}
  domain=$(domain_of "$dir" "$name")
  rm -f "$work/plan"
  nice /usr/bin/time -f '%e %M' -o "$work/time" "$exe" plan "$domain" "$dir/$name.pddl" --no-anytime \
    --time-limit "$time_s" --memory-limit "$memory_mb" -o "$work/plan" >"$work/out" 2>/dev/null || true
  status=$(sed -n 's/^; status: //p' "$work/out" | head -1)
  # No search line (a load error, or stopped while grounding): read fails, the row says "-".
  read -r expanded generated < <(sed -n 's/^; search: \([0-9]*\) expanded, \([0-9]*\) generated.*/\1 \2/p' \
    "$work/out" | head -1) || true
  read -r wall_s rss_kb < <(tail -1 "$work/time")
  valid=-
  if [[ -s $work/plan ]]; then
    if "$exe" validate "$domain" "$dir/$name.pddl" "$work/plan" >/dev/null 2>&1; then
      valid=yes solved=$((solved + 1))
    else
      valid=NO
    fi
  fi
  printf '%-24s %-22s %8s %8d %10s %10s %s\n' "$p" "${status:-none}" "$wall_s" $((rss_kb / 1024)) \
    "${expanded:--}" "${generated:--}" "$valid"
done
echo "coverage (valid plans): $solved/${#problems[@]} at ${time_s} s / ${memory_mb} MB"
