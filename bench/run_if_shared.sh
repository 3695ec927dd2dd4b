#!/usr/bin/env bash
# run_if_shared.sh PATH COMMAND...: runs COMMAND when PATH (shared data)
# exists; otherwise exits 77 (ctest: skipped) with the reason, or 1 under CI
# (environment variable CI set), where the shared folder must be present.
set -euo pipefail
needed=$1
shift
if [[ ! -e "$needed" ]]; then
  echo "shared data $needed not found (set SEAPLAN_SHARED)" >&2
  if [[ -n "${CI:-}" ]]; then exit 1; fi
  echo "skipped: needs $needed"
  exit 77
fi
exec "$@"
