#!/bin/sh
# `make repo` (docs/release.md): a signed apt repository, made by reprepro,
# from the packages `make deb` builds.
#
#   make-repo.sh --repo DIR --key KEYID --url URL [--channel candidate|stable] DEB...
#   make-repo.sh --repo DIR --promote            candidate's packages into stable
#   make-repo.sh --repo DIR --unsigned ... DEB...  (tests only: a repository apt must refuse)
#
# The signing key is found through GNUPGHOME (or gpg's default home). It must
# never be inside the source tree; this script refuses when it is. The
# repository gets the public key as xregulator-archive-keyring.gpg and the
# keyring package (tools/update/build-keyring-deb.sh) in both channels.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
repo="" key="" url="" channel=candidate promote=0 unsigned=0 keyring_version=1
while [ $# -gt 0 ]; do
  case "$1" in
    --repo) repo=$2; shift 2 ;;
    --key) key=$2; shift 2 ;;
    --url) url=$2; shift 2 ;;
    --channel) channel=$2; shift 2 ;;
    --keyring-version) keyring_version=$2; shift 2 ;;
    --promote) promote=1; shift ;;
    --unsigned) unsigned=1; shift ;;
    --) shift; break ;;
    -*) echo "make-repo.sh: unknown option $1" >&2; exit 64 ;;
    *) break ;;
  esac
done
[ -n "$repo" ] || { echo "make-repo.sh: --repo DIR is required" >&2; exit 64; }
case "$channel" in stable | candidate) ;; *) echo "make-repo.sh: channel is stable or candidate, not $channel" >&2; exit 64 ;; esac

if [ $promote = 1 ]; then
  reprepro -b "$repo" copymatched stable candidate '*'
  reprepro -b "$repo" export stable
  echo "make-repo.sh: candidate's packages are now in stable"
  exit 0
fi

home=$(readlink -f "${GNUPGHOME:-$HOME/.gnupg}")
case "$home/" in "$src"/*)
  echo "make-repo.sh: GNUPGHOME ($home) is inside the source tree: the signing key must never be there" >&2
  exit 1 ;;
esac
if [ $unsigned = 0 ]; then
  [ -n "$key" ] || { echo "make-repo.sh: --key KEYID is required (the release signing subkey, docs/release.md)" >&2; exit 64; }
  gpg --batch --list-secret-keys "$key" >/dev/null 2>&1 ||
    { echo "make-repo.sh: no secret key $key in $home (docs/release.md: where releases are signed)" >&2; exit 1; }
  [ -n "$url" ] || { echo "make-repo.sh: --url URL is required (the address owners add, for the keyring package)" >&2; exit 64; }
fi
[ $# -gt 0 ] || { echo "make-repo.sh: no packages given (run make deb first)" >&2; exit 64; }

mkdir -p "$repo/conf"
sign=""
[ $unsigned = 1 ] || sign="SignWith: $key"
: >"$repo/conf/distributions"
for c in stable candidate; do
  cat >>"$repo/conf/distributions" <<EOT
Origin: xregulator
Label: xregulator
Suite: $c
Codename: $c
Architectures: amd64 arm64 armhf
Components: main
Description: xregulator alternator field regulator ($c channel)
$sign

EOT
done
# Older versions stay in the pool (not in the index): a rollback at the
# repository republishes one of them (docs/release.md).
echo "keepunreferencedfiles" >"$repo/conf/options"

if [ $unsigned = 0 ]; then
  gpg --batch --export "$key" >"$repo/xregulator-archive-keyring.gpg"
  # The keyring package once per --keyring-version: a rebuild of the same
  # version would differ in its file times, which reprepro rightly refuses.
  if ! reprepro -b "$repo" list stable xregulator-archive-keyring 2>/dev/null | grep -q " $keyring_version\$"; then
    kdeb=$("$here/build-keyring-deb.sh" --key-file "$repo/xregulator-archive-keyring.gpg" --url "$url" \
      --out "$repo/.build" --version "$keyring_version")
    reprepro -b "$repo" includedeb stable "$kdeb"
    reprepro -b "$repo" includedeb candidate "$kdeb"
    # A fixed name at the top for the owner's first step (docs/install.md).
    cp -f "$kdeb" "$repo/xregulator-archive-keyring.deb"
  fi
fi
for deb in "$@"; do
  reprepro -b "$repo" includedeb "$channel" "$deb"
done
reprepro -b "$repo" export
if [ $unsigned = 0 ]; then
  gpgv --keyring "$repo/xregulator-archive-keyring.gpg" "$repo/dists/$channel/InRelease" 2>/dev/null ||
    { echo "make-repo.sh: dists/$channel/InRelease does not verify with the exported key" >&2; exit 1; }
fi
echo "make-repo.sh: $repo: channel $channel: $(reprepro -b "$repo" list "$channel" | sed 's/^[^:]*: //' | sort -u | tr '\n' ' ')"
