#!/usr/bin/env bash
# The plan seaplan's anytime search holds after a short time, against the
# peers' first plans: runs `seaplan plan` (anytime, its default) with
# --time-limit S on problems of the benchmark set, whole processes, one at a
# time (under nice), checks every plan with `seaplan validate` of the same
# executable, and compares its makespan with the shortest first plan of the
# planners in peers.md that stop at their first plan (OPTIC -N and TFD's
# non-anytime configuration, whenever within their 60 s; STP keeps improving
# its plan, so its rows are not first plans and are left out).
#
# One line per problem, then: how many seaplan solved, and on the problems
# both seaplan and a peer solved how many of seaplan's plans are shorter,
# within 0.1 %, or longer than the best peer's first plan, with the
# distribution of seaplan / peer (median, 90th percentile, largest).
#
# usage: anytime_vs_peers.sh SEAPLAN [--first-plan] [--time-limit 1] [--memory-limit 2048]
#            [--cpu-limit S] [--bench DIR] [PROBLEM...]
#   PROBLEM: domain/pNN; none: every pNN.pddl of every folder of DIR
#   (default $SEAPLAN_SHARED/bench, else ../shared/bench); peers: DIR/../peers.md.
#   --cpu-limit S also stops the search after S s of its CPU time (for a
#   loaded machine; the time limit still applies).
#   --first-plan: seaplan stops after its first plan and the bounded searches
#   that follow it (`--no-anytime`), like for like with the peers' first plans.
set -euo pipefail
exe=$1
shift
time_s=1 memory_mb=2048 cpu_s=0 bench=${SEAPLAN_SHARED:-../shared}/bench
mode=() mode_name=anytime
args=()
for a in "$@"; do
  if [[ $a == --first-plan ]]; then mode=(--no-anytime) mode_name="first plan"; else args+=("$a"); fi
done
set -- "${args[@]}"
source "$(dirname "$0")/problem_args.sh"
peers=$bench/../peers.md
[[ -f $peers ]] || {
  echo "anytime_vs_peers: $peers not found" >&2
  exit 2
}
if [[ ${#problems[@]} == 0 ]]; then
  for f in "$bench"/*/p[0-9][0-9].pddl; do
    d=${f%/*}
    problems+=("${d##*/}/$(basename "$f" .pddl)")
  done
fi

# Best first-plan makespan per "domain/pNN" of the first-plan peers.
awk -F'|' '
  NF >= 9 && ($4 ~ /^ *(optic|tfd) *$/) && $5 ~ /^ *solved *$/ {
    gsub(/ /, "", $2); gsub(/ /, "", $3); gsub(/ /, "", $4); gsub(/ /, "", $8)
    key = $2 "/" $3
    if (!(key in best) || $8 + 0 < best[key] + 0) { best[key] = $8; who[key] = $4 }
  }
  END { for (k in best) print k, best[k], who[k] }' "$peers" | sort >"$work/peers"

printf '%-30s %-20s %7s %12s %6s %12s %-6s %8s\n' problem status wall_s makespan valid peer_best \
  peer ratio
: >"$work/rows"
for p in "${problems[@]}"; do
  dir=$bench/${p%/*} name=${p#*/}
  domain=$(domain_of "$dir" "$name")
  rm -f "$work/plan"
  limits=(--time-limit "$time_s" --memory-limit "$memory_mb")
  [[ $cpu_s == 0 ]] || limits+=(--cpu-limit "$cpu_s")
  start=$(date +%s.%N)
  nice timeout -s KILL "$(echo "$time_s + 10" | bc)" "$exe" plan "$domain" "$dir/$name.pddl" \
    "${limits[@]}" "${mode[@]}" -o "$work/plan" >"$work/out" 2>"$work/err" || true
  wall=$(echo "$(date +%s.%N) - $start" | bc)
  status=$(sed -n 's/^; status: //p' "$work/out" | head -1)
  makespan=$(sed -n 's/^; makespan: \([0-9.e+]*\) s.*/\1/p' "$work/out" | head -1)
  valid=$(plan_validity "$exe" "$domain" "$dir/$name.pddl")
  if [[ $valid == yes && -n $makespan ]]; then
    makespan=$(printf '%.3f' "$makespan")
  else
    makespan=-
  fi
  read -r _ peer_ms peer_name < <(grep "^$p " "$work/peers") || { peer_ms=- peer_name=-; }
  ratio=-
  if [[ $makespan != - && $peer_ms != - ]]; then
    ratio=$(printf '%.4f' "$(echo "scale=6; $makespan / $peer_ms" | bc)")
  fi
  printf '%-30s %-20s %7.2f %12s %6s %12s %-6s %8s\n' "$p" "${status:-none}" "$wall" \
    "$makespan" "$valid" "$peer_ms" "$peer_name" "$ratio"
  echo "$p $makespan $peer_ms $ratio" >>"$work/rows"
done
# Ratios sorted for the distribution (mawk has no sort of its own).
awk '$4 != "-" { print $4 }' "$work/rows" | sort -g >"$work/ratios"
awk -v limit="$time_s" -v mode="$mode_name" -v ratios="$work/ratios" '
  { n++ }
  $2 != "-" { solved++ }
  $3 != "-" { peer++ }
  $2 != "-" && $3 == "-" { only_seaplan++ }
  $2 == "-" && $3 != "-" { only_peer++ }
  $4 != "-" {
    both++
    if ($4 + 0 < 0.999) shorter++; else if ($4 + 0 <= 1.001) equal++; else longer++
  }
  END {
    printf "seaplan %s, %s s limit: %d/%d with a valid plan; a first-plan peer solved %d\n",
           mode, limit, solved, n, peer
    printf "both: %d; seaplan shorter %d, within 0.1 %% %d, longer %d; only seaplan %d, only a peer %d\n",
           both, shorter, equal, longer, only_seaplan, only_peer
    if (both > 0) {
      k = 0
      while ((getline line < ratios) > 0) r[++k] = line + 0
      median = r[int((both + 1) / 2)]
      p90 = r[int(0.9 * both + 0.999)]
      printf "seaplan / best peer first plan: median %.3f, 90th percentile %.3f, largest %.3f\n",
             median, p90, r[both]
    }
  }' "$work/rows"
