#!/usr/bin/env bash
# `make test-kernel` (docs/development.md): the board backends on a real Linux kernel.
#
#   run.sh ARM64_BUILD WORKDIR
#
# Downloads Debian 12's arm64 kernel (linux-image-arm64's dependency) and
# busybox-static:arm64 with apt-get download (arm64 must be a foreign
# architecture: `make deps-cross`), packs an initramfs with the arm64
# xregulatord, xregulator-field-off, xr_board_check, their libraries, the
# modules softdog, vcan, can, can-raw, can-dev, i2c-dev and
# tests/kernel/init.sh, and boots it in qemu-system-aarch64 -M virt (TCG).
# init.sh prints RIG PASS/FAIL/GAP lines; its last check hangs the control
# thread, and softdog must reset the VM (-no-reboot: qemu exits). Prints
# `N passed, N failed` and exits non-zero on any failure.
set -uo pipefail
[ $# = 2 ] || { echo "usage: $0 ARM64_BUILD WORKDIR" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
arm=$(cd "$1" && pwd)
work=$2
mkdir -p "$work"
work=$(cd "$work" && pwd)
triplet=aarch64-linux-gnu
bins=("$arm/daemon/app/xregulatord" "$arm/tools/xregulator-field-off" "$arm/tests/kernel/xr_board_check")
for b in "${bins[@]}"; do [ -x "$b" ] || { echo "missing $b (build the arm64 tree first)" >&2; exit 2; }; done

# --- the kernel and busybox from the Debian registry -----------------------
kpkg=$(apt-cache depends linux-image-arm64:arm64 | sed -n 's/^ *Depends: \(linux-image-[^ ]*\)$/\1/p' | head -1)
[ -n "$kpkg" ] || { echo "no linux-image-arm64:arm64 in the apt lists (make deps-cross; apt-get update)" >&2; exit 2; }
kpkg=${kpkg%:arm64}
cd "$work" || exit 2
if ! ls "${kpkg}"_*_arm64.deb >/dev/null 2>&1; then apt-get download "$kpkg:arm64" || exit 2; fi
if ! ls busybox-static_*_arm64.deb >/dev/null 2>&1; then apt-get download busybox-static:arm64 || exit 2; fi
rm -rf kernel root && mkdir -p kernel root
dpkg-deb -x "$(ls "${kpkg}"_*_arm64.deb | head -1)" kernel
kver=${kpkg#linux-image-}
config=kernel/boot/config-$kver
echo "kernel $kver: $(grep -E '^(# )?CONFIG_(GPIO_SIM|GPIO_MOCKUP|I2C_STUB|SOFT_WATCHDOG|CAN_VCAN)[= ]' "$config" | tr '\n' ';')"

# --- the initramfs ------------------------------------------------------------
dpkg-deb -x "$(ls busybox-static_*_arm64.deb | head -1)" bb
mkdir -p root/bin root/usr/bin root/etc/xr root/proc root/sys root/dev root/tmp root/run
cp bb/bin/busybox root/bin/busybox
cp "$here/init.sh" root/init && chmod 755 root/init
cp "$here/vm.toml" root/etc/xr/vm.toml
cp "${bins[@]}" root/usr/bin/
# The SocketCAN backend's self-test (tests/kernel/vcan_check.cpp, from the
# CAN work), when the tree has it.
[ -x "$arm/tests/kernel/vcan_check" ] && cp "$arm/tests/kernel/vcan_check" root/usr/bin/
# Libraries: what the arm64 loader resolves for each binary, from the
# multiarch directories of this machine.
for b in root/usr/bin/*; do
  qemu-aarch64-static -L / /lib/ld-linux-aarch64.so.1 --list "$b" | sed -n 's/.*=> \(\/[^ ]*\) .*/\1/p'
done | sort -u | while read -r lib; do
  mkdir -p "root$(dirname "$lib")" && cp -L "$lib" "root$lib"
done
mkdir -p root/lib && cp -L /lib/ld-linux-aarch64.so.1 root/lib/
mods=(drivers/watchdog/softdog.ko drivers/net/can/vcan.ko drivers/net/can/dev/can-dev.ko net/can/can.ko
  net/can/can-raw.ko drivers/i2c/i2c-dev.ko)
for m in "${mods[@]}"; do
  src=kernel/lib/modules/$kver/kernel/$m
  [ -f "$src" ] || { echo "kernel $kver has no $m" >&2; exit 2; }
  mkdir -p "root/lib/modules/$kver/kernel/$(dirname "$m")" && cp "$src" "root/lib/modules/$kver/kernel/$m"
done
(cd root && find . | cpio -o -H newc --quiet | gzip -1) >initrd.gz
echo "initramfs: $(du -h initrd.gz | cut -f1) ($(find root -type f | wc -l) files, $(ls root/usr/bin | tr '\n' ' '))"

# --- boot -----------------------------------------------------------------------
start=$(date +%s)
timeout 900 qemu-system-aarch64 -M virt -cpu cortex-a57 -smp 2 -m 512 -nographic -nic none -no-reboot \
  -kernel "kernel/boot/vmlinuz-$kver" -initrd initrd.gz \
  -append "console=ttyAMA0 rdinit=/init panic=-1 loglevel=3" </dev/null >console.log 2>&1
qrc=$?
echo "qemu exit $qrc after $(($(date +%s) - start)) s; console in $work/console.log"
tr -d '\r' <console.log >console.txt
grep -E '^RIG (PASS|FAIL|GAP|INFO|BOOT)' console.txt

passed=$(grep -c '^RIG PASS' console.txt)
failed=$(grep -c '^RIG FAIL' console.txt)
# The watchdog reset: armed, softdog's reboot message, qemu left by itself.
if grep -q '^RIG WDHANG armed' console.txt && grep -q 'softdog: Initiating system reboot' console.txt &&
  [ $qrc = 0 ]; then
  echo "RIG PASS watchdog_reset: hung control thread -> softdog reset the VM"
  passed=$((passed + 1))
else
  echo "RIG FAIL watchdog_reset: no softdog reset seen (qemu exit $qrc)"
  failed=$((failed + 1))
fi
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
