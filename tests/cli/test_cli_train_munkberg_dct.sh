# The munkberg DCT mode's tables are reproducible: `blocklab train munkberg-dct` on ../shared/data writes
# formats/munkberg/dct_tables.yaml byte for byte (the file the build embeds), and it refuses a held-out name that is
# not an image of the set, or a missing data root, with a one-line error.
source "$(dirname "$0")/common.sh"
need_shared_data

"$BLOCKLAB" train munkberg-dct --quiet --data-root "$SHARED_DATA" --out "$WORK/tables.yaml"
cmp "$WORK/tables.yaml" "$SOURCE_DIR/formats/munkberg/dct_tables.yaml" ||
  die "training does not reproduce formats/munkberg/dct_tables.yaml (retrained without committing, or nondeterministic)"
echo "ok: training reproduces formats/munkberg/dct_tables.yaml"

expect_error "held-out image 'hdr/nope.exr'" \
  "$BLOCKLAB" train munkberg-dct --data-root "$SHARED_DATA" --hold-out hdr/nope.exr --out "$WORK/x.yaml"
expect_error "not a folder" "$BLOCKLAB" train munkberg-dct --data-root "$WORK/missing" --out "$WORK/x.yaml"
expect_error "unknown training 'bc9'" "$BLOCKLAB" train bc9 --data-root "$SHARED_DATA" --out "$WORK/x.yaml"
