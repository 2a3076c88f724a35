// The CAN service on a board (see can_wiring.h).
#include "app/can_wiring.h"

#include <spdlog/spdlog.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "app/store_service.h"
#include "app/thread_names.h"
#include "drivers/can/socketcan_bus.h"

namespace xr::app {

std::unique_ptr<std::ofstream> openCanLog(const std::string& path) {
  errno = 0;
  auto f = std::make_unique<std::ofstream>(path, std::ios::out | std::ios::trunc);
  // libstdc++ opens with open(2): errno says why.
  if (!*f)
    throw std::runtime_error("cannot create CAN log " + path + ": " +
                             (errno ? std::strerror(errno) : "unknown error"));
  return f;
}

CanThread::CanThread(const Settings& s, rt::Handoffs& h, Clock& clock, std::unique_ptr<std::ofstream> log)
    : clock_(clock),
      log_(std::move(log)),
      service_(h, [](const std::string& what) { spdlog::warn("{}", what); }) {
  if (log_) {
    // candump -l stamps lines with the time of day; so do we on a board.
    sink_ =
        std::make_unique<can::CandumpSink>(*log_, [] { return static_cast<double>(unixMsNow()) / 1000.0; });
    service_.setLog(sink_.get());
  }
  if (!s.can.bms_interface.empty()) {
    const std::string iface = s.can.bms_interface;
    // The BMS set only (0x351-0x35F): the kernel drops the rest.
    auto open = [iface]() -> std::unique_ptr<CanBus> {
      return std::make_unique<can::SocketCanBus>(iface, std::vector<can::CanFilter>{{0x350, 0x7F0, false}});
    };
    service_.setBmsBus(
        std::make_unique<canlink::BusSlot>(
            iface, open,
            [](const std::string& what) {
              spdlog::error("{}: the BMS limits go stale; the regulator runs on the fallback cap meanwhile",
                            what);
            }),
        can::parseBmsProtocol(s.can.bms_protocol).value_or(can::BmsProtocol::Victron),
        s.hardware.battery_temp_sensor
            .empty());  // the BMS's 0x356 temperature, unless a DS18B20 is on the bank
    if (h.acceptedParams().BmsLimitsEnabled)
      spdlog::info("bms: following the {} BMS on {} (its limits are stale after BmsStaleS without a frame)",
                   s.can.bms_protocol, iface);
    else
      spdlog::warn(
          "bms: monitor only (BmsLimitsEnabled = 0): the {} BMS on {} is read and shown, not followed",
          s.can.bms_protocol, iface);
  }
  if (!s.can.n2k_interface.empty()) {
    const std::string iface = s.can.n2k_interface;
    auto open = [iface]() -> std::unique_ptr<CanBus> { return std::make_unique<can::SocketCanBus>(iface); };
    service_.setN2kBus(
        std::make_unique<canlink::BusSlot>(
            iface, open, [](const std::string& what) { spdlog::error("{}: no NMEA 2000 output", what); }),
        static_cast<std::uint8_t>(s.can.n2k_preferred_address), XR_VERSION_STRING);
  }
  thread_ = std::thread([this] { run(); });
}

CanThread::~CanThread() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (log_) log_->flush();
}

void CanThread::run() {
  nameThisThread("xr-can");
  const auto period = std::chrono::duration<double>(canlink::CanService::kPollPeriodS);
  while (!stop_) {
    service_.poll(clock_.now());
    std::this_thread::sleep_for(period);
  }
}

std::unique_ptr<CanThread> startCanThread(const Settings& s, rt::Handoffs& h, Clock& clock,
                                          std::unique_ptr<std::ofstream> canLog) {
  if (s.can.bms_interface.empty() && s.can.n2k_interface.empty() && !canLog) return nullptr;
  return std::make_unique<CanThread>(s, h, clock, std::move(canLog));
}

}  // namespace xr::app
