// Self-checking test of the SocketCAN backend on a real kernel (vcan):
// run by tests/kernel/vcan_check.sh inside the qemu arm64 VM (make
// test-kernel). Exit 0 when every check passed; each check prints one line.
//   1. a standard frame sent on one socket arrives on another, bit-exact
//   2. an extended (29-bit) frame likewise
//   3. a kernel filter (only 0x351) drops other ids
//   4. an error frame injected on the interface arrives as error = true
//   5. a missing interface is a clear exception, not a crash
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "drivers/can/socketcan_bus.h"

using namespace std::chrono_literals;
using xr::CanFrame;
using xr::can::SocketCanBus;

namespace {
int failures = 0;
void check(bool ok, const char* what) {
  std::printf("%s %s\n", ok ? "PASS" : "FAIL", what);
  if (!ok) ++failures;
}

CanFrame frame(std::uint32_t id, bool extended, std::uint8_t dlc) {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.dlc = dlc;
  for (int i = 0; i < dlc; ++i) f.data[i] = static_cast<std::uint8_t>(0xA0 + i);
  return f;
}

// Drains `bus` until `want` arrives or nothing more comes in 200 ms.
bool receives(SocketCanBus& bus, const CanFrame& want) {
  while (auto f = bus.receive(200ms))
    if (*f == want) return true;
  return false;
}

// The kernel accepts a frame with CAN_ERR_FLAG on vcan from a raw socket.
bool injectError(const std::string& ifname, std::uint32_t errClass) {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) return false;
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(::if_nametoindex(ifname.c_str()));
  bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  can_frame k{};
  k.can_id = CAN_ERR_FLAG | errClass;
  k.len = 8;
  ok = ok && ::write(fd, &k, sizeof k) == static_cast<ssize_t>(sizeof k);
  ::close(fd);
  return ok;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string ifname = argc > 1 ? argv[1] : "vcan0";
  try {
    SocketCanBus tx(ifname), rx(ifname);
    const CanFrame std351 = frame(0x351, false, 8);
    check(tx.send(std351) && receives(rx, std351), "standard frame 0x351 sent and received");
    const CanFrame ext = frame(0x09F20123, true, 8);
    check(tx.send(ext) && receives(rx, ext), "extended frame 0x09F20123 sent and received");

    SocketCanBus filtered(ifname, {{0x351, 0x7FF, false}});
    const CanFrame other = frame(0x356, false, 6);
    tx.send(other);
    tx.send(std351);
    auto first = filtered.receive(200ms);
    check(first && *first == std351, "kernel filter passes 0x351 and drops 0x356");

    const bool injected = injectError(ifname, CAN_ERR_BUSOFF);
    bool gotError = false;
    while (auto f = rx.receive(200ms))
      if (f->error && (f->id & CAN_ERR_BUSOFF)) gotError = true;
    check(injected && gotError && rx.stats().busOff >= 1, "error frame (bus-off) received and counted");
    check(rx.stats().rx >= 2 && tx.stats().tx >= 4, "counters move");
  } catch (const std::exception& e) {
    check(false, e.what());
  }
  try {
    SocketCanBus missing("xr-no-such-can");
    check(false, "a missing interface throws");
  } catch (const std::runtime_error& e) {
    check(std::strstr(e.what(), "xr-no-such-can") != nullptr, "a missing interface throws a clear error");
  }
  std::printf("%s: %d failure(s)\n", failures ? "FAIL" : "PASS", failures);
  return failures ? 1 : 0;
}
