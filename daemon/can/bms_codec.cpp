// BMS CAN protocols: decoder and encoders (see bms_codec.h for the layouts).
#include "can/bms_codec.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "can/can_bytes.h"

namespace xr::can {
namespace {

std::span<const std::uint8_t> payload(const CanFrame& f) { return {f.data.data(), f.dlc}; }

CanFrame frame(std::uint32_t id, std::uint8_t dlc) {
  CanFrame f;
  f.id = id;
  f.dlc = dlc;
  return f;
}

std::int16_t toS16(double v, double scale) {
  return static_cast<std::int16_t>(std::clamp(std::lround(v / scale), -32768L, 32767L));
}
std::uint16_t toU16(double v, double scale) {
  return static_cast<std::uint16_t>(std::clamp(std::lround(v / scale), 0L, 65535L));
}

// 0x35A: (byte, bit pair) of each flag; the same layout for alarms (bytes
// 0-3) and warnings (bytes 4-7).
struct PairBit {
  std::uint32_t flag;
  int byte, shift;
};
constexpr PairBit k35A[] = {
    {bmswarn::HighVoltage, 0, 2},
    {bmswarn::LowVoltage, 0, 4},
    {bmswarn::HighTemp, 0, 6},
    {bmswarn::LowTemp, 1, 0},
    {bmswarn::HighTemp, 1, 2},
    {bmswarn::LowTemp, 1, 4},
    {bmswarn::HighDischargeCurrent, 1, 6},
    {bmswarn::HighChargeCurrent, 2, 0},
    {bmswarn::Internal, 2, 6},
    {bmswarn::CellImbalance, 3, 0},
};
// 0x359 (Pylontech): single bits; protection in bytes 0-1, warnings in 2-3.
struct Bit {
  std::uint32_t flag;
  int byte, bit;
};
constexpr Bit k359[] = {
    {bmswarn::HighVoltage, 0, 1}, {bmswarn::LowVoltage, 0, 2},           {bmswarn::HighTemp, 0, 3},
    {bmswarn::LowTemp, 0, 4},     {bmswarn::HighDischargeCurrent, 0, 7}, {bmswarn::HighChargeCurrent, 1, 0},
    {bmswarn::Internal, 1, 3},
};

std::uint32_t decode35A(std::span<const std::uint8_t> d, int base) {
  std::uint32_t flags = 0;
  for (const auto& p : k35A)
    if (((d[base + p.byte] >> p.shift) & 0x3) == 0x1) flags |= p.flag;
  return flags;
}
std::uint32_t decode359(std::span<const std::uint8_t> d, int base) {
  std::uint32_t flags = 0;
  for (const auto& b : k359)
    if ((d[base + b.byte] >> b.bit) & 1) flags |= b.flag;
  return flags;
}

}  // namespace

std::optional<BmsProtocol> parseBmsProtocol(std::string_view s) {
  if (s == "victron") return BmsProtocol::Victron;
  if (s == "pylontech") return BmsProtocol::Pylontech;
  if (s == "rec") return BmsProtocol::Rec;
  return std::nullopt;
}

std::string_view toString(BmsProtocol p) {
  switch (p) {
    case BmsProtocol::Victron:
      return "victron";
    case BmsProtocol::Pylontech:
      return "pylontech";
    case BmsProtocol::Rec:
      return "rec";
  }
  return "?";
}

BmsFrameResult BmsDecoder::reject(const CanFrame& f, BmsReject why) {
  ++rejected_;
  lastRejectedId_ = f.id;
  lastReject_ = why;
  return BmsFrameResult::Rejected;
}

// 0x355: SoC and SoH. REC: bytes 4-5 carry the SoC at 0.01 %; the finer
// value is used when it agrees with the whole percent (within its rounding).
BmsFrameResult BmsDecoder::feedSoc(const CanFrame& f) {
  if (f.dlc < 4) return reject(f, BmsReject::ShortDlc);
  const auto d = payload(f);
  const double soc = getU16(d, 0), soh = getU16(d, 2);
  if (soc > 100.0 || soh > 100.0) return reject(f, BmsReject::SocRange);
  double fine = soc;
  if (protocol_ == BmsProtocol::Rec && f.dlc >= 6) {
    fine = getU16(d, 4) * 0.01;
    if (fine > 100.0 || std::abs(fine - soc) > 1.0) return reject(f, BmsReject::SocRange);
  }
  limits_.socPct = fine;
  limits_.sohPct = soh;
  return BmsFrameResult::Accepted;
}

// 0x373 (REC only): the lowest and highest cell voltage and temperature.
BmsFrameResult BmsDecoder::feedCells(const CanFrame& f) {
  if (protocol_ != BmsProtocol::Rec) return BmsFrameResult::Ignored;
  if (f.dlc < 8) return reject(f, BmsReject::ShortDlc);
  const auto d = payload(f);
  const double vMin = getU16(d, 0) * 0.001, vMax = getU16(d, 2) * 0.001;
  const double tMin = getU16(d, 4) - 273.0, tMax = getU16(d, 6) - 273.0;
  if (vMin < kMinCellV || vMax > kMaxCellV || vMin > vMax) return reject(f, BmsReject::CellVoltageRange);
  if (tMin < kMinTempC || tMax > kMaxTempC || tMin > tMax) return reject(f, BmsReject::TempRange);
  limits_.cellMinV = vMin;
  limits_.cellMaxV = vMax;
  limits_.cellTempMinC = tMin;
  limits_.cellTempMaxC = tMax;
  return BmsFrameResult::Accepted;
}

BmsFrameResult BmsDecoder::feed(const CanFrame& f, TimeNs now) {
  if (f.error || f.extended) return BmsFrameResult::Ignored;
  const auto d = payload(f);
  switch (f.id) {
    case 0x351: {
      if (f.dlc < 6) return reject(f, BmsReject::ShortDlc);
      const double cvl = getU16(d, 0) * 0.1;
      const double ccl = getS16(d, 2) * 0.1;
      const double dcl = getS16(d, 4) * 0.1;
      if (cvl < kMinCvlV || cvl > kMaxCvlV) return reject(f, BmsReject::CvlRange);
      if (ccl < 0.0 || ccl > kMaxCclA) return reject(f, BmsReject::CclRange);
      if (dcl < 0.0 || dcl > kMaxCclA) return reject(f, BmsReject::DclRange);
      limits_.cvlV = cvl;
      limits_.cclA = ccl;
      limits_.dclA = dcl;
      limits_.stamp = now;
      break;
    }
    case 0x355:
      if (const auto r = feedSoc(f); r != BmsFrameResult::Accepted) return r;
      break;
    case 0x373:
      if (const auto r = feedCells(f); r != BmsFrameResult::Accepted) return r;
      break;
    case 0x356: {
      if (f.dlc < 6) return reject(f, BmsReject::ShortDlc);
      const double v = getS16(d, 0) * 0.01, i = getS16(d, 2) * 0.1, t = getS16(d, 4) * 0.1;
      if (v < 0.0 || v > 100.0) return reject(f, BmsReject::VoltageRange);
      if (t < kMinTempC || t > kMaxTempC) return reject(f, BmsReject::TempRange);
      limits_.voltageV = v;
      limits_.currentA = i;
      limits_.tempC = t;
      break;
    }
    case 0x35A:
      if (f.dlc < 8) return reject(f, BmsReject::ShortDlc);
      alarms35A_ = decode35A(d, 0);
      warnings35A_ = decode35A(d, 4);
      break;
    case 0x359:
      if (protocol_ != BmsProtocol::Pylontech) return BmsFrameResult::Ignored;
      if (f.dlc < 4) return reject(f, BmsReject::ShortDlc);
      alarms359_ = decode359(d, 0);
      warnings359_ = decode359(d, 2);
      break;
    case 0x35E: {
      name_.assign(reinterpret_cast<const char*>(f.data.data()), f.dlc);
      while (!name_.empty() && (name_.back() == ' ' || name_.back() == '\0')) name_.pop_back();
      break;
    }
    default:
      return BmsFrameResult::Ignored;
  }
  limits_.alarms = alarms35A_ | alarms359_;
  limits_.warnings = warnings35A_ | warnings359_;
  limits_.source = BmsSource::Can;
  // The SMA set has no charge-disable flag: CCL = 0 caps the battery current
  // at 0 and the alternator still serves the house. Pylontech's protection
  // flags mean the pack blocked charging: the field goes off.
  limits_.chargeAllowed = (alarms359_ & bmswarn::ChargeRampDown) == 0;
  ++accepted_;
  return BmsFrameResult::Accepted;
}

CanFrame encode351(double cvlV, double cclA, double dclA, double dvlV) {
  CanFrame f = frame(0x351, 8);
  putU16(f.data, 0, toU16(cvlV, 0.1));
  putS16(f.data, 2, toS16(cclA, 0.1));
  putS16(f.data, 4, toS16(dclA, 0.1));
  putU16(f.data, 6, toU16(dvlV, 0.1));
  return f;
}

CanFrame encode355(double socPct, double sohPct) {
  CanFrame f = frame(0x355, 4);
  putU16(f.data, 0, toU16(socPct, 1.0));
  putU16(f.data, 2, toU16(sohPct, 1.0));
  return f;
}

CanFrame encode355Rec(double socPct, double sohPct) {
  CanFrame f = encode355(socPct, sohPct);
  f.dlc = 6;
  putU16(f.data, 4, toU16(socPct, 0.01));
  return f;
}

CanFrame encode373(double cellMinV, double cellMaxV, double tempMinC, double tempMaxC) {
  CanFrame f = frame(0x373, 8);
  putU16(f.data, 0, toU16(cellMinV, 0.001));
  putU16(f.data, 2, toU16(cellMaxV, 0.001));
  // Kelvin as whole degrees over 273 (the encoding GX devices read).
  putU16(f.data, 4, toU16(tempMinC + 273.0, 1.0));
  putU16(f.data, 6, toU16(tempMaxC + 273.0, 1.0));
  return f;
}

CanFrame encode356(double voltageV, double currentA, double tempC) {
  CanFrame f = frame(0x356, 6);
  putS16(f.data, 0, toS16(voltageV, 0.01));
  putS16(f.data, 2, toS16(currentA, 0.1));
  putS16(f.data, 4, toS16(tempC, 0.1));
  return f;
}

CanFrame encode35A(std::uint32_t alarms, std::uint32_t warnings) {
  CanFrame f = frame(0x35A, 8);
  // Every known pair starts "normal" (10); a raised flag is 01.
  for (int base : {0, 4}) {
    const std::uint32_t flags = base == 0 ? alarms : warnings;
    for (const auto& p : k35A) {
      auto& byte = f.data[base + p.byte];
      const bool raised = (flags & p.flag) != 0;
      const bool already = ((byte >> p.shift) & 0x3) == 0x1;
      byte = static_cast<std::uint8_t>((byte & ~(0x3 << p.shift)) |
                                       ((raised || already ? 0x1 : 0x2) << p.shift));
    }
  }
  return f;
}

CanFrame encode359(std::uint32_t protection, std::uint32_t warnings) {
  CanFrame f = frame(0x359, 8);
  for (int base : {0, 2}) {
    const std::uint32_t flags = base == 0 ? protection : warnings;
    for (const auto& b : k359)
      if (flags & b.flag) f.data[base + b.byte] |= static_cast<std::uint8_t>(1u << b.bit);
  }
  f.data[4] = 1;  // module count
  f.data[5] = 'P';
  f.data[6] = 'N';
  return f;
}

CanFrame encode35E(std::string_view name) {
  CanFrame f = frame(0x35E, static_cast<std::uint8_t>(std::min<std::size_t>(name.size(), 8)));
  std::copy_n(name.begin(), f.dlc, f.data.begin());
  return f;
}

}  // namespace xr::can
