#!/usr/bin/env bash
# Kill -9 trials: seaplan-server SIGKILLed at a random moment of each of N
# running case C missions (default 20) and restarted on the same port and
# data folder, while seaplan-sim executes the mission. Each trial checks that
# the mission completes, no acknowledged report is lost or stored twice, no
# plan version is duplicated, a watch from the start replays the mission,
# and the database passes PRAGMA integrity_check. Prints one line per trial
# and the total; exits non-zero on any failure. ctest runs the same test
# with 3 trials.
#   bash scripts/kill9_trials.sh [N]        (SEAPLAN_KILL_SEED=S repeats a run)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
cmake --build "$BUILD_DIR" --target seaplan-server seaplan-sim outage_e2e_test -j "${JOBS:-2}" >/dev/null
SEAPLAN_KILL_TRIALS="${1:-20}" "$BUILD_DIR/tests/outage_e2e_test" \
  --gtest_filter='OutageE2eTest.ServerKilledAtRandomMomentsLosesNothing'
