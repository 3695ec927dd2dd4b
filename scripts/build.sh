#!/usr/bin/env bash
# Installs the dependencies (scripts/install-deps.sh) and builds seaplan into
# build/ (binaries in build/bin, the operator console's static files in
# build/bin/console). Idempotent; incremental on reruns.
#   BUILD_DIR=build  BUILD_TYPE=RelWithDebInfo  JOBS=<cores>
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-$(nproc)}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}" ${CMAKE_ARGS:-}
cmake --build "$BUILD_DIR" -j "$JOBS"

# The operator console (clients/console, TypeScript): npm ci when the lock
# file changed, then bundled beside the server binary, which serves it at /.
# Playwright's own browser download is skipped: the tests use Debian's Chromium.
if command -v npm >/dev/null 2>&1; then
  (
    cd clients/console
    if [[ ! -f node_modules/.package-lock.json || package-lock.json -nt node_modules/.package-lock.json ]]; then
      PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error
    fi
    CONSOLE_OUT_DIR="$OLDPWD/$BUILD_DIR/bin/console" npm run --silent build
  )
else
  echo "build: npm not found: the operator console is not built (scripts/install-deps.sh installs it)" >&2
fi
