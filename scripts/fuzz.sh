#!/usr/bin/env bash
# The libFuzzer targets of tests/fuzz (README there), built with clang and
# ASan + UBSan in build-fuzz/.
#   scripts/fuzz.sh build                  configure + build every target
#   scripts/fuzz.sh smoke [SECONDS]        build, then run each target SECONDS (default 20)
#                                          from its seed corpus; non-zero on any finding
#   scripts/fuzz.sh run TARGET SECONDS     one long run; the corpus grows in
#                                          build-fuzz/corpus/TARGET, findings in build-fuzz/findings/TARGET
# Targets: gateway_json chart_upload scenario plan.  FUZZ_BUILD_DIR=build-fuzz  JOBS=<cores>
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${FUZZ_BUILD_DIR:-build-fuzz}
JOBS=${JOBS:-$(nproc)}
TARGETS=(gateway_json chart_upload scenario plan)

build() {
  bash scripts/install-deps.sh >/dev/null
  local launcher=()
  if command -v ccache >/dev/null 2>&1; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  fi
  # -O1 and line tables only: the sanitizers' usual build, and half the
  # compile time of -O2 -g.
  CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DSEAPLAN_BUILD_FUZZ=ON -DSEAPLAN_SANITIZE=address,undefined -DSEAPLAN_BUILD_BENCH=OFF \
    "${launcher[@]}" ${CMAKE_ARGS:-} >/dev/null
  cmake --build "$BUILD_DIR" -j "$JOBS" --target "${TARGETS[@]/%/_fuzz}"
}

# run TARGET SECONDS: the seed corpus is read, new inputs go to a scratch
# corpus so the repository's seeds stay small.
run() {
  local target=$1 seconds=$2
  local corpus="$BUILD_DIR/corpus/$target" findings="$BUILD_DIR/findings/$target"
  mkdir -p "$corpus" "$findings"
  local dict=()
  if [[ -f tests/fuzz/$target.dict ]]; then dict=(-dict="tests/fuzz/$target.dict"); fi
  # Leaks: GDAL and gRPC keep process-wide caches that LeakSanitizer reports.
  ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 \
    "$BUILD_DIR/bin/${target}_fuzz" "$corpus" "tests/fuzz/corpus/$target" "${dict[@]}" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
    -artifact_prefix="$findings/" -print_final_stats=1
}

case "${1:-smoke}" in
  build) build ;;
  smoke)
    build
    for t in "${TARGETS[@]}"; do
      log="$BUILD_DIR/findings/$t.smoke.log"
      mkdir -p "$BUILD_DIR/findings"
      if ! run "$t" "${2:-20}" >"$log" 2>&1; then
        tail -n 60 "$log"
        echo "fuzz smoke: $t FAILED (log: $log, input in $BUILD_DIR/findings/$t/)"
        exit 1
      fi
      echo "fuzz smoke: $t $(grep -E 'stat::number_of_executed_units' "$log" | tr -s ' ')"
    done
    echo "fuzz smoke: ${#TARGETS[@]} targets, no finding"
    ;;
  run) run "$2" "$3" ;;
  *) echo "usage: $0 build | smoke [SECONDS] | run TARGET SECONDS" >&2; exit 2 ;;
esac
