#!/usr/bin/env bash
# The generated instances of bench/planner/README.md's sections "Larger
# generated instances: satellite-tw-til", "Helpful events on time", "A run
# of goals ordered to the end: floortile", "Stacks from the right end:
# depots", "driverlogshift past p05", "Long plans: turnandopen", "Drives
# by each driver: one operator", "Larger print jobs: parcprinter" and
# "Larger elevators and satellite instances", run
# with one executable: for each, `seaplan plan` (first plan, --no-anytime)
# as a whole process under a CPU limit, then `seaplan validate` of the same
# executable on the plan. One line per instance, then how many were solved
# with a valid plan. To compare two executables like for like, run the
# script for each at the same time, one per core.
#
# usage: scaled_suite.sh SEAPLAN SUITE [--cpu-limit 20] [--quick] [-- PLAN-OPTIONS...]
#   PLAN-OPTIONS: passed on to each `seaplan plan` (--switch-after 0.01, say)
#   SUITE: satellite-tw (26 instances of satellite-tw-til's domain),
#          satellite-tw-large (6, 10-12 satellites), trucks (18 of
#          trucks-time-til's domain), floortile (22 of floortile-2011's,
#          4 x 3 to 8 x 8 tiles, 2-4 robots), depots (18 of depots-time's,
#          10-20 crates), driverlogshift (8 of driverlogshift-upf's, 4-6
#          drivers, 3-5 sites), turnandopen (12 of turnandopen-2011's,
#          2 robots, 9-12 rooms, 20-30 balls), parcprinter (14 of
#          parcprinter-2011's two printers: 12-20 sheets on the printer of
#          its p01-p03, 9-14 on the larger one of p04-p05), driverlog (10
#          of driverlog-2014's, the sizes its p01-p05 grow by: 10 drivers,
#          10 trucks, 25 packages to 14, 14, 37), elevators (10 of
#          elevators-2011's, 24-40 floors, 28-40 passengers), satellite (10
#          of satellite-2014's, 5-10 satellites, 40-60 directions, 32-50
#          images)
#   --quick: the suite's first two instances only, and exit 1 unless both
#            get a valid plan (the smoke test)
#   The shared domains are read from $SEAPLAN_SHARED/bench (default
#   ../shared/bench beside the repository).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage() {
  sed -n '/^# usage:/,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
  exit 2
}
[[ $# -ge 2 ]] || usage
seaplan=$1 suite=$2
shift 2
cpu=20 quick=0 plan_options=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --) shift; plan_options=("$@"); break ;;
    --cpu-limit) cpu=${2:?--cpu-limit needs seconds}; shift 2 ;;
    --quick) quick=1; shift ;;
    *) echo "scaled_suite: unknown argument $1" >&2; usage ;;
  esac
done
[[ -x $seaplan ]] || { echo "scaled_suite: $seaplan is not an executable" >&2; exit 2; }
bench=${SEAPLAN_SHARED:-$here/../../../shared}/bench
# Each entry: generator arguments without the seed, then the seeds.
case $suite in
  satellite-tw)
    domain=satellite-tw-til
    sets=("3 10 7 2|1 2" "4 12 8 2|3 4 5 6" "4 14 10 2|1 2" "5 16 12 3|1 2 3 4 5 6"
      "6 20 16 3|1 2 3 4 5 6" "8 25 20 4|1 2 3 4 5 6") ;;
  satellite-tw-large)
    domain=satellite-tw-til
    sets=("10 32 28 5|1 2 3" "12 40 36 6|1 2 3") ;;
  trucks)
    domain=trucks-time-til
    sets=("2 4 8 3|1 2 3" "2 4 10 3|1 2 3" "2 5 12 3|1 2 3" "2 6 14 3|1 2" "3 4 12 3|1 2 3"
      "3 5 15 3|1 2 3" "3 6 20 3|1") ;;
  floortile)
    domain=floortile-2011
    sets=("4 3 2|1 2" "4 4 2|1 2 3" "5 3 2|1 2" "5 4 2|1 2 3" "5 5 2|1 2 3" "6 4 2|1 2"
      "6 5 3|1 2" "6 6 3|1 2" "7 5 3|1" "7 7 3|1" "8 8 4|1") ;;
  depots)
    domain=depots-time
    sets=("1 2 2 3 3 10|1 2 3 4" "1 2 2 3 3 15|1 2 3" "2 2 2 4 4 10|1 2 3" "2 2 2 4 4 15|1 2 3"
      "3 3 3 6 6 15|1 2" "3 3 3 6 6 20|1 2 3") ;;
  driverlogshift)
    domain=driverlogshift-upf
    sets=("4 3 3 3|1 2 3" "5 3 4 4|1 2" "5 4 4 4|1" "6 4 5 4|1" "6 5 6 5|1") ;;
  turnandopen)
    domain=turnandopen-2011
    sets=("2 9 20|1 2 3" "2 10 22|1 2" "2 10 24|1 2" "2 11 26|1 2" "2 11 28|1 2" "2 12 30|1") ;;
  driverlog)
    domain=driverlog-2014
    sets=("10 10 25|1 2" "11 11 28|1 2" "12 12 31|1 2" "13 13 34|1 2" "14 14 37|1 2") ;;
  elevators)
    domain=elevators-2011
    sets=("24 28|1 2" "24 32|1 2" "32 32|1 2" "32 40|1 2" "40 40|1 2") ;;
  satellite)
    domain=satellite-2014
    sets=("5 5 7 40 32|1 2" "6 5 8 44 36|1 2" "7 5 8 48 40|1 2" "8 5 9 52 44|1 2"
      "10 5 10 60 50|1 2") ;;
  parcprinter)
    # A domain per printer: the generator's first argument names it.
    domain=parcprinter-2011
    sets=("upp 12|1 2" "upp 14|1 2" "upp 16|1 2" "upp 20|1" "eTipp 9|1 2" "eTipp 10|1 2"
      "eTipp 12|1 2" "eTipp 14|1") ;;
  *) echo "scaled_suite: unknown suite $suite" >&2; usage ;;
esac
generator=${suite%-large}
domain_file() {  # domain_file GENERATOR_ARGS: the shared domain the instance is for
  case $1 in
    upp) echo "$bench/$domain/domain-1.pddl" ;;
    eTipp) echo "$bench/$domain/domain-4.pddl" ;;
    *) echo "$bench/$domain/domain.pddl" ;;
  esac
}
for set in "${sets[@]}"; do
  # shellcheck disable=SC2086  # the sizes split on purpose
  file=$(domain_file ${set%|*})
  [[ -f $file ]] || { echo "scaled_suite: no $file (set SEAPLAN_SHARED)" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
solved=0 total=0
printf '%-28s %-22s %12s %s\n' instance status first_plan_s valid
for set in "${sets[@]}"; do
  for seed in ${set#*|}; do
    if [[ $quick == 1 && $total -ge 2 ]]; then break 2; fi
    name="$generator ${set%|*} $seed"
    # shellcheck disable=SC2086  # the sizes split on purpose
    python3 "$here/scaled_problems.py" "$generator" ${set%|*} "$seed" >"$work/p.pddl"
    rm -f "$work/plan"
    # shellcheck disable=SC2086
    file=$(domain_file ${set%|*})
    "$seaplan" plan "$file" "$work/p.pddl" --no-anytime --cpu-limit "$cpu" \
      --memory-limit 2048 -o "$work/plan" "${plan_options[@]}" >"$work/out" 2>&1 || true
    status=$(sed -n 's/^; status: //p' "$work/out" | head -1)
    first=$(sed -n 's/.*first plan \([0-9.]*\) s.*/\1/p' "$work/out" | head -1)
    valid=-
    if [[ -f $work/plan && $status == SOLVED* ]]; then  # empty: the empty plan
      if "$seaplan" validate "$file" "$work/p.pddl" "$work/plan" >/dev/null 2>&1; then
        valid=yes solved=$((solved + 1))
      else
        valid=NO
      fi
    fi
    total=$((total + 1))
    printf '%-28s %-22s %12s %s\n' "$name" "${status:-none}" "${first:--}" "$valid"
  done
done
echo "scaled_suite $suite: $solved/$total with a valid first plan within $cpu CPU s"
if [[ $quick == 1 && $solved -lt $total ]]; then exit 1; fi
