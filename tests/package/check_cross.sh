#!/usr/bin/env bash
# Checks a cross-built xregulator package (docs/development.md): `make deb ARCH=arm64`
# and `ARCH=armhf` run it on what they built, and so does `make test-arm64`.
#
#   check_cross.sh [--no-lintian] ARCH PACKAGE.deb [PACKAGE.changes]
#
# ARCH is a Debian architecture (arm64, armhf). It checks:
#   - the control file's Architecture: is ARCH;
#   - every ELF file in the package is of ARCH's class, machine and (armhf)
#     float ABI, not the build machine's;
#   - each shared library those binaries need is resolved in ARCH's multiarch
#     directory, and the package owning it (for ARCH) is named in Depends:;
#   - Depends: names no amd64 package and no architecture qualifier;
#   - lintian (on the .changes if given, else the .deb) reports no error or
#     warning (--no-lintian: not run; check_cross_test.sh uses it on its
#     hand-made packages, which are not meant to be lintian-clean).
# Prints one "ok:"/"FAIL:" line per check; exits 1 on any failure.
set -uo pipefail
lintian=1
[ "${1:-}" = --no-lintian ] && { lintian=0; shift; }
[ $# -ge 2 ] || { echo "usage: $0 ARCH PACKAGE.deb [PACKAGE.changes]" >&2; exit 2; }
arch=$1 deb=$2 changes=${3:-}
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok: $*"; }

# readelf's words for each architecture (readelf -h: Class, Machine, Flags).
case "$arch" in
  arm64) class=ELF64 machine=AArch64 triplet=aarch64-linux-gnu flags="" ;;
  armhf) class=ELF32 machine=ARM triplet=arm-linux-gnueabihf flags="hard-float ABI" ;;
  amd64) class=ELF64 machine="Advanced Micro Devices X86-64" triplet=x86_64-linux-gnu flags="" ;;
  *) echo "unknown architecture $arch" >&2; exit 2 ;;
esac
[ -f "$deb" ] || { echo "FAIL: $deb not found"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

got=$(dpkg-deb -f "$deb" Architecture)
[ "$got" = "$arch" ] && ok "Architecture: $got" || fail "Architecture: is '$got', want $arch"

dpkg-deb -x "$deb" "$tmp/root"
elves=0
needed=""
while IFS= read -r f; do
  head -c 4 "$f" | grep -q $'^\x7fELF' || continue
  elves=$((elves + 1))
  hdr=$(LC_ALL=C readelf -h "$f")
  rel=${f#"$tmp/root"}
  c=$(sed -n 's/^ *Class: *//p' <<<"$hdr")
  m=$(sed -n 's/^ *Machine: *//p' <<<"$hdr")
  [ "$c" = "$class" ] && [ "$m" = "$machine" ] && ok "$rel: $c $m" || fail "$rel is $c $m, want $class $machine"
  if [ -n "$flags" ]; then
    grep -q "Flags:.*$flags" <<<"$hdr" && ok "$rel: $flags" || fail "$rel: not $flags ($(grep Flags: <<<"$hdr"))"
  fi
  needed+=$(LC_ALL=C readelf -d "$f" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')$'\n'
done < <(find "$tmp/root" -type f)
[ $elves -ge 2 ] && ok "$elves ELF files (daemon and field-off helper)" || fail "only $elves ELF files in the package"

depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
# Package names in Depends: (alternatives split, versions dropped).
dep_names=$(tr ',|' '\n\n' <<<"$depends" | sed 's/(.*)//; s/^ *//; s/ *$//' | grep -v '^$')
if grep -q ':' <<<"$dep_names"; then fail "Depends: has an architecture qualifier"; else ok "no architecture qualifier in Depends:"; fi
grep -qi 'amd64' <<<"$depends" && fail "Depends: names amd64" || ok "Depends: names no amd64 package"

for lib in $(sort -u <<<"$needed" | grep -v '^$'); do
  # The package of ARCH that ships the library in ARCH's multiarch directory
  # (/lib/<triplet> or /usr/lib/<triplet>), never the host's; it, or a name
  # it Provides: (libspdlog1.10 provides libspdlog1.10-fmt9), must be in
  # Depends:.
  owner=$(dpkg -S "*/$triplet/$lib" 2>/dev/null | grep "^[^:]*:$arch: " | head -1 | cut -d: -f1)
  [ -n "$owner" ] || { fail "$lib: no $arch package ships it (is the :$arch library installed?)"; continue; }
  names="$owner $(dpkg-query -W -f='${Provides}' "$owner:$arch" | tr ',' '\n' | sed 's/(.*)//; s/ //g')"
  found=""
  for n in $names; do grep -qx "$n" <<<"$dep_names" && found=$n; done
  # libc6 ships libc, libm and the loader; dpkg-shlibdeps names it once.
  if [ -n "$found" ]; then ok "$lib -> $owner:$arch, in Depends: as $found"
  else fail "$lib ($owner:$arch) is not in Depends:"; fi
done

if [ $lintian = 0 ]; then
  echo "lintian not run (--no-lintian)"
elif command -v lintian >/dev/null; then
  out=$(lintian --fail-on none "${changes:-$deb}" 2>&1 | grep -E '^[EW]: ' || true)
  [ -z "$out" ] && ok "lintian: no errors or warnings" || { printf '%s\n' "$out"; fail "lintian reports errors or warnings"; }
else
  fail "lintian not installed (make deps-tools)"
fi

echo "cross package check ($arch, $(basename "$deb")): $fails failure(s)"
[ $fails = 0 ]
