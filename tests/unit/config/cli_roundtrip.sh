#!/bin/sh
# End to end through the real binary (docs/configuration.md): the printed default
# configuration is exactly config/xregulator.toml, it passes --check-config
# (exit 0), and a bad file exits 78 with its errors on stderr.
#   cli_roundtrip.sh XREGULATORD SOURCE_ROOT
set -u
exe=$1
root=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

"$exe" --print-default-config >"$tmp/default.toml" || { echo "FAIL: --print-default-config exited $?"; fail=1; }
cmp -s "$tmp/default.toml" "$root/config/xregulator.toml" && echo "ok: printed default == config/xregulator.toml" \
  || { echo "FAIL: --print-default-config differs from config/xregulator.toml"; fail=1; }

"$exe" --config "$tmp/default.toml" --check-config >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc = 0 ] && echo "ok: printed default passes --check-config" \
  || { cat "$tmp/out" "$tmp/err"; echo "FAIL: --check-config on the printed default exited $rc"; fail=1; }

printf '[voltage]\nBulkVoltag = 14.5\nFloatVoltage = 99\n[web]\nport = "x"\n' >"$tmp/bad.toml"
"$exe" --config "$tmp/bad.toml" --check-config >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc = 78 ] && echo "ok: bad file exits 78" || { echo "FAIL: bad file exited $rc, want 78"; fail=1; }
for want in "bad.toml:2:1: voltage.BulkVoltag: unknown parameter (did you mean BulkVoltage?)" \
  "bad.toml:3:1: voltage.FloatVoltage: 99 is out of range: allowed 8 to 64 V" \
  "bad.toml:5:1: web.port: expected a whole number"; do
  grep -qF "$want" "$tmp/err" && echo "ok: stderr has: $want" || { echo "FAIL: stderr lacks: $want"; cat "$tmp/err"; fail=1; }
done

printf '[voltage\n' >"$tmp/syntax.toml"
"$exe" --config "$tmp/syntax.toml" --check-config >/dev/null 2>"$tmp/err"
rc=$?
[ $rc = 78 ] && grep -q "syntax.toml:1:" "$tmp/err" && echo "ok: syntax error exits 78 with file:line" \
  || { cat "$tmp/err"; echo "FAIL: syntax error: exit $rc"; fail=1; }

# a profile's limits through the binary (exit 78 naming value and
# limit), and --print-config naming each value's source.
printf '[battery]\nBatteryProfile = "lifepo4"\n[voltage]\nBulkVoltage = 14.8\nAbsorptionVoltage = 14.8\n' >"$tmp/lfp.toml"
"$exe" --config "$tmp/lfp.toml" --check-config >"$tmp/out" 2>"$tmp/err"
rc=$?
want="lfp.toml:5:1: voltage.AbsorptionVoltage: 14.8 V is 3.7 V/cell on 4 cells, above the LiFePO4 limit 3.65 V/cell"
[ $rc = 78 ] && grep -qF "$want" "$tmp/err" && echo "ok: LiFePO4 over 3.65 V/cell exits 78 naming the limit" \
  || { cat "$tmp/err"; echo "FAIL: LiFePO4 limit: exit $rc"; fail=1; }
printf '[battery]\nBatteryProfile = "agm"\n[voltage]\nFloatVoltage = 13.2\n' >"$tmp/agm.toml"
"$exe" --config "$tmp/agm.toml" --state-db "$tmp/none.db" --print-config >"$tmp/out" 2>"$tmp/err"
rc=$?
for want in 'BatteryProfile = "agm"  # file' 'FloatVoltage = 13.2  # file' 'AbsorptionVoltage = 14.4  # profile' \
  'TempCompMvPerCellC = -4  # profile' 'PidKp = 0.3  # default'; do
  [ $rc = 0 ] && grep -qF "$want" "$tmp/out" && echo "ok: --print-config has: $want" \
    || { echo "FAIL: --print-config (exit $rc) lacks: $want"; cat "$tmp/err"; fail=1; }
done
# The shipped file as it comes names no battery: not set up, it runs within
# the limits safe for every chemistry, and says so (docs/configuration.md
# "Not set up").
"$exe" --config "$root/config/xregulator.toml" --check-config >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc = 0 ] && grep -qF "note: no BatteryProfile in this file" "$tmp/out" \
  && echo "ok: the shipped file passes --check-config with the not-set-up note" \
  || { cat "$tmp/out" "$tmp/err"; echo "FAIL: shipped file --check-config (exit $rc)"; fail=1; }
"$exe" --config "$root/config/xregulator.toml" --state-db "$tmp/none.db" --print-config >"$tmp/out" 2>"$tmp/err"
for want in '# NOT SET UP' 'BulkVoltage = 14  # not set up' 'FloatVoltage = 13.4  # not set up' \
  'ChargeMinTempC = 5  # not set up' 'ChargeMaxTempC = 45  # not set up' 'MaxTableValue = 60  # default'; do
  grep -qF "$want" "$tmp/out" && echo "ok: the shipped file, not set up: $want" \
    || { echo "FAIL: the shipped file, not set up, lacks: $want"; fail=1; }
done
# An install that ran before "not set up" existed (a v3 state database with
# a saved ledger) keeps its values after the upgrade: --print-config says so
# before the daemon has migrated the database (the migration itself:
# Migration.FromEarlierSchemaKeepsData).
sqlite3 "$tmp/old.db" "CREATE TABLE ledger(name TEXT PRIMARY KEY, value REAL NOT NULL);
  CREATE TABLE overrides(name TEXT PRIMARY KEY, value TEXT NOT NULL, file_value TEXT,
    changed_at_ms INTEGER NOT NULL DEFAULT 0);
  CREATE TABLE ledger_meta(id INTEGER PRIMARY KEY CHECK (id = 1), saved_at_ms INTEGER NOT NULL, reason TEXT NOT NULL);
  INSERT INTO ledger_meta VALUES(1, 1700000000000, 'stop'); CREATE TABLE kv(key TEXT PRIMARY KEY, value TEXT NOT NULL);
  PRAGMA user_version = 3;"
"$exe" --config "$root/config/xregulator.toml" --state-db "$tmp/old.db" --print-config >"$tmp/out" 2>"$tmp/err"
! grep -qF "NOT SET UP" "$tmp/out" && grep -qF "BulkVoltage = 14.5  # default" "$tmp/out" \
  && echo "ok: an install from before keeps its values (unmigrated database)" \
  || { cat "$tmp/err"; echo "FAIL: an upgraded install is shown as not set up"; fail=1; }
# The shipped file pins none of a profile's values: with only the battery
# lines edited, a profile is what runs (docs/configuration.md "One chain of
# values"), for a 24 V LiFePO4 bank and for 12 V AGM.
sed -e 's/^# BatteryProfile = "custom"/BatteryProfile = "lifepo4"/' -e 's/^BatteryCells = 0/BatteryCells = 8/' \
  -e 's/^BatteryCapacity_Ah = 200.0/BatteryCapacity_Ah = 400/' "$root/config/xregulator.toml" >"$tmp/lfp24.toml"
"$exe" --config "$tmp/lfp24.toml" --check-config >/dev/null 2>"$tmp/err" && echo "ok: shipped file + LiFePO4 24 V passes --check-config" \
  || { cat "$tmp/err"; echo "FAIL: shipped file + LiFePO4 24 V refused"; fail=1; }
"$exe" --config "$tmp/lfp24.toml" --state-db "$tmp/none.db" --print-config >"$tmp/out" 2>"$tmp/err"
for want in 'AbsorptionVoltage = 28.4  # profile' 'BulkVoltage = 28.4  # profile' 'UseFloat = false  # profile' \
  'BatteryCells = 8  # file' 'ChargeMinTempC = 0  # profile'; do
  grep -qF "$want" "$tmp/out" && echo "ok: shipped file + LiFePO4 24 V: $want" \
    || { echo "FAIL: shipped file + LiFePO4 24 V lacks: $want"; fail=1; }
done
sed -e 's/^# BatteryProfile = "custom"/BatteryProfile = "agm"/' "$root/config/xregulator.toml" >"$tmp/agm12.toml"
"$exe" --config "$tmp/agm12.toml" --state-db "$tmp/none.db" --print-config >"$tmp/out" 2>"$tmp/err"
for want in 'AbsorptionVoltage = 14.4  # profile' 'FloatVoltage = 13.3  # profile'; do
  grep -qF "$want" "$tmp/out" && echo "ok: shipped file + AGM 12 V: $want" \
    || { echo "FAIL: shipped file + AGM 12 V lacks: $want"; cat "$tmp/err"; fail=1; }
done
# the kept fuzz finding (a non-ASCII letter after a bare
# key, undefined behaviour inside toml++ 3.3.0) is refused before toml++ sees
# it: exit 78 as a configuration, 64 as a scenario, at file:line:column.
kept="$root/tests/fuzz/regressions/non-ascii-after-bare-key.toml"
"$exe" --config "$kept" --check-config >/dev/null 2>"$tmp/err"
rc=$?
[ $rc = 78 ] && grep -q "non-ascii-after-bare-key.toml:4:10: non-ASCII character outside a string" "$tmp/err" \
  && echo "ok: non-ASCII after a bare key in the config exits 78 at file:4:10" \
  || { cat "$tmp/err"; echo "FAIL: non-ASCII config: exit $rc"; fail=1; }
"$exe" --sim --scenario "$kept" --speed max --duration 1 --state-db "$tmp/sim.db" --http 127.0.0.1:0 \
  --log-level warn >/dev/null 2>"$tmp/err"
rc=$?
[ $rc = 64 ] && grep -q "non-ascii-after-bare-key.toml:4:10: non-ASCII character outside a string" "$tmp/err" \
  && echo "ok: non-ASCII after a bare key in a scenario exits 64 at file:4:10" \
  || { cat "$tmp/err"; echo "FAIL: non-ASCII scenario: exit $rc"; fail=1; }
exit $fail
