# Shared helpers for the command-line tests. Each test script is run by CTest as
#   bash <script> <blocklab binary> <source dir> <shared data dir>
set -euo pipefail
BLOCKLAB=$1
SOURCE_DIR=$2
SHARED_DATA=$3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

die() { echo "FAIL: $*" >&2; exit 1; }

# expect_error <pattern> <command...>: the command must exit non-zero with exactly one line on stderr matching pattern.
expect_error() {
  local pattern=$1; shift
  local status=0
  "$@" >"$WORK/stdout" 2>"$WORK/stderr" || status=$?
  [ "$status" -ne 0 ] || die "expected failure, got exit 0: $*"
  [ "$(wc -l <"$WORK/stderr")" -eq 1 ] || die "expected a one-line error from '$*', got: $(cat "$WORK/stderr")"
  grep -qE "$pattern" "$WORK/stderr" || die "error of '$*' does not match /$pattern/: $(cat "$WORK/stderr")"
  echo "ok: $(cat "$WORK/stderr")"
}

need_shared_data() {
  if [ ! -d "$SHARED_DATA/hdr" ]; then echo "shared data not found at $SHARED_DATA: skipped"; exit 77; fi
}

# small_sweep_config <file> <name>: 15 cells on the bundled samples (3 images x fp16, rgbe, 2 bc1 seeds, bc4),
# each a fraction of a second.
small_sweep_config() {
  cat >"$1" <<YAML
schema: 1
name: $2
images: [hdr/Desk.exr, hdr/blender_world_sunset.exr, ldr/kodak/kodim03.png]
metrics: [psnr, log2rgb]
formats:
  - format: fp16
  - format: rgbe
  - {format: bc1, options: {preset: fast, seed: [1, 2]}}
  - {format: bc4, options: {preset: fast}}
YAML
}

# same_results_apart_from_execution <run dir A> <run dir B>: the results.jsonl and results.csv of both runs agree
# apart from the execution fields (timings, host, rank: experiments/results_writer.h kExecutionFields).
same_results_apart_from_execution() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import csv, json, sys
EXECUTION = {"encode_seconds", "decode_seconds", "host", "rank"}
def records(folder):
    return [{k: v for k, v in json.loads(line).items() if k not in EXECUTION} for line in open(folder + "/results.jsonl")]
def rows(folder):
    table = list(csv.reader(open(folder + "/results.csv", newline="")))
    drop = {i for i, name in enumerate(table[0]) if name in EXECUTION}
    return [[v for i, v in enumerate(row) if i not in drop] for row in table]
a, b = sys.argv[1], sys.argv[2]
ra, rb = records(a), records(b)
assert len(ra) == len(rb), f"{len(ra)} records in {a}, {len(rb)} in {b}"
for x, y in zip(ra, rb):
    differing = {k: (x.get(k), y.get(k)) for k in set(x) | set(y) if x.get(k) != y.get(k)}
    assert not differing, f"{x.get('image')} {x.get('label')} differs: {differing}"
assert rows(a) == rows(b), "results.csv differs beyond the execution columns"
print(f"ok: the {len(ra)} records of {b} equal those of {a} apart from the execution fields")
PY
}
