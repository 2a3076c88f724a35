// xr_board_check: the board backends against a real Linux kernel, for the
// `make test-kernel` rig (docs/development.md). It runs inside the arm64 VM
// (tests/kernel/init.sh) and drives the project's own drivers — GpioLibgpiod,
// the runtime's fatal-signal guard, LinuxWatchdog, PwmSysfs — on the
// kernel's devices. Each command prints what it saw; init.sh judges.
//
//   xr_board_check level CHIP LINE      the line's level (0/1) without
//                                        changing its direction
//   xr_board_check hold CONFIG MODE     field enable and buzzer ON, then
//                                        MODE term: LOW on SIGTERM, exit 0;
//                                        kill: wait to be SIGKILLed;
//                                        segv: write through a null pointer
//   xr_board_check watchdog DEV T S     feed DEV (timeout T s) from a control
//                                        thread for S s, then close clean
//   xr_board_check watchdog-hang DEV T  feed 3 times, then the control thread
//                                        hangs on a lock: softdog must reset
//   xr_board_check pwm ROOT             PwmSysfs on a tmpfs tree shaped like
//                                        /sys/class/pwm (export emulated)
//   xr_board_check can IFACE            one CAN frame across two raw sockets
//   xr_board_check ready CHIP LINE      AdsReadyLine's edge request on a
//                                        real irq chip; a wait with no edge
//                                        must time out (0), not fail (-1)
#include <gpiod.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>

#include "config/config.h"
#include "drivers/gpio/gpio_libgpiod.h"
#include "drivers/watchdog/linux_watchdog.h"
#include "runtime/fatal_guard.h"
#include "tests/kernel/pwm_fake_sysfs.h"

namespace {

int usage() {
  std::cerr << "usage: xr_board_check level CHIP LINE | hold CONFIG term|kill|segv | watchdog DEV T S |"
               " watchdog-hang DEV T | pwm ROOT | can IFACE | ready CHIP LINE\n";
  return 2;
}

// Requests the line "as is" (no direction change, so an output keeps its
// latch) and reads it: the level the hardware is left at.
int level(const std::string& chipName, unsigned offset) {
  gpiod_chip* chip = gpiod_chip_open_lookup(chipName.c_str());
  if (!chip) return -1;
  int v = -1;
  gpiod_line* line = gpiod_chip_get_line(chip, offset);
  gpiod_line_request_config cfg{"xr_board_check", GPIOD_LINE_REQUEST_DIRECTION_AS_IS, 0};
  if (line && gpiod_line_request(line, &cfg, 0) == 0) {
    v = gpiod_line_get_value(line);
    gpiod_line_release(line);
  }
  gpiod_chip_close(chip);
  return v;
}

// The daemon's start sequence for the lines (BoardRig: GPIO first, field
// enable requested LOW) and its fatal action (registerFatalActions: the
// libgpiod line set LOW from the signal handler), then the field ON.
int hold(const std::string& config, const std::string& mode) {
  const xr::LoadResult loaded = xr::loadConfigFile(config);
  if (!loaded.ok()) {
    std::cerr << "hold: bad config " << config << "\n";
    return 2;
  }
  const xr::HardwareSettings& hw = loaded.config->settings.hardware;
  xr::GpioLibgpiod gpio;
  if (!gpio.open(hw)) {
    std::cerr << "hold: " << gpio.error() << "\n";
    return 1;
  }
  xr::rt::fatal::addCallback(&xr::GpioOutputLine::setOffSignalSafe, gpio.fieldEnable());
  xr::rt::fatal::install();
  sigset_t term;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &term, nullptr);
  const int bms = gpio.bms() ? gpio.bms()->get() : -2;
  const int ign = gpio.ignition() ? gpio.ignition()->get() : -2;
  if (!gpio.fieldEnable()->set(true) || !gpio.buzzer()->set(true)) {
    std::cerr << "hold: cannot drive the outputs\n";
    return 1;
  }
  std::cout << "hold: field on, buzzer on, bms " << bms << ", ignition " << ign << std::endl;
  if (mode == "segv") {
    // A real fault: the fatal guard must drive the field LOW. The pointer is
    // volatile so the compiler cannot see the null (and emit a trap), and so
    // is the store (GCC 12 drops a plain one before the endless pause loop).
    volatile int* volatile nowhere = nullptr;
    *nowhere = 1;
  } else if (mode == "term") {
    int sig = 0;
    sigwait(&term, &sig);
    gpio.fieldEnable()->set(false);
    gpio.buzzer()->set(false);
    gpio.close();
    std::cout << "hold: SIGTERM, field off" << std::endl;
    return 0;
  }
  for (;;) pause();  // kill: only SIGKILL ends this
}

int watchdog(const std::string& dev, int timeoutS, int seconds, bool hang) {
  xr::LinuxWatchdog wd;
  if (!wd.open(dev, timeoutS)) {
    std::cerr << "watchdog: " << wd.error() << "\n";
    return 1;
  }
  std::cout << "watchdog: " << dev << " timeout " << wd.timeoutS() << " s" << std::endl;
  std::mutex stuck;
  std::thread control([&] {
    const int feeds = hang ? 3 : seconds;
    for (int i = 0; i < feeds; ++i) {
      wd.keepAlive();
      std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    if (hang) {
      std::cout << "watchdog: control thread hung after " << wd.keepAlives() << " keep-alives" << std::endl;
      stuck.lock();
      stuck.lock();  // a self-deadlock, as a hung control thread: no more keep-alives
    }
  });
  control.join();
  wd.closeClean();
  std::cout << "watchdog: " << wd.keepAlives() << " keep-alives over " << seconds << " s, closed clean"
            << std::endl;
  return 0;
}

int canRoundTrip(const std::string& iface) {
  auto openRaw = [&]() {
    const int s = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (s < 0) return -1;
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = static_cast<int>(if_nametoindex(iface.c_str()));
    if (addr.can_ifindex == 0 || ::bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
      ::close(s);
      return -1;
    }
    return s;
  };
  const int tx = openRaw(), rx = openRaw();
  if (tx < 0 || rx < 0) {
    std::cerr << "can: cannot open raw sockets on " << iface << ": " << std::strerror(errno) << "\n";
    return 1;
  }
  can_frame out{};
  out.can_id = 0x18FF50E5 | CAN_EFF_FLAG;  // an extended id, as J1939 uses
  out.len = 8;
  for (int i = 0; i < 8; ++i) out.data[i] = static_cast<unsigned char>(0x11 * (i + 1));
  if (::write(tx, &out, sizeof out) != static_cast<ssize_t>(sizeof out)) {
    std::cerr << "can: write: " << std::strerror(errno) << "\n";
    return 1;
  }
  can_frame in{};
  if (::read(rx, &in, sizeof in) != static_cast<ssize_t>(sizeof in)) {
    std::cerr << "can: read: " << std::strerror(errno) << "\n";
    return 1;
  }
  const bool same = in.can_id == out.can_id && in.len == out.len && std::memcmp(in.data, out.data, 8) == 0;
  std::printf("can: sent id %08x, received id %08x len %u: %s\n", out.can_id, in.can_id, in.len,
              same ? "same frame" : "DIFFERENT");
  return same ? 0 : 1;
}

int readyLine(const std::string& chip, int line) {
  xr::AdsReadyLine ready;
  if (!ready.open(chip, line)) {
    std::cerr << "ready: " << ready.error() << "\n";
    return 1;
  }
  long long stamp = 0;
  const int r = ready.wait(100'000'000, &stamp);
  std::cout << "ready: edge events requested on " << chip << " line " << line << ", wait without an edge -> "
            << r << std::endl;
  return r == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  if (cmd == "level" && argc == 4) {
    const int v = level(argv[2], static_cast<unsigned>(std::stoi(argv[3])));
    std::cout << v << std::endl;
    return v < 0 ? 1 : 0;
  }
  if (cmd == "hold" && argc == 4) return hold(argv[2], argv[3]);
  if (cmd == "watchdog" && argc == 5) return watchdog(argv[2], std::stoi(argv[3]), std::stoi(argv[4]), false);
  if (cmd == "watchdog-hang" && argc == 4) return watchdog(argv[2], std::stoi(argv[3]), 0, true);
  if (cmd == "pwm" && argc == 3) return xr::kernelrig::pwmCheck(argv[2]);
  if (cmd == "can" && argc == 3) return canRoundTrip(argv[2]);
  if (cmd == "ready" && argc == 4) return readyLine(argv[2], std::stoi(argv[3]));
  return usage();
}
