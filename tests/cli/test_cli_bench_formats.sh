# `blocklab bench formats` on the bundled samples at the fast preset: one CSV row per (encoder, image) with every
# registered format on the images of its kind, the peers (astcenc at 4x4/6x6/8x8 on both kinds; libsquish and
# NVTT for BC1/BC3 on LDR) where installed, the metrics of each kind, one-core times, speed ratio 1 for the
# reference itself, and a printed Pareto front whose rows are not dominated at their bit rate.
source "$(dirname "$0")/common.sh"
cd "$SOURCE_DIR"
"$BLOCKLAB" bench formats --data-root samples --presets fast --reference astcenc-4x4-fast --csv "$WORK/bench.csv" \
  >"$WORK/out.md" 2>"$WORK/err.txt" || die "bench formats failed: $(cat "$WORK/err.txt")"
grep -q "Pareto front" "$WORK/out.md" || die "no Pareto front printed"
grep -q "ETA" "$WORK/err.txt" || die "no progress with an ETA on stderr: $(cat "$WORK/err.txt")"
"$BLOCKLAB" list --json >"$WORK/list.json"
/usr/bin/python3 - "$WORK/bench.csv" "$WORK/out.md" "$WORK/list.json" <<'PY'
import csv, json, math, shutil, sys
rows = list(csv.DictReader(open(sys.argv[1])))
header = open(sys.argv[1]).readline().strip().split(",")
assert header[:5] == ["format", "preset", "image", "kind", "bpp"], header
assert header[-3:] == ["encode_seconds", "decode_seconds", "speed_ratio"], header
for metric in ["log2rgb", "log2rgb_skip", "mpsnr", "mpsnr_auto", "pu21_psnr", "psnr", "psnr_luma"]:
    assert metric in header, metric
listing = json.load(open(sys.argv[3]))
formats = [f["name"] for f in listing["formats"]]
by_format = {}
for row in rows:
    assert row["preset"] == "fast", row
    by_format.setdefault(row["format"], set()).add(row["kind"])
    assert float(row["encode_seconds"]) >= 0 and float(row["decode_seconds"]) >= 0, row
    if row["kind"] == "hdr":
        assert row["image"].startswith("hdr/") and row["psnr_luma"] == "", row
        assert math.isfinite(float(row["log2rgb"])) and float(row["log2rgb"]) >= 0, row
        float(row["mpsnr"])
    else:
        assert row["image"].startswith("ldr/") and row["log2rgb"] == "" and row["mpsnr"] == "", row
        assert 0 < float(row["psnr"]) <= 100, row
for name in formats:
    assert name in by_format, f"format {name} has no row"
for hdr_format in ["munkberg", "banterle", "wang", "fp16", "rgbe"]:
    assert by_format[hdr_format] == {"hdr"}, (hdr_format, by_format[hdr_format])
for ldr_format in ["bc1", "bc3", "bc7", "mavridis"]:
    assert by_format[ldr_format] == {"ldr"}, (ldr_format, by_format[ldr_format])
images = {r["image"] for r in rows}
assert len(images) == 5, images
if shutil.which("astcenc"):
    assert by_format["astcenc-4x4"] == {"hdr", "ldr"}, by_format["astcenc-4x4"]
    bpp = {r["format"]: float(r["bpp"]) for r in rows}
    assert abs(bpp["astcenc-6x6"] - 128 / 36) < 1e-4 and bpp["astcenc-8x8"] == 2 and bpp["astcenc-4x4"] == 8, bpp
    for r in rows:
        if r["format"] == "astcenc-4x4":
            assert float(r["speed_ratio"]) == 1.0, r
        else:
            assert float(r["speed_ratio"]) > 0, r
if shutil.which("nvcompress"):
    assert by_format["nvtt-bc1"] == {"ldr"}, by_format
# The printed front: no row dominated by another row of the same kind and bit rate (mean error, total seconds).
agg = {}
for r in rows:
    key = (r["kind"], round(float(r["bpp"]), 3), r["format"] + "-" + r["preset"])
    metric = float(r["log2rgb"]) if r["kind"] == "hdr" else -float(r["psnr"])
    e, t, n = agg.get(key, (0.0, 0.0, 0))
    agg[key] = (e + metric, t + float(r["encode_seconds"]), n + 1)
front = [l.split("|")[1:-1] for l in open(sys.argv[2]) if l.startswith("| hdr") or l.startswith("| ldr")]
named = {(c[0].strip(), c[2].strip()) for c in front}   # (kind, encoder): an encoder has one bit rate per kind
for (kind, bpp, name), (e, t, n) in agg.items():
    dominated = any(k == kind and b == bpp and (e2 / n2 <= e / n and t2 <= t) and (e2 / n2 < e / n or t2 < t)
                    for (k, b, nm), (e2, t2, n2) in agg.items() if nm != name)
    assert dominated != ((kind, name) in named), (kind, bpp, name, dominated)
print(f"ok: {len(rows)} rows, {len(by_format)} encoders, front of {len(named)}")
PY
expect_error "unknown format 'nope'" "$BLOCKLAB" bench formats --data-root samples --formats nope
expect_error "unknown preset 'slow'" "$BLOCKLAB" bench formats --data-root samples --presets slow
