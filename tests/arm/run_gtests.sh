#!/usr/bin/env bash
# Runs cross-built GoogleTest binaries under qemu-user, each split into JOBS
# shards run side by side (GoogleTest's GTEST_TOTAL_SHARDS/GTEST_SHARD_INDEX:
# every test runs in exactly one shard). Used by `make test-arm64-ci`, CI's
# subset of `make test-arm64`: one qemu process per shard instead of one per
# test keeps the emulator's start-up cost out of CI's budget.
#
#   run_gtests.sh QEMU PREFIX JOBS BINARY...
#
# Prints one line per binary (tests passed, failed, seconds) and the output of
# any failing shard; exits 1 if any test failed, or if a binary ran no test.
set -uo pipefail
[ $# -ge 4 ] || { echo "usage: $0 QEMU PREFIX JOBS BINARY..." >&2; exit 2; }
qemu=$1 prefix=$2 jobs=$3
shift 3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0 total=0
for bin in "$@"; do
  name=$(basename "$bin")
  [ -x "$bin" ] || { echo "FAIL: $bin not built"; fails=$((fails + 1)); continue; }
  start=$(date +%s)
  pids=()
  for ((i = 0; i < jobs; i++)); do
    GTEST_TOTAL_SHARDS=$jobs GTEST_SHARD_INDEX=$i "$qemu" -L "$prefix" "$bin" >"$tmp/$name.$i" 2>&1 &
    pids+=($!)
  done
  bad=0
  for i in "${!pids[@]}"; do wait "${pids[$i]}" || bad=1; done
  passed=0 failed=0
  for ((i = 0; i < jobs; i++)); do
    p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$tmp/$name.$i")
    f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$tmp/$name.$i")
    passed=$((passed + ${p:-0})) failed=$((failed + ${f:-0}))
    if grep -q '^\[  FAILED  \]' "$tmp/$name.$i" || [ -z "$p" ]; then cat "$tmp/$name.$i"; bad=1; fi
  done
  total=$((total + passed))
  if [ $bad = 0 ] && [ $failed = 0 ] && [ $passed -gt 0 ]; then
    echo "ok: $name: $passed passed in $(($(date +%s) - start)) s ($jobs shards)"
  else
    echo "FAIL: $name: $passed passed, $failed failed"
    fails=$((fails + 1))
  fi
done
echo "$total tests passed under $(basename "$qemu"); $fails binary(ies) failed"
[ $fails = 0 ]
