# `blocklab analyze` with the wang_filtering analysis (Wang et al. 2007 section 4.4, Fig. 5, Appendix B) on a crop of
# the bundled samples/hdr/hdr-rgb-arboretum.hdr: one row per variant with 9 (W-1)(H-1) samples, the pair counts of
# Appendix B's statistic, finite errors, the filtering artefact of the residual ratio T larger than that of the
# residual S; the plot script draws a PNG; schema mistakes are one-line errors naming file:line.
source "$(dirname "$0")/common.sh"
mkdir -p "$WORK/data/hdr"
"$BLOCKLAB" convert --crop 100,200,48,40 "$SOURCE_DIR/samples/hdr/hdr-rgb-arboretum.hdr" "$WORK/data/hdr/crop.exr" \
  >/dev/null 2>&1 || die "crop failed"

cat >"$WORK/filtering.yaml" <<YAML
analysis: wang_filtering
schema: 1
name: wang_filtering_test
data_root: "$WORK/data"
images: [hdr/crop.exr]
variants:
  residual_s: {}
  residual_ratio: {residual: ratio}
offsets: [0.25, 0.5, 0.75]
YAML
"$BLOCKLAB" analyze "$WORK/filtering.yaml" --out "$WORK/out" >"$WORK/stdout" || die "analyze failed"
measured="$WORK/out/filtering_measured.csv"
[ -f "$WORK/out/analysis.json" ] && [ -f "$WORK/out/config.yaml" ] || die "analysis.json / config.yaml missing"
[ "$(head -1 "$measured")" = "image,width,height,variant,samples,shader_psnr,decoded_psnr,shader_vs_decoded_psnr,shader_log2rgb,decoded_log2rgb,shader_vs_decoded_log2rgb,rgb_pairs,rgb_same_direction,s_pairs,s_same_direction" ] \
  || die "unexpected header: $(head -1 "$measured")"
awk -F, 'NR > 1 {
  if ($1 != "hdr/crop.exr" || $2 != 48 || $3 != 40) { print "image " $1 " " $2 "x" $3; bad = 1 }
  if ($5 != 9 * 47 * 39) { print "samples " $5 " != 9 (W-1)(H-1)"; bad = 1 }
  pairs = 47 * 40 + 48 * 39
  if ($12 != 3 * pairs || $14 != pairs) { print "pair counts " $12 ", " $14 " (expected " 3 * pairs ", " pairs ")"; bad = 1 }
  if ($13 > $12 || $15 > $14 || $13 < 0.5 * $12) { print "same-direction counts " $13 " of " $12 ", " $15 " of " $14; bad = 1 }
  for (i = 6; i <= 8; ++i) if (!($i > 20 && $i < 200)) { print "psnr column " i " is " $i; bad = 1 }
  for (i = 9; i <= 11; ++i) if (!($i >= 0 && $i < 5)) { print "log2rgb column " i " is " $i; bad = 1 }
  artefact[$4] = $11
}
END {
  if (NR != 3) { print NR " lines"; bad = 1 }
  if (!(artefact["residual_ratio"] > artefact["residual_s"])) {
    print "ratio artefact " artefact["residual_ratio"] " not above S artefact " artefact["residual_s"]; bad = 1
  }
  exit bad
}' "$measured" || die "measured CSV properties failed"
grep -q "same direction" "$WORK/stdout" || die "no same-direction summary on stdout"
echo "ok: measurement"

if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  /usr/bin/python3 "$SOURCE_DIR/configs/papers/wang2007/plot_filtering.py" "$WORK/out" >/dev/null || die "plot script failed"
  [ "$(head -c 4 "$WORK/out/filtering.png" | tail -c 3)" = "PNG" ] || die "filtering.png is not a PNG"
  echo "ok: plot"
fi

sed -e 's/^offsets: \[0.25, 0.5, 0.75\]/offsets: [0.5, 1]/' "$WORK/filtering.yaml" >"$WORK/offset.yaml"
expect_error "offset.yaml:9:.*offsets\[1\] must be in \(0, 1\)" "$BLOCKLAB" analyze "$WORK/offset.yaml" --out "$WORK/bad"
sed -e 's/residual: ratio/residual: half/' "$WORK/filtering.yaml" >"$WORK/option.yaml"
expect_error "option.yaml:.*variants.residual_ratio: .*residual" "$BLOCKLAB" analyze "$WORK/option.yaml" --out "$WORK/bad"
sed -e 's/^offsets:/ofsets:/' "$WORK/filtering.yaml" >"$WORK/typo.yaml"
expect_error "typo.yaml:9:.*ofsets" "$BLOCKLAB" analyze "$WORK/typo.yaml" --out "$WORK/bad"
echo "all wang_filtering checks passed"
