# `run --shard i/n` and `merge`: a small sweep on the bundled samples, computed by one process and as 2 shards in
# their own folders (and as 3 shards sharing one folder), merges into results.jsonl / results.csv equal to the single
# process's apart from the execution fields (timings, host, rank). merge refuses folders of another config and
# incomplete shards with one line; a malformed --shard is refused before anything is written.
source "$(dirname "$0")/common.sh"
cd "$SOURCE_DIR"
small_sweep_config "$WORK/tiny.yaml" tiny_sweep
run() { "$BLOCKLAB" run "$WORK/tiny.yaml" --data-root samples --threads 1 --quiet "$@" >/dev/null; }
run --out "$WORK/single"
run --out "$WORK/shard0" --shard 0/2
run --out "$WORK/shard1" --shard 1/2
[ -f "$WORK/shard0/results.shard-0-of-2.jsonl" ] || die "shard 0 wrote no results.shard-0-of-2.jsonl"
[ ! -e "$WORK/shard0/results.jsonl" ] || die "a shard wrote results.jsonl as if it were the whole run"
cells0=$(wc -l <"$WORK/shard0/results.shard-0-of-2.jsonl"); cells1=$(wc -l <"$WORK/shard1/results.shard-1-of-2.jsonl")
[ $((cells0 + cells1)) -eq 15 ] || die "the shards computed $cells0 + $cells1 cells, not the 15 of the sweep"
"$BLOCKLAB" merge "$WORK/shard0" "$WORK/shard1" --out "$WORK/merged" >"$WORK/merge.txt"
grep -q "^15 cells from 2 run folders: 15 ok, 0 failed" "$WORK/merge.txt" || die "merge summary: $(tail -2 "$WORK/merge.txt")"
same_results_apart_from_execution "$WORK/single" "$WORK/merged"

# Three shards writing into one folder, merged in place; a run over the merged folder then finds every cell cached.
for i in 0 1 2; do run --out "$WORK/shared" --shard $i/3; done
"$BLOCKLAB" merge "$WORK/shared" --out "$WORK/shared" >/dev/null
same_results_apart_from_execution "$WORK/single" "$WORK/shared"
"$BLOCKLAB" run "$WORK/tiny.yaml" --data-root samples --out "$WORK/shared" --quiet | grep -q "^15 cells: 0 computed, 15 cached" \
  || die "the merged folder is not a complete cache"
echo "ok: the shared folder is a complete cache after the merge"

# Every record names its host; outside MPI the rank is null.
/usr/bin/python3 - "$WORK/merged/results.jsonl" "$(hostname)" <<'PY'
import json, sys
records = [json.loads(line) for line in open(sys.argv[1])]
assert all(r["host"] == sys.argv[2] and r["rank"] is None for r in records), [(r["host"], r["rank"]) for r in records]
print(f"ok: every record names host {sys.argv[2]}, no rank")
PY

# Refusals: another config, a missing shard, a malformed --shard.
sed 's/name: tiny_sweep/name: other_sweep/' "$WORK/tiny.yaml" >"$WORK/other.yaml"
"$BLOCKLAB" run "$WORK/other.yaml" --data-root samples --out "$WORK/other" --quiet --shard 1/2 >/dev/null
expect_error "merge: .*/other is a run of another plan than .*/shard0 \(experiment \"tiny_sweep\" vs \"other_sweep\"\)" \
  "$BLOCKLAB" merge "$WORK/shard0" "$WORK/other" --out "$WORK/refused"
expect_error "merge: $cells1 of 15 cells are in none of the 1 run folders \(first: .*\)" \
  "$BLOCKLAB" merge "$WORK/shard0" --out "$WORK/refused"
[ ! -e "$WORK/refused" ] || die "a refused merge created its output folder"
expect_error "error: --shard: shard index 2 is out of range for 2 shards" \
  "$BLOCKLAB" run "$WORK/tiny.yaml" --data-root samples --out "$WORK/bad" --shard 2/2
expect_error "error: --shard: expected i/n" "$BLOCKLAB" run "$WORK/tiny.yaml" --data-root samples --out "$WORK/bad" --shard 1
[ ! -e "$WORK/bad" ] || die "a refused --shard created a run folder"
