#!/usr/bin/env bash
# The qemu-user environment of the arm tests (docs/development.md, "the arm64 daemon
# hangs"). Under `qemu-aarch64-static -L /usr/aarch64-linux-gnu` the daemon
# printed its start lines and then spun at 100 % CPU with no system call,
# deaf to SIGTERM: qemu took the program interpreter from the cross
# toolchain's glibc (libc6-arm64-cross 2.36-8cross1) and that loader mapped
# libc.so.6 from multiarch libc6:arm64 (2.36-9+deb12u14); the two builds
# disagree on the layout of _rtld_global, and libc's first pthread_create
# loops on the loader's stack cache list. A test environment that pairs two
# glibc builds proves nothing about the daemon, so this checks it first.
#
#   emulator_check.sh pairing QEMU PREFIX BINARY       loader and libc are one build
#   emulator_check.sh detects-mismatch QEMU TRIPLET BINARY
#                     the pairing check does fail on the cross toolchain's
#                     prefix when its glibc differs from multiarch (77 = the
#                     two are the same build here: nothing to detect)
#   emulator_check.sh daemon QEMU PREFIX XREGULATORD   threads start, a short
#                     run ends by itself, SIGTERM stops it with the field off
set -uo pipefail
mode=$1 qemu=$2 prefix=$3 bin=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL [$mode]: $*" >&2; exit 1; }

# What qemu-user opens for a guest path: the copy under -L PREFIX if there
# is one, else the host's file of that name.
host_path() { if [ "$prefix" != / ] && [ -e "$prefix$1" ]; then echo "$prefix$1"; else echo "$1"; fi; }

# "Debian GLIBC 2.36-9+deb12u14" from a loader or a libc.so.6.
glibc_build() { grep -aoE -m1 '\(Debian GLIBC [^)]*\)' "$1" | head -1 | tr -d '()'; }

# Prints "LOADER-BUILD|LIBC-BUILD|loader path|libc path" as the guest sees them.
resolve_pair() {
  local interp libc
  interp=$(LC_ALL=C readelf -l "$bin" | sed -n 's/.*Requesting program interpreter: \(.*\)]/\1/p')
  [ -n "$interp" ] || fail "$bin has no program interpreter"
  # The loader's own resolution (LD_TRACE_LOADED_OBJECTS, like ldd): maps
  # nothing but the libraries, starts no thread, so it works even when the
  # pair is mismatched.
  # The variable is set for qemu's guest only (via env): set on `timeout`, the
  # host's loader would trace timeout itself and print the host's libc.
  libc=$(timeout 60 env LD_TRACE_LOADED_OBJECTS=1 "$qemu" -L "$prefix" "$bin" 2>&1 |
    sed -n 's/.*libc\.so\.6 => \([^ ]*\) .*/\1/p')
  [ -n "$libc" ] || fail "the loader did not resolve libc.so.6 under -L $prefix"
  local lp cp
  lp=$(host_path "$interp") cp=$(host_path "$libc")
  echo "$(glibc_build "$lp")|$(glibc_build "$cp")|$lp|$cp"
}

check_pairing() {
  local r ld c
  r=$(resolve_pair) || exit 1
  IFS='|' read -r ld c lp cp <<<"$r"
  echo "under -L $prefix: loader $lp ($ld), libc $cp ($c)"
  [ -n "$ld" ] && [ -n "$c" ] || { echo "mismatch: no glibc build string found"; return 1; }
  [ "$ld" = "$c" ] || { echo "mismatch: loader and libc are different glibc builds"; return 1; }
  echo "ok: one glibc build"
}

case "$mode" in
  pairing) check_pairing || fail "loader/libc mismatch: run the tests with -L / (multiarch glibc)" ;;
  detects-mismatch)
    triplet=$prefix prefix=/usr/$triplet
    cross=$(glibc_build "/usr/$triplet/lib/libc.so.6" 2>/dev/null)
    multi=$(glibc_build "/usr/lib/$triplet/libc.so.6" 2>/dev/null)
    echo "cross toolchain glibc: ${cross:-none}; multiarch glibc: ${multi:-none}"
    if [ -z "$cross" ] || [ "$cross" = "$multi" ]; then echo "SKIP: one glibc build on this host"; exit 77; fi
    if check_pairing; then fail "the pairing check passed a prefix whose loader is $cross and libc $multi"; fi
    echo "ok: the pairing check rejects -L $prefix" ;;
  daemon)
    check_pairing || fail "loader/libc mismatch"
    # A 2 s simulated run at full speed: the run that hung. A wall-clock
    # deadline (generous for emulation on a loaded 2-core CI machine) turns
    # a hang into a failure instead of a stuck test.
    start=$(date +%s)
    timeout -s KILL 120 "$qemu" -L "$prefix" "$bin" --sim --duration 2 --speed max \
      --telemetry-csv "$tmp/t.csv" >"$tmp/log" 2>&1
    rc=$?
    [ $rc = 137 ] && { tail "$tmp/log"; fail "--sim --duration 2 --speed max still running after 120 s (hang)"; }
    [ $rc = 0 ] || { tail "$tmp/log"; fail "--sim --duration 2 exited $rc"; }
    rows=$(($(wc -l <"$tmp/t.csv") - 1))
    [ "$rows" -gt 0 ] || fail "no telemetry rows"
    echo "ok: 2 s simulated run ended in $(($(date +%s) - start)) s wall, $rows telemetry rows"

    # Paced run: wait for the field to come on (the control thread runs),
    # count the process's threads, then SIGTERM must stop it, field off.
    "$qemu" -L "$prefix" "$bin" --sim --speed 20 --sim-outputs "$tmp/out" >"$tmp/log2" 2>&1 &
    pid=$!
    on=0
    for _ in $(seq 1 600); do
      grep -q 'enable=1' "$tmp/out" 2>/dev/null && { on=1; break; }
      kill -0 $pid 2>/dev/null || break
      sleep 0.1
    done
    [ $on = 1 ] || { kill -9 $pid 2>/dev/null; tail "$tmp/log2"; fail "field never came on within 60 s"; }
    threads=$(ls /proc/$pid/task | wc -l)
    [ "$threads" -ge 3 ] || { kill -9 $pid; fail "only $threads threads running"; }
    echo "ok: field on, $threads threads"
    kill -TERM $pid
    for _ in $(seq 1 300); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done
    if kill -0 $pid 2>/dev/null; then kill -9 $pid; fail "still running 30 s after SIGTERM"; fi
    wait $pid
    rc=$?
    [ $rc = 0 ] || { tail "$tmp/log2"; fail "exit code $rc after SIGTERM"; }
    grep -q 'enable=0' "$tmp/out" && grep -q 'via=stop' "$tmp/out" || fail "field not left off: $(cat "$tmp/out")"
    echo "ok: SIGTERM stopped it, field off ($(cat "$tmp/out"))" ;;
  *) fail "unknown mode $mode" ;;
esac
