#!/bin/sh
# Checks systemd/ with systemd's own tools ("systemd-analyze verify
# is clean (a test)"). Any message from the verifier fails the test, not only a
# non-zero exit: systemd-analyze exits 0 on unknown keys and bad values. The
# script first proves it would notice a broken unit.
#   verify_units.sh SYSTEMD_DIR
set -u
src=$(cd "$1" && pwd)
if ! command -v systemd-analyze >/dev/null 2>&1; then
  echo "SKIP: systemd-analyze not installed"
  exit 77
fi
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
# A private root holding the stock units (targets the unit orders against) and
# stand-ins for the installed executables, so the check does not depend on the
# package being installed on this machine.
mkdir -p "$root/usr/lib/systemd" "$root/etc/systemd/system" "$root/usr/sbin" "$root/usr/libexec/xregulator"
cp -a /usr/lib/systemd/system "$root/usr/lib/systemd/" 2>/dev/null || cp -a /lib/systemd/system "$root/usr/lib/systemd/"
for exe in /usr/sbin/xregulatord /usr/libexec/xregulator/xregulator-field-off /usr/libexec/xregulator/xregulator-update-check; do
  printf '#!/bin/sh\nexit 0\n' >"$root$exe"
  chmod 755 "$root$exe"
done

verify() {  # verify UNITFILE -> prints messages, returns 1 when there are any
  cp "$1" "$root/etc/systemd/system/"
  out=$(systemd-analyze verify --man=no --root="$root" "/etc/systemd/system/$(basename "$1")" 2>&1)
  rc=$?
  if [ $rc -ne 0 ] || [ -n "$out" ]; then
    printf '%s\n' "$out"
    return 1
  fi
  return 0
}

fail=0
# 1. The verifier must catch a broken copy, or a clean result means nothing.
sed -e 's/^Type=notify$/Type=notifyy/' -e 's/^WatchdogSec=.*/WatchdogSecs=5s/' \
  "$src/xregulatord.service" >"$root/broken-copy.service"
if verify "$root/broken-copy.service" >/dev/null; then
  echo "FAIL: systemd-analyze did not notice a broken unit; this check would prove nothing"
  fail=1
fi

# 2. The real unit is clean.
if verify "$src/xregulatord.service"; then
  echo "ok: xregulatord.service verifies clean"
else
  echo "FAIL: xregulatord.service has problems (above)"
  fail=1
fi

# 2b. The post-update health check's unit (docs/operations.md "Updates and the way back").
if verify "$src/xregulator-update-check.service"; then
  echo "ok: xregulator-update-check.service verifies clean"
else
  echo "FAIL: xregulator-update-check.service has problems (above)"
  fail=1
fi

# 3. The unit's properties (docs/install.md) are really there; SIGKILL
# cannot be caught, so ExecStopPost's xregulator-field-off must run after
# every end of the main process (ExecStopPost runs after a kill -9 too), and
# config/usage errors must not be restarted into a loop.
for want in '^Type=notify$' '^WatchdogSec=' '^Restart=on-failure$' '^LimitRTPRIO=' '^LimitMEMLOCK=infinity$' \
  '^User=xregulator$' '^SupplementaryGroups=i2c gpio dialout$' '^DeviceAllow=' '^ReadWritePaths=.*/sys/class/pwm' \
  '^ProtectSystem=strict$' '^ProtectHome=yes$' '^NoNewPrivileges=yes$' '^StateDirectory=xregulator$' \
  '^ConfigurationDirectory=xregulator$' '^ExecStopPost=.*xregulator-field-off' \
  '^RestartPreventExitStatus=64 78$' '^ExecStartPre=.*--state-db .*--check-config$' \
  '^RuntimeDirectory=xregulator$' '^ExecStart=.* --update-watch$'; do
  grep -q "$want" "$src/xregulatord.service" || { echo "FAIL: xregulatord.service lacks $want"; fail=1; }
done

# 4. sysusers.d snippet parses and creates the user.
if command -v systemd-sysusers >/dev/null 2>&1; then
  mkdir -p "$root/sysroot/etc"
  out=$(systemd-sysusers --dry-run --root="$root/sysroot" "$src/xregulator.sysusers.conf" 2>&1)
  if [ $? -ne 0 ] || ! printf '%s' "$out" | grep -q "Creating user 'xregulator'"; then
    printf '%s\n' "$out"
    echo "FAIL: xregulator.sysusers.conf"
    fail=1
  else
    echo "ok: sysusers snippet creates the xregulator user"
  fi
fi
exit $fail
