# `convert` keeps the input's precision: a 32-bit float PFM or EXR holding 1e6 and 1e-9 comes back bit-exact through
# EXR (float in, float out), a half-float EXR stays half (RGBA kept), and --half warns on stderr about the values it
# turns to infinity or zero.
source "$(dirname "$0")/common.sh"
/usr/bin/python3 - "$WORK" <<'PY'
import struct, sys
values = [1e6, 1e-9, 0.5] * 64
open(f"{sys.argv[1]}/wide.pfm", "wb").write(b"PF\n8 8\n-1\n" + struct.pack("<192f", *values))
PY
"$BLOCKLAB" convert "$WORK/wide.pfm" "$WORK/wide.exr" 2>"$WORK/stderr"
[ ! -s "$WORK/stderr" ] || die "float output warned: $(cat "$WORK/stderr")"
"$BLOCKLAB" convert "$WORK/wide.exr" "$WORK/again.exr"
"$BLOCKLAB" convert "$WORK/again.exr" "$WORK/back.pfm"
# Same raster (the last 768 bytes; the writer's header spells the scale "-1.0").
cmp -s <(tail -c 768 "$WORK/wide.pfm") <(tail -c 768 "$WORK/back.pfm") || die "PFM -> EXR -> EXR -> PFM changed the values"

# The EXR channel list says each channel's type (OpenEXR file layout: name, int32 pixel type 0 uint, 1 half, 2 float).
channel_types() {
  /usr/bin/python3 - "$1" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
at = data.index(b"channels\0chlist\0") + 16 + 4   # attribute name, type name, int32 size
types = []
while data[at] != 0:
    end = data.index(b"\0", at)
    types.append(data[at:end].decode() + "=" + "uint half float".split()[struct.unpack("<i", data[end + 1:end + 5])[0]])
    at = end + 1 + 16
print(" ".join(types))
PY
}
[ "$(channel_types "$WORK/wide.exr")" = "B=float G=float R=float" ] || die "float input: $(channel_types "$WORK/wide.exr")"
"$BLOCKLAB" convert "$SOURCE_DIR/samples/hdr/Desk.exr" "$WORK/desk.exr" --crop 0,0,32,32
[ "$(channel_types "$WORK/desk.exr")" = "A=half B=half G=half R=half" ] || die "half input: $(channel_types "$WORK/desk.exr")"

status=0
"$BLOCKLAB" convert "$WORK/wide.pfm" "$WORK/half.exr" --half 2>"$WORK/stderr" || status=$?
[ "$status" -eq 0 ] || die "--half failed"
grep -q "half.exr: half-float output: 64 values beyond +-65504 become infinite, 64 non-zero values below 2^-24 become 0" \
  "$WORK/stderr" || die "no precise warning: $(cat "$WORK/stderr")"
[ "$(wc -l <"$WORK/stderr")" -eq 1 ] || die "more than one warning line"
"$BLOCKLAB" convert --help | tr -s ' \n' ' ' | grep -q "alpha channel is kept when the target format has one" \
  || die "convert --help does not say what happens to alpha"
echo "all convert precision cases passed"
