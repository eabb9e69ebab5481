# A full disk is reported by every writer: with the output a symbolic link to /dev/full, convert, decode, encode
# (.blk and .dds) and compare --error-maps exit non-zero with one line naming the path and "No space left on
# device", and the link is left as it was (core/atomic_write.h writes a device in place, and never renames over it).
source "$(dirname "$0")/common.sh"
[ -w /dev/full ] || { echo "/dev/full not available: skipped"; exit 77; }
"$BLOCKLAB" convert "$SOURCE_DIR/samples/hdr/Desk.exr" "$WORK/in.exr" --crop 0,0,16,16
"$BLOCKLAB" encode --format rgbe "$WORK/in.exr" "$WORK/in.blk" 2>/dev/null
"$BLOCKLAB" convert "$SOURCE_DIR/samples/ldr/kodak/kodim03.png" "$WORK/in.png" --crop 0,0,16,16

full() { ln -sf /dev/full "$WORK/$1"; echo "$WORK/$1"; }
for ext in exr hdr pfm png; do
  expect_error "out.$ext: cannot write \(No space left on device\)" "$BLOCKLAB" convert "$WORK/in.exr" "$(full out.$ext)"
  [ -L "$WORK/out.$ext" ] || die "the link out.$ext was replaced"
done
expect_error "out.exr: cannot write \(No space left on device\)" "$BLOCKLAB" decode "$WORK/in.blk" "$(full out.exr)"
expect_error "out.blk: cannot write \(No space left on device\)" \
  "$BLOCKLAB" encode --format rgbe "$WORK/in.exr" "$(full out.blk)"
expect_error "out.dds: cannot write \(No space left on device\)" \
  "$BLOCKLAB" encode --format bc1 "$WORK/in.png" "$(full out.dds)"
mkdir "$WORK/maps"
ln -sf /dev/full "$WORK/maps/log2rgb.exr"
expect_error "log2rgb.exr: cannot write \(No space left on device\)" \
  "$BLOCKLAB" compare "$WORK/in.exr" "$WORK/in.exr" -m log2rgb --error-maps "$WORK/maps"

# A failed write leaves the previous file and no temporary: an output file bigger than the file-size limit.
"$BLOCKLAB" convert "$WORK/in.exr" "$WORK/kept.pfm"
cp "$WORK/kept.pfm" "$WORK/kept.before"
status=0
(ulimit -f 1; trap '' XFSZ; "$BLOCKLAB" convert "$SOURCE_DIR/samples/hdr/Desk.exr" "$WORK/kept.pfm") 2>"$WORK/stderr" || status=$?
[ "$status" -ne 0 ] || die "a write beyond the file-size limit succeeded"
grep -q "kept.pfm: cannot write (File too large)" "$WORK/stderr" || die "unexpected error: $(cat "$WORK/stderr")"
cmp -s "$WORK/kept.pfm" "$WORK/kept.before" || die "the previous kept.pfm was changed"
[ -z "$(ls "$WORK" | grep '\.tmp\.')" ] || die "a temporary file was left: $(ls "$WORK")"
echo "all disk-full cases passed"
