# BC7 through DDS on real data: `blocklab encode --format bc7 in.png out.dds` then `blocklab decode out.dds out.png` works for
# every LDR image in the shared data (RGB and RGBA) and for crops whose sizes are not multiples of 4; `blocklab
# compare` reports the PSNR. Also: DDS files of every BC format are byte-identical at 1 and 2 threads.
source "$(dirname "$0")/common.sh"
need_shared_data
PY=/usr/bin/python3   # Debian's python with python3-pil (installed by scripts/install-deps.sh)

size_of() { "$PY" -c 'import sys; from PIL import Image; im = Image.open(sys.argv[1]); print(*im.size, im.mode)' "$1"; }

check_roundtrip() {   # <input png> <name>
  local in=$1 name=$2
  "$BLOCKLAB" encode --format bc7 "$in" "$WORK/$name.dds" >/dev/null 2>&1 || die "$name: bc7 encode to DDS failed"
  "$BLOCKLAB" decode "$WORK/$name.dds" "$WORK/$name.png" >/dev/null 2>&1 || die "$name: decode of the DDS failed"
  local in_w in_h in_mode out_w out_h out_mode
  read -r in_w in_h in_mode <<<"$(size_of "$in")"
  read -r out_w out_h out_mode <<<"$(size_of "$WORK/$name.png")"
  [ "$in_w $in_h" = "$out_w $out_h" ] || die "$name: decoded size ${out_w}x$out_h, expected ${in_w}x$in_h"
  # An RGBA source keeps its alpha channel through BC7.
  if [ "$in_mode" = RGBA ] && [ "$out_mode" != RGBA ]; then die "$name: alpha lost (decoded mode $out_mode)"; fi
  local psnr
  psnr=$("$BLOCKLAB" compare --metrics psnr --json "$in" "$WORK/$name.png" | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["psnr"])')
  # compare also takes the DDS itself (decoded by its format first): the same number.
  local direct
  direct=$("$BLOCKLAB" compare --metrics psnr --json "$in" "$WORK/$name.dds" | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["psnr"])')
  [ "$direct" = "$psnr" ] || die "$name: compare against the DDS gives $direct dB, against its decoded PNG $psnr dB"
  # BC7 default reaches 38-50 dB on these images (docs/benchmarks-bc7.md); 30 dB catches a broken path.
  "$PY" -c "import sys; sys.exit(0 if float('$psnr') > 30.0 else 1)" || die "$name: PSNR $psnr dB is implausibly low"
  echo "ok: $name ${in_w}x$in_h $in_mode -> bc7 DDS -> ${out_w}x$out_h $out_mode, PSNR $psnr dB"
}

count=0
while IFS= read -r -d '' image; do
  check_roundtrip "$image" "$(basename "${image%.png}")"
  count=$((count + 1))
done < <(find "$SHARED_DATA/ldr" -name '*.png' -print0 | sort -z)
[ "$count" -gt 0 ] || die "no LDR images found under $SHARED_DATA/ldr"

# Sizes that are not multiples of 4, RGB and RGBA, and the 1x1 edge case.
"$BLOCKLAB" convert --crop 300,200,61,47 "$SHARED_DATA/ldr/kodak/kodim03.png" "$WORK/odd_rgb.png" >/dev/null
"$BLOCKLAB" convert --crop 400,400,33,18 "$SHARED_DATA/ldr/textures/ldr-rgba-base.png" "$WORK/odd_rgba.png" >/dev/null
"$BLOCKLAB" convert --crop 10,10,1,1 "$SHARED_DATA/ldr/textures/ldr-rgba-base.png" "$WORK/one_rgba.png" >/dev/null
check_roundtrip "$WORK/odd_rgb.png" odd_rgb_61x47
check_roundtrip "$WORK/odd_rgba.png" odd_rgba_33x18
check_roundtrip "$WORK/one_rgba.png" one_rgba_1x1
echo "ok: $count shared LDR images and 3 crops"

# Byte-identical DDS at 1 and 2 threads, every BC format, on an RGBA texture crop with a partial block row/column.
for format in bc1 bc3 bc4 bc7; do
  for threads in 1 2; do
    "$BLOCKLAB" encode --threads "$threads" --format "$format" "$WORK/odd_rgba.png" "$WORK/$format.$threads.dds" >/dev/null 2>&1 \
      || die "$format: encode to DDS failed"
  done
  cmp "$WORK/$format.1.dds" "$WORK/$format.2.dds" || die "$format: DDS differs between 1 and 2 threads"
  echo "ok: $format DDS identical at 1 and 2 threads"
done
