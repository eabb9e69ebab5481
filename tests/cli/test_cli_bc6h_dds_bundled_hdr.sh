# BC6H through DDS on the bundled HDR samples: `blocklab encode IN.exr OUT.dds --format bc6h` (and bc6h_sf) writes a
# DX10 DDS with dxgiFormat 95 (96), `blocklab decode OUT.dds OUT.exr` gives an image of the source's size whose
# log2[RGB] against the source equals `compare` against the DDS itself, and the DDS bytes are identical at 1 and 2
# threads, also for a crop whose size is not a multiple of 4.
source "$(dirname "$0")/common.sh"
PY=/usr/bin/python3

dxgi_format() { "$PY" -c 'import struct,sys; d=open(sys.argv[1],"rb").read(); print(struct.unpack_from("<I", d, 128)[0])' "$1"; }
log2rgb() { "$BLOCKLAB" compare --metrics log2rgb --json "$1" "$2" | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["log2rgb"])'; }

"$BLOCKLAB" convert --crop 3,5,61,47 "$SOURCE_DIR/samples/hdr/Desk.exr" "$WORK/odd.exr" >/dev/null
for format in bc6h bc6h_sf; do
  expected=95
  [ "$format" = bc6h_sf ] && expected=96
  for image in "$SOURCE_DIR"/samples/hdr/* "$WORK/odd.exr"; do
    name=$(basename "$image")
    "$BLOCKLAB" encode "$image" "$WORK/$name.dds" --format "$format" >/dev/null 2>&1 || die "$format $name: encode to DDS failed"
    [ "$(dxgi_format "$WORK/$name.dds")" = "$expected" ] || die "$format $name: dxgiFormat $(dxgi_format "$WORK/$name.dds")"
    "$BLOCKLAB" decode "$WORK/$name.dds" "$WORK/$name.back.exr" >/dev/null 2>&1 || die "$format $name: decode failed"
    via_file=$(log2rgb "$image" "$WORK/$name.back.exr")
    direct=$(log2rgb "$image" "$WORK/$name.dds")
    [ "$via_file" = "$direct" ] || die "$format $name: log2rgb $direct against the DDS, $via_file against its decode"
    # medium reaches 0.04-0.13 on these samples (tests/quality/baseline.csv); 0.5 catches a broken path.
    "$PY" -c "import sys; sys.exit(0 if float('$direct') < 0.5 else 1)" || die "$format $name: log2rgb $direct"
    echo "ok: $format $name -> DDS $expected, log2[RGB] $direct"
  done
  for threads in 1 2; do
    "$BLOCKLAB" encode --threads "$threads" --format "$format" "$WORK/odd.exr" "$WORK/$format.$threads.dds" >/dev/null 2>&1 \
      || die "$format: encode at $threads threads failed"
  done
  cmp -s "$WORK/$format.1.dds" "$WORK/$format.2.dds" || die "$format: DDS differs between 1 and 2 threads"
  echo "ok: $format DDS identical at 1 and 2 threads"
done
