#!/usr/bin/env bash
# Installs every Debian 12 package needed to build, test and run seaplan.
# Non-interactive and idempotent: packages already present are skipped by apt.
# Used by the README, .ci/run and the Dockerfile, so all three agree.
#
#   scripts/install-deps.sh            build + test + demo dependencies
#   scripts/install-deps.sh --runtime  only the shared libraries the binaries need
set -euo pipefail

# The packages of the libraries the five binaries name (readelf -d, NEEDED).
runtime_packages=(
  libgrpc++1.51 libgrpc29 libprotobuf32 libsqlite3-0 libgeos-c1v5 libgdal32 libnlopt0
  libcpp-httplib0.11 libspdlog1.10 libabsl20220623 libfmt9 ca-certificates libpq5 libssl3
)
build_packages=(
  build-essential cmake ninja-build pkg-config git
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler grpc-proto
  libabsl-dev libsqlite3-dev sqlite3 libpq-dev postgresql
  nginx  # the failover test and bench/replicas run it (as a child, not a service)
  libeigen3-dev libnlopt-cxx-dev libgeos-dev libgdal-dev gdal-bin libpagmo-dev
  libcli11-dev libcpp-httplib-dev libspdlog-dev libfmt-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev clang-format curl libexpat1-dev
  chromium fonts-dejavu-core
  jq  # bench/colav/scenario_seeds.sh reads the sim reports
  python3  # bench/planner/scaled_problems.py writes larger benchmark instances
)

packages=("${build_packages[@]}")
# The operator console is built with Node.js and npm: Debian's, unless a
# node is already installed (e.g. a newer one from elsewhere).
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  build_packages+=(nodejs npm)
  packages=("${build_packages[@]}")
fi
if [[ "${1:-}" == "--runtime" ]]; then packages=("${runtime_packages[@]}"); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
# Packages such as nginx and postgresql start a system service when
# installed (nginx on port 80); the tests start their own instances, so keep
# apt from starting any (policy-rc.d exit 101 = "not allowed") unless the
# machine already has such a policy.
POLICY=/usr/sbin/policy-rc.d
if [[ ! -e $POLICY ]]; then
  printf '#!/bin/sh\nexit 101\n' | $SUDO tee "$POLICY" >/dev/null
  $SUDO chmod 755 "$POLICY"
  trap '$SUDO rm -f "$POLICY"' EXIT
fi
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
