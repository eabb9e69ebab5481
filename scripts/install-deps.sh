#!/usr/bin/env bash
# Installs every Debian 12 package blocklab needs. Idempotent: packages already present are skipped by apt-get,
# and apt-get update runs only when something is missing. Run as root (or through sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  # required numerical libraries
  libceres-dev libeigen3-dev libopenexr-dev libnlopt-cxx-dev
  # configuration, CLI, parallelism, results
  libyaml-cpp-dev libcli11-dev libtbb-dev nlohmann-json3-dev libssl-dev
  # image I/O and interval arithmetic
  libpng-dev libboost-dev
  # optional MPI cell dispatcher (mpirun -np N blocklab run; CMake BLOCKLAB_MPI, docs/cluster.md)
  libopenmpi-dev openmpi-bin
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # reference encoders and independent decoders (benchmarks and oracle tests)
  libsquish-dev libnvtt-bin libnvtt-dev astcenc python3-pil python3-numpy
  # notebooks (Debian's python3 sees these; the pyenv python3 on some images does not)
  jupyter-nbconvert python3-nbclient python3-nbformat python3-ipykernel python3-matplotlib python3-pandas
  # the report test renders `blocklab report`'s page in headless Chromium (tests/cli/test_cli_report.sh)
  chromium
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present" >&2
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
