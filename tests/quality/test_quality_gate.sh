#!/usr/bin/env bash
# The quality gate: every format x preset on the bundled samples (configs/quality/gate.yaml) must be no worse than
# tests/quality/baseline.csv in any metric beyond tests/quality/tolerances.csv. Improvements and encode-time changes
# are printed, not failed on. Usage: test_quality_gate.sh BLOCKLAB REPO_ROOT
set -euo pipefail
blocklab=$1
root=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$blocklab" run "$root/configs/quality/gate.yaml" --out "$out/run" --data-root "$root/samples" --threads 0 > "$out/log"
python3 "$root/scripts/quality_gate.py" check "$out/run/results.csv" "$root/tests/quality/baseline.csv" \
  --tolerances "$root/tests/quality/tolerances.csv"
