#!/bin/sh
# Builds the xregulator-archive-keyring package (docs/release.md) with
# dpkg-deb: it is arch-independent and holds only the PUBLIC key, which is not
# in the source tree (it comes from where releases are signed), so it is built
# next to the repository rather than by debian/rules.
#
#   build-keyring-deb.sh --key-file PUB.gpg --url URL --out DIR [--version V] [--channel stable]
#
# Installs:
#   /usr/share/keyrings/xregulator-archive-keyring.gpg   the public key (binary)
#   /etc/apt/sources.list.d/xregulator.sources           deb822, Signed-By that key only
#   /etc/apt/preferences.d/xregulator.pref               the repository may provide only our packages
set -eu
key="" url="" out="" version=1 channel=stable
while [ $# -gt 0 ]; do
  case "$1" in
    --key-file) key=$2; shift 2 ;;
    --url) url=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --version) version=$2; shift 2 ;;
    --channel) channel=$2; shift 2 ;;
    *) echo "build-keyring-deb.sh: unknown argument $1" >&2; exit 64 ;;
  esac
done
[ -f "$key" ] && [ -n "$url" ] && [ -n "$out" ] || { echo "usage: build-keyring-deb.sh --key-file PUB.gpg --url URL --out DIR" >&2; exit 64; }
if grep -aq "PRIVATE KEY" "$key" || gpg --show-keys --with-colons "$key" 2>/dev/null | grep -q '^sec'; then
  echo "build-keyring-deb.sh: $key holds a SECRET key; give the public key only (gpg --export)" >&2; exit 1
fi
case "$channel" in stable | candidate) ;; *) echo "build-keyring-deb.sh: channel is stable or candidate" >&2; exit 64 ;; esac
# The pin names the repository's host: a Release file can claim any Origin,
# but not the address apt fetched it from.
host=$(echo "$url" | sed -e 's|^[a-z]*://||' -e 's|/.*||' -e 's|^.*@||' -e 's|:[0-9]*$||')

root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
chmod 755 "$root"
mkdir -p "$root/DEBIAN" "$root/usr/share/keyrings" "$root/etc/apt/sources.list.d" "$root/etc/apt/preferences.d" \
  "$root/usr/share/doc/xregulator-archive-keyring"
gpg --dearmor <"$key" >"$root/usr/share/keyrings/xregulator-archive-keyring.gpg" 2>/dev/null ||
  cp "$key" "$root/usr/share/keyrings/xregulator-archive-keyring.gpg"
# Already binary? gpg --dearmor refuses binary input: keep the file as it is.
gpg --show-keys "$root/usr/share/keyrings/xregulator-archive-keyring.gpg" >/dev/null 2>&1 ||
  cp "$key" "$root/usr/share/keyrings/xregulator-archive-keyring.gpg"
cat >"$root/etc/apt/sources.list.d/xregulator.sources" <<EOT
# xregulator's apt repository (docs/install.md). Suites: stable, or candidate
# for release candidates (docs/release.md "Channels").
Types: deb
URIs: $url
Suites: $channel
Components: main
Signed-By: /usr/share/keyrings/xregulator-archive-keyring.gpg
EOT
cat >"$root/etc/apt/preferences.d/xregulator.pref" <<EOT
# xregulator's repository may provide only xregulator's own packages
# (docs/install.md): anything else it offers is never installed.
Package: xregulator xregulator-dbgsym xregulator-archive-keyring
Pin: origin "$host"
Pin-Priority: 500

Package: *
Pin: origin "$host"
Pin-Priority: -1
EOT
cat >"$root/usr/share/doc/xregulator-archive-keyring/copyright" <<'EOT'
Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/
Upstream-Name: xregulator

Files: *
Copyright: xregulator developers
License: public-domain
 The public key of xregulator's apt repository and the configuration to use it.
EOT
printf '/etc/apt/sources.list.d/xregulator.sources\n/etc/apt/preferences.d/xregulator.pref\n' >"$root/DEBIAN/conffiles"
cat >"$root/DEBIAN/control" <<EOT
Package: xregulator-archive-keyring
Version: $version
Architecture: all
Maintainer: xregulator developers <xregulator@lists.example.org>
Section: misc
Priority: optional
Multi-Arch: foreign
Description: xregulator's apt repository: public key, source and pin
 The OpenPGP public key that signs xregulator's apt repository, a deb822
 source for it that trusts only this key (Signed-By), and an apt pin that lets
 the repository provide xregulator's packages and nothing else.
EOT
chmod 0644 "$root"/usr/share/keyrings/* "$root"/etc/apt/*/* "$root"/DEBIAN/control "$root"/DEBIAN/conffiles
mkdir -p "$out"
dpkg-deb --root-owner-group -Zxz --build "$root" "$out/xregulator-archive-keyring_${version}_all.deb" >/dev/null
echo "$out/xregulator-archive-keyring_${version}_all.deb"
