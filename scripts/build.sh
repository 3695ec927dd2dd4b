#!/usr/bin/env bash
# Installs the dependencies (scripts/install-deps.sh) and builds seaplan into
# build/ (binaries in build/bin). Idempotent; incremental on reruns.
#   BUILD_DIR=build  BUILD_TYPE=RelWithDebInfo  JOBS=<cores>
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-$(nproc)}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}" ${CMAKE_ARGS:-}
cmake --build "$BUILD_DIR" -j "$JOBS"
