#pragma once
// Our node on NMEA 2000 (docs/integrations.md), on the CAN service's thread:
//   start    ISO address claim (60928) at [can] n2k_preferred_address;
//            conflicts and requests for claims through N2kAddressClaimer
//   answers  a request (59904) for product information (126996)
//   sends    heartbeat 126993 every 60 s; 127506 DC detailed status,
//            127508 battery status, 127750 converter status and 127751 DC
//            voltage/current every 1.5 s (the default intervals in the
//            canboat PGN database), from the newest telemetry snapshot
// What goes in each field (docs/integrations.md "NMEA 2000"):
//   127508 / 127751 voltage   battery_v      127508 current  bcur_a
//   127751 current            alt_a          127506 SoC      soc_pct
//   127750 operating state    from the mode, field enable and stage
// Nothing is sent before an address is claimed, nor after we lost every one.
#include <array>
#include <cstdint>
#include <functional>
#include <string>

#include "can/n2k_address.h"
#include "can/n2k_codec.h"
#include "control/telemetry.h"
#include "drivers/hal/can_bus.h"
#include "runtime/handoffs.h"

namespace xr::canlink {

// The 127750 operating state for a telemetry snapshot.
can::N2kConverterState converterStateOf(const Telemetry& t);

class N2kNode {
 public:
  static constexpr double kHeartbeatS = 60.0, kStatusS = 1.5;
  // What the node hears that is not for it (engine speed, for RpmSource = n2k).
  using OnMessage = std::function<void(const can::N2kMessage&, TimeNs)>;

  N2kNode(CanBus& bus, std::uint8_t preferredAddress, const rt::Handoffs& h, std::string version);
  void onMessage(OnMessage f) { onMessage_ = std::move(f); }
  // Reads what is waiting, answers, and sends what is due at `now`.
  void poll(TimeNs now);
  std::uint8_t address() const { return claimer_.address(); }
  std::uint64_t errorFrames() const { return errorFrames_; }
  std::uint64_t txFrames() const { return txFrames_; }
  std::uint64_t rxFrames() const { return rxFrames_; }
  bool claimed() const { return claimer_.claimed(); }
  std::uint32_t lastErrorClass() const { return lastErrorClass_; }

 private:
  void send(const can::N2kMessage& m);
  void publish(TimeNs now);
  CanBus& bus_;
  can::N2kAddressClaimer claimer_;
  can::N2kAssembler assembler_;
  const rt::Handoffs& h_;
  std::string version_;
  OnMessage onMessage_;
  bool started_ = false;
  TimeNs nextHeartbeat_ = 0, nextStatus_ = 0;
  std::uint8_t sid_ = 0, heartbeatSeq_ = 0, fastSeq_ = 0;
  std::uint64_t sendFailures_ = 0, errorFrames_ = 0, txFrames_ = 0, rxFrames_ = 0;
  std::uint32_t lastErrorClass_ = 0;
};

}  // namespace xr::canlink
