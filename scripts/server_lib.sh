# Shell functions shared by the scripts that run a seaplan-server of their
# own on loopback (scripts/demo.sh, bench/colav/scenario_seeds.sh). Source it:
#   . scripts/server_lib.sh

# start_seaplan_server BIN_DIR PORT_FILE [seaplan-server flags...]
# Starts BIN_DIR/seaplan-server in the background with --port-file PORT_FILE
# (give --grpc-addr 127.0.0.1:0 and friends for ports the system picks), sets
# SEAPLAN_SERVER_PID and waits up to 10 s for the port file's grpc= line.
# Returns 1 when the server exits before writing it.
start_seaplan_server() {
  local bin_dir=$1 port_file=$2
  shift 2
  "$bin_dir/seaplan-server" "$@" --port-file "$port_file" &
  SEAPLAN_SERVER_PID=$!
  for _ in $(seq 1 100); do
    grep -q '^grpc=' "$port_file" 2>/dev/null && return 0
    kill -0 "$SEAPLAN_SERVER_PID" 2>/dev/null || return 1
    sleep 0.1
  done
}

# stop_seaplan_server: stops the server start_seaplan_server started (TERM,
# then waits for it); does nothing when none was started.
stop_seaplan_server() {
  [ -n "${SEAPLAN_SERVER_PID:-}" ] || return 0
  kill -TERM "$SEAPLAN_SERVER_PID" 2>/dev/null || true
  wait "$SEAPLAN_SERVER_PID" 2>/dev/null || true
}

# server_port NAME PORT_FILE: the port the server wrote for NAME (grpc, http).
server_port() {
  sed -n "s/^$1=//p" "$2"
}
