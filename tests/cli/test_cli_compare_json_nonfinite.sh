# `compare --json` writes +inf, -inf and NaN as the strings "inf", "-inf" and "nan" (never null), as results.jsonl
# does (experiments/results_writer.h): identical images give psnr "inf", a reference holding +Inf gives log2rgb
# "inf", and mpsnr_auto with no valid exposure range gives "nan".
source "$(dirname "$0")/common.sh"
/usr/bin/python3 - "$WORK" <<'PY'
import struct, sys
work = sys.argv[1]
def pfm(name, values):
    open(f"{work}/{name}", "wb").write(b"PF\n8 8\n-1\n" + struct.pack("<192f", *values))
pfm("ok.pfm", [0.5] * 192)
pfm("inf.pfm", [float("inf")] + [0.5] * 191)
pfm("zero.pfm", [0.0] * 192)
PY
"$BLOCKLAB" compare "$WORK/ok.pfm" "$WORK/ok.pfm" --json -m psnr,log2rgb >"$WORK/same.json"
"$BLOCKLAB" compare "$WORK/inf.pfm" "$WORK/ok.pfm" --json -m log2rgb,psnr >"$WORK/inf.json"
"$BLOCKLAB" compare "$WORK/zero.pfm" "$WORK/ok.pfm" --json -m mpsnr_auto --details >"$WORK/nan.json"
/usr/bin/python3 - "$WORK" <<'PY'
import json, math, sys
work = sys.argv[1]
same, inf, nan = (json.load(open(f"{work}/{n}.json")) for n in ("same", "inf", "nan"))
assert same == {"psnr": "inf", "log2rgb": 0.0}, same
assert inf["log2rgb"] == "inf" and isinstance(inf["psnr"], float), inf
assert nan["mpsnr_auto"]["value"] == "nan", nan
for value in (same["psnr"], inf["log2rgb"], nan["mpsnr_auto"]["value"]):
    float(value)   # Python reads every encoding back as a float
assert math.isinf(float(same["psnr"])) and math.isnan(float(nan["mpsnr_auto"]["value"]))
print("ok: inf, nan as strings")
PY
