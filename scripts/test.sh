#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite; exits non-zero on any failure.
# Tests that need the shared benchmark/chart data read it from SEAPLAN_SHARED
# (default: ../shared beside the clone) and skip with a reason when absent
# (under CI, with the environment variable CI set, they fail instead).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
BUILD_DIR=${BUILD_DIR:-build}
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "${JOBS:-$(nproc)}" "$@"
