#pragma once
// The BMS CAN protocols (500 kbit/s, 11-bit identifiers), both directions,
// with no I/O: BmsDecoder turns received frames into BmsLimits; the encode*
// functions build the frames a BMS sends (the simulator's BMS and the tests).
//
// The SMA / Victron "CAN-bus BMS" set (most LFP BMSs, Victron GX relays):
//   0x351 CVL u16 0.1 V, CCL s16 0.1 A, DCL s16 0.1 A, DVL u16 0.1 V
//   0x355 SoC u16 1 %, SoH u16 1 %
//   0x356 voltage s16 0.01 V, current s16 0.1 A, temperature s16 0.1 degC
//   0x35A alarms (bytes 0-3) and warnings (bytes 4-7), two bits per flag,
//         01 = raised, 10 = normal: byte 0 bits 2-3 high voltage, 4-5 low
//         voltage, 6-7 high temperature; byte 1 bits 0-1 low temperature,
//         2-3 high charge temperature, 4-5 low charge temperature, 6-7 high
//         discharge current; byte 2 bits 0-1 high charge current, 6-7 BMS
//         internal; byte 3 bits 0-1 cell imbalance
//   0x35E manufacturer name, ASCII
// Pylontech adds 0x359: protection flags (bytes 0-1) and warnings (2-3):
//   byte 0/2 bit 1 high voltage, bit 2 low voltage, bit 3 high temperature,
//   bit 4 low temperature, bit 7 discharge over-current; byte 1/3 bit 0
//   charge over-current, bit 3 system error.
// REC (REC Q / ABMS "Victron" firmware) sends the same set and adds, among
// ids it lists (0x35F, 0x370, 0x374-0x377, 0x379, 0x380: names, ids of the
// extreme cells, capacity, serial: ignored here):
//   0x355 bytes 4-5: SoC u16 0.01 % (the high-resolution SoC)
//   0x373 lowest cell u16 1 mV, highest cell u16 1 mV, lowest cell
//         temperature u16 1 K, highest cell temperature u16 1 K
// Sources: docs/integrations.md "CAN" (docs/sources.md P3.10.2 for 0x351); REC:
// the id list of REC's "UserManual_REC_Victron_BMS" and a candump of a REC Q
// published by its owner (github.com/natecostello/van_two_point_oh,
// blog/2021-4-8, which also decodes 0x355 bytes 4-5 and 0x373 in
// natecostello/REC-BMS_CAN); 0x373's units (mV, and kelvin as 273 + degC)
// as the diyBMS controller firmware encodes them for Victron GX devices
// (stuartpittaway/diyBMSv4ESP32, victron_canbus.cpp, victron_message_373).
//
// Bad frames (short DLC, values out of range, e.g. a CCL of 6 000 A) are
// counted and dropped whole: they never reach the limits.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/bms_limits.h"
#include "drivers/hal/can_bus.h"

namespace xr::can {

enum class BmsProtocol { Victron, Pylontech, Rec };
std::optional<BmsProtocol> parseBmsProtocol(std::string_view s);
std::string_view toString(BmsProtocol p);
// The names parseBmsProtocol() accepts, for error messages.
inline constexpr std::string_view kBmsProtocolNames = "victron, pylontech, rec";

enum class BmsFrameResult { Ignored, Accepted, Rejected };

// Plausibility bounds of a decoded value (beyond them the frame is rejected).
inline constexpr double kMaxCvlV = 70.0;  // 48 V class packs charge to ~58 V
inline constexpr double kMinCvlV = 8.0;
inline constexpr double kMaxCclA = 2000.0;  // MaximumAllowedBatteryAmps' own ceiling
inline constexpr double kMinTempC = -40.0, kMaxTempC = 100.0;
// A cell reading is decoded when a BMS could send it: one set up for another
// cell count reads the pack over the wrong count (4 cells on a 48 V bank:
// ~13 V "cells"). Whether it fits the bank is BmsPlausibility's call (it
// tells the owner), not the decoder's: a dropped frame says nothing.
inline constexpr double kMinCellV = 0.5, kMaxCellV = 16.0;

class BmsDecoder {
 public:
  explicit BmsDecoder(BmsProtocol p) : protocol_(p) {}

  // One received frame at `now`. Accepted frames update limits(); a 0x351
  // also moves its stamp (the staleness clock).
  BmsFrameResult feed(const CanFrame& f, TimeNs now);

  const BmsLimits& limits() const { return limits_; }
  const std::string& name() const { return name_; }
  std::uint64_t accepted() const { return accepted_; }
  std::uint64_t rejected() const { return rejected_; }
  // What the last rejected frame was (for the rate-limited event).
  std::uint32_t lastRejectedId() const { return lastRejectedId_; }
  BmsReject lastReject() const { return lastReject_; }
  std::string_view lastRejectWhy() const { return bmsRejectText(lastReject_); }

 private:
  BmsFrameResult reject(const CanFrame& f, BmsReject why);
  BmsFrameResult feedSoc(const CanFrame& f);
  BmsFrameResult feedCells(const CanFrame& f);
  BmsProtocol protocol_;
  BmsLimits limits_;
  std::uint32_t alarms35A_ = 0, warnings35A_ = 0, alarms359_ = 0, warnings359_ = 0;
  std::string name_;
  std::uint64_t accepted_ = 0, rejected_ = 0;
  std::uint32_t lastRejectedId_ = 0;
  BmsReject lastReject_ = BmsReject::None;
};

// ---- encoders (what a BMS sends) ---------------------------------------
CanFrame encode351(double cvlV, double cclA, double dclA, double dvlV);
CanFrame encode355(double socPct, double sohPct);
// REC's 0x355: the SoC again at 0.01 % in bytes 4-5 (DLC 6).
CanFrame encode355Rec(double socPct, double sohPct);
// REC's 0x373: cell voltage extremes (V) and cell temperature extremes (degC).
CanFrame encode373(double cellMinV, double cellMaxV, double tempMinC, double tempMaxC);
CanFrame encode356(double voltageV, double currentA, double tempC);
CanFrame encode35A(std::uint32_t alarms, std::uint32_t warnings);      // bmswarn flags
CanFrame encode359(std::uint32_t protection, std::uint32_t warnings);  // bmswarn flags
CanFrame encode35E(std::string_view name);

}  // namespace xr::can
