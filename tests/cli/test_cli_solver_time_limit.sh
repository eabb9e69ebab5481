# Every solver's `time_limit` option bounds a solve whose other budget is enormous: a BC1 encode of an 8x8 crop of
# kodim03 with anneal at 10^9 moves per run (the largest accepted) and time_limit=0.01 s finishes in well under 10 s (each of the four
# block solves stops at its limit with the best endpoints so far) and writes a decodable file; time_limit=0 is
# refused with an error naming the option, and so is 10^12 moves (a run that could never finish).
source "$(dirname "$0")/common.sh"
cd "$SOURCE_DIR"
"$BLOCKLAB" convert samples/ldr/kodak/kodim03.png "$WORK/crop.png" --crop 0,0,8,8
started=$(date +%s.%N)
"$BLOCKLAB" encode --format bc1 --set solver=anneal \
  --set solver_options=iterations=1000000000,time_limit=0.01 "$WORK/crop.png" "$WORK/crop.blk"
finished=$(date +%s.%N)
elapsed=$(/usr/bin/python3 -c "print(f'{$finished - $started:.3f}')")
/usr/bin/python3 -c "import sys; sys.exit(0 if $elapsed < 10 else 1)" || die "encode took $elapsed s (limit 10 s)"
echo "ok: bc1 anneal encode with iterations=1e9, time_limit=0.01 took $elapsed s"
"$BLOCKLAB" decode "$WORK/crop.blk" "$WORK/decoded.png"
[ -s "$WORK/decoded.png" ] || die "decoding the time-limited encode wrote nothing"
expect_error "time_limit" "$BLOCKLAB" encode --format bc1 --set solver=anneal \
  --set solver_options=time_limit=0 "$WORK/crop.png" "$WORK/refused.blk"
expect_error "iterations" "$BLOCKLAB" encode --format bc1 --set solver=anneal \
  --set solver_options=iterations=1000000000000 "$WORK/crop.png" "$WORK/refused.blk"
[ ! -e "$WORK/refused.blk" ] || die "a refused encode left $WORK/refused.blk"
