# Encoded files are byte-identical with --threads 1, 2 and 4, for every format in the registry.
source "$(dirname "$0")/common.sh"
img="$SOURCE_DIR/samples/hdr/Desk.exr"
formats=$("$BLOCKLAB" list --json | /usr/bin/python3 -c 'import json,sys; print(" ".join(f["name"] for f in json.load(sys.stdin)["formats"]))')
for f in $formats; do
  for t in 1 2 4; do "$BLOCKLAB" encode --threads $t --format "$f" "$img" "$WORK/$f.$t.blk" 2>/dev/null; done
  cmp "$WORK/$f.1.blk" "$WORK/$f.2.blk" || die "$f: threads 1 vs 2 differ"
  cmp "$WORK/$f.1.blk" "$WORK/$f.4.blk" || die "$f: threads 1 vs 4 differ"
  for t in 1 2; do "$BLOCKLAB" decode --threads $t "$WORK/$f.1.blk" "$WORK/$f.$t.pfm"; done
  cmp "$WORK/$f.1.pfm" "$WORK/$f.2.pfm" || die "$f: decoded pixels differ between thread counts"
  echo "ok: $f identical at 1, 2, 4 threads"
done
