#!/usr/bin/env bash
# Whole-daemon tests (docs/architecture.md): end xregulatord by each exit path
# and read back the last PWM duty and field enable it left, from the
# simulation's output mirror (--sim-outputs). Also the command line's exit
# codes. Usage: exit_paths.sh XREGULATORD CASE [REPO_ROOT]
# Nothing here asserts a duration: the daemon's own time is simulated.
set -uo pipefail
bin=$1
case_name=$2
root=${3:-$(cd "$(dirname "$0")/../.." && pwd)}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL [$case_name]: $*" >&2; [ -f "$tmp/log" ] && tail -20 "$tmp/log" >&2; exit 1; }

# The mirror line: "duty_pct=  0.000 enable=0 buzzer=0 via=stop"
field_of() { sed -n 's/.*enable=\([01]\).*/\1/p' "$1"; }
duty_of() { sed -n 's/^duty_pct= *\([0-9.]*\).*/\1/p' "$1"; }
via_of() { sed -n 's/.*via=\([a-z]*\).*/\1/p' "$1"; }

expect_field_off() {  # file via
  [ -s "$1" ] || fail "no sim outputs file"
  [ "$(field_of "$1")" = 0 ] || fail "field enable left HIGH: $(cat "$1")"
  [ "$(duty_of "$1")" = "0.000" ] || fail "duty left at $(duty_of "$1"): $(cat "$1")"
  [ "$(via_of "$1")" = "$2" ] || fail "expected via=$2: $(cat "$1")"
}

# Waits (up to 120 s of wall time, a generous CI bound, not an assertion on
# speed) until the mirror says the field is on.
wait_field_on() {
  for _ in $(seq 1 1200); do
    [ "$(field_of "$1" 2>/dev/null)" = 1 ] && return 0
    kill -0 "$2" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}

# A stop signal while the field is on: controlled ramp, then enable LOW and
# duty 0, exit 0, mirror via=stop.
stop_signal() {
  local sig=$1
  "$bin" --sim --speed 50 --sim-outputs "$tmp/out" --telemetry-csv "$tmp/t.csv" >"$tmp/log" 2>&1 &
  local pid=$!
  wait_field_on "$tmp/out" "$pid" || { kill -9 $pid 2>/dev/null; fail "field never came on"; }
  kill -"$sig" "$pid"
  wait "$pid"
  local rc=$?
  [ "$rc" = 0 ] || fail "exit code $rc after SIG$sig"
  expect_field_off "$tmp/out" stop
  grep -q "controlled ramp" "$tmp/log" || fail "no controlled-ramp log line"
  grep -q "stopped cleanly" "$tmp/log" || fail "no clean-stop log line"
}

# Any other signal whose default action ends the process (docs/security.md):
# the same controlled ramp, a journal line naming it, and exit 128 + signal
# so that systemd restarts the regulator. A fault signal sent from outside:
# the fatal handler drives the field LOW, names the signal, dies with it.
# An ignored one (SIGHUP, SIGTSTP) leaves the regulator running.
signal_path() {
  local sig=$1 want=$2
  local num
  num=$(kill -l "$sig") || fail "no signal $sig"
  "$bin" --sim --speed 50 --sim-outputs "$tmp/out" >"$tmp/log" 2>&1 &
  local pid=$!
  wait_field_on "$tmp/out" "$pid" || { kill -9 $pid 2>/dev/null; fail "field never came on"; }
  kill -"$sig" "$pid"
  if [ "$want" = ignored ]; then
    sleep 1  # not an assertion on speed: the daemon must simply still be there
    kill -0 "$pid" 2>/dev/null || fail "SIG$sig ended the daemon"
    [ "$(field_of "$tmp/out")" = 1 ] || fail "SIG$sig turned the field off: $(cat "$tmp/out")"
    kill -TERM "$pid"
    wait "$pid"
    local rc=$?
    [ "$rc" = 0 ] || fail "exit code $rc after SIGTERM"
    expect_field_off "$tmp/out" stop
    grep -q "SIG$sig.*ignored" "$tmp/log" || fail "no log line for the ignored SIG$sig"
    return
  fi
  wait "$pid"
  local rc=$?
  [ "$rc" = $((128 + num)) ] || fail "exit code $rc after SIG$sig, expected $((128 + num))"
  if [ "$want" = stop ]; then
    expect_field_off "$tmp/out" stop
    grep -q "SIG$sig: not a signal xregulatord uses; stopping through the controlled ramp" "$tmp/log" ||
      fail "no journal line naming SIG$sig"
  else
    expect_field_off "$tmp/out" fatal
    grep -q "fatal signal SIG$sig: field enable LOW" "$tmp/log" || fail "no journal line naming SIG$sig"
  fi
}

# A fault at simulated t = 60 s (or just after, for the main thread), when a reference run of the same seed has
# the field on (the simulation is deterministic at --speed max).
fault_path() {
  local kind=$1 want_rc=$2 speed=${3:-max}
  "$bin" --sim --speed max --duration 60 --seed 3 --telemetry-csv "$tmp/ref.csv" >"$tmp/reflog" 2>&1 ||
    fail "reference run failed"
  local col on
  col=$(head -1 "$tmp/ref.csv" | tr ',' '\n' | grep -n '^field_enable$' | cut -d: -f1)
  on=$(tail -1 "$tmp/ref.csv" | cut -d, -f"$col")
  [ "$on" = 1 ] || fail "reference run does not have the field on at 60 s"
  "$bin" --sim --speed "$speed" --duration 120 --seed 3 --sim-outputs "$tmp/out" \
    --test-fault "$kind" --test-fault-at 60 >"$tmp/log" 2>&1
  local rc=$?
  [ "$rc" = "$want_rc" ] || fail "exit code $rc, expected $want_rc"
  expect_field_off "$tmp/out" fatal
}

case "$case_name" in
  sigterm) stop_signal TERM ;;
  sigint) stop_signal INT ;;
  segv) fault_path segv 139 ;;
  abort) fault_path abort 134 ;;
  terminate) fault_path terminate 134 ;;
  throw_main) fault_path throw 70 50 ;;  # the main thread polls in wall time: pace the run
  throw_control) fault_path throw-control 70 ;;
  signal_*)
    sig=${case_name#signal_}
    case "$sig" in
      SEGV | ABRT | BUS | FPE | ILL | TRAP | SYS) signal_path "$sig" fatal ;;
      HUP | TSTP | TTIN | TTOU) signal_path "$sig" ignored ;;
      *) signal_path "$sig" stop ;;
    esac
    ;;
  duration)
    "$bin" --sim --speed max --duration 10 --telemetry-csv "$tmp/t.csv" --telemetry-rate 10 \
      --sim-outputs "$tmp/out" >"$tmp/log" 2>&1 || fail "exit code $?"
    expect_field_off "$tmp/out" stop
    rows=$(($(wc -l <"$tmp/t.csv") - 1))
    [ "$rows" -ge 99 ] && [ "$rows" -le 101 ] || fail "expected ~100 rows at 10 Hz for 10 s, got $rows"
    for c in t_s mode stage reason ibv_v battery_v bcur_a alt_a rpm temp_f duty_pct field_enable setpoint_a \
      target_a target_v thermal_penalty_a fast_ov_active soc_pct alarm charged_wh_lifetime \
      alt_charged_wh_lifetime sim_battery_v sim_alt_a sim_alt_temp_f sim_soc_pct sim_bms_connected sim_field_on; do
      head -1 "$tmp/t.csv" | tr ',' '\n' | grep -qx "$c" || fail "CSV column $c missing"
    done
    grep -q "^10," "$tmp/t.csv" || grep -q "^9.9," "$tmp/t.csv" || fail "CSV does not reach t_s = 10"
    ;;
  cli)
    "$bin" --bogus >"$tmp/log" 2>&1; [ $? = 64 ] || fail "unknown option: exit code not 64"
    grep -q "unknown option '--bogus'" "$tmp/log" || fail "unknown option not named"
    "$bin" --speed fast --sim >"$tmp/log" 2>&1; [ $? = 64 ] || fail "bad --speed: not 64"
    "$bin" --scenario x.toml >"$tmp/log" 2>&1; [ $? = 64 ] || fail "--scenario without --sim: not 64"
    "$bin" --version | grep -q "^xregulatord [0-9]" || fail "--version"
    "$bin" --print-default-config >"$tmp/default.toml" || fail "--print-default-config exit code"
    cmp -s "$tmp/default.toml" "$root/config/xregulator.toml" || fail "--print-default-config differs from config/xregulator.toml"
    "$bin" --config "$tmp/default.toml" --check-config >"$tmp/log" 2>&1 || fail "--check-config of the default: $?"
    printf '[voltage]\nBulkVoltage = 99\n' >"$tmp/bad.toml"
    "$bin" --config "$tmp/bad.toml" --check-config >"$tmp/log" 2>&1; [ $? = 78 ] || fail "bad config: not 78"
    grep -q BulkVoltage "$tmp/log" || fail "bad config error does not name the key"
    "$bin" --config "$tmp/bad.toml" --sim --duration 1 --speed max >"$tmp/log" 2>&1
    [ $? = 78 ] || fail "daemon with a bad config: not 78"
    # only regular files, bounded.
    mkdir "$tmp/confdir"
    "$bin" --config "$tmp/confdir" --check-config >"$tmp/log" 2>&1; [ $? = 78 ] || fail "a directory as --config: not 78"
    grep -q "is a directory, not a configuration file" "$tmp/log" || fail "directory not named as such"
    "$bin" --config /dev/zero --check-config >"$tmp/log" 2>&1; [ $? = 78 ] || fail "/dev/zero as --config: not 78"
    mkfifo "$tmp/fifo.toml"
    "$bin" --config "$tmp/fifo.toml" --sim --duration 1 --speed max >"$tmp/log" 2>&1
    [ $? = 78 ] || fail "a FIFO as --config: not 78"
    # a listen address the server could not bind is a config error.
    printf '[web]\nlisten = "localhost"\n' >"$tmp/listen.toml"
    "$bin" --config "$tmp/listen.toml" --check-config >"$tmp/log" 2>&1; [ $? = 78 ] || fail "listen = localhost: not 78"
    grep -q "web.listen: 'localhost' is not an IP address" "$tmp/log" || fail "bad listen not named"
    # A bad scenario (and a bad plant parameter in one) is bad command-line
    # input: exit 64 with a file:line: message, and the field never enabled.
    printf 'name = "x"\nduration_s = -5\n' >"$tmp/bad-scenario.toml"
    "$bin" --sim --scenario "$tmp/bad-scenario.toml" --speed max >"$tmp/log" 2>&1
    [ $? = 64 ] || fail "bad scenario: not 64"
    grep -q "bad-scenario.toml:2:" "$tmp/log" || fail "bad scenario: no file:line:"
    printf 'name = "x"\n[alternator]\nfield_r_ohm = -2.5\n' >"$tmp/neg-r.toml"
    "$bin" --sim --scenario "$tmp/neg-r.toml" --speed max >"$tmp/log" 2>&1
    [ $? = 64 ] || fail "negative field resistance: not 64"
    grep -q "neg-r.toml:3:.*field_r_ohm" "$tmp/log" || fail "negative resistance: no file:line: naming the key"
    printf 'name = "x"\n[alternator]\npulley_ratio = 3\ncut_in_rpm = 7000\n' >"$tmp/knee.toml"
    "$bin" --sim --scenario "$tmp/knee.toml" --speed max >"$tmp/log" 2>&1
    [ $? = 64 ] || fail "knee above the maximum speed: not 64"
    grep -q "knee.toml:4:.*maximum speed" "$tmp/log" || fail "knee above the maximum speed: no file:line:"
    printf 'name = "x"\n[battery]\nocv_soc_pct = [0, 50, 100]\nocv_cell_v = [3.0, 3.4, 3.3]\n' >"$tmp/ocv.toml"
    "$bin" --sim --scenario "$tmp/ocv.toml" --speed max >"$tmp/log" 2>&1
    [ $? = 64 ] || fail "OCV table not monotone: not 64"
    grep -q "ocv.toml:4:.*monotone" "$tmp/log" || fail "OCV table not monotone: no file:line:"
    # Output files that cannot be created stop the daemon at start (exit 78,
    # like --telemetry-csv), naming the file and the OS error; the field is
    # never enabled.
    "$bin" --sim --speed max --duration 5 --can-log "$tmp/no-such-dir/can.log" --sim-outputs "$tmp/out-can" \
      >"$tmp/log" 2>&1
    [ $? = 78 ] || fail "--can-log in a missing directory: not 78"
    grep -q "cannot create CAN log $tmp/no-such-dir/can.log: No such file or directory" "$tmp/log" \
      || fail "--can-log error does not name the file and the OS error: $(cat "$tmp/log")"
    [ "$(field_of "$tmp/out-can" 2>/dev/null)" != 1 ] || fail "--can-log failure: the field was enabled"
    "$bin" --sim --speed max --duration 5 --telemetry-csv "$tmp/no-such-dir/t.csv" >"$tmp/log" 2>&1
    [ $? = 78 ] || fail "--telemetry-csv in a missing directory: not 78"
    grep -q "no-such-dir/t.csv: No such file or directory" "$tmp/log" || fail "--telemetry-csv error not named"
    ;;
  board_bad_http)
    # On a board, a bad --http is refused with the command line, before any
    # device opens: the watchdog (a plain file standing in for
    # /dev/watchdog) is never opened, so it can neither be armed nor reset
    # the board. A board whose GPIO is missing stops before the watchdog too.
    : >"$tmp/wd"
    printf '[hardware]\nwatchdog_device = "%s"\ngpio_chip = "%s/no-gpiochip"\n' "$tmp/wd" "$tmp" >"$tmp/board.toml"
    "$bin" --config "$tmp/board.toml" --http 'not-an-address' --state-db "$tmp/s.db" >"$tmp/log" 2>&1
    rc=$?
    [ "$rc" = 78 ] || fail "bad --http on a board: exit $rc, not 78"
    grep -q -- "--http:" "$tmp/log" || fail "the --http error is not named"
    grep -q "GPIO\|hardware setup" "$tmp/log" && fail "a device was opened before the --http check"
    [ ! -s "$tmp/wd" ] || fail "the watchdog was written: $(od -c "$tmp/wd" | head -2)"
    [ ! -e "$tmp/s.db" ] || fail "the state database was created before the --http check"
    "$bin" --config "$tmp/board.toml" --http 127.0.0.1:0 --state-db "$tmp/s.db" >"$tmp/log" 2>&1
    rc=$?
    [ "$rc" = 69 ] || fail "a board without its GPIO: exit $rc, not 69"
    grep -q "hardware setup failed: GPIO" "$tmp/log" || fail "the missing GPIO is not named"
    [ ! -s "$tmp/wd" ] || fail "the watchdog was armed by a board that could not start"
    ;;
  web_cannot_start)
    # 192.0.2.1 (TEST-NET-1) is a valid address no interface
    # has: the server cannot bind it. The regulator runs on, loudly.
    "$bin" --sim --speed max --duration 20 --http 192.0.2.1:8080 --sim-outputs "$tmp/out" >"$tmp/log" 2>&1
    rc=$?
    [ "$rc" = 0 ] || fail "exit code $rc: a web server that cannot start stopped the regulator"
    grep -q "the regulator runs WITHOUT the dashboard and API" "$tmp/log" || fail "no loud log line"
    grep -q "Field enabled" "$tmp/log" || fail "the regulator never enabled the field"
    expect_field_off "$tmp/out" stop
    ;;
  command_refused)
    # items 9 and 11 through the real daemon and HTTP.
    token=0123456789abcdef-e2e
    printf '[web]\ntoken = "%s"\n' "$token" >"$tmp/web.toml"
    chmod 644 "$tmp/web.toml"
    "$bin" --config "$tmp/web.toml" --sim --speed 5 --http 127.0.0.1:0 --state-db "$tmp/s.db" >"$tmp/log" 2>&1 &
    pid=$!
    port=""
    for _ in $(seq 1 300); do
      port=$(sed -n 's|.*dashboard at http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$tmp/log")
      [ -n "$port" ] && break
      sleep 0.1
    done
    [ -n "$port" ] || { kill $pid; fail "no dashboard port in the log"; }
    post() { curl -s -o "$tmp/body" -w '%{http_code}' -H "Authorization: Bearer $token" \
      -H 'Content-Type: application/json' -d "$1" "http://127.0.0.1:$port/api/commands"; }
    code=$(post '{"command":"tuning_commit"}')
    [ "$code" = 409 ] || { kill $pid; fail "refused command answered $code: $(cat "$tmp/body")"; }
    grep -q "refused by the regulator: TuningMode is off" "$tmp/body" || { kill $pid; fail "no reason: $(cat "$tmp/body")"; }
    code=$(post '{"command":"manual","duty":10}')
    [ "$code" = 200 ] || { kill $pid; fail "applied command answered $code: $(cat "$tmp/body")"; }
    grep -q '"applied: manual"' "$tmp/body" || { kill $pid; fail "applied command: $(cat "$tmp/body")"; }
    kill -TERM $pid
    wait $pid || fail "exit code $? after SIGTERM"
    grep -q "$token" "$tmp/log" && fail "the token reached the log"
    grep -q "token is set in a file every user of this machine can read" "$tmp/log" || fail "no world-readable warning"
    [ "$(stat -c %a "$tmp/s.db")" = 600 ] || fail "state database mode $(stat -c %a "$tmp/s.db"), expected 600"
    ;;
  store_damaged | store_newer)
    # item 4 through the daemon binary: the user's data survives a
    # damaged state database (restored from the verified .bak, said once in
    # the log) and a newer release's database is never written; the field
    # control runs either way.
    db="$tmp/s.db"
    "$bin" --sim --speed max --duration 600 --state-db "$db" --http 127.0.0.1:0 >"$tmp/log" 2>&1 || fail "first run: exit $?"
    token=$("$bin" --print-token --state-db "$db" 2>/dev/null) || fail "no token stored"
    energy() { sqlite3 "file:$db?mode=ro" "SELECT value FROM ledger WHERE name = 'ChargedEnergy_AllTime'"; }
    e1=$(energy)
    awk -v e="$e1" 'BEGIN { exit !(e > 0) }' || fail "no lifetime energy after the first run ($e1)"
    "$bin" --sim --speed max --duration 1 --state-db "$db" >"$tmp/log" 2>&1 || fail "second run: exit $?"
    [ -s "$db.bak" ] || fail "no backup $db.bak"
    if [ "$case_name" = store_damaged ]; then
      head -c 40000 /dev/urandom >"$db"
      rm -f "$db-wal" "$db-shm"
    else
      sqlite3 "$db" "PRAGMA user_version = 99" || fail "cannot set user_version"
      before=$(md5sum <"$db")
    fi
    "$bin" --sim --speed max --duration 20 --state-db "$db" --sim-outputs "$tmp/out" >"$tmp/log" 2>&1
    rc=$?
    [ "$rc" = 0 ] || fail "exit code $rc with a $case_name database"
    grep -q "Field enabled" "$tmp/log" || fail "the regulator never enabled the field"
    expect_field_off "$tmp/out" stop
    if [ "$case_name" = store_damaged ]; then
      [ "$(grep -c 'error store: StoreRestored: .*restored from the verified backup' "$tmp/log")" = 1 ] ||
        fail "not said once in the log"
      ls "$db".corrupt-* >/dev/null 2>&1 || fail "the damaged file was not kept"
      [ "$("$bin" --print-token --state-db "$db" 2>/dev/null)" = "$token" ] || fail "the token changed"
      awk -v a="$(energy)" -v b="$e1" 'BEGIN { exit !(a >= b) }' || fail "lifetime energy went down: $(energy) < $e1"
    else
      grep -q "error store: StoreNewerSchema: .*schema v99.*NOTHING IS SAVED" "$tmp/log" || fail "not said loudly"
      [ "$(md5sum <"$db")" = "$before" ] || fail "the newer release's database was changed"
      ls "$db".corrupt-* >/dev/null 2>&1 && fail "the newer database was moved aside"
    fi
    ;;
  store_locked)
    # One daemon per state database (docs/operations.md "State database"):
    # a second daemon on the same file exits 75 with the holder's pid before
    # it drives any output; kill -9 of the holder frees the lock.
    db="$tmp/s.db"
    "$bin" --sim --speed 50 --state-db "$db" --sim-outputs "$tmp/out1" >"$tmp/log1" 2>&1 &
    first=$!
    wait_field_on "$tmp/out1" "$first" || { kill -9 $first 2>/dev/null; fail "first daemon never enabled the field"; }
    "$bin" --sim --speed max --duration 5 --state-db "$db" --sim-outputs "$tmp/out2" >"$tmp/log" 2>&1
    rc=$?
    kill -0 "$first" 2>/dev/null || fail "the first daemon died"
    [ "$rc" = 75 ] || { kill -9 $first; fail "second daemon: exit $rc, expected 75"; }
    grep -q "another xregulatord (pid $first) uses the state database $db" "$tmp/log" ||
      { kill -9 $first; fail "no clear message naming the holder"; }
    if [ -s "$tmp/out2" ]; then [ "$(field_of "$tmp/out2")" = 0 ] || { kill -9 $first; fail "second daemon enabled the field"; }; fi
    kill -9 "$first"
    wait "$first" 2>/dev/null
    "$bin" --sim --speed max --duration 2 --state-db "$db" >"$tmp/log" 2>&1 || fail "after kill -9 of the holder: exit $?"
    ;;
  *) fail "unknown case" ;;
esac
echo "PASS [$case_name]"
