#!/bin/sh
# SocketCAN backend check on a real kernel (run as root inside the qemu
# arm64 VM of `make test-kernel`; CI machines have no AF_CAN). Creates a
# vcan interface and runs the self-checking program built as `vcan_check`.
#   usage: vcan_check.sh PATH/TO/vcan_check [IFNAME]
set -eu
bin=${1:?usage: vcan_check.sh PATH/TO/vcan_check [IFNAME]}
ifname=${2:-vcan0}
modprobe vcan 2>/dev/null || true
if ! ip link show "$ifname" >/dev/null 2>&1; then
  ip link add dev "$ifname" type vcan
fi
ip link set up "$ifname"
"$bin" "$ifname"
