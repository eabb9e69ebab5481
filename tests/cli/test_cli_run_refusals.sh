# `blocklab run` on hostile configs: a failing cell also prints one line on stderr; an image path that climbs out
# of the data root is refused before it is opened; a sweep above --max-cells (default 100000) is refused from the
# list lengths in well under a second and 100 MB; two entries with one label are refused. Nothing is written then.
source "$(dirname "$0")/common.sh"
cd "$SOURCE_DIR"
config() { printf 'schema: 1\nname: %s\nimages: [%s]\nmetrics: [psnr]\nformats:\n%s\n' "$1" "$2" "$3" >"$WORK/$1.yaml"; }

# A cell that fails: its error is in the table on stdout and on one stderr line.
config bad_cell ldr/kodak/kodim03.png '  - {format: bc7, options: {modes: "9"}}'
expect_error "1 of 1 cells failed \(first: ldr/kodak/kodim03.png bc7: .*modes" \
  "$BLOCKLAB" run "$WORK/bad_cell.yaml" --out "$WORK/bad_cell" --data-root samples --quiet
grep -q "1 failed" "$WORK/stdout" || die "the summary on stdout is missing: $(cat "$WORK/stdout")"

# '..' out of the data root: refused, nothing read (no run folder, no bytes of the file in the message).
config escape ../../../etc/passwd '  - format: fp16'
expect_error "images\[0\]: '../../../etc/passwd' leads outside the data root" \
  "$BLOCKLAB" run "$WORK/escape.yaml" --out "$WORK/escape" --data-root samples
[ ! -e "$WORK/escape" ] || die "a run folder was created for a refused config"
grep -q "root:" "$WORK/stderr" && die "the error shows the file's content"

# Two entries under one label.
config twins ldr/kodak/kodim03.png '  - {format: bc1, label: x}
  - {format: bc1, label: x, options: {search: fast}}'
expect_error "formats\[1\] has the label 'x', already used by formats\[0\]" \
  "$BLOCKLAB" run "$WORK/twins.yaml" --out "$WORK/twins" --data-root samples

# 3000 x 64 x 32 x 2 x 2 = 24,576,000 cells: refused before expansion, with the lists and their product.
seeds=$(seq -s, 1 3000); partitions=$(seq -s, 1 64); iterations=$(seq -s, 1 32)
config sweep ldr/kodak/kodim03.png "  - format: bc7
    options: {seed: [$seeds], partitions_to_refine: [$partitions], refine_iterations: [$iterations], pbit_search: [\"on\", \"off\"], rotation_search: [\"on\", \"off\"]}"
/usr/bin/python3 - "$BLOCKLAB" "$WORK" <<'PY'
import resource, subprocess, sys, time
blocklab, work = sys.argv[1], sys.argv[2]
start = time.monotonic()
run = subprocess.run([blocklab, "run", f"{work}/sweep.yaml", "--out", f"{work}/sweep", "--data-root", "samples"],
                     capture_output=True, text=True, timeout=60)
seconds = time.monotonic() - start
rss_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
lines = run.stderr.splitlines()
assert run.returncode != 0 and len(lines) == 1, (run.returncode, run.stderr)
expected = ("the experiment expands to 24576000 cells, above the limit of 100000 (raise it with --max-cells N): "
            "formats[0] bc7: seed (3000) x partitions_to_refine (64) x refine_iterations (32) x pbit_search (2) x "
            "rotation_search (2) = 24576000")
assert expected in lines[0], lines[0]
assert seconds < 1.0 and rss_mb < 100, f"refusal took {seconds:.2f} s and {rss_mb:.0f} MB"
print(f"ok: refused in {seconds:.3f} s with {rss_mb:.0f} MB peak RSS: {lines[0]}")
PY
[ ! -e "$WORK/sweep" ] || die "a run folder was created for a refused sweep"

# --max-cells lowers (or raises) the bound, and the plan's size is printed before work starts.
config small ldr/kodak/kodim03.png '  - {format: fp16, options: {seed: [1, 2, 3]}}'
expect_error "3 cells, above the limit of 2 .*seed \(3\) = 3; total 3 treatments x at least 1 image" \
  "$BLOCKLAB" run "$WORK/small.yaml" --out "$WORK/small" --data-root samples --max-cells 2
"$BLOCKLAB" run "$WORK/small.yaml" --out "$WORK/small" --data-root samples --max-cells 3 >/dev/null 2>"$WORK/plan"
head -1 "$WORK/plan" | grep -q "blocklab: run: 3 cells (3 format variants and ablations x 1 images)" \
  || die "no plan line: $(cat "$WORK/plan")"
size=$(stat -c %s "$WORK/small/resolved.json")
echo "ok: resolved.json of 3 cells is $size bytes"
echo "all run refusals passed"
