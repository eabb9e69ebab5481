# `blocklab analyze` with the banterle_filtering analysis (Banterle et al. 2008 section 4.5, eq. 7) on the bundled
# samples/hdr/Desk.exr: the CSVs have the documented shape, eq. 7 is 0 at both interval end points (x = 0, 1) and
# positive inside, the closed form agrees with g, the image measurement covers every bilinear sample, given TMO
# parameters are used as given, and schema mistakes are one-line errors naming file:line.
source "$(dirname "$0")/common.sh"

cat >"$WORK/filtering.yaml" <<YAML
analysis: banterle_filtering
schema: 1
name: filtering_test
data_root: "$SOURCE_DIR/samples"
images: [hdr/Desk.exr]
intervals:
  - [0.3, 0.6]
  - [0, 1]
samples: 11
tmo: {fit: ceres_lm, mean: geometric}
YAML
"$BLOCKLAB" analyze "$WORK/filtering.yaml" --out "$WORK/out" >"$WORK/stdout" || die "analyze failed"
curves="$WORK/out/filtering_curves.csv"
measured="$WORK/out/filtering_measured.csv"
[ -f "$WORK/out/analysis.json" ] && [ -f "$WORK/out/config.yaml" ] || die "analysis.json / config.yaml missing"

# Shape: header + 2 intervals x 11 samples.
[ "$(head -1 "$curves")" = "image,a,b,x,tone_mapped,hdr_filtered,tone_mapped_filtered,error,closed_form_error,relative_error" ] \
  || die "unexpected curves header: $(head -1 "$curves")"
[ "$(wc -l <"$curves")" -eq 23 ] || die "expected 23 lines in filtering_curves.csv, got $(wc -l <"$curves")"
[ "$(wc -l <"$measured")" -eq 2 ] || die "expected 2 lines in filtering_measured.csv, got $(wc -l <"$measured")"

# Properties of eq. 7 on each interval.
awk -F, 'NR > 1 {
  key = $2 "," $3; n[key]++
  if ($4 + 0 == 0 || $4 + 0 == 1) { if ($8 + 0 != 0) { print "eq. 7 is " $8 " at x = " $4 " on [" key "]"; bad = 1 } }
  else if (!($8 + 0 > 0)) { print "eq. 7 is not positive at x = " $4 " on [" key "]"; bad = 1 }
  if ($8 + 0 > max[key]) max[key] = $8 + 0
  d = $8 - $9; if (d < 0) d = -d
  if (d > 1e-6 * ($8 + 1e-12) + 1e-12) { print "closed form " $9 " != " $8 " at x = " $4; bad = 1 }
  if ($5 + 0 < $2 + 0 || $5 + 0 > $3 + 0) { print "tone-mapped value " $5 " outside [" key "]"; bad = 1 }
}
END {
  if (n["0.3,0.6"] != 11 || n["0,1"] != 11) { print "expected 11 rows per interval"; bad = 1 }
  # The worst case interval [0, 1] has a larger error than the average one (paper, Figure 4).
  if (!(max["0,1"] > max["0.3,0.6"])) { print "max error on [0,1] not above [0.3,0.6]"; bad = 1 }
  exit bad
}' "$curves" || die "eq. 7 properties failed"

# The image measurement: 4 samples per 2x2 quad, errors finite and >= 0, relative errors in [0, 1].
awk -F, 'NR == 2 {
  if ($1 != "hdr/Desk.exr") { print "image " $1; exit 1 }
  if ($8 != 4 * ($2 - 1) * ($3 - 1)) { print "samples " $8 " != 4 (W-1)(H-1) for " $2 "x" $3; exit 1 }
  if (!($12 >= 0 && $13 >= $12 && $15 >= 0 && $16 <= 1 && $18 >= 0)) { print "bad error statistics: " $0; exit 1 }
}' "$measured" || die "measured CSV properties failed"
echo "ok: curves and measurement"

# Given TMO parameters are used as given.
sed -e 's/^tmo: .*/tmo: {alpha: 0.25, l_white: 12, mean_luminance: 0.5}/' "$WORK/filtering.yaml" >"$WORK/given.yaml"
"$BLOCKLAB" analyze "$WORK/given.yaml" --out "$WORK/given" >/dev/null || die "analyze with given parameters failed"
awk -F, 'NR == 2 && !($4 == "given" && $5 == 0.25 && $6 == 12 && $7 == 0.5) { print "not the given parameters: " $0; exit 1 }' \
  "$WORK/given/filtering_measured.csv" || die "given parameters"
echo "ok: given parameters"

# The plot script draws a PNG from the CSVs (when matplotlib is installed).
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  /usr/bin/python3 "$SOURCE_DIR/configs/papers/banterle2008/plot_filtering.py" "$WORK/out" >/dev/null || die "plot script failed"
  [ "$(head -c 4 "$WORK/out/filtering.png" | tail -c 3)" = "PNG" ] || die "filtering.png is not a PNG"
  echo "ok: plot"
fi

# Strict schema: one-line errors with file:line.
sed -e 's/^samples: 11/sampels: 11/' "$WORK/filtering.yaml" >"$WORK/typo.yaml"
expect_error "typo.yaml:9:.*sampels" "$BLOCKLAB" analyze "$WORK/typo.yaml" --out "$WORK/bad"
sed -e 's/  - \[0.3, 0.6\]/  - [0.6, 0.3]/' "$WORK/filtering.yaml" >"$WORK/reversed.yaml"
expect_error "reversed.yaml:7:.*0 <= a < b <= 1" "$BLOCKLAB" analyze "$WORK/reversed.yaml" --out "$WORK/bad"
sed -e 's/^analysis: .*/analysis: banterle_filter/' "$WORK/filtering.yaml" >"$WORK/kind.yaml"
expect_error "kind.yaml:1:.*unknown analysis 'banterle_filter'.*banterle_filtering" "$BLOCKLAB" analyze "$WORK/kind.yaml" --out "$WORK/bad"
sed -e 's/^tmo: .*/tmo: {fit: ceres, mean: geometric}/' "$WORK/filtering.yaml" >"$WORK/fit.yaml"
expect_error "fit.yaml:10:.*'fit'.*ceres_lm" "$BLOCKLAB" analyze "$WORK/fit.yaml" --out "$WORK/bad"
sed -e 's/^tmo: .*/tmo: {fit: nlopt, fit_options: "algorithmm=LN_SBPLX"}/' "$WORK/filtering.yaml" >"$WORK/fit_options.yaml"
expect_error "fit_options.yaml:10:.*unknown option 'algorithmm'" "$BLOCKLAB" analyze "$WORK/fit_options.yaml" --out "$WORK/bad"
echo "all analyze checks passed"
