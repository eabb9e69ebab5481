#!/usr/bin/env bash
# README command 2 (and what CI runs through .ci/run): install the Debian packages, build, and pass every test.
#  1. Release build (invariant floating point) and the whole CTest suite (labels unit, contract, stress, golden, cli).
#  2. An ASan + UBSan build running the unit and stress tests.
# The full data set is taken from ../shared/data when it is there (BLOCKLAB_DATA_ROOT overrides).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${BLOCKLAB_JOBS:-$(nproc)}
"$root/scripts/install-deps.sh"

echo "== release build and full test suite" >&2
BLOCKLAB_BUILD_DIR="$root/build" "$root/scripts/build.sh"
(cd "$root/build" && ctest --output-on-failure -j "$jobs" --timeout 600)

if [ "${BLOCKLAB_SKIP_SANITIZE:-0}" != "1" ]; then
  echo "== sanitizer build (ASan + UBSan): unit and stress tests" >&2
  BLOCKLAB_BUILD_DIR="$root/build-sanitize" "$root/scripts/build.sh" -DBLOCKLAB_SANITIZE=ON
  (cd "$root/build-sanitize" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
     ctest --output-on-failure -j "$jobs" -L 'unit|stress' --timeout 900)
fi
