#!/usr/bin/env bash
# clang-tidy with the checks in .clang-tidy over every project source in
# build/compile_commands.json (generated protobuf code left out). Builds first
# (scripts/build.sh) so that generated headers exist. Exits non-zero on any
# finding (.clang-tidy makes every warning an error).
#
#   scripts/tidy.sh                    the whole tree
#   scripts/tidy.sh engine/route ...   only sources whose path contains these
#   BUILD_DIR=build  JOBS=<cores>
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-$(nproc)}
BUILD_DIR="$BUILD_DIR" JOBS="$JOBS" bash scripts/build.sh
filters=("$@")
if [[ ${#filters[@]} -eq 0 ]]; then filters=(engine/ proto/convert/ server/ storage/ clients/ bench/ tests/); fi
regexes=()
for f in "${filters[@]}"; do regexes+=("^$PWD/${f%/}/"); done
run-clang-tidy -p "$BUILD_DIR" -j "$JOBS" -quiet "${regexes[@]}"
