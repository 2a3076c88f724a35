#!/bin/bash
# The update gate (tools/update/xregulator-update-gate) against state files
# as the daemon writes them (daemon/app/update_watch.cpp): busy while the
# engine turns or the field is on, at the staleness limit and just inside it,
# quiet when no regulator runs; as apt's hook it refuses only our package,
# with one line saying why, and lets a rollback through.
set -uo pipefail
src=${1:?usage: gate_test.sh SOURCE_DIR}
gate=$src/tools/update/xregulator-update-gate
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
export XR_RUN_DIR=$t/run XR_STATE_DIR=$t/lib
mkdir -p "$XR_RUN_DIR" "$XR_STATE_DIR" "$t/bin"
# pidof as the test says: no xregulatord running unless $t/running exists.
printf '#!/bin/sh\n[ -e %s/running ]\n' "$t" >"$t/bin/pidof" && chmod 755 "$t/bin/pidof"
printf '#!/bin/sh\nexit 0\n' >"$t/bin/logger" && chmod 755 "$t/bin/logger"
export PATH=$t/bin:$PATH
fails=0
state() {  # AGE_S ENGINE FIELD [PID]
  printf 'pid=%s\nupdated_ms=%s\ntick=100\nengine_running=%s\nfield_on=%s\nrpm=%s\nversion=1\n' "${4:-$$}" \
    "$((($(date +%s) - $1) * 1000))" "$2" "$3" "$([ "$2" = 1 ] && echo 1800 || echo 0)" >"$XR_RUN_DIR/state"
}
expect() {  # WANT_RC WHAT
  local out rc
  out=$("$gate" --check 2>&1)
  rc=$?
  if [ "$rc" = "$1" ]; then echo "ok: $2: $out"; else echo "FAIL: $2: exit $rc, wanted $1 ($out)"; fails=1; fi
}
state 0 1 1 && expect 1 "engine running and field on"
state 0 1 0 && expect 1 "engine running, field off"
state 0 0 1 && expect 1 "engine stopped, field still on"
state 0 0 0 && expect 0 "engine stopped, field off"
state 9 0 0 && expect 0 "state 9 s old (inside the 10 s limit)"
state 12 0 0 && expect 1 "state 12 s old: the daemon does not answer"
dead=$(sh -c 'echo $$')  # a process that has exited
state 0 1 1 "$dead" && expect 0 "state left by a daemon that is gone"
rm -f "$XR_RUN_DIR/state" && expect 0 "no state file, no regulator"
touch "$t/running" && expect 1 "no state file but a regulator runs" && rm "$t/running"

hook() {  # WANT_RC WHAT DEB...
  local want=$1 what=$2 out rc
  shift 2
  out=$(printf '%s\n' "$@" | "$gate" --apt-hook 2>&1)
  rc=$?
  if [ "$rc" = "$want" ]; then echo "ok: hook: $what"; else echo "FAIL: hook: $what: exit $rc ($out)"; fails=1; fi
  hook_out=$out
}
touch "$t/xregulator_2_amd64.deb"
state 0 1 1
hook 0 "another package while busy" /var/cache/apt/archives/curl_8_amd64.deb
hook 1 "xregulator while the engine runs" /var/cache/apt/archives/curl_8_amd64.deb "$t/xregulator_2_amd64.deb"
echo "$hook_out" | grep -q "update refused: the engine is running (1800 rpm) and the field is on" ||
  { echo "FAIL: refusal line: $hook_out"; fails=1; }
XR_UPDATE_ROLLBACK=1 hook 0 "a rollback while busy" "$t/xregulator_2_amd64.deb"
state 0 0 0
hook 0 "xregulator when quiet" "$t/xregulator_2_amd64.deb"
[ -f "$XR_STATE_DIR/packages/xregulator_2_amd64.deb" ] && echo "ok: the new package kept for a rollback" ||
  { echo "FAIL: package not kept"; fails=1; }
for f in xregulator-update-gate xregulator-update-check xregulator-update-record build-keyring-deb.sh make-repo.sh; do
  sh -n "$src/tools/update/$f" || { echo "FAIL: $f does not parse"; fails=1; }
done
exit $fails
