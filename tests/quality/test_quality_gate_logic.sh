#!/usr/bin/env bash
# The gate's comparison rules on hand-made CSVs: an equal run passes, a worse error or a lower PSNR beyond the
# tolerance fails, a change within the tolerance or an improvement passes (and is reported), a missing row or a
# failed row fails. Usage: test_quality_gate_logic.sh BLOCKLAB REPO_ROOT
set -euo pipefail
root=$2
gate="python3 $root/scripts/quality_gate.py"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
results_header='key,experiment,image,image_sha256,width,height,channels,format,label,ablation,options,ablation_patch,bpp,encode_seconds,decode_seconds,threads,seed,input_policy,input_changed,status,error,blocklab_version,git_sha,mode_shares,log2rgb,mpsnr'
row() {   # label log2rgb mpsnr [status]
  echo "k,gate,a.exr,sha,4,4,3,f,$1,,{},,8,0.5,0.1,1,1,clamp,0,${4:-ok},,v,g,,$2,$3"
}
printf '%s\n%s\n%s\n' "$results_header" "$(row f1 0.5 40)" "$(row f2 0.25 inf)" > "$dir/base_run.csv"
$gate update "$dir/base_run.csv" "$dir/baseline.csv" > /dev/null
printf 'metric,absolute,relative\nlog2rgb,0,0.01\nmpsnr,0.01,0\n' > "$dir/tol.csv"
expect() {   # expected-exit description log2rgb(f1) mpsnr(f1) [status(f1)] [drop f2]
  local want=$1 what=$2
  { echo "$results_header"; row f1 "$3" "$4" "${5:-ok}"; [ "${6:-}" = drop ] || row f2 0.25 inf; } > "$dir/run.csv"
  set +e
  $gate check "$dir/run.csv" "$dir/baseline.csv" --tolerances "$dir/tol.csv" > "$dir/out" 2>&1
  local got=$?
  set -e
  if [ "$got" != "$want" ]; then
    echo "FAIL: $what: exit $got, expected $want"; cat "$dir/out"; exit 1
  fi
  echo "ok: $what (exit $got)"
}
expect 0 "the same values pass" 0.5 40
expect 0 "a log2rgb rise within 1 % passes" 0.504 40
expect 1 "a log2rgb rise beyond 1 % fails" 0.51 40
expect 1 "an mPSNR drop beyond 0.01 dB fails" 0.5 39.9
expect 0 "an improvement passes" 0.4 41
grep -q "improved" "$dir/out" || { echo "FAIL: the improvement is not reported"; exit 1; }
expect 1 "an error that becomes nan fails" nan 40
expect 1 "a failed row fails" 0.5 40 failed
expect 1 "a missing row fails" 0.5 40 ok drop
