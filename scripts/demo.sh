#!/usr/bin/env bash
# The main job: set up and build, start seaplan-server on loopback with its
# SQLite database in ./data, and run the demo mission through it:
#   1. plan the paper's case A (examples/fjord) through the server and print the plan;
#   2. run case C (fuel-triggered replanning) end to end with the simulation
#      client: the server plans, refines and replans, seaplan-sim executes and
#      reports; prints the navigation log and where the mission report is.
# It prints the operator console's URL (the server serves it on its HTTP port).
# Environment: DATA_DIR (default ./data; the server's first start writes its
# admin token to DATA_DIR/admin.token, which the demo uses), OUT_DIR (default ./out), SCENARIO
# (default examples/scenarios/case-c.scenario), HTTP_ADDR (default
# 127.0.0.1:0, any free port), KEEP_SERVING=1 (keep the server and its
# console up after the mission until Ctrl-C).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh

BIN=build/bin
DATA_DIR=${DATA_DIR:-data}
OUT_DIR=${OUT_DIR:-out}
SCENARIO=${SCENARIO:-examples/scenarios/case-c.scenario}
mkdir -p "$DATA_DIR" "$OUT_DIR"
PORT_FILE=$(mktemp)

. scripts/server_lib.sh
cleanup() {
  stop_seaplan_server
  rm -f "$PORT_FILE"
}
trap cleanup EXIT
start_seaplan_server "$BIN" "$PORT_FILE" --grpc-addr 127.0.0.1:0 --http-addr "${HTTP_ADDR:-127.0.0.1:0}" \
  --data-dir "$DATA_DIR" --log-level warn || { echo "demo: seaplan-server exited early" >&2; exit 1; }
# The server wrote its admin token to $DATA_DIR/admin.token at its first
# start (mode 0600); the CLI and the simulation client read it through
# SEAPLAN_TOKEN_FILE (give another admin token's file there to override).
export SEAPLAN_TOKEN_FILE=${SEAPLAN_TOKEN_FILE:-$DATA_DIR/admin.token}
[[ -r "$SEAPLAN_TOKEN_FILE" ]] || {
  echo "demo: no admin token in $SEAPLAN_TOKEN_FILE (the database in $DATA_DIR has tokens from" \
    "elsewhere): set SEAPLAN_TOKEN_FILE to an admin token's file or use another DATA_DIR" >&2
  exit 1
}
GRPC_PORT=$(server_port grpc "$PORT_FILE")
HTTP_PORT=$(server_port http "$PORT_FILE")
SERVER=127.0.0.1:$GRPC_PORT
echo "== seaplan-server on $SERVER (gRPC) and 127.0.0.1:$HTTP_PORT (HTTP), database in $DATA_DIR"
echo "== operator console: http://127.0.0.1:$HTTP_PORT/ (open it in a browser while the demo runs;"
echo "   sign in with the admin token in $SEAPLAN_TOKEN_FILE)"

echo
echo "== Case A: temporal plan from the server"
"$BIN/seaplan" --server "$SERVER" plan examples/fjord/domain.pddl examples/fjord/case-a.pddl --time-limit 5

echo
echo "== Mission loop: $SCENARIO through seaplan-server and seaplan-sim"
"$BIN/seaplan-sim" --server "$SERVER" --scenario "$SCENARIO" --report-dir "$OUT_DIR"
if [[ "${KEEP_SERVING:-0}" == "1" ]]; then
  echo
  echo "== serving the console at http://127.0.0.1:$HTTP_PORT/ until Ctrl-C"
  wait "$SEAPLAN_SERVER_PID"
fi
