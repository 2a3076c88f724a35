#!/usr/bin/env bash
# Every library the package build needs (debian/control Build-Depends: the
# lib*-dev packages and pkg-config) must be in `make deps-cross`'s list
# (CROSS_LIBS), or `make deb ARCH=arm64|armhf` and the cross trees fail on a
# fresh machine: libssl-dev came in with the pairing code and was missing
# there until the first cross-build on a new machine found it.
#
#   check_cross_deps.sh CONTROL CROSS_LIB...
#
# Prints one line per needed package; exits 1 if any is missing.
set -uo pipefail
[ $# -ge 1 ] || { echo "usage: $0 CONTROL CROSS_LIB..." >&2; exit 2; }
control=$1
shift
have=" $* "
# The Build-Depends field: its first line and its indented continuation lines.
needed=$(sed -n '/^Build-Depends:/,/^[^ ]/{/^Build-Depends:/{s/^Build-Depends://;p;d};/^ /p}' "$control" |
  tr ',' '\n' | sed 's/([^)]*)//; s/\[[^]]*\]//; s/^ *//; s/ *$//' | grep -E '^(lib.*-dev|pkg-config)$')
[ -n "$needed" ] || { echo "FAIL: no lib*-dev in Build-Depends of $control"; exit 1; }
missing=0
for p in $needed; do
  if [[ "$have" == *" $p "* ]]; then echo "ok: $p"; else echo "FAIL: $p is a build dependency but not in CROSS_LIBS"; missing=$((missing + 1)); fi
done
[ $missing = 0 ]
