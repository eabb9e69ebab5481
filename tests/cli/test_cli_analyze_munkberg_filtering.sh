# `blocklab analyze` with the munkberg_filtering analysis (Munkberg et al. 2008 section 4, eqs. 8-10, Figure 1) on
# the bundled samples/hdr/Desk.exr: Figure 1's curve has the paper's end points (about -0.1 at Y2 = 0.1, over 1.1 at
# Y2 = 10), agrees with eq. 10, and the normalised error is much smaller; the image measurement covers every
# bilinear sample; the plot script draws a PNG; schema mistakes are one-line errors naming file:line.
source "$(dirname "$0")/common.sh"

cat >"$WORK/fig1.yaml" <<YAML
analysis: munkberg_filtering
schema: 1
name: fig1_test
data_root: "$SOURCE_DIR/samples"
images: [hdr/Desk.exr]
curve: {v1: 0.25, v2: 0.1, y1: 1, y2: [0.1, 10], alpha: 0.5, samples: 100}
normalisation: {shift: nearest, reference: first}
magnification: 2
YAML
"$BLOCKLAB" analyze "$WORK/fig1.yaml" --out "$WORK/out" >"$WORK/stdout" || die "analyze failed"
curve="$WORK/out/fig1_curve.csv"
measured="$WORK/out/filtering_measured.csv"
[ -f "$WORK/out/analysis.json" ] && [ -f "$WORK/out/config.yaml" ] || die "analysis.json / config.yaml missing"
[ "$(head -1 "$curve")" = "y2,correct_red,plain_red,plain_error,plain_closed_form,shift1,shift2,normalised_red,normalised_error,normalised_closed_form" ] \
  || die "unexpected curve header: $(head -1 "$curve")"
[ "$(wc -l <"$curve")" -eq 101 ] || die "expected 101 lines in fig1_curve.csv, got $(wc -l <"$curve")"

awk -F, 'NR > 1 {
  d = $4 - $5; if (d < 0) d = -d
  if (d > 1e-9) { print "eq. 9 - eq. 8 = " $4 " but eq. 10 = " $5 " at Y2 = " $1; bad = 1 }
  d = $9 - $10; if (d < 0) d = -d
  if (d > 1e-9) { print "normalised " $9 " but eq. 10 = " $10 " at Y2 = " $1; bad = 1 }
  if ($6 != 0) { print "texel 1 is the reference, yet shift1 = " $6; bad = 1 }
  if ($7 == 0 && $8 != $3) { print "no shift but normalised != plain at Y2 = " $1; bad = 1 }
  a = $4 < 0 ? -$4 : $4; if (a > pmax) pmax = a
  a = $9 < 0 ? -$9 : $9; if (a > nmax) nmax = a
  if (NR == 2) first = $4
  last = $4
}
END {
  if (!(first > -0.15 && first < -0.05)) { print "plain error at Y2 = 0.1 is " first ", the paper: about -0.1"; bad = 1 }
  if (!(last > 1.1)) { print "plain error at Y2 = 10 is " last ", the paper: over 1.1"; bad = 1 }
  if (!(nmax < 0.25 * pmax)) { print "normalised peak " nmax " not much smaller than " pmax; bad = 1 }
  exit bad
}' "$curve" || die "Figure 1 properties failed"
echo "ok: Figure 1 curve"

# The image measurement: m^2 samples per 2x2 quad, finite non-negative statistics.
check_measured() {
  awk -F, -v m="$2" 'NR == 2 {
    if ($1 != "hdr/Desk.exr") { print "image " $1; exit 1 }
    if ($7 != m * m * ($2 - 1) * ($3 - 1)) { print "samples " $7 " != m^2 (W-1)(H-1) for " $2 "x" $3; exit 1 }
    if ($8 != ($2 - 1) * ($3 - 1) || $9 > $8) { print "bad quad counts: " $0; exit 1 }
    for (i = 11; i <= 18; ++i) if (!($i >= 0)) { print "column " i " is " $i; exit 1 }
    if (!($11 > 0 && $15 > 0 && $12 >= $11 && $16 >= $15)) { print "bad log2 statistics: " $0; exit 1 }
  } END { if (NR != 2) { print NR " lines"; exit 1 } }' "$1"
}
check_measured "$measured" 2 || die "measured CSV properties failed"
sed -e 's/^magnification: 2/magnification: 1/' "$WORK/fig1.yaml" >"$WORK/mid.yaml"
"$BLOCKLAB" analyze "$WORK/mid.yaml" --out "$WORK/mid" >/dev/null || die "analyze with magnification 1 failed"
check_measured "$WORK/mid/filtering_measured.csv" 1 || die "magnification 1 measurement failed"
echo "ok: measurement"

# The plot script draws a PNG from the CSVs (when matplotlib is installed).
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  /usr/bin/python3 "$SOURCE_DIR/configs/papers/munkberg2008/plot_fig1_filtering.py" "$WORK/out" >/dev/null || die "plot script failed"
  [ "$(head -c 4 "$WORK/out/fig1_filtering.png" | tail -c 3)" = "PNG" ] || die "fig1_filtering.png is not a PNG"
  echo "ok: plot"
fi

# Strict schema: one-line errors with file:line.
sed -e 's/^magnification: 2/magnifcation: 2/' "$WORK/fig1.yaml" >"$WORK/typo.yaml"
expect_error "typo.yaml:8:.*magnifcation" "$BLOCKLAB" analyze "$WORK/typo.yaml" --out "$WORK/bad"
sed -e 's/^magnification: 2/magnification: 0/' "$WORK/fig1.yaml" >"$WORK/zero.yaml"
expect_error "zero.yaml:8:.*magnification must be in \[1, 16\]" "$BLOCKLAB" analyze "$WORK/zero.yaml" --out "$WORK/bad"
sed -e 's/shift: nearest/shift: round/' "$WORK/fig1.yaml" >"$WORK/shift.yaml"
expect_error "shift.yaml:7:.*'round'.*nearest, exponent, truncate" "$BLOCKLAB" analyze "$WORK/shift.yaml" --out "$WORK/bad"
sed -e 's/alpha: 0.5/alpha: 1.5/' "$WORK/fig1.yaml" >"$WORK/alpha.yaml"
expect_error "alpha.yaml:6:.*curve.alpha must be in \[0, 1\]" "$BLOCKLAB" analyze "$WORK/alpha.yaml" --out "$WORK/bad"
printf 'samples: 11\n' >>"$WORK/fig1.yaml"
expect_error "fig1.yaml:9:.*samples" "$BLOCKLAB" analyze "$WORK/fig1.yaml" --out "$WORK/bad"
echo "all munkberg_filtering checks passed"
