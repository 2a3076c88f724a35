#!/usr/bin/env bash
# Control-loop timing benchmark (docs/architecture.md): a 60 s real-time simulated run
# (--sim --speed 1) with 20 WebSocket clients on the dashboard; reports the
# period error p50/p99/max, overruns, compute and I/O time, and the ADS
# sample rates from the daemon's final statistics line.
# Usage: run-control-loop.sh BUILD_DIR OUT_DIR [SECONDS] [CLIENTS]
set -euo pipefail
build=${1:-build}
out=${2:-$build/bench-results}
secs=${3:-60}
clients=${4:-20}
here=$(cd "$(dirname "$0")" && pwd)
bin=$build/daemon/app/xregulatord
mkdir -p "$out"
# First what the platform allows: a bare SCHED_FIFO thread sleeping to the
# same 2.5 ms deadlines, under the same load (the WebSocket clients are not
# running yet, so this is the quiet baseline).
baseline=$("$build/bench-tools/xr_timer_baseline" 20 2500 || echo "timer baseline: not available")
port=$((20000 + RANDOM % 20000))
log=$out/control-loop.log
"$bin" --sim --speed 1 --duration "$secs" --http 127.0.0.1:$port >"$log" 2>&1 &
pid=$!
for _ in $(seq 1 100); do
  curl -sf "http://127.0.0.1:$port/healthz" >/dev/null 2>&1 && break
  sleep 0.1
done
python3 "$here/ws_clients.py" 127.0.0.1 "$port" "$clients" "$((secs - 3))" >"$out/control-loop-ws.txt" || true
wait "$pid"
line=$(grep "control loop:" "$log" | tail -1)
{
  echo "run: --sim --speed 1, ${secs} s, $clients WebSocket clients, $(nproc) CPUs, kernel $(uname -r)"
  echo "$baseline"
  echo "${line#*info  }"
  cat "$out/control-loop-ws.txt"
} | tee "$out/control-loop.txt"
