#!/usr/bin/env bash
# README command 1: install the Debian packages, build, and run the quick-start experiment on the bundled samples.
# Prints the results table and leaves the run folder in runs/quickstart.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
cd "$root"
"$root/build/cli/blocklab" run configs/quickstart.yaml "$@"
