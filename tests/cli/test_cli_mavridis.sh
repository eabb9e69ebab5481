# `mavridis` from the command line on the bundled kodim03 crop: `encode OUT.dds` writes one DDS per texture the
# paper's shader samples (formats/mavridis/README.md, "DDS output") plus OUT.blk, for one and for two wavelet levels;
# the mavridis_coefficient_search analysis reports the section 3.2 choice per plane and effort, its `none` rows at
# clamp 0, gamma 1 and no gain; option mistakes are one-line errors naming the option.
source "$(dirname "$0")/common.sh"
image="$SOURCE_DIR/samples/ldr/kodak/kodim03.png"

"$BLOCKLAB" encode "$image" "$WORK/k.dds" --format mavridis --set preset=fast 2>"$WORK/stderr" || die "encode failed"
for part in y co cg; do
  [ -s "$WORK/k.$part.dds" ] || die "k.$part.dds missing: $(cat "$WORK/stderr")"
  [ "$(head -c 4 "$WORK/k.$part.dds")" = "DDS " ] || die "k.$part.dds is not a DDS file"
done
[ -s "$WORK/k.blk" ] || die "k.blk missing"
# 256x256: Y's coefficient texture is 128x128 (height and width at bytes 12 and 16 of the file), 128 x 128 x 1 byte.
[ "$(od -An -tu4 -j12 -N8 "$WORK/k.y.dds" | tr -s ' ')" = " 128 128" ] || die "k.y.dds is not 128x128"
[ "$(stat -c %s "$WORK/k.y.dds")" -eq $((128 + 128 * 128)) ] || die "k.y.dds size $(stat -c %s "$WORK/k.y.dds")"

"$BLOCKLAB" encode "$image" "$WORK/g.dds" --format mavridis --set bpp=2 --set levels=2 --set preset=fast \
  2>"$WORK/stderr" || die "two-level encode failed"
[ -s "$WORK/g.y_level1.dds" ] && [ -s "$WORK/g.y.dds" ] || die "two-level DDS files missing: $(cat "$WORK/stderr")"
[ ! -e "$WORK/g.co.dds" ] || die "gray wrote a chroma texture"
# Level 1 (DXT1, 8 bytes per block) at 128x128, the last level (DXT5) at 64x64.
[ "$(stat -c %s "$WORK/g.y_level1.dds")" -eq $((128 + 32 * 32 * 8)) ] || die "g.y_level1.dds size"
[ "$(stat -c %s "$WORK/g.y.dds")" -eq $((128 + 16 * 16 * 16)) ] || die "g.y.dds size"

cat >"$WORK/search.yaml" <<YAML
analysis: mavridis_coefficient_search
schema: 1
name: search_test
data_root: "$SOURCE_DIR/samples"
images: ["ldr/kodak/kodim03.png"]
options: {bpp: "3"}
efforts: [fast, medium]
YAML
"$BLOCKLAB" analyze "$WORK/search.yaml" --out "$WORK/out" >"$WORK/stdout" || die "analyze failed"
rows="$WORK/out/coefficient_search.csv"
[ "$(wc -l <"$rows")" -eq 10 ] || die "expected 3 efforts x 3 planes: $(cat "$rows")"
awk -F, 'NR > 1 && $2 == "none" && !($4 == 0 && $5 == 1 && $9 == 0) { print "none row " $0; bad = 1 }
         NR > 1 && $2 == "fast" && !($4 == 0.26 && $5 == 0.86) { print "fast row " $0; bad = 1 }
         NR > 1 && !($6 >= 0 && $6 <= 1) { print "clamped share " $0; bad = 1 }
         END { exit bad }' "$rows" || die "coefficient search rows"

expect_error "levels" "$BLOCKLAB" encode "$image" "$WORK/x.blk" --format mavridis --set bpp=5 --set levels=2
expect_error "plhaar" "$BLOCKLAB" encode "$image" "$WORK/x.blk" --format mavridis --set transform=plhaar --set packing=best
echo "all mavridis command-line checks passed"
