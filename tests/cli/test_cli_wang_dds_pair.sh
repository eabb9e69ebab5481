# `blocklab encode IN OUT.dds --format wang` writes the paper's two DXT5 textures and the container with the shader
# constants (Wang et al. 2007 section 3.3; formats/wang/wang_dds.h, cli/command_codec.cpp): OUT.tex0.dds,
# OUT.tex1.dds and OUT.blk, no OUT.dds. Each DDS is a standard DXT5 file (magic "DDS ", FourCC "DXT5") that
# `blocklab decode` reads as bc3; `blocklab decode OUT.blk` gives the same image as encoding straight to .blk.
source "$(dirname "$0")/common.sh"
IN="$SOURCE_DIR/samples/hdr/hdr-rgb-arboretum.hdr"
"$BLOCKLAB" convert --crop 8,4,45,30 "$IN" "$WORK/crop.exr" >/dev/null 2>&1 || die "crop of $IN failed"

"$BLOCKLAB" encode --format wang "$WORK/crop.exr" "$WORK/out.dds" >/dev/null 2>"$WORK/encode.log" \
  || die "wang encode to DDS failed: $(cat "$WORK/encode.log")"
for file in out.tex0.dds out.tex1.dds out.blk; do
  [ -s "$WORK/$file" ] || die "encode ... out.dds --format wang did not write $file"
done
[ ! -e "$WORK/out.dds" ] || die "a wang encode wrote out.dds as well (expected only the two textures)"
for texture in tex0 tex1; do
  [ "$(head -c 4 "$WORK/out.$texture.dds")" = "DDS " ] || die "out.$texture.dds lacks the DDS magic"
  [ "$(dd if="$WORK/out.$texture.dds" bs=1 skip=84 count=4 2>/dev/null)" = "DXT5" ] \
    || die "out.$texture.dds is not DXT5"
  # 45x30 -> 12x8 blocks of 16 bytes after the 128-byte header.
  [ "$(stat -c %s "$WORK/out.$texture.dds")" -eq $((128 + 12 * 8 * 16)) ] || die "out.$texture.dds has the wrong size"
  "$BLOCKLAB" decode "$WORK/out.$texture.dds" "$WORK/$texture.png" >/dev/null 2>&1 || die "decode of out.$texture.dds failed"
  echo "ok: out.$texture.dds is a 45x30 DXT5 texture"
done

"$BLOCKLAB" decode "$WORK/out.blk" "$WORK/from_pair.exr" >/dev/null 2>&1 || die "decode of out.blk failed"
"$BLOCKLAB" encode --format wang "$WORK/crop.exr" "$WORK/direct.blk" >/dev/null 2>&1 || die "wang encode to .blk failed"
"$BLOCKLAB" decode "$WORK/direct.blk" "$WORK/direct.exr" >/dev/null 2>&1 || die "decode of direct.blk failed"
cmp "$WORK/out.blk" "$WORK/direct.blk" || die "the .blk written beside the DDS pair differs from encoding to .blk"
cmp "$WORK/from_pair.exr" "$WORK/direct.exr" || die "decoded images differ"
psnr=$("$BLOCKLAB" compare --metrics psnr --json "$WORK/crop.exr" "$WORK/from_pair.exr" \
  | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)["psnr"])')
/usr/bin/python3 -c "import sys; sys.exit(0 if float('$psnr') > 35.0 else 1)" || die "PSNR $psnr dB is implausibly low"
echo "ok: decode out.blk works (psnr $psnr dB), same .blk and image as encoding to .blk"
