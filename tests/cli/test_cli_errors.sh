# Bad input gives a one-line error naming the file, key or name, and a non-zero exit code.
source "$(dirname "$0")/common.sh"
img="$SOURCE_DIR/samples/hdr/Desk.exr"

# truncated image file
head -c 1000 "$img" >"$WORK/truncated.exr"
expect_error "truncated.exr" "$BLOCKLAB" encode --format fp16 "$WORK/truncated.exr" "$WORK/out.blk"
# truncated container
"$BLOCKLAB" encode --format rgbe "$img" "$WORK/good.blk" 2>/dev/null
head -c 100 "$WORK/good.blk" >"$WORK/truncated.blk"
expect_error "truncated.blk" "$BLOCKLAB" decode "$WORK/truncated.blk" "$WORK/out.exr"
# unknown format name lists the valid ones
expect_error "unknown format 'fp17'.*fp16" "$BLOCKLAB" encode --format fp17 "$img" "$WORK/out.blk"
# unknown option
expect_error "unknown option 'qualty'" "$BLOCKLAB" encode --format fp16 --set qualty=3 "$img" "$WORK/out.blk"
# unknown metric
expect_error "unknown metric 'psnrr'" "$BLOCKLAB" compare --metrics psnrr "$img" "$img"
# a YAML key spelled wrong: the error names the file and the line
cat >"$WORK/bad.yaml" <<'YAML'
schema: 1
name: bad
images: [hdr/Desk.exr]
metrics: [log2rgb]
formats:
  - format: fp16
    optoins: {seed: 2}
YAML
expect_error "bad.yaml:7.*optoins" "$BLOCKLAB" run "$WORK/bad.yaml" --out "$WORK/run"
# malformed YAML
printf 'schema: 1\nname: [unclosed\n' >"$WORK/malformed.yaml"
expect_error "malformed.yaml" "$BLOCKLAB" run "$WORK/malformed.yaml" --out "$WORK/run"
# a format without a DDS form is refused before the input is even read (here it does not exist), not after encoding
expect_error "out.dds.*'munkberg' has no DDS form" "$BLOCKLAB" encode --format munkberg "$WORK/no_input.exr" "$WORK/out.dds"
[[ ! -e "$WORK/out.dds" ]] || die "a refused encode wrote out.dds"
# missing file
expect_error "no_such_file.exr" "$BLOCKLAB" compare "$WORK/no_such_file.exr" "$img"
echo "all error cases passed"
