#!/usr/bin/env bash
# ctest package.check_cross: check_cross.sh (what `make deb ARCH=...` and
# `make test-arm64` trust) passes a well-formed package and rejects each kind
# of wrong one. The packages are made here with dpkg-deb from the host's own
# /bin/true, so this runs in `make test` on any Debian machine.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
host=$(dpkg --print-architecture)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0

# make_deb NAME ARCHITECTURE DEPENDS [ELF-FILE]
make_deb() {
  local d=$tmp/$1
  mkdir -p "$d/DEBIAN" "$d/usr/sbin" "$d/usr/libexec/xregulator"
  cp "${4:-/bin/true}" "$d/usr/sbin/xregulatord"
  cp "${4:-/bin/true}" "$d/usr/libexec/xregulator/xregulator-field-off"
  printf 'Package: xregulator\nVersion: 0.1.0\nArchitecture: %s\nMaintainer: t <t@example.org>\nDepends: %s\nDescription: test\n test\n' \
    "$2" "$3" >"$d/DEBIAN/control"
  dpkg-deb --root-owner-group -b "$d" "$tmp/$1.deb" >/dev/null
}
# expect RC PATTERN ARGS...: check_cross.sh exits RC and prints PATTERN.
expect() {
  local rc=$1 pat=$2; shift 2
  out=$("$here/check_cross.sh" --no-lintian "$@" 2>&1)
  got=$?
  if [ $got = "$rc" ] && grep -q -- "$pat" <<<"$out"; then echo "ok: $* -> exit $got, '$pat'"
  else printf '%s\n' "$out"; echo "FAIL: $* exited $got (want $rc) or lacks '$pat'"; fails=$((fails + 1)); fi
}

make_deb good "$host" "libc6 (>= 2.34)"
expect 0 "0 failure(s)" "$host" "$tmp/good.deb"
# A host package offered as an arm one: wrong Architecture: and ELF machine.
expect 1 "Architecture: is '$host', want arm64" arm64 "$tmp/good.deb"
expect 1 "want ELF64 AArch64" arm64 "$tmp/good.deb"
expect 1 "want ELF32 ARM" armhf "$tmp/good.deb"
# Right Architecture: field, binaries of the build machine inside.
make_deb lying arm64 "libc6 (>= 2.34)"
expect 1 "usr/sbin/xregulatord is ELF64 Advanced Micro Devices X86-64, want ELF64 AArch64" arm64 "$tmp/lying.deb"
# A needed library whose package is missing from Depends:.
make_deb nolibc "$host" "libsystemd0"
expect 1 "libc.so.6 (libc6:$host) is not in Depends:" "$host" "$tmp/nolibc.deb"
# Architecture qualifiers and amd64 packages in Depends:.
make_deb qualified "$host" "libc6:amd64 (>= 2.34)"
expect 1 "Depends: has an architecture qualifier" "$host" "$tmp/qualified.deb"
expect 1 "Depends: names amd64" "$host" "$tmp/qualified.deb"

echo "check_cross self-test: $fails failure(s)"
[ $fails = 0 ]
