#!/bin/bash
# Package test (docs/install.md): build the .deb, lintian it, install it on this
# machine, check files, owners, permissions, the user and the daemon's own
# checks, then purge it and put the machine back as it was.
#
#   tests/package/run.sh [PACKAGE.deb]     (run as root; `make package-test`)
#
# Slow (a full release build), so it is not part of `make test`.
# The service is never started: a policy-rc.d that denies starts is in place
# while the package is installed.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
pkg=xregulator
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok: $*"; }

if [ "$(id -u)" != 0 ]; then echo "SKIP: must run as root (installs a package)"; exit 77; fi
if dpkg -s "$pkg" >/dev/null 2>&1; then
  echo "ERROR: $pkg is already installed here; refusing to touch it"; exit 1
fi

work=$(mktemp -d /tmp/xr-package-test.XXXXXX)
created_policy=0
users_before=$(cut -d: -f1 /etc/passwd | sort)
groups_before=$(cut -d: -f1 /etc/group | sort)

cleanup() {
  dpkg -s "$pkg" >/dev/null 2>&1 && dpkg --purge "$pkg" >/dev/null 2>&1
  [ $created_policy = 1 ] && rm -f /usr/sbin/policy-rc.d
  # Remove only the users and groups this test made (sysusers.d entries stay
  # on purge by Debian convention; a test must not leave them behind).
  for u in $(comm -13 <(echo "$users_before") <(cut -d: -f1 /etc/passwd | sort)); do userdel "$u" 2>/dev/null; done
  for g in $(comm -13 <(echo "$groups_before") <(cut -d: -f1 /etc/group | sort)); do groupdel "$g" 2>/dev/null; done
  rm -rf "$work"
}
trap cleanup EXIT

# ---------------------------------------------------------------- build
if [ $# -ge 1 ]; then
  deb=$(readlink -f "$1")
  changes=""
else
  echo "building the package from the committed tree (git HEAD; this takes minutes)"
  mkdir -p "$work/src"
  (cd "$repo" && git archive HEAD) | tar -xf - -C "$work/src"
  # The dashboard's pinned uPlot and qrcode-generator come from npm (`make deps`), not from git.
  for pkg in uplot qrcode-generator; do
    if [ -d "$repo/web/node_modules/$pkg" ]; then
      mkdir -p "$work/src/web/node_modules" && cp -a "$repo/web/node_modules/$pkg" "$work/src/web/node_modules/"
    fi
  done
  start=$(date +%s)
  if ! (cd "$work/src" && dpkg-buildpackage -us -uc -b >"$work/build.log" 2>&1); then
    tail -40 "$work/build.log"; echo "FAIL: dpkg-buildpackage"; exit 1
  fi
  echo "ok: dpkg-buildpackage took $(($(date +%s) - start)) s"
  deb=$(ls "$work"/${pkg}_*.deb | head -1)
  changes=$(ls "$work"/${pkg}_*.changes | head -1)
fi
[ -f "$deb" ] || { echo "FAIL: no .deb"; exit 1; }

# ---------------------------------------------------------------- lintian
if command -v lintian >/dev/null; then
  out=$(lintian --fail-on none ${changes:-$deb} 2>&1 | grep -E '^[EW]: ' || true)
  if [ -n "$out" ]; then printf '%s\n' "$out"; fail "lintian reports errors or warnings"; else ok "lintian: no errors or warnings"; fi
else
  fail "lintian not installed"
fi

# ---------------------------------------------------------------- install
if [ ! -e /usr/sbin/policy-rc.d ]; then
  printf '#!/bin/sh\nexit 101\n' >/usr/sbin/policy-rc.d && chmod 755 /usr/sbin/policy-rc.d && created_policy=1
fi
if ! dpkg -i "$deb" >"$work/install.log" 2>&1; then
  cat "$work/install.log"; fail "dpkg -i (dependencies missing? run make deps)"; exit 1
fi
ok "installed $(basename "$deb")"

check_file() {  # path owner:group mode
  if [ ! -e "$1" ]; then fail "$1 missing"; return; fi
  got="$(stat -c '%U:%G %a' "$1")"
  [ "$got" = "$2 $3" ] && ok "$1 $got" || fail "$1 is $got, want $2 $3"
}
check_file /usr/sbin/xregulatord root:root 755
check_file /usr/libexec/xregulator/xregulator-field-off root:root 755
check_file /etc/xregulator/xregulator.toml root:root 644
check_file /lib/systemd/system/xregulatord.service root:root 644
check_file /usr/lib/sysusers.d/xregulator.conf root:root 644
check_file /lib/udev/rules.d/60-xregulator.rules root:root 644
check_file /usr/share/xregulator/www root:root 755
check_file /usr/share/xregulator/www/index.html root:root 644
check_file /usr/share/man/man8/xregulatord.8.gz root:root 644
check_file /usr/share/doc/xregulator/copyright root:root 644

dpkg-query -W -f='${Conffiles}\n' "$pkg" | grep -q '/etc/xregulator/xregulator.toml' \
  && ok "xregulator.toml is a conffile" || fail "xregulator.toml is not a conffile"
cmp -s /etc/xregulator/xregulator.toml "$repo/config/xregulator.toml" \
  && ok "installed config is config/xregulator.toml" || fail "installed config differs from config/xregulator.toml"

if getent passwd xregulator >/dev/null; then
  shell=$(getent passwd xregulator | cut -d: -f7)
  case "$shell" in */nologin|/bin/false) ok "user xregulator exists, shell $shell" ;; *) fail "user xregulator has a login shell $shell" ;; esac
  for g in i2c gpio dialout; do
    id -nG xregulator | tr ' ' '\n' | grep -qx "$g" && ok "xregulator is in $g" || fail "xregulator is not in group $g"
  done
else
  fail "user xregulator was not created"
fi

if /usr/sbin/xregulatord --version >"$work/version" 2>&1; then ok "xregulatord --version: $(head -1 "$work/version")"
else cat "$work/version"; fail "xregulatord --version"; fi
if /usr/sbin/xregulatord --config /etc/xregulator/xregulator.toml --check-config >"$work/check" 2>&1; then
  ok "xregulatord --check-config /etc/xregulator/xregulator.toml"
else cat "$work/check"; fail "--check-config on the installed file"; fi
printf '[voltage]\nBulkVoltage = 99\n' >"$work/bad.toml"
/usr/sbin/xregulatord --config "$work/bad.toml" --check-config >/dev/null 2>&1
[ $? = 78 ] && ok "--check-config exits 78 on a bad file" || fail "--check-config did not exit 78 on a bad file"

if command -v systemd-analyze >/dev/null; then
  out=$(systemd-analyze verify /lib/systemd/system/xregulatord.service 2>&1)
  [ -z "$out" ] && ok "installed unit verifies clean" || { printf '%s\n' "$out"; fail "installed unit does not verify"; }
fi

# ---------------------------------------------------------------- purge
if dpkg --purge "$pkg" >"$work/purge.log" 2>&1; then ok "purged"; else cat "$work/purge.log"; fail "dpkg --purge"; fi
for p in /usr/sbin/xregulatord /etc/xregulator /lib/systemd/system/xregulatord.service /usr/share/xregulator \
  /usr/libexec/xregulator /usr/lib/sysusers.d/xregulator.conf /etc/systemd/system/multi-user.target.wants/xregulatord.service; do
  [ -e "$p" ] && fail "$p left behind after purge"
done
dpkg -s "$pkg" >/dev/null 2>&1 && fail "package still known to dpkg after purge"

echo "package test: $fails failure(s)"
[ $fails = 0 ]
