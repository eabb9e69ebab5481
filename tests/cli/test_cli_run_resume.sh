# A finished experiment re-run reports every cell cached; a run killed midway and re-run ends with every cell
# exactly once in results.jsonl (and the same cells as an uninterrupted run).
source "$(dirname "$0")/common.sh"
cd "$SOURCE_DIR"
"$BLOCKLAB" run configs/quickstart.yaml --out "$WORK/full" --quiet >"$WORK/first.txt"
"$BLOCKLAB" run configs/quickstart.yaml --out "$WORK/full" --quiet >"$WORK/second.txt"
grep -qE "^([0-9]+) cells: 0 computed, \1 cached, 0 failed" "$WORK/second.txt" || die "re-run recomputed cells: $(tail -3 "$WORK/second.txt")"
cmp "$WORK/full/results.jsonl" <(cat "$WORK/full/results.jsonl") >/dev/null
echo "ok: re-run served every cell from the cache"

# Kill a run as soon as its first cell file exists, then resume it.
"$BLOCKLAB" run configs/quickstart.yaml --out "$WORK/killed" --quiet --threads 1 >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  if [ -d "$WORK/killed/cells" ] && [ -n "$(find "$WORK/killed/cells" -name '*.json' | head -1)" ]; then break; fi
  sleep 0.05
done
kill -9 $pid 2>/dev/null || true
wait $pid 2>/dev/null || true
"$BLOCKLAB" run configs/quickstart.yaml --out "$WORK/killed" --quiet >"$WORK/resumed.txt"
/usr/bin/python3 - "$WORK/full/results.jsonl" "$WORK/killed/results.jsonl" <<'PY'
import json, sys
full = [json.loads(l) for l in open(sys.argv[1])]
resumed = [json.loads(l) for l in open(sys.argv[2])]
keys = [r["key"] for r in resumed]
assert len(keys) == len(set(keys)), "a cell appears twice after resuming"
assert keys == [r["key"] for r in full], "resumed run does not hold exactly the cells of a full run, in order"
for a, b in zip(full, resumed):
    assert a["metrics"] == b["metrics"], f"metrics differ for {a['image']} {a['format']}"
print(f"ok: {len(keys)} cells, each exactly once, metrics identical to the uninterrupted run")
PY
