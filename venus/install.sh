#!/bin/sh
# Installs, re-links and removes the xregulator GX driver on a Victron GX
# (Venus OS). See venus/README.md and docs/integrations.md "Victron GX".
#
#   install.sh install --xregulator http://HOST:PORT (--token-file FILE | --code 123456) [--id ID]
#   install.sh boot        re-link the service after a reboot or a firmware update
#                          (what /data/rc.local runs at every boot)
#   install.sh uninstall   stop the service, remove it and every file it added
#   install.sh status
#
# Only /data survives a Venus OS firmware update, so everything lives in
# /data/xregulator; /service (daemontools' svscan) is rebuilt at boot, so
# /data/rc.local re-links it. --root DIR (first argument) runs it all under a
# fake root (the tests).
set -eu

ROOT=""
if [ "${1:-}" = "--root" ]; then
  ROOT="${2:?--root needs a directory}"
  shift 2
fi
NAME=dbus-xregulator
APP="$ROOT/data/xregulator"
SERVICE_LINK="$ROOT/service/$NAME"
RC_LOCAL="$ROOT/data/rc.local"
MARK="# xregulator GX driver"
HERE="$(cd "$(dirname "$0")" && pwd)"
PYTHON="${PYTHON:-/usr/bin/python3}"
FILES="$NAME xr_busitem.py xr_regulator.py xr_settings.py install.sh README.md"

die() { echo "install.sh: $*" >&2; exit 1; }

write_run_scripts() {
  mkdir -p "$APP/service/log"
  cat > "$APP/service/run" <<EOF
#!/bin/sh
# daemontools runs this; the settings are in $APP/xregulator.conf.
exec 2>&1
. "$APP/xregulator.conf"
exec $PYTHON "$APP/$NAME" --xregulator "\$XREGULATOR_URL" --token-file "$APP/token" --id "\$XREGULATOR_ID"
EOF
  cat > "$APP/service/log/run" <<EOF
#!/bin/sh
exec multilog t s99999 n8 /var/log/$NAME
EOF
  chmod 755 "$APP/service/run" "$APP/service/log/run"
}

# /data/rc.local runs at every boot: one marked line re-links the service.
add_boot_line() {
  if [ ! -f "$RC_LOCAL" ]; then
    printf '#!/bin/sh\n' > "$RC_LOCAL"
  fi
  if ! grep -qF "$MARK" "$RC_LOCAL"; then
    if [ -n "$ROOT" ]; then
      printf '%s --root %s boot %s\n' "$APP/install.sh" "$ROOT" "$MARK" >> "$RC_LOCAL"
    else
      printf '%s boot %s\n' "$APP/install.sh" "$MARK" >> "$RC_LOCAL"
    fi
  fi
  chmod 755 "$RC_LOCAL"
}

remove_boot_line() {
  [ -f "$RC_LOCAL" ] || return 0
  grep -vF "$MARK" "$RC_LOCAL" > "$RC_LOCAL.xr-tmp" || true
  cat "$RC_LOCAL.xr-tmp" > "$RC_LOCAL"
  rm -f "$RC_LOCAL.xr-tmp"
}

link_service() {
  [ -d "$APP/service" ] || die "not installed: $APP/service is missing"
  mkdir -p "$ROOT/service"
  if [ ! -L "$SERVICE_LINK" ] || [ "$(readlink "$SERVICE_LINK")" != "$APP/service" ]; then
    rm -rf "$SERVICE_LINK"
    ln -s "$APP/service" "$SERVICE_LINK"
  fi
}

cmd_install() {
  url="" token_file="" code="" id=""
  while [ $# -gt 0 ]; do
    case "$1" in
      --xregulator) url="${2:?}"; shift 2 ;;
      --token-file) token_file="${2:?}"; shift 2 ;;
      --code) code="${2:?}"; shift 2 ;;
      --id) id="${2:?}"; shift 2 ;;
      *) die "unknown option $1" ;;
    esac
  done
  case "$url" in http://?*) ;; *) die "--xregulator http://HOST:PORT is needed" ;; esac
  [ -n "$token_file" ] || [ -n "$code" ] || die "--token-file FILE or --code CODE (a pairing code) is needed"
  if [ -z "$id" ]; then
    id="$(echo "$url" | sed -e 's|^http://||' -e 's|[:/].*$||' -e 's/[^A-Za-z0-9_]/_/g')"
  fi
  case "$id" in *[!A-Za-z0-9_]*|"") die "--id takes letters, digits and _ only" ;; esac

  for f in $FILES; do
    [ -f "$HERE/$f" ] || die "$HERE/$f is missing: run install.sh from the driver's folder"
  done
  mkdir -p "$APP"
  # The program first, the link last: svscan never starts half a copy.
  for f in $FILES; do
    cp "$HERE/$f" "$APP/$f.xr-new"
    mv -f "$APP/$f.xr-new" "$APP/$f"
  done
  chmod 755 "$APP/$NAME" "$APP/install.sh"
  umask 077
  if [ -n "$token_file" ]; then
    [ -s "$token_file" ] || die "$token_file is empty or missing"
    [ "$(cd "$(dirname "$token_file")" && pwd)/$(basename "$token_file")" = "$APP/token" ] || cp "$token_file" "$APP/token"
  else
    "$PYTHON" "$APP/$NAME" --xregulator "$url" --token-file "$APP/token" --pair "$code" \
      || die "pairing with $url failed (is the code fresh? see venus/README.md)"
  fi
  chmod 600 "$APP/token"
  printf 'XREGULATOR_URL=%s\nXREGULATOR_ID=%s\n' "$url" "$id" > "$APP/xregulator.conf"
  umask 022
  write_run_scripts
  add_boot_line
  link_service
  echo "installed: $APP, service $SERVICE_LINK, com.victronenergy.alternator.xregulator_$id"
}

cmd_uninstall() {
  if [ -L "$SERVICE_LINK" ] || [ -e "$SERVICE_LINK" ]; then
    # Stop the driver and its logger before the files go (svc is on a GX).
    if command -v svc >/dev/null 2>&1 && [ -z "$ROOT" ]; then
      svc -d "$SERVICE_LINK" "$SERVICE_LINK/log" 2>/dev/null || true
    fi
    rm -f "$SERVICE_LINK"
  fi
  remove_boot_line
  rm -rf "$APP"
  echo "uninstalled: $APP and $SERVICE_LINK removed, /data/rc.local line dropped"
}

cmd_status() {
  [ -d "$APP" ] && echo "files: $APP" || echo "files: not installed"
  [ -L "$SERVICE_LINK" ] && echo "service: $SERVICE_LINK -> $(readlink "$SERVICE_LINK")" || echo "service: not linked"
  grep -qF "$MARK" "$RC_LOCAL" 2>/dev/null && echo "boot: $RC_LOCAL re-links it" || echo "boot: no line in $RC_LOCAL"
  if command -v svstat >/dev/null 2>&1 && [ -L "$SERVICE_LINK" ]; then svstat "$SERVICE_LINK"; fi
}

case "${1:-}" in
  install) shift; cmd_install "$@" ;;
  boot) link_service ;;
  uninstall) cmd_uninstall ;;
  status) cmd_status ;;
  *) die "usage: install.sh [--root DIR] install|boot|uninstall|status (see venus/README.md)" ;;
esac
