// SocketCAN backend (see socketcan_bus.h).
#include "drivers/can/socketcan_bus.h"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace xr::can {

SocketCanBus::SocketCanBus(const std::string& interface, const std::vector<CanFilter>& filters) {
  auto fail = [&](const char* what) {
    const int e = errno;
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("CAN " + interface + ": " + what + ": " + std::strerror(e));
  };
  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC | SOCK_NONBLOCK, CAN_RAW);
  if (fd_ < 0) fail("socket(PF_CAN)");
  if (!filters.empty()) {
    std::vector<can_filter> kf;
    for (const auto& f : filters) {
      can_filter k{};
      k.can_id = f.extended ? (f.id & CAN_EFF_MASK) | CAN_EFF_FLAG : f.id & CAN_SFF_MASK;
      k.can_mask =
          (f.extended ? (f.mask & CAN_EFF_MASK) : (f.mask & CAN_SFF_MASK)) | CAN_EFF_FLAG | CAN_RTR_FLAG;
      kf.push_back(k);
    }
    if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, kf.data(),
                     static_cast<socklen_t>(kf.size() * sizeof(can_filter))) < 0)
      fail("CAN_RAW_FILTER");
  }
  const can_err_mask_t errMask = CAN_ERR_MASK;  // every error class, bus-off included
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errMask, sizeof errMask) < 0)
    fail("CAN_RAW_ERR_FILTER");
  const unsigned index = ::if_nametoindex(interface.c_str());
  if (index == 0) fail("no such interface");
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) fail("bind");
}

SocketCanBus::~SocketCanBus() {
  if (fd_ >= 0) ::close(fd_);
}

bool SocketCanBus::send(const CanFrame& f) noexcept {
  can_frame k{};
  k.can_id = f.extended ? (f.id & CAN_EFF_MASK) | CAN_EFF_FLAG : f.id & CAN_SFF_MASK;
  k.len = f.dlc > 8 ? 8 : f.dlc;
  std::memcpy(k.data, f.data.data(), k.len);
  if (::write(fd_, &k, sizeof k) != static_cast<ssize_t>(sizeof k)) {
    ++stats_.txErrors;  // ENOBUFS while the queue is full, ENETDOWN when bus-off
    return false;
  }
  ++stats_.tx;
  return true;
}

std::optional<CanFrame> SocketCanBus::receive(std::chrono::milliseconds timeout) noexcept {
  pollfd p{fd_, POLLIN, 0};
  const int ms = static_cast<int>(timeout.count());
  if (::poll(&p, 1, ms < 0 ? 0 : ms) <= 0) return std::nullopt;
  can_frame k{};
  if (::read(fd_, &k, sizeof k) != static_cast<ssize_t>(sizeof k)) return std::nullopt;
  CanFrame f;
  f.error = (k.can_id & CAN_ERR_FLAG) != 0;
  f.extended = (k.can_id & CAN_EFF_FLAG) != 0 || f.error;
  f.id = f.error      ? (k.can_id & CAN_ERR_MASK)
         : f.extended ? (k.can_id & CAN_EFF_MASK)
                      : (k.can_id & CAN_SFF_MASK);
  f.dlc = k.len > 8 ? 8 : k.len;
  std::memcpy(f.data.data(), k.data, f.dlc);
  ++stats_.rx;
  if (f.error) {
    ++stats_.errorFrames;
    if (f.id & CAN_ERR_BUSOFF) ++stats_.busOff;
  }
  return f;
}

}  // namespace xr::can
