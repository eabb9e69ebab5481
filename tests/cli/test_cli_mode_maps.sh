# Block-mode usage (formats/common/mode_map.h): `encode --mode-map` writes a PNG of the image's size and prints one
# legend line per mode whose shares add up to 100%; a run with `mode_maps: true` records mode_shares per cell (JSON
# and CSV, matching the map's own count) and writes one map per cell; a metric listed twice with `column:` gives two
# result columns (log2rgb with both zero rules).
source "$(dirname "$0")/common.sh"
cd "$SOURCE_DIR"

"$BLOCKLAB" encode --format bc1 --mode-map "$WORK/bc1.png" samples/ldr/kodak/kodim03.png "$WORK/bc1.blk" \
  >"$WORK/encode.txt" 2>/dev/null
[ -s "$WORK/bc1.png" ] || die "no mode map written"
/usr/bin/python3 - "$WORK/encode.txt" "$WORK/bc1.png" <<'PY'
import re, sys
from PIL import Image
lines = [l for l in open(sys.argv[1]) if re.match(r"^\w+: ", l)]
modes = [l.split(":")[0] for l in lines]
shares = [float(re.search(r"([0-9.]+)%$", l.strip()).group(1)) for l in lines]
assert len(modes) >= 2, f"expected a legend line per bc1 mode, got {modes}"
assert abs(sum(shares) - 100.0) < 0.05, f"shares add up to {sum(shares)}"
size = Image.open(sys.argv[2]).size
assert size == (256, 256), f"mode map is {size}, the image 256x256"
print(f"ok: encode --mode-map: {dict(zip(modes, shares))}, map {size}")
PY

cat >"$WORK/modes.yaml" <<YAML
schema: 1
name: modes
data_root: $SOURCE_DIR/samples
images: [hdr/Desk.exr]
metrics:
  - log2rgb
  - {name: log2rgb, column: log2rgb_skip, zero_rule: skip}
formats:
  - format: munkberg
    options: {modes: all}
  - format: fp16
mode_maps: true
YAML
"$BLOCKLAB" run "$WORK/modes.yaml" --out "$WORK/run" --quiet >/dev/null
/usr/bin/python3 - "$WORK/run" <<'PY'
import csv, json, os, sys
run = sys.argv[1]
records = [json.loads(l) for l in open(os.path.join(run, "results.jsonl"))]
munkberg = next(r for r in records if r["format"] == "munkberg")
shares = munkberg["mode_shares"]
assert set(shares) >= {"shape_i", "shape_ii", "ext_s3tc", "two_plane", "dct"}, shares
assert abs(sum(shares.values()) - 1.0) < 1e-9, shares
assert os.path.exists(os.path.join(run, munkberg["artifacts"]["mode_map"])), "mode map artifact missing"
for column in ("log2rgb", "log2rgb_skip"):
    assert munkberg["metrics"][column] > 0.0, (column, munkberg["metrics"])
rows = list(csv.DictReader(open(os.path.join(run, "results.csv"))))
row = next(r for r in rows if r["format"] == "munkberg")
parsed = dict(item.split("=") for item in row["mode_shares"].split(";"))
assert all(abs(float(parsed[m]) - shares[m]) < 1e-4 for m in shares), (parsed, shares)
assert row["log2rgb_skip"] != "", "labelled metric column missing from the CSV"
print(f"ok: run records mode_shares {shares} and both log2rgb columns "
      f"({munkberg['metrics']['log2rgb']:.4f} / {munkberg['metrics']['log2rgb_skip']:.4f})")
PY
