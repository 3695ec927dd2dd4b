# Sourced by state_memory.sh, state_speed.sh, run_problems.sh and anytime_vs_peers.sh: reads the options they
# take (--time-limit S, --memory-limit MB, --bench DIR, --cpu-limit S;
# defaults set by the caller in time_s, memory_mb, bench, cpu_s) and the
# problems (domain/pNN) into `problems`, and makes the scratch folder `work`
# (removed on exit).
problems=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --time-limit) time_s=$2; shift 2 ;;
    --memory-limit) memory_mb=$2; shift 2 ;;
    --bench) bench=$2; shift 2 ;;
    --cpu-limit) cpu_s=$2; shift 2 ;;
    *) problems+=("$1"); shift ;;
  esac
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The domain of problem `name` (pNN) in folder `dir`: the per-instance
# domain-pNN.pddl or domain-N.pddl when present, else domain.pddl.
domain_of() {
  local dir=$1 name=$2
  local k=$((10#${name#p}))
  if [[ -f $dir/domain-$name.pddl ]]; then
    echo "$dir/domain-$name.pddl"
  elif [[ -f $dir/domain-$k.pddl ]]; then
    echo "$dir/domain-$k.pddl"
  else
    echo "$dir/domain.pddl"
  fi
}

# "yes" when $work/plan holds a plan that `EXE validate` accepts for DOMAIN
# and PROBLEM, "NO" when it rejects it, "-" when there is no plan (the
# callers remove the file first; an empty file is the empty plan).
plan_validity() {
  local exe=$1 domain=$2 problem=$3
  if [[ ! -f $work/plan ]]; then
    echo -
  elif "$exe" validate "$domain" "$problem" "$work/plan" >/dev/null 2>&1; then
    echo yes
  else
    echo NO
  fi
}

# The median of the numbers on standard input, one a line (nothing for none).
median() {
  sort -g | awk '{ v[NR] = $1 } END { if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'
}
