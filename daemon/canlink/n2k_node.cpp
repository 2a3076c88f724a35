// Our NMEA 2000 node (see n2k_node.h).
#include "canlink/n2k_node.h"

#include <cmath>

namespace xr::canlink {
namespace {

// Fast-packet PGNs we reassemble on receipt (none we act on today beyond
// single frames, but a claim or request may follow one on the bus).
constexpr std::uint32_t kFastPgns[] = {126996, 127506, 129029};

// Our NAME: marine industry group, device class 35 "Electrical Generation",
// function 141 "DC Generator/Alternator" (canboat's DEVICE_CLASS and
// DEVICE_FUNCTION lookups), manufacturer code 2047 (the largest, assigned
// to nobody: we are not an NMEA member).
can::N2kName ourName() {
  can::N2kName n;
  n.uniqueNumber = 0x1A2E0;
  n.manufacturerCode = 2047;
  n.deviceFunction = 141;
  n.deviceClass = 35;
  n.industryGroup = 4;
  n.arbitraryAddressCapable = true;
  return n;
}

constexpr std::uint16_t kProductCode = 2201;  // ours; any value is allowed for an unregistered maker

}  // namespace

can::N2kConverterState converterStateOf(const Telemetry& t) {
  switch (t.mode) {
    case FieldControlMode::MODE_CRITICAL_RAMP:
    case FieldControlMode::MODE_WARNING_RAMP_AND_LOCKOUT:
    case FieldControlMode::MODE_LOCKOUT_RAMP:
      return can::N2kConverterState::Fault;
    case FieldControlMode::MODE_DISABLED_RAMP:
      return can::N2kConverterState::Off;
    default:
      break;
  }
  if (!t.field_enable) return can::N2kConverterState::Off;
  switch (t.stage) {
    case ChargeStage::BULK:
      return can::N2kConverterState::Bulk;
    case ChargeStage::ABSORPTION:
      return can::N2kConverterState::Absorption;
    case ChargeStage::FLOAT:
      return can::N2kConverterState::Float;
    default:
      return can::N2kConverterState::Off;
  }
}

N2kNode::N2kNode(CanBus& bus, std::uint8_t preferredAddress, const rt::Handoffs& h, std::string version)
    : bus_(bus),
      claimer_(ourName(), preferredAddress),
      assembler_(kFastPgns),
      h_(h),
      version_(std::move(version)) {}

void N2kNode::send(const can::N2kMessage& m) {
  const bool fast = m.data.size() > 8;
  for (const CanFrame& f : can::toFrames(m, fastSeq_))
    if (!bus_.send(f))
      ++sendFailures_;
    else
      ++txFrames_;
  if (fast) fastSeq_ = static_cast<std::uint8_t>((fastSeq_ + 1) & 0x7);
}

void N2kNode::poll(TimeNs now) {
  if (!started_) {
    started_ = true;
    send(claimer_.start());
    // ISO 11783-5: wait 250 ms for a contending claim before sending data.
    nextHeartbeat_ = nextStatus_ = now + fromMs(250);
  }
  while (auto f = bus_.receive(std::chrono::milliseconds(0))) {
    ++rxFrames_;
    if (f->error) {
      ++errorFrames_;
      lastErrorClass_ = f->id;
      continue;
    }
    if (!f->extended) continue;
    auto m = assembler_.feed(*f);
    if (!m) continue;
    if (auto answer = claimer_.onMessage(*m)) send(*answer);
    if (m->id.pgn == 59904 && m->data.size() >= 3 && claimer_.claimed() &&
        (m->id.destination == 0xFF || m->id.destination == claimer_.address())) {
      const std::uint32_t asked = m->data[0] | (m->data[1] << 8) | (m->data[2] << 16);
      if (asked == 126996)
        send(can::productInformation(claimer_.address(), kProductCode, "xregulator", version_, version_, ""));
    }
    if (onMessage_) onMessage_(*m, now);
  }
  if (claimer_.claimed()) publish(now);
}

void N2kNode::publish(TimeNs now) {
  const std::uint8_t src = claimer_.address();
  if (now >= nextHeartbeat_) {
    nextHeartbeat_ = now + fromSec(kHeartbeatS);
    send(can::heartbeat(src, kHeartbeatS, heartbeatSeq_++));
  }
  if (now < nextStatus_) return;
  nextStatus_ = now + fromSec(kStatusS);
  const rt::RuntimeSnapshot s = h_.latest();
  if (s.tick == 0) return;  // no telemetry yet
  const Telemetry& t = s.telemetry;
  const std::uint8_t sid = sid_;
  sid_ = static_cast<std::uint8_t>((sid_ + 1) % 253);  // 253..255 mean "no SID"
  send(can::dcDetailedStatus(src, sid, 0, can::N2kDcType::Battery, socShown(t).pct, kBmsNoValue));
  send(can::batteryStatus(src, 0, t.battery_v, t.bcur_a, t.battery_temp_c, sid));
  send(can::converterStatus(src, sid, 0, converterStateOf(t)));
  send(can::dcVoltageCurrent(src, sid, 0, t.battery_v, t.alt_a));
}

}  // namespace xr::canlink
