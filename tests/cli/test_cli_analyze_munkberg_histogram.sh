# `blocklab analyze` with the munkberg_luminance_histogram analysis (Munkberg et al. 2008 section 7.3, Figure 8) on
# the bundled samples/hdr images: every block is counted once, the histogram sums to the blocks with a range, the
# pooled "all" rows are the sums over the images, the precision shares grow with fewer bits and carry the paper's
# numbers, the plot script draws a PNG, and schema mistakes are one-line errors naming file:line.
source "$(dirname "$0")/common.sh"

cat >"$WORK/fig8.yaml" <<YAML
analysis: munkberg_luminance_histogram
schema: 1
name: fig8_test
data_root: "$SOURCE_DIR/samples"
images: ["hdr/*.exr", "hdr/*.hdr"]
bin_width: 0.25
bins: 49
precision:
  - {bits: 10, paper: 51.0}
  - {bits: 8, paper: 84.7}
  - {bits: 6}
YAML
"$BLOCKLAB" analyze "$WORK/fig8.yaml" --out "$WORK/out" >"$WORK/stdout" || die "analyze failed"
histogram="$WORK/out/luminance_range_histogram.csv"
summary="$WORK/out/luminance_range_summary.csv"
precision="$WORK/out/luminance_range_precision.csv"
[ -f "$WORK/out/analysis.json" ] || die "analysis.json missing"
images=$(ls "$SOURCE_DIR"/samples/hdr/*.exr "$SOURCE_DIR"/samples/hdr/*.hdr | wc -l)
[ "$(wc -l <"$summary")" -eq $((images + 2)) ] || die "expected $images images + all in the summary: $(cat "$summary")"
[ "$(wc -l <"$histogram")" -eq $(((images + 1) * 49 + 1)) ] || die "expected 49 bins per image and all"
[ "$(wc -l <"$precision")" -eq $(((images + 1) * 3 + 1)) ] || die "expected 3 precision rows per image and all"

# Blocks: ceil(W/4) ceil(H/4) per image, black + ranged = all, pooled row = sums.
awk -F, 'NR > 1 && $1 != "all" {
  if ($4 != int(($2 + 3) / 4) * int(($3 + 3) / 4)) { print "blocks " $4 " for " $2 "x" $3; bad = 1 }
  if ($5 + $6 != $4) { print "black + ranged != blocks: " $0; bad = 1 }
  if (!($7 >= 0 && $8 >= 0 && $9 >= 0 && $10 >= $9 && $10 >= $8)) { print "bad range statistics: " $0; bad = 1 }
  blocks += $4; ranged += $6
}
$1 == "all" { if ($4 != blocks || $6 != ranged) { print "pooled row " $0 " != sums " blocks ", " ranged; bad = 1 } }
END { exit bad }' "$summary" || die "summary properties failed"
# Histogram counts sum to the ranged blocks of each image (and of all).
awk -F, 'FNR == 1 { next } FILENAME == ARGV[1] { ranged[$1] = $6; next }
{ total[$1] += $5; share[$1] += $6 }
END {
  for (image in ranged) {
    if (total[image] != ranged[image]) { print image ": histogram sums to " total[image] " != " ranged[image]; bad = 1 }
    if (ranged[image] > 0 && (share[image] < 0.999999 || share[image] > 1.000001)) { print image ": shares sum to " share[image]; bad = 1 }
  }
  exit bad
}' "$summary" "$histogram" || die "histogram sums failed"
# Precision: limits 0.5 / 2 / 8; shares grow as the bits go down; the paper's percentages as given.
awk -F, 'NR > 1 {
  limit[$2] = $3
  if ($2 == 10 && $7 != 51) { print "paper column of 10 bits: " $7; bad = 1 }
  if ($2 == 6 && $7 != "") { print "no paper value given for 6 bits, got " $7; bad = 1 }
  if ($2 == 10) s10[$1] = $6; if ($2 == 8) s8[$1] = $6; if ($2 == 6) s6[$1] = $6
}
END {
  if (limit[10] != 0.5 || limit[8] != 2 || limit[6] != 8) { print "limits " limit[10] " " limit[8] " " limit[6]; bad = 1 }
  for (image in s10) if (!(s10[image] <= s8[image] && s8[image] <= s6[image] && s6[image] <= 100)) { print image " shares not monotone"; bad = 1 }
  exit bad
}' "$precision" || die "precision properties failed"
echo "ok: histogram, summary and precision"

if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  /usr/bin/python3 "$SOURCE_DIR/configs/papers/munkberg2008/plot_fig8_histogram.py" "$WORK/out" >/dev/null || die "plot script failed"
  [ "$(head -c 4 "$WORK/out/fig8_histogram.png" | tail -c 3)" = "PNG" ] || die "fig8_histogram.png is not a PNG"
  echo "ok: plot"
fi

# Strict schema: one-line errors with file:line.
sed -e 's/^bins: 49/bins: 0/' "$WORK/fig8.yaml" >"$WORK/bins.yaml"
expect_error "bins.yaml:7:.*bins must be in" "$BLOCKLAB" analyze "$WORK/bins.yaml" --out "$WORK/bad"
sed -e 's/^bin_width: 0.25/bin_width: -1/' "$WORK/fig8.yaml" >"$WORK/width.yaml"
expect_error "width.yaml:6:.*bin_width must be > 0" "$BLOCKLAB" analyze "$WORK/width.yaml" --out "$WORK/bad"
sed -e 's/{bits: 6}/{bits: 6, papr: 99.8}/' "$WORK/fig8.yaml" >"$WORK/key.yaml"
expect_error "key.yaml:11:.*papr" "$BLOCKLAB" analyze "$WORK/key.yaml" --out "$WORK/bad"
sed -e 's/{bits: 6}/{bits: 31}/' "$WORK/fig8.yaml" >"$WORK/bits.yaml"
expect_error "bits.yaml:11:.*precision\[2\].bits must be in \[1, 30\]" "$BLOCKLAB" analyze "$WORK/bits.yaml" --out "$WORK/bad"
sed -e 's/^bins: 49/intervals: [[0, 1]]/' "$WORK/fig8.yaml" >"$WORK/other.yaml"
expect_error "other.yaml:7:.*intervals" "$BLOCKLAB" analyze "$WORK/other.yaml" --out "$WORK/bad"
echo "all munkberg_luminance_histogram checks passed"
