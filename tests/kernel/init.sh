#!/bin/busybox sh
# /init of the kernel rig's initramfs (tests/kernel/run.sh builds it): runs
# inside qemu-system-aarch64 on Debian's arm64 kernel. Prints one
# "RIG PASS name: ..." or "RIG FAIL name: ..." line per check and
# "RIG GAP name: ..." for what this kernel cannot test; run.sh counts them.
# The last check makes softdog reset the VM, which run.sh detects.
/bin/busybox --install -s /bin
export PATH=/bin:/usr/bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
mount -t debugfs debugfs /sys/kernel/debug
mount -t tmpfs tmp /tmp
mkdir -p /run && mount -t tmpfs run /run
ip link set lo up
echo "RIG BOOT kernel $(uname -r)"
depmod

pass() { echo "RIG PASS $1: $2"; }
fail() { echo "RIG FAIL $1: $2"; }
gap() { echo "RIG GAP $1: $2"; }
check() { # name detail command...
  n=$1 d=$2
  shift 2
  if "$@"; then pass "$n" "$d"; else fail "$n" "$d"; fi
}

CFG=/etc/xr/vm.toml
CHIP=gpiochip0
FE=0 # field enable line, as in vm.toml
level() { xr_board_check level $CHIP $FE; }
wait_for() { # text file: up to 20 s
  i=0
  while ! grep -q "$1" "$2" 2>/dev/null; do
    i=$((i + 1))
    [ $i -gt 200 ] && return 1
    usleep 100000
  done
}

# --- GPIO on the PL061 of the virt board (a real gpiochip driver) ---------
echo "RIG INFO $CHIP: $(ls /sys/bus/gpio/devices/) $(cat /sys/kernel/debug/gpio | head -1)"

# SIGTERM: the outputs go LOW and stay LOW after the line is released.
xr_board_check hold $CFG term >/tmp/hold.out 2>&1 &
pid=$!
if wait_for "hold: field on" /tmp/hold.out; then
  cat /tmp/hold.out
  held=$(grep xregulatord /sys/kernel/debug/gpio)
  echo "$held"
  check gpio_outputs_on "the kernel shows field enable and buzzer requested by xregulatord, out hi" \
    [ "$(echo "$held" | grep -c 'out hi')" = 2 ]
  check gpio_inputs "BMS and ignition requested as inputs, read 0 or 1" \
    sh -c "[ \$(echo '$held' | grep -c ' in ') = 2 ] && grep -q 'bms [01], ignition [01]' /tmp/hold.out"
  kill -TERM $pid
  wait $pid
  rc=$?
  check exit_sigterm "SIGTERM: exit $rc, field enable level after exit $(level)" [ $rc = 0 -a "$(level)" = 0 ]
else
  fail gpio_outputs_on "hold did not start: $(cat /tmp/hold.out)"
fi

# SIGKILL: nothing in the process can act; the kernel leaves the latch
# HIGH. The daemon refusing to start, then xregulator-field-off, drive it LOW.
kill_holding() {
  xr_board_check hold $CFG kill >/tmp/hold.out 2>&1 &
  hp=$!
  wait_for "hold: field on" /tmp/hold.out || return 1
  kill -KILL $hp
  wait $hp
  return 0
}
kill_holding
check sigkill_leaves_high "after SIGKILL the field enable stays at $(level) (the premise of the next checks)" \
  [ "$(level)" = 1 ]
# An exported channel on tmpfs, so that the daemon gets past PWM to I2C.
mkdir -p /run/pwm/pwmchip0/pwm0
for a in period duty_cycle enable; do echo 0 >/run/pwm/pwmchip0/pwm0/$a; done
echo normal >/run/pwm/pwmchip0/pwm0/polarity
xregulatord --config $CFG --state-db /tmp/state.db >/tmp/daemon.out 2>&1
rc=$?
tail -3 /tmp/daemon.out
check daemon_no_i2c_field_low "xregulatord without an I2C adapter: exit $rc naming I2C, field enable $(level)" \
  sh -c "[ $rc != 0 ] && grep -q 'I2C' /tmp/daemon.out && [ \"\$(xr_board_check level $CHIP $FE)\" = 0 ]"
kill_holding
xregulator-field-off --config $CFG
rc=$?
check sigkill_field_off "SIGKILL then xregulator-field-off: exit $rc, field enable $(level)" [ $rc = 0 -a "$(level)" = 0 ]

# A crash: the runtime's fatal guard drives the line LOW from the handler.
xr_board_check hold $CFG segv >/tmp/hold.out 2>&1
rc=$?
cat /tmp/hold.out
check exit_crash "SIGSEGV: exit $rc (139 = killed by SIGSEGV), field enable $(level)" [ $rc = 139 -a "$(level)" = 0 ]

# ADS1115 ALERT/RDY: the edge request on a real irq chip.
check ready_line_request "AdsReadyLine requests edge events on $CHIP line 6" xr_board_check ready $CHIP 6
gap alert_rdy_edges "Debian's arm64 kernels (6.1 bookworm, 6.12 bookworm-backports and trixie) have no gpio-sim or gpio-mockup: no edge can be injected, so edge-paced loops are not run on a kernel"

# --- sysfs PWM: no software PWM chip in this kernel; a tmpfs tree ----------
mkdir -p /run/pwmcheck
check pwm_sysfs_tmpfs "PwmSysfs on a tmpfs /sys/class/pwm tree (export, period, duty, enable, safe state)" \
  xr_board_check pwm /run/pwmcheck

# --- i2c-dev -----------------------------------------------------------------
modprobe i2c-dev
check i2c_dev_loaded "i2c-dev loads and registers its class" [ -d /sys/class/i2c-dev ]
gap i2c_rdwr "the virt board has no I2C adapter and CONFIG_I2C_STUB is unset: I2C_RDWR is covered by the driver tests against a fake bus only"

# --- SocketCAN on vcan ---------------------------------------------------------
modprobe vcan && modprobe can-raw
ip link add dev vcan0 type vcan && ip link set vcan0 up
check vcan_frame "a frame across two raw CAN sockets on vcan0" xr_board_check can vcan0
if [ -x /usr/bin/vcan_check ]; then
  check can_backend "the SocketCAN backend's self-test (vcan_check) on vcan0" vcan_check vcan0
else
  gap can_backend "no vcan_check in this tree: the SocketCAN backend is not run on the kernel"
fi

# --- softdog -------------------------------------------------------------------
modprobe softdog
check watchdog_fed "softdog (timeout 3 s) fed by the control thread for 9 s, closed clean; the VM is still up" \
  xr_board_check watchdog /dev/watchdog 3 9
echo "RIG WDHANG armed"
xr_board_check watchdog-hang /dev/watchdog 3 &
sleep 30
fail watchdog_reset "the control thread hung for 27 s and softdog did not reset the VM"
poweroff -f
