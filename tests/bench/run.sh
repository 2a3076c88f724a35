#!/usr/bin/env bash
# make bench: run every Google Benchmark binary, then every whole-program
# benchmark script (tests/bench/*/run-*.sh). Results go to build/bench-results/.
set -euo pipefail
build=${1:-build}
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$build/bench-results
mkdir -p "$out"
for b in "$build"/bench/*; do
  [ -x "$b" ] || continue
  name=$(basename "$b")
  echo "== $name"
  "$b" --benchmark_out="$out/$name.json" --benchmark_out_format=json
done
for s in "$root"/tests/bench/*/run-*.sh; do
  [ -x "$s" ] || continue
  echo "== $(basename "$s")"
  "$s" "$build" "$out"
done
echo "results in $out"
