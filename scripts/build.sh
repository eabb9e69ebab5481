#!/usr/bin/env bash
# Configures and builds blocklab (Release, invariant floating point) into build/ (or $BLOCKLAB_BUILD_DIR).
# Extra arguments go to the CMake configure step, e.g. scripts/build.sh -DBLOCKLAB_BENCHMARKS=ON
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BLOCKLAB_BUILD_DIR:-$root/build}
jobs=${BLOCKLAB_JOBS:-$(nproc)}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j "$jobs"
