#!/usr/bin/env bash
# Web load benchmark (docs/security.md): xregulatord --sim --speed 1, 50 WebSocket
# clients plus wrk on /api/status for DURATION seconds (default 60). Reports
# req/s, p99 latency, server RSS, WebSocket frames, and the control loop's
# overruns (must stay 0) and period p99 from /api/status loop statistics.
# Usage: tests/bench/web/run-web.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
out=${2:-$build/bench-results}
mkdir -p "$out"
duration=${DURATION:-60}
clients=${WS_CLIENTS:-50}
daemon=$build/daemon/app/xregulatord
wsc=$build/tests/bench/web/xr_ws_clients
for f in "$daemon" "$wsc"; do [ -x "$f" ] || { echo "run-web: missing $f (build first)"; exit 1; }; done
command -v wrk >/dev/null || { echo "run-web: wrk not installed (make deps)"; exit 1; }

tmp=$(mktemp -d)
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
cat >"$tmp/xregulator.toml" <<TOML
[web]
token = "bench-token-for-the-web-benchmark"
max_connections = 256   # 50 WebSocket + 50 wrk connections fit under the cap
www_root = "$build/web/www"
TOML
"$daemon" --sim --speed 1 --config "$tmp/xregulator.toml" --state-db "$tmp/state.db" \
  --http "127.0.0.1:$port" >"$tmp/daemon.log" 2>&1 &
pid=$!
cleanup() { kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; rm -rf "$tmp"; }
trap cleanup EXIT
for _ in $(seq 1 100); do
  curl -sf "http://127.0.0.1:$port/api/status" >/dev/null 2>&1 && break
  sleep 0.2
done
curl -sf "http://127.0.0.1:$port/api/status" >/dev/null || { echo "run-web: daemon did not serve"; cat "$tmp/daemon.log"; exit 1; }

loopstat() { curl -s "http://127.0.0.1:$port/api/status" | python3 -c '
import json,sys; l=json.load(sys.stdin)["loop"]
print(l["ticks"], l["overruns"], l["period_p99_us"], l["period_max_us"], l["target_period_us"])'; }
read -r ticks0 over0 _ _ target <<<"$(loopstat)"
rss0=$(awk '/VmRSS/{print $2}' /proc/$pid/status)

"$wsc" "$port" "$clients" "$duration" >"$tmp/ws.txt" &
wspid=$!
sleep 1
wrk -t2 -c50 -d"${duration}s" --latency "http://127.0.0.1:$port/api/status" >"$tmp/wrk.txt"
wait "$wspid"
read -r ticks1 over1 p99 pmax _ <<<"$(loopstat)"
rss1=$(awk '/VmRSS/{print $2}' /proc/$pid/status)
hwm=$(awk '/VmHWM/{print $2}' /proc/$pid/status)
rps=$(awk '/Requests\/sec/{print $2}' "$tmp/wrk.txt")
lat99=$(awk '$1=="99%"{print $2}' "$tmp/wrk.txt")
lat50=$(awk '$1=="50%"{print $2}' "$tmp/wrk.txt")
errs=$(grep -E "Non-2xx|Socket errors" "$tmp/wrk.txt" | tr '\n' ' ' || true)
[ -n "$errs" ] && errs="(WARNING: $errs)"

{
  echo "web load: ${duration} s, ${clients} WebSocket clients + wrk -t2 -c50 on /api/status ($(nproc) CPUs)"
  echo "  wrk: ${rps} req/s, latency p50 ${lat50}, p99 ${lat99} ${errs}"
  echo "  ws:  $(cat "$tmp/ws.txt")"
  echo "  server RSS: ${rss0} kB before, ${rss1} kB after, peak ${hwm} kB"
  echo "  control loop: overruns ${over0} -> ${over1} (during load: $((over1 - over0))), ticks $((ticks1 - ticks0)), period p99 ${p99} us, max ${pmax} us (target ${target} us)"
} | tee "$out/web.txt"
