# `blocklab compare` agrees with an independent numpy implementation of SPECS.md 1a (log2[RGB], astcenc
# normalisation) and 1b (mPSNR, stops -10..+10) to 1e-6 relative, on HDR pairs (reference vs its rgbe and fp16 codings).
source "$(dirname "$0")/common.sh"
images=("$SOURCE_DIR"/samples/hdr/*)
if [ -d "$SHARED_DATA/hdr" ]; then images+=("$SHARED_DATA/hdr/memorial.hdr" "$SHARED_DATA/hdr/Desk.exr" "$SHARED_DATA/hdr/grace.hdr"); fi
for img in "${images[@]}"; do
  "$BLOCKLAB" convert "$img" "$WORK/ref.pfm"
  for f in rgbe fp16; do
    "$BLOCKLAB" encode --format $f "$img" "$WORK/t.blk" 2>/dev/null
    "$BLOCKLAB" decode "$WORK/t.blk" "$WORK/test.pfm"
    "$BLOCKLAB" compare --metrics log2rgb,mpsnr --json "$WORK/ref.pfm" "$WORK/test.pfm" >"$WORK/ours.json"
    /usr/bin/python3 "$SOURCE_DIR/tests/tools/reference_metrics.py" "$WORK/ref.pfm" "$WORK/test.pfm" >"$WORK/theirs.json"
    /usr/bin/python3 - "$WORK/ours.json" "$WORK/theirs.json" "$(basename "$img") $f" <<'PY'
import json, sys
ours, theirs = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
for k in ("log2rgb", "mpsnr"):
    a, b = ours[k], theirs[k]
    if isinstance(a, str):   # non-finite values are the strings "inf" / "-inf" / "nan" (JSON numbers hold none)
        assert float(a) == b, f"{sys.argv[3]} {k}: blocklab {a} vs reference {b}"
        print(f"ok: {sys.argv[3]} {k} +inf on both sides"); continue
    rel = abs(a - b) / max(abs(b), 1e-300)
    assert rel <= 1e-6, f"{sys.argv[3]} {k}: blocklab {a} vs reference {b} (relative {rel:.2e})"
    print(f"ok: {sys.argv[3]} {k} {a:.9g} vs {b:.9g} (relative {rel:.1e})")
PY
  done
done
