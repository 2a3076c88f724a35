#!/bin/bash
# No key, passphrase or secret in the repository (docs/release.md "The
# key"): every file git tracks or would add is searched for private-key
# markers, OpenPGP secret-key packets and written-down passphrases.
#
#   no_secrets.sh SOURCE_DIR          exit 0 when clean, 1 with each hit
#   no_secrets.sh --self-test         a planted secret of each kind is caught
set -uo pipefail
# The marker is put together here so that this file does not match itself:
# "-----BEGIN ... PRIVATE KEY" in every armour (PGP, RSA, EC, OPENSSH, PKCS#8).
B="-----BEGIN"
key_re="$B ([A-Z0-9]+ )*PRIVATE KEY"
pass_re='^[[:space:]]*(Passphrase|passphrase|XR_SIGN_PASSPHRASE|GPG_PASSPHRASE)[[:space:]]*[:=][[:space:]]*[^[:space:]$]'

files_of() {
  if git -C "$1" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git -C "$1" ls-files -z --cached --others --exclude-standard
  else
    (cd "$1" && find . -path ./build -prune -o -name node_modules -prune -o -type f -print0)
  fi
}

scan() {  # DIR: prints each hit, returns 1 when there is one
  local dir=$1 hits=0 f
  while IFS= read -r f; do echo "secret: $f holds a private key"; hits=1; done < <(
    cd "$dir" && files_of . | xargs -0 -r grep -laE -- "$key_re" 2>/dev/null)
  while IFS= read -r f; do echo "secret: $f writes down a passphrase"; hits=1; done < <(
    cd "$dir" && files_of . | xargs -0 -r grep -laE -- "$pass_re" 2>/dev/null)
  while IFS= read -r -d '' f; do
    case "$f" in
      *.gpg | *.asc | *.pgp | *.key | *.kbx | *secring* | *private-keys-v1.d/*)
        if gpg --list-packets "$dir/$f" 2>/dev/null | grep -q "secret key packet\|secret sub key packet"; then
          echo "secret: $f is an OpenPGP secret key"; hits=1
        fi ;;
    esac
  done < <(cd "$dir" && files_of .)
  return $hits
}

if [ "${1:-}" = --self-test ]; then
  t=$(mktemp -d)
  trap 'rm -rf "$t"' EXIT
  fails=0
  for planted in "$B PGP PRIVATE KEY BLOCK-----" "$B OPENSSH PRIVATE KEY-----" "Passphrase: hunter2"; do
    rm -rf "$t/tree" && mkdir -p "$t/tree" && echo "$planted" >"$t/tree/file.txt"
    if scan "$t/tree" >/dev/null; then echo "FAIL: '$planted' not caught"; fails=1; else echo "ok: '${planted#-----}' caught"; fi
  done
  export GNUPGHOME=$t/g
  mkdir -m 700 "$GNUPGHOME"
  rm -rf "$t/tree" && mkdir -p "$t/tree"
  gpg --batch --passphrase '' --quick-gen-key "planted <p@test.invalid>" ed25519 sign 1d 2>/dev/null &&
    gpg --batch --pinentry-mode loopback --passphrase '' --export-secret-keys >"$t/tree/release.gpg" 2>/dev/null
  if scan "$t/tree" >/dev/null; then echo "FAIL: binary secret key not caught"; fails=1; else echo "ok: binary OpenPGP secret key caught"; fi
  rm -rf "$t/tree" && mkdir -p "$t/tree" && echo "a public text; Signed-By: /usr/share/keyrings/x.gpg" >"$t/tree/ok.txt"
  if scan "$t/tree"; then echo "ok: a clean tree passes"; else echo "FAIL: a clean tree flagged"; fails=1; fi
  gpgconf --kill all 2>/dev/null
  exit $fails
fi

dir=${1:?usage: no_secrets.sh SOURCE_DIR | --self-test}
if scan "$dir"; then echo "ok: no private key, passphrase or secret key file in $dir"; exit 0; fi
exit 1
