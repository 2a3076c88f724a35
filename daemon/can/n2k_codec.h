#pragma once
// NMEA 2000 (250 kbit/s, 29-bit identifiers, ISO 11783 / J1939 transport),
// both directions, with no I/O. Field layouts follow the public canboat PGN
// database (canboat/canboat, pgns.json), which is also what the ctest's
// independent decoder (canboatjs) reads.
//
//   60928  ISO Address Claim: the 64-bit NAME
//   126993 Heartbeat: transmit interval u16 0.01 s, sequence counter u8
//   126996 Product Information (fast packet, 134 bytes)
//   127488 Engine Parameters, Rapid Update: instance u8, speed u16 0.25 rpm
//   61444  J1939 EEC1: engine speed bytes 3-4, u16 0.125 rpm
//   127506 DC Detailed Status (fast packet): SID, instance, DC type, SoC, SoH,
//          time remaining, ripple, remaining capacity
//   127508 Battery Status: instance, voltage s16 0.01 V, current s16 0.1 A,
//          temperature u16 0.01 K, SID
//   127750 Converter Status: SID, connection, operating state, temperature,
//          overload, low DC voltage, ripple states
//   127751 DC Voltage/Current: SID, connection, voltage u16 0.1 V, current
//          s24 0.01 A
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "drivers/hal/can_bus.h"

namespace xr::can {

// The 29-bit identifier: priority (3), PGN (18; PDU1 PGNs carry the
// destination in their low byte), source address (8).
struct N2kId {
  std::uint8_t priority = 6;
  std::uint32_t pgn = 0;
  std::uint8_t source = 0;
  std::uint8_t destination = 0xFF;  // PDU1 only (PF < 240); 255 = global
};
std::uint32_t encodeN2kId(const N2kId& id);
N2kId decodeN2kId(std::uint32_t canId);

// A whole NMEA 2000 message (any length; > 8 bytes goes as fast packet).
struct N2kMessage {
  N2kId id;
  std::vector<std::uint8_t> data;
};

// A message of `len` bytes, every one 0xFF ("not available"), to fill in.
N2kMessage blankMessage(std::uint32_t pgn, std::uint8_t priority, std::uint8_t source, std::size_t len);

// Frames of one message: a single frame up to 8 bytes, else fast packet
// (frame 0: sequence/counter, total length, 6 bytes; then 7 a frame).
// `sequence` (0..7) tells consecutive fast-packet messages of one PGN apart.
std::vector<CanFrame> toFrames(const N2kMessage& m, std::uint8_t sequence);

// Reassembles fast packets of the PGNs in `fastPgns`; single frames pass.
class N2kAssembler {
 public:
  explicit N2kAssembler(std::span<const std::uint32_t> fastPgns)
      : fastPgns_(fastPgns.begin(), fastPgns.end()) {}
  std::optional<N2kMessage> feed(const CanFrame& f);

 private:
  struct Partial {
    std::uint32_t key = 0;  // pgn << 8 | source
    std::uint8_t sequence = 0, expected = 0, nextFrame = 0;
    std::vector<std::uint8_t> data;
  };
  std::vector<std::uint32_t> fastPgns_;
  std::vector<Partial> partial_;
};

// ISO 11783-5 NAME fields.
struct N2kName {
  std::uint32_t uniqueNumber = 0;      // 21 bits
  std::uint16_t manufacturerCode = 0;  // 11 bits
  std::uint8_t deviceInstance = 0;     // 8 bits (lower 3 + upper 5)
  std::uint8_t deviceFunction = 0;     // 8 bits
  std::uint8_t deviceClass = 0;        // 7 bits
  std::uint8_t systemInstance = 0;     // 4 bits
  std::uint8_t industryGroup = 4;      // 3 bits; 4 = marine
  bool arbitraryAddressCapable = true;
};
std::uint64_t encodeName(const N2kName& n);
N2kName decodeName(std::uint64_t v);

// Operating states of 127750 (canboat's CONVERTER_STATE).
enum class N2kConverterState : std::uint8_t {
  Off = 0,
  LowPower = 1,
  Fault = 2,
  Bulk = 3,
  Absorption = 4,
  Float = 5
};
// DC types of 127506 (canboat's DC_SOURCE).
enum class N2kDcType : std::uint8_t { Battery = 0, Alternator = 1 };

N2kMessage addressClaim(std::uint8_t source, const N2kName& name);
N2kMessage heartbeat(std::uint8_t source, double intervalS, std::uint8_t sequence);
N2kMessage productInformation(std::uint8_t source, std::uint16_t productCode, std::string_view model,
                              std::string_view software, std::string_view version, std::string_view serial);
N2kMessage dcDetailedStatus(std::uint8_t source, std::uint8_t sid, std::uint8_t instance, N2kDcType type,
                            double socPct, double sohPct);
N2kMessage batteryStatus(std::uint8_t source, std::uint8_t instance, double voltageV, double currentA,
                         double tempC, std::uint8_t sid);
N2kMessage converterStatus(std::uint8_t source, std::uint8_t sid, std::uint8_t connection,
                           N2kConverterState s);
N2kMessage dcVoltageCurrent(std::uint8_t source, std::uint8_t sid, std::uint8_t connection, double voltageV,
                            double currentA);

// Engine speed from 127488 (Engine Parameters, Rapid) or J1939 PGN 61444
// (EEC1); nullopt for other PGNs or "not available".
struct EngineSpeed {
  std::uint8_t instance = 0;
  double rpm = 0.0;
};
std::optional<EngineSpeed> decodeEngineSpeed(const N2kMessage& m);
N2kMessage engineRapid(std::uint8_t source, std::uint8_t instance, double rpm);  // the simulated ECU

}  // namespace xr::can
