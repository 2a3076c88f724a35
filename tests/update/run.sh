#!/bin/bash
# `make update-test` (docs/operations.md "Updates and the way back"), as root
# on this machine, in about two minutes: two packages that differ only in
# version and a third whose daemon fails, a reprepro repository signed with a
# throw-away key (temporary GNUPGHOME) served on 127.0.0.1, and the whole
# owner's path through apt: install 1 with the keyring, the update to 2
# refused while the simulated engine runs and let through once it stops, 3
# installed under way (by hand) and started only when the engine stops, 3
# failing its health check and 2 coming back with the same settings and
# history, and repositories signed with another key or not at all refused.
#
# What it does NOT cover: there is no systemd here (PID 1 is not systemd), so
# the test plays systemd's part: it starts the daemon (as root, --sim), starts
# it again after its exit 75, and runs xregulator-update-check itself, which a
# board runs as xregulator-update-check.service. The packages are the build
# tree's binaries staged in the package's layout (tests/update/stage_deb.sh);
# `make package-test` covers the dpkg-buildpackage package itself.
#
#   tests/update/run.sh [BUILD_DIR]
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo_src=$(cd "$here/../.." && pwd)
build=$(readlink -f "${1:-$repo_src/build}")
t0=$(date +%s)
fails=0
ok() { echo "ok   [$(($(date +%s) - t0)) s] $*"; }
fail() { echo "FAIL [$(($(date +%s) - t0)) s] $*"; fails=$((fails + 1)); }
die() { fail "$*"; exit 1; }
step() { echo "---- $*"; }

[ "$(id -u)" = 0 ] || { echo "SKIP: must run as root (installs packages)"; exit 77; }
for p in xregulator xregulator-archive-keyring; do
  dpkg -s "$p" >/dev/null 2>&1 && { echo "ERROR: $p is installed on this machine; refusing to touch it"; exit 1; }
done
for d in /var/lib/xregulator /run/xregulator /etc/xregulator; do
  [ -e "$d" ] && { echo "ERROR: $d exists (a regulator lives here?); refusing to touch it"; exit 1; }
done
for t in reprepro gpg gpgv python3 curl sqlite3; do command -v $t >/dev/null || die "$t missing (make deps)"; done

work=$(mktemp -d /tmp/xr-update-test.XXXXXX)
chmod 755 "$work"
export GNUPGHOME=$work/gnupg
mkdir -m 700 "$GNUPGHOME"
daemon_pid="" http_pid="" port=none
cleanup() {
  [ -n "$daemon_pid" ] && kill "$daemon_pid" 2>/dev/null && wait "$daemon_pid" 2>/dev/null
  [ -n "$http_pid" ] && kill "$http_pid" 2>/dev/null
  dpkg --purge xregulator xregulator-archive-keyring >/dev/null 2>&1
  rm -f /etc/apt/sources.list.d/xregulator.sources /etc/apt/preferences.d/xregulator.pref \
    /usr/share/keyrings/xregulator-archive-keyring.gpg /etc/apt/apt.conf.d/51xregulator-update-gate \
    /etc/apt/apt.conf.d/52xregulator-unattended-upgrades
  rm -f /var/lib/apt/lists/127.0.0.1:"$port"_* /var/lib/apt/lists/partial/127.0.0.1:"$port"_*
  rm -rf /var/lib/xregulator /run/xregulator /etc/xregulator /var/cache/apt/archives/xregulator*_*.deb
  gpgconf --kill all 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

# apt limited to the test's sources (the machine's own lists stay as they are).
parts=$work/parts
mkdir -p "$parts"
apt_update() { apt-get update -q -o Dir::Etc::SourceList=/dev/null -o Dir::Etc::SourceParts="$parts" \
  -o APT::Get::List-Cleanup=0 >"$work/update.log" 2>&1; }
installed() { dpkg-query -W -f='${Version}' xregulator 2>/dev/null; }

step "build: the daemon and the dashboard assets from $build"
cmake --build "$build" --target xregulatord xregulator-field-off xr_www >"$work/build.log" 2>&1 ||
  { tail -20 "$work/build.log"; die "build"; }
ok "build up to date (nothing to do after make test)"
t_build=$(date +%s)
base=$(cd "$repo_src" && dpkg-parsechangelog -S Version)
v1="$base+upd1" v2="$base+upd2" v3="$base+upd3"
for v in "$v1" "$v2"; do "$here/stage_deb.sh" "$build" "$v" "$work/debs" >/dev/null || die "staging $v"; done
"$here/stage_deb.sh" "$build" "$v3" "$work/debs" --broken >/dev/null || die "staging $v3"
d1=$(ls "$work"/debs/xregulator_"$v1"_*.deb) d2=$(ls "$work"/debs/xregulator_"$v2"_*.deb) d3=$(ls "$work"/debs/xregulator_"$v3"_*.deb)
diff <(dpkg-deb -c "$d1" | awk '{print $1, $6}') <(dpkg-deb -c "$d2" | awk '{print $1, $6}') >/dev/null &&
  [ "$(dpkg-deb -f "$d1" Version)" = "$v1" ] && [ "$(dpkg-deb -f "$d2" Version)" = "$v2" ] &&
  cmp -s <(dpkg-deb --fsys-tarfile "$d1" | tar -xO ./usr/sbin/xregulatord) <(dpkg-deb --fsys-tarfile "$d2" | tar -xO ./usr/sbin/xregulatord) &&
  ok "packages $v1 and $v2 differ only in version; $v3's daemon fails at start" || fail "the staged packages differ"

step "keys and repository"
gpg --batch --passphrase '' --quick-gen-key "xregulator test release key <release@test.invalid>" ed25519 sign 1d 2>/dev/null
gpg --batch --passphrase '' --quick-gen-key "someone else <other@test.invalid>" ed25519 sign 1d 2>/dev/null
key=$(gpg --with-colons --list-secret-keys release@test.invalid | awk -F: '/^fpr/{print $10; exit}')
other=$(gpg --with-colons --list-secret-keys other@test.invalid | awk -F: '/^fpr/{print $10; exit}')
[ -n "$key" ] && [ -n "$other" ] && ok "throw-away keys in a temporary GNUPGHOME" || die "gpg key generation"
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
url=http://127.0.0.1:$port/repo
mkdir -p "$work/www"
python3 -m http.server --bind 127.0.0.1 --directory "$work/www" "$port" >"$work/http.log" 2>&1 &
http_pid=$!
R=$work/www/repo
"$repo_src/tools/update/make-repo.sh" --repo "$R" --key "$key" --url "$url" --channel stable "$d1" >"$work/repo.log" 2>&1 ||
  { cat "$work/repo.log"; die "make-repo.sh"; }
grep -q "BEGIN PGP SIGNED MESSAGE" "$R/dists/stable/InRelease" && gpgv --keyring "$R/xregulator-archive-keyring.gpg" \
  "$R/dists/stable/InRelease" 2>/dev/null && [ -f "$R/dists/candidate/InRelease" ] &&
  ok "repository: stable and candidate, InRelease signed by the release key" || fail "repository signature"
grep -rqs "PRIVATE KEY" "$R" && fail "a private key is in the published repository" || ok "no private key in the published tree"
# A package that is not ours, for the pin.
mkdir -p "$work/probe/DEBIAN"
printf 'Package: xr-pin-probe\nVersion: 1\nSection: misc\nPriority: optional\nArchitecture: all\nMaintainer: test <t@test.invalid>\nDescription: pin probe\n probe\n' \
  >"$work/probe/DEBIAN/control"
dpkg-deb --root-owner-group --build "$work/probe" "$work/xr-pin-probe_1_all.deb" >/dev/null
reprepro -b "$R" includedeb stable "$work/xr-pin-probe_1_all.deb" >/dev/null 2>&1
for _ in $(seq 50); do curl -sf "$url/dists/stable/InRelease" >/dev/null && break; sleep 0.1; done

step "install $v1 from the repository with the keyring (docs/install.md)"
curl -sf -o "$work/keyring.deb" "$url/xregulator-archive-keyring.deb" && apt-get install -y -q "$work/keyring.deb" >"$work/kinstall.log" 2>&1 ||
  { cat "$work/kinstall.log"; die "keyring install"; }
grep -q "^Signed-By: /usr/share/keyrings/xregulator-archive-keyring.gpg" /etc/apt/sources.list.d/xregulator.sources &&
  [ -s /usr/share/keyrings/xregulator-archive-keyring.gpg ] && ok "keyring package: key, deb822 source with Signed-By, pin" ||
  fail "keyring package contents"
ln -s /etc/apt/sources.list.d/xregulator.sources "$parts/xregulator.sources"
apt_update || { cat "$work/update.log"; die "apt-get update of the signed repository"; }
apt-get install -y -q -o Dpkg::Options::=--force-confold xregulator >"$work/install1.log" 2>&1 || { tail -20 "$work/install1.log"; die "apt-get install xregulator"; }
[ "$(installed)" = "$v1" ] && ok "apt-get install xregulator: $v1" || fail "installed $(installed), expected $v1"
version_line=$(/usr/sbin/xregulatord --version)
grep -q "package $v1, channel stable, installed 20" <<<"$version_line" &&
  ok "xregulatord --version: $version_line" || fail "--version: $version_line"
policy=$(apt-cache policy xr-pin-probe 2>/dev/null)
if grep -q "Candidate: (none)" <<<"$policy" && grep -q "^ *1 -1$" <<<"$policy"; then
  ok "pin: the repository cannot provide another package (xr-pin-probe: no candidate)"
else
  fail "pin: $(tr '\n' ' ' <<<"$policy")"
fi

# The daemon as systemd would run it (--update-watch), the engine stopping at $1 s.
# --run-dir: in --sim the daemon writes the gate's state file only when told where.
db=/var/lib/xregulator/xregulator.db
mkdir -p /run/xregulator
start_daemon() {  # ENGINE_STOP_S LOG
  sed "s/ENGINE_STOP_S/$1/" "$here/engine_then_stop.toml" >"$work/scenario.toml"
  /usr/sbin/xregulatord --sim --speed 1 --scenario "$work/scenario.toml" --config /etc/xregulator/xregulator.toml \
    --state-db "$db" --http 127.0.0.1:0 --update-watch --run-dir /run/xregulator --sim-outputs "$work/outputs" >"$2" 2>&1 &
  daemon_pid=$!
  api=""
  for _ in $(seq 100); do
    p=$(sed -n 's|.*dashboard at http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$2" | head -n 1)
    [ -n "$p" ] && api=http://127.0.0.1:$p && break
    sleep 0.1
  done
  [ -n "$api" ]
}
wait_state() {  # KEY VALUE SECONDS
  for _ in $(seq $(($3 * 5))); do
    [ "$(sed -n "s/^$1=//p" /run/xregulator/state 2>/dev/null)" = "$2" ] && return 0
    sleep 0.2
  done
  return 1
}
wait_exit() {  # SECONDS: sets rc to the daemon's exit code, or "running"
  rc=running
  for _ in $(seq $(($1 * 5))); do
    if ! kill -0 "$daemon_pid" 2>/dev/null; then
      wait "$daemon_pid"
      rc=$?
      daemon_pid=""
      return
    fi
    sleep 0.2
  done
}

step "update to $v2: refused while the engine runs, through once it stops"
start_daemon 25 "$work/daemon1.log" || die "daemon $v1 did not start: $(tail -5 "$work/daemon1.log")"
wait_state engine_running 1 10 && ok "daemon $v1 runs the simulated engine (state: rpm $(sed -n 's/^rpm=//p' /run/xregulator/state))" ||
  fail "no engine_running=1 in /run/xregulator/state"
token=$(/usr/sbin/xregulatord --print-token --state-db "$db" 2>/dev/null)
code=$(curl -s -o "$work/patch" -w '%{http_code}' -X PATCH -H "Authorization: Bearer $token" \
  -H 'Content-Type: application/json' -d '{"MaxDuty": 87}' "$api/api/params")
[ "$code" = 200 ] && ok "a setting changed through the API (MaxDuty 87)" || fail "PATCH MaxDuty: $code $(cat "$work/patch")"
echo "# the owner's own line" >>/etc/xregulator/xregulator.toml
"$repo_src/tools/update/make-repo.sh" --repo "$R" --key "$key" --url "$url" --channel stable "$d2" >>"$work/repo.log" 2>&1 ||
  die "publishing $v2"
apt_update || die "apt-get update after publishing $v2"
if apt-get install -y -q -o Dpkg::Options::=--force-confold xregulator >"$work/install2a.log" 2>&1; then
  fail "apt-get installed $v2 while the engine runs"
elif grep -q "xregulator-update: update refused: the engine is running" "$work/install2a.log" && [ "$(installed)" = "$v1" ]; then
  ok "refused while the engine runs: $(grep -m1 'update refused' "$work/install2a.log" | cut -c1-150)"
else
  fail "refusal without the gate's line: $(tail -3 "$work/install2a.log")"
fi
kill -0 "$daemon_pid" 2>/dev/null && ok "daemon $v1 still regulating after the refusal" || fail "daemon $v1 died"
wait_state engine_running 0 40 && wait_state field_on 0 20 && ok "engine stopped, field off" || fail "engine did not stop"
if apt-get install -y -q -o Dpkg::Options::=--force-confold xregulator >"$work/install2b.log" 2>&1 && [ "$(installed)" = "$v2" ]; then
  ok "apt-get install xregulator once the engine stopped: $v2"
else
  fail "update to $v2 after the engine stopped: $(tail -3 "$work/install2b.log")"
fi
wait_exit 20
[ "$rc" = 75 ] && ok "daemon $v1 noticed $v2 and stopped by itself (exit 75, for systemd to restart)" ||
  fail "daemon $v1 after the update: exit $rc"
grep -q "enable=0" "$work/outputs" 2>/dev/null && ok "field enable LOW at its exit ($(tr '\n' ' ' <"$work/outputs"))" ||
  fail "outputs at exit: $(cat "$work/outputs" 2>/dev/null)"
ls /var/lib/xregulator/packages/xregulator_"$v1"_*.deb >/dev/null 2>&1 && ls /var/lib/xregulator/packages/xregulator_"$v2"_*.deb >/dev/null 2>&1 &&
  ok "previous package kept for a rollback: $(ls /var/lib/xregulator/packages | tr '\n' ' ')" || fail "package cache: $(ls /var/lib/xregulator/packages)"

step "$v2 runs and is confirmed; $v3 installed under way starts only when the engine stops"
start_daemon 25 "$work/daemon2.log" || die "daemon $v2 did not start"
/usr/libexec/xregulator/xregulator-update-check --url "$api" --timeout 30 >"$work/check2.log" 2>&1 &&
  grep -q "update to $v2 confirmed" "$work/check2.log" && ok "health check confirmed $v2" || fail "health check of $v2: $(cat "$work/check2.log")"
sys=$(curl -s "$api/api/system")
grep -q "\"package\":\"$v2\"" <<<"$sys" && grep -q "\"channel\":\"stable\"" <<<"$sys" && ok "/api/system: package $v2, channel stable, install time" ||
  fail "/api/system: $(curl -s "$api/api/system" | head -c 300)"
wait_state engine_running 1 10 || fail "engine not running for $v2"
"$repo_src/tools/update/make-repo.sh" --repo "$R" --key "$key" --url "$url" --channel stable "$d3" >>"$work/repo.log" 2>&1 ||
  die "publishing $v3"
apt_update || die "apt-get update after publishing $v3"
# The owner installs by hand, past apt's gate: dpkg installs, the postinst
# does not restart, the running daemon keeps regulating and says so.
dpkg -i --force-confold "$R"/pool/main/x/xregulator/xregulator_"$v3"_*.deb >"$work/install3.log" 2>&1
grep -q "Update installed; starts when the engine stops" "$work/install3.log" && ok "dpkg -i $v3 under way: $(grep -m1 'Update installed' "$work/install3.log" | cut -c1-120)" ||
  fail "postinst under way: $(cat "$work/install3.log")"
sleep 2
sys=$(curl -s "$api/api/system")
grep -q "Update installed; starts when the engine stops ($v3)" <<<"$sys" && kill -0 "$daemon_pid" &&
  ok "/api/system (System page) says: Update installed; starts when the engine stops ($v3)" || fail "no notice in /api/system"
wait_exit 60
[ "$rc" = 75 ] && ok "daemon $v2 stopped by itself once the engine stopped (exit 75)" || fail "daemon $v2: exit $rc"
events_before=$(sqlite3 "$db" 'select count(*) from events')
[ "$(sqlite3 "$db" "select value from overrides where name='MaxDuty'")" = 87 ] || [ "$(sqlite3 "$db" "select value from overrides where name='MaxDuty'")" = 87.0 ] ||
  fail "MaxDuty not stored: $(sqlite3 "$db" "select * from overrides")"

step "$v3 fails its health check: $v2 comes back by itself"
/usr/sbin/xregulatord --sim >"$work/daemon3.log" 2>&1 &
daemon_pid=$!
/usr/libexec/xregulator/xregulator-update-check --url "$api" --timeout 8 >"$work/check3.log" 2>&1
rc=$?
wait "$daemon_pid" 2>/dev/null; daemon_pid=""
[ $rc = 2 ] && [ "$(installed)" = "$v2" ] && ok "rolled back to $v2: $(grep -m1 'rolled back' "$work/check3.log" | cut -c1-160)" ||
  fail "rollback (rc $rc, installed $(installed)): $(cat "$work/check3.log")"
grep -q "reason=version $v3 failed its health check" /var/lib/xregulator/update/rollback 2>/dev/null && ok "one rollback note says why" ||
  fail "rollback note: $(cat /var/lib/xregulator/update/rollback 2>/dev/null)"
[ "$(sqlite3 "$db" 'select count(*) from events')" = "$events_before" ] && ok "history kept ($events_before events)" || fail "events changed"
grep -q "^# the owner's own line" /etc/xregulator/xregulator.toml && ok "configuration file kept" || fail "configuration file lost"
start_daemon 600 "$work/daemon2b.log" || die "daemon $v2 did not start again"
sleep 2
got=$(curl -s "$api/api/params" | python3 -c 'import json,sys; print(next(p["value"] for p in json.load(sys.stdin)["params"] if p["name"]=="MaxDuty"))')
[ "$got" = 87 ] || [ "$got" = 87.0 ] && ok "setting kept through the rollback (MaxDuty $got)" || fail "MaxDuty after rollback: $got"
sys=$(curl -s "$api/api/system")
grep -q "\"package\":\"$v2\"" <<<"$sys" && ok "$v2 runs again" || fail "/api/system after rollback"
kill "$daemon_pid"; wait "$daemon_pid" 2>/dev/null; daemon_pid=""

step "unattended-upgrades: off as shipped, on with its one setting"
sed 's|^//\( *"origin=xregulator";\)|\1|' /etc/apt/apt.conf.d/52xregulator-unattended-upgrades >"$work/uu-on.conf"
grep -q '^ *"origin=xregulator";' "$work/uu-on.conf" || fail "the setting line is not in 52xregulator-unattended-upgrades"
if out=$(/usr/bin/python3 "$here/uu_origin.py" "$work/uu-on.conf" 2>&1); then ok "$out"; else fail "unattended-upgrades origin: $out"; fi

step "repositories apt must refuse"
O=$work/www/other U=$work/www/unsigned
"$repo_src/tools/update/make-repo.sh" --repo "$O" --key "$other" --url "$url" --channel stable "$d2" >>"$work/repo.log" 2>&1
"$repo_src/tools/update/make-repo.sh" --repo "$U" --unsigned --channel stable "$d2" >>"$work/repo.log" 2>&1
for r in other unsigned; do
  rm -f "$parts"/*
  sed "s|^URIs: .*|URIs: http://127.0.0.1:$port/$r|" /etc/apt/sources.list.d/xregulator.sources >"$parts/$r.sources"
  if apt_update; then
    fail "apt-get update accepted the $r repository"
  elif grep -Eq "NO_PUBKEY|is not signed|signatures couldn't be verified" "$work/update.log"; then
    ok "$r repository refused: $(grep -Em1 'NO_PUBKEY|is not signed' "$work/update.log" | cut -c1-140)"
  else
    fail "$r repository: $(tail -3 "$work/update.log")"
  fi
done

step "clean up"
cleanup
trap - EXIT
leftover=$(ls -d /var/lib/xregulator /etc/xregulator /etc/apt/sources.list.d/xregulator.sources \
  /usr/share/keyrings/xregulator-archive-keyring.gpg /var/lib/apt/lists/127.0.0.1:"$port"_* 2>/dev/null)
dpkg -s xregulator >/dev/null 2>&1 && leftover="$leftover xregulator(package)"
[ -z "$leftover" ] && ok "purged; sources, keyring and state removed" || fail "left behind: $leftover"
echo "update test: $fails failure(s) in $(($(date +%s) - t0)) s ($(($(date +%s) - t_build)) s after the build step)"
[ $fails = 0 ]
