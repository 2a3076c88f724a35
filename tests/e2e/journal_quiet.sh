#!/bin/sh
# The journal says what changed, once (docs/operations.md "The journal"):
# after start-up, 10 simulated minutes of healthy charging write at most 10
# lines, and so does a 100 s alternator over-temperature fault. Run at
# --speed 40 (15 s of wall time each), so a line written every wall second
# (15 of them) would show as well as one every simulated second.
# Usage: journal_quiet.sh XREGULATORD ROOT (healthy|thermal)
set -eu
bin=$1
root=$2
case=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; cat "$tmp/log"; exit 1; }

cat >"$tmp/scenario.toml" <<'TOML'
name = "quiet journal"
duration_s = 600
seed = 3
[config]
BatteryProfile = "agm"
BatteryCapacity_Ah = 200
[battery]
chemistry = "agm"
capacity_ah = 200
soc_pct = 60
[alternator]
rated_a = 100
temp_f = 80
ambient_f = 85
[engine]
rpm = 1600
[loads]
house_a = 5
TOML
if [ "$case" = thermal ]; then
  cat >>"$tmp/scenario.toml" <<'TOML'
[[events]]
at_s = 200
fault = "temp_value"
value = 170
[[events]]
at_s = 300
clear = "temp_value"
TOML
fi

"$bin" --sim --scenario "$tmp/scenario.toml" --speed 40 --duration 600 --http 127.0.0.1:0 \
  --config "$root/config/xregulator.toml" >"$tmp/log" 2>&1 || fail "xregulatord exited $?"

# Start-up ends with the control thread's line; what follows is counted,
# the first tick's events included, up to the stop (its "stopped cleanly"
# and the final loop figures are the stop's own).
start=$(grep -n "control thread:" "$tmp/log" | head -1 | cut -d: -f1)
[ -n "$start" ] || fail "no start-up line"
after=$(tail -n +"$((start + 1))" "$tmp/log" | grep -v "stopped cleanly\|control loop:" || true)
# The fault's lines: from its first one to the stop.
[ "$case" = thermal ] && after=$(printf '%s\n' "$after" | sed -n '/Temperature/,$p')
count=$(printf '%s' "$after" | grep -c . || true)
echo "$case: $count journal lines after start-up"
printf '%s\n' "$after"
printf '%s\n' "$after" | grep -q "nan" && fail "a line shows nan"
[ "$count" -le 10 ] || fail "$count lines after start-up (at most 10)"
if [ "$case" = thermal ]; then
  grep -q -i "temperature" "$tmp/log" || fail "the fault was not told at all"
fi
exit 0
