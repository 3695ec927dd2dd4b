#!/usr/bin/env bash
# Sanitizer runs. Exits non-zero on any finding (every sanitizer aborts on its
# first report) or failing test.
#
#   asan: AddressSanitizer + UndefinedBehaviorSanitizer (and LeakSanitizer)
#         over every library, binary, test and benchmark in build-asan/ (the
#         benchmarks because bench/ holds tests too: the collision-avoidance
#         encounter suite, the mission generator's); the whole ctest suite
#         but the operator console's JavaScript (console_* and the console's
#         render benchmark: no C++ of their own; the server paths the browser
#         drives are run by tests/server/console_api_e2e_test.cc). Extra
#         arguments go to ctest.
#   tsan: ThreadSanitizer in build-tsan/, only what runs threads and its
#         tests: the server (work pool, mission coordinator, route caches,
#         caller rate limits, authentication; in-process, and as binaries
#         with the simulation client, over TLS, and as replicas sharing
#         PostgreSQL with replan leases and the change feed), the storage
#         backends, the mission engine's chart-routing cache, the Level-2
#         optimiser's PSO threads, stop tokens, the chart's per-thread
#         obstacle queries.
#   ci:   what CI runs after the test command (.ci/run), chosen to fit its
#         time limit: asan without the tests labelled `data` (the real charts
#         and benchmark problems: minutes each under ASan, and what they add
#         is GDAL's and the planner's work on bigger inputs, which the unit
#         tests run on small ones) and without the benchmarks' smoke runs,
#         then tsan.
#
#   scripts/sanitize.sh [asan|tsan|all|ci] [ctest arguments for asan]   (default all)
#   JOBS=<cores>  CMAKE_ARGS=...            as scripts/build.sh
#
# Both builds compile with -O1 -g1: line tables are all a report needs, and
# an ASan+UBSan compile costs half of what it does with -O2 -g (validator.cc:
# 11.8 CPU-s against 23.2; a plain -O2 -g compile 7.6). The test sources
# themselves compile at -O0 (SEAPLAN_TEST_OPTIMIZATION, cmake/Seaplan.cmake):
# instrumented GoogleTest bodies are most of an instrumented build's time
# (validator_test.cc: 45.7 CPU-s at -O1, 20.2 at -O0), and the code under test
# keeps -O1. The code's own wall-clock budgets are stretched by
# SEAPLAN_WALL_CLOCK_SCALE (CMakeLists.txt) so that the slower builds'
# searches find the same plans.
# Suppressions (third-party false positives only, one reason per entry):
# scripts/sanitizers/*.supp.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-all}
case "$what" in asan | tsan | all | ci) ;; *)
  echo "usage: $0 [asan|tsan|all|ci] [ctest arguments for asan]" >&2
  exit 2
  ;;
esac
shift $(($# > 0 ? 1 : 0))
asan_ctest_args=("$@")
if [[ "$what" == ci ]]; then asan_ctest_args+=(-LE 'data|bench-smoke'); fi
bash scripts/install-deps.sh
JOBS=${JOBS:-$(nproc)}
supp="$PWD/scripts/sanitizers"
configure() {  # dir, sanitizers, benchmarks ON/OFF
  cmake -S . -B "$1" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSEAPLAN_BUILD_BENCH="$3" \
    -DSEAPLAN_SANITIZE="$2" -DSEAPLAN_TEST_OPTIMIZATION=-O0 \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
    "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" ${CMAKE_ARGS:-}
}
elapsed() { echo "sanitize: $1 took $((SECONDS - $2)) s"; }

if [[ "$what" != tsan ]]; then
  start=$SECONDS
  configure build-asan address,undefined ON
  cmake --build build-asan -j "$JOBS"
  elapsed "asan build" "$start"
  start=$SECONDS
  ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:detect_stack_use_after_return=1" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$supp/ubsan.supp" \
    LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0" \
    ctest --test-dir build-asan --output-on-failure -j "$JOBS" -E '^console_|console_render' \
    "${asan_ctest_args[@]}"
  elapsed "asan tests" "$start"
fi

if [[ "$what" != asan ]]; then
  tsan_tests=(common_test chart_risk_test route_test route_planner_test mission_test
    storage_test server_core_test server_auth_test server_e2e_test server_binary_test
    access_matrix_e2e_test vessel_token_e2e_test failover_e2e_test mission_e2e_test)
  start=$SECONDS
  configure build-tsan thread OFF
  cmake --build build-tsan -j "$JOBS" --target "${tsan_tests[@]}" seaplan-server seaplan-sim
  elapsed "tsan build" "$start"
  start=$SECONDS
  failed=()
  for t in "${tsan_tests[@]}"; do
    echo "sanitize: tsan $t"
    if ! TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$supp/tsan.supp" \
      "build-tsan/tests/$t" --gtest_brief=1; then
      failed+=("$t")
    fi
  done
  elapsed "tsan tests" "$start"
  if [[ ${#failed[@]} -gt 0 ]]; then
    echo "sanitize: tsan failures in: ${failed[*]}" >&2
    exit 1
  fi
fi
echo "sanitize: clean"
