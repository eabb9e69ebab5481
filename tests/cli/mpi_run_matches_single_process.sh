# `mpirun -np 2 blocklab run` (BLOCKLAB_MPI builds; registered by tests/CMakeLists.txt with the mpirun found): the
# merged results equal a 1-process run's apart from the execution fields; every record names its host and rank;
# only rank 0 prints; a job killed midway resumes with every cell exactly once; a failing cell is recorded and the
# other cells still run.
#   bash mpi_run_matches_single_process.sh <blocklab> <source dir> <shared data dir> <mpirun>
source "$(dirname "$0")/common.sh"
MPIRUN=$4
cd "$SOURCE_DIR"
mpi() { "$MPIRUN" --allow-run-as-root --oversubscribe --bind-to none -np 2 "$@"; }
small_sweep_config "$WORK/tiny.yaml" tiny_mpi
"$BLOCKLAB" run "$WORK/tiny.yaml" --data-root samples --threads 1 --quiet --out "$WORK/single" >/dev/null
mpi "$BLOCKLAB" run "$WORK/tiny.yaml" --data-root samples --threads 1 --out "$WORK/ranks" >"$WORK/stdout" 2>"$WORK/stderr" \
  || die "mpirun failed: $(cat "$WORK/stderr")"
same_results_apart_from_execution "$WORK/single" "$WORK/ranks"
[ "$(grep -c '^15 cells: 15 computed, 0 cached, 0 failed' "$WORK/stdout")" -eq 1 ] \
  || die "expected one summary (rank 0's): $(grep cells: "$WORK/stdout")"
grep -q "blocklab: run: 15 cells .*spread over Open MPI .*2 ranks on 1 host" "$WORK/stderr" \
  || die "the plan line does not name the ranks: $(head -2 "$WORK/stderr")"
/usr/bin/python3 - "$WORK/ranks" "$(hostname)" <<'PY'
import json, sys
records = [json.loads(line) for line in open(sys.argv[1] + "/results.jsonl")]
assert all(r["host"] == sys.argv[2] and r["rank"] in (0, 1) for r in records), [(r["host"], r["rank"]) for r in records]
provenance = json.load(open(sys.argv[1] + "/provenance.json"))
assert "2 ranks" in provenance["dispatch"], provenance["dispatch"]
ranks = sorted({r["rank"] for r in records})
print(f"ok: every record names host {sys.argv[2]} and its rank (ranks used: {ranks}); provenance: {provenance['dispatch']}")
PY

# Kill the job (every rank, SIGKILL) once a cell file exists; the next job computes only what is missing. Cells of
# a fraction of a second each, so the kill lands midway.
cat >"$WORK/slow.yaml" <<'YAML'
schema: 1
name: slow_mpi
images: [hdr/Desk.exr, hdr/hdr-rgb-arboretum.hdr, ldr/kodak/kodim03.png]
metrics: [psnr, log2rgb]
formats:
  - {format: munkberg, options: {preset: fast}}
  - {format: banterle, options: {preset: medium, bpp: [4, 8]}}
YAML
"$BLOCKLAB" run "$WORK/slow.yaml" --data-root samples --threads 1 --quiet --out "$WORK/slow_single" >/dev/null
"$MPIRUN" --allow-run-as-root --oversubscribe --bind-to none -np 2 \
  "$BLOCKLAB" run "$WORK/slow.yaml" --data-root samples --threads 1 --quiet --out "$WORK/killed" >/dev/null 2>&1 &
launcher=$!
for _ in $(seq 1 600); do
  if [ -d "$WORK/killed/cells" ] && [ -n "$(find "$WORK/killed/cells" -name '*.json' | head -1)" ]; then break; fi
  sleep 0.05
done
for rank in $(pgrep -P "$launcher"); do kill -9 "$rank" 2>/dev/null || true; done
kill -9 "$launcher" 2>/dev/null || true
wait "$launcher" 2>/dev/null || true
mpi "$BLOCKLAB" run "$WORK/slow.yaml" --data-root samples --threads 1 --out "$WORK/killed" >"$WORK/resumed.txt" 2>/dev/null \
  || die "the resumed job failed"
summary=$(grep -E "^9 cells: " "$WORK/resumed.txt") || die "resume: $(tail -2 "$WORK/resumed.txt")"
[[ "$summary" =~ ^9\ cells:\ ([1-9][0-9]*)\ computed,\ ([1-9][0-9]*)\ cached,\ 0\ failed ]] \
  || die "the kill did not land midway, or cells failed: $summary"
same_results_apart_from_execution "$WORK/slow_single" "$WORK/killed"
echo "ok: killed job resumed: $summary"

# A cell that fails (bc7 with a mode it refuses) is recorded by the rank that ran it; the others complete.
cat >"$WORK/failing.yaml" <<'YAML'
schema: 1
name: failing_mpi
images: [ldr/kodak/kodim03.png, ldr/textures/ldr-rgba-base.png]
metrics: [psnr]
formats:
  - {format: bc7, options: {modes: "9"}}
  - format: fp16
  - {format: bc4, options: {preset: fast}}
YAML
status=0
mpi "$BLOCKLAB" run "$WORK/failing.yaml" --data-root samples --threads 1 --quiet --out "$WORK/failing" \
  >"$WORK/stdout" 2>"$WORK/stderr" || status=$?
[ "$status" -ne 0 ] || die "a job with failed cells exited 0"
grep -q "2 of 6 cells failed (first: ldr/kodak/kodim03.png bc7" "$WORK/stderr" || die "stderr: $(cat "$WORK/stderr")"
grep -q "^6 cells: 4 computed, 0 cached, 2 failed" "$WORK/stdout" || die "stdout: $(tail -2 "$WORK/stdout")"
echo "ok: failed cells recorded, the other 4 computed"
