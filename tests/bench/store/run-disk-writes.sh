#!/usr/bin/env bash
# make bench: what the daemon writes to its disk per hour in cruising, at
# anchor and in a fault storm (disk_writes_daemon.py); fails (exit 1) when
# steady running writes 1 MB/h or more with the daily backup's share.
# Usage: run-disk-writes.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:-build}
out=${2:-$build/bench-results}
here=$(cd "$(dirname "$0")" && pwd)
python3 "$here/disk_writes_daemon.py" "$build" "$out" | tee "$out/disk-writes.txt"
