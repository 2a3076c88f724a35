#!/bin/bash
# The update test's packages (tests/update/run.sh), without running
# dpkg-buildpackage three times (far too slow on a small CI machine): the
# binaries of the build tree staged in the package's layout
# (cmake/xr_install.cmake) with debian/'s control and maintainer scripts, and
# only the version changed. With XR_UPDATE_TEST_DEB=path/xregulator_*.deb
# (`make deb`), that real package is re-versioned instead.
#
#   stage_deb.sh BUILD_DIR VERSION OUT_DIR [--broken]
#
# --broken: a release whose daemon fails at once (exit 70 after saying so),
# for the rollback step.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
build=$(readlink -f "$1")
version=$2
out=$3
broken=${4:-}
arch=$(dpkg --print-architecture)
root=$(mktemp -d)
chmod 755 "$root"
trap 'rm -rf "$root"' EXIT

if [ -n "${XR_UPDATE_TEST_DEB:-}" ]; then
  dpkg-deb -R "$XR_UPDATE_TEST_DEB" "$root"
else
  # Stripped as dh_strip would (the build tree's binaries carry their debug information).
  install -D -m 755 "$build/daemon/app/xregulatord" "$root/usr/sbin/xregulatord"
  install -D -m 755 "$build/tools/xregulator-field-off" "$root/usr/libexec/xregulator/xregulator-field-off"
  strip --strip-unneeded "$root/usr/sbin/xregulatord" "$root/usr/libexec/xregulator/xregulator-field-off"
  for f in xregulator-update-gate xregulator-update-check xregulator-update-record; do
    install -D -m 755 "$repo/tools/update/$f" "$root/usr/libexec/xregulator/$f"
  done
  install -D -m 644 "$repo/config/xregulator.toml" "$root/etc/xregulator/xregulator.toml"
  install -D -m 644 "$repo/tools/update/51xregulator-update-gate" "$root/etc/apt/apt.conf.d/51xregulator-update-gate"
  install -D -m 644 "$repo/tools/update/52xregulator-unattended-upgrades" \
    "$root/etc/apt/apt.conf.d/52xregulator-unattended-upgrades"
  install -D -m 644 "$repo/systemd/xregulatord.service" "$root/lib/systemd/system/xregulatord.service"
  install -D -m 644 "$repo/systemd/xregulator-update-check.service" "$root/lib/systemd/system/xregulator-update-check.service"
  mkdir -p "$root/usr/share/xregulator" "$root/DEBIAN"
  [ -d "$build/web/www" ] && cp -r "$build/web/www" "$root/usr/share/xregulator/www"
  # debhelper's own part of the postinst (the user, enabling the unit) is not
  # in this staged package: the test runs the daemon itself, as root.
  sed 's/^#DEBHELPER#$/# (debhelper part: not in the staged test package)/' "$repo/debian/xregulator.postinst" \
    >"$root/DEBIAN/postinst"
  sed 's/^#DEBHELPER#$//' "$repo/debian/xregulator.postrm" >"$root/DEBIAN/postrm"
  chmod 755 "$root/DEBIAN/postinst" "$root/DEBIAN/postrm"
  (cd "$root" && find etc -type f | sed 's|^|/|') >"$root/DEBIAN/conffiles"
  depends=$(cd "$repo" && dpkg-shlibdeps -O -e"$root/usr/sbin/xregulatord" -e"$root/usr/libexec/xregulator/xregulator-field-off" 2>/dev/null |
    sed -n 's/^shlibs:Depends=//p')
  awk '/^Package: xregulator$/{p=1} p&&/^Description:/{d=1} d' "$repo/debian/control" >"$root/DEBIAN/description"
  {
    echo "Package: xregulator"
    echo "Version: 0"
    echo "Architecture: $arch"
    echo "Maintainer: $(sed -n 's/^Maintainer: //p' "$repo/debian/control")"
    echo "Depends: ${depends:+$depends, }curl"
    echo "Section: utils"
    echo "Priority: optional"
    cat "$root/DEBIAN/description"
  } >"$root/DEBIAN/control"
  rm "$root/DEBIAN/description"
fi
sed -i "s/^Version: .*/Version: $version/" "$root/DEBIAN/control"
if [ "$broken" = --broken ]; then
  printf '#!/bin/sh\n[ "${1:-}" = --version ] && exec /bin/echo "xregulatord (faulty test release)"\necho "xregulatord: simulated faulty release: exiting" >&2\nexit 70\n' \
    >"$root/usr/sbin/xregulatord"
  chmod 755 "$root/usr/sbin/xregulatord"
fi
mkdir -p "$out"
dpkg-deb --root-owner-group -Zxz -z1 --build "$root" "$out/xregulator_${version}_${arch}.deb" >/dev/null
echo "$out/xregulator_${version}_${arch}.deb"
