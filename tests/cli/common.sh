# Shared helpers for the command-line tests. Each test script is run by CTest as
#   bash <script> <blocklab binary> <source dir> <shared data dir>
set -euo pipefail
BLOCKLAB=$1
SOURCE_DIR=$2
SHARED_DATA=$3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

die() { echo "FAIL: $*" >&2; exit 1; }

# expect_error <pattern> <command...>: the command must exit non-zero with exactly one line on stderr matching pattern.
expect_error() {
  local pattern=$1; shift
  local status=0
  "$@" >"$WORK/stdout" 2>"$WORK/stderr" || status=$?
  [ "$status" -ne 0 ] || die "expected failure, got exit 0: $*"
  [ "$(wc -l <"$WORK/stderr")" -eq 1 ] || die "expected a one-line error from '$*', got: $(cat "$WORK/stderr")"
  grep -qE "$pattern" "$WORK/stderr" || die "error of '$*' does not match /$pattern/: $(cat "$WORK/stderr")"
  echo "ok: $(cat "$WORK/stderr")"
}

need_shared_data() {
  if [ ! -d "$SHARED_DATA/hdr" ]; then echo "shared data not found at $SHARED_DATA: skipped"; exit 77; fi
}
