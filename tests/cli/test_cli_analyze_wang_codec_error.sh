# `blocklab analyze` with the wang_codec_error analysis (Wang et al. 2007 section 3.5) on the bundled HDR samples:
# one row per image with finite, non-negative mean errors for the 1D codec and plain BC3, the residual's gain equal
# to alpha_error - error, the 1D codec's error not above BC3's on every sample (the acceptance claim in the format's
# own error, both as the encoder scores it and as eq. 9) and the winner column naming it; mismatched error_c and unknown keys are one-line errors naming file:line.
source "$(dirname "$0")/common.sh"

cat >"$WORK/codec_error.yaml" <<YAML
analysis: wang_codec_error
schema: 1
name: wang_codec_error_test
data_root: "$SOURCE_DIR/samples"
images: ["hdr/*.exr", "hdr/*.hdr"]
variants:
  1d: {}
  bc3: {codec: bc3}
YAML
"$BLOCKLAB" analyze "$WORK/codec_error.yaml" --out "$WORK/out" >"$WORK/stdout" || die "analyze failed"
measured="$WORK/out/codec_error_measured.csv"
[ -f "$WORK/out/analysis.json" ] && [ -f "$WORK/out/config.yaml" ] || die "analysis.json / config.yaml missing"
[ "$(head -1 "$measured")" = "image,width,height,texels,1d_error,1d_error_eq9,1d_alpha_error,1d_residual_gain,1d_black,bc3_error,bc3_error_eq9,bc3_alpha_error,bc3_residual_gain,bc3_black,winner" ] \
  || die "unexpected header: $(head -1 "$measured")"
images=$(cd "$SOURCE_DIR/samples" && ls hdr/*.exr hdr/*.hdr | sort)
[ "$(tail -n +2 "$measured" | cut -d, -f1 | sort)" = "$images" ] || die "rows are not one per sample image"
awk -F, 'function finite(v) { return v ~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/ }
NR > 1 {
  if ($4 != $2 * $3 || $4 <= 0) { print $1 ": texels " $4 " for " $2 "x" $3; bad = 1 }
  for (i = 5; i <= 14; ++i) if (!finite($i)) { print $1 ": column " i " is " $i; bad = 1 }
  for (i = 5; i <= 13; ++i) if (i != 8 && i != 13 && !($i >= 0)) { print $1 ": column " i " is " $i; bad = 1 }
  if ($9 > $4 || $14 > $4 || $9 != int($9) || $14 != int($14)) { print $1 ": black counts " $9 ", " $14; bad = 1 }
  if (($7 - $5 - $8) ^ 2 > 1e-20 || ($12 - $10 - $13) ^ 2 > 1e-20) { print $1 ": residual_gain != alpha - error"; bad = 1 }
  if (!($5 <= $10)) { print $1 ": 1d error " $5 " above bc3 error " $10; bad = 1 }
  if (!($6 <= $11)) { print $1 ": 1d eq. 9 error " $6 " above bc3 eq. 9 error " $11; bad = 1 }
  if ($15 != "1d") { print $1 ": winner " $15; bad = 1 }
}
END { exit bad }' "$measured" || die "measured CSV properties failed"
grep -q "all images, 1d: mean error" "$WORK/stdout" || die "no total on stdout"
echo "ok: measurement"

sed -e 's/bc3: {codec: bc3}/bc3: {codec: bc3, error_c: 0.001}/' "$WORK/codec_error.yaml" >"$WORK/c.yaml"
expect_error "c.yaml:7:.*variants.bc3.error_c: every variant must use the same error_c" \
  "$BLOCKLAB" analyze "$WORK/c.yaml" --out "$WORK/bad"
sed -e 's/codec: bc3}/codec: bc2}/' "$WORK/codec_error.yaml" >"$WORK/option.yaml"
expect_error "option.yaml:.*variants.bc3: .*codec" "$BLOCKLAB" analyze "$WORK/option.yaml" --out "$WORK/bad"
sed -e 's/^variants:/varients:/' "$WORK/codec_error.yaml" >"$WORK/typo.yaml"
expect_error "typo.yaml:6:.*varients" "$BLOCKLAB" analyze "$WORK/typo.yaml" --out "$WORK/bad"
echo "all wang_codec_error checks passed"
