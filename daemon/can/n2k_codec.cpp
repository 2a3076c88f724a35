// NMEA 2000 codec (see n2k_codec.h for the layouts).
#include "can/n2k_codec.h"

#include <algorithm>
#include <cmath>

#include "can/can_bytes.h"

namespace xr::can {
namespace {

constexpr std::uint8_t kNa8 = 0xFF;
constexpr std::uint16_t kNa16 = 0xFFFF;

bool isPdu1(std::uint32_t pgn) { return ((pgn >> 8) & 0xFF) < 240; }

std::uint16_t u16Of(double v, double scale) {
  if (!std::isfinite(v)) return kNa16;
  return static_cast<std::uint16_t>(std::clamp(std::lround(v / scale), 0L, 0xFFFDL));
}
std::int16_t s16Of(double v, double scale) {
  if (!std::isfinite(v)) return 0x7FFF;
  return static_cast<std::int16_t>(std::clamp(std::lround(v / scale), -32767L, 32765L));
}
void putText(std::vector<std::uint8_t>& d, std::size_t at, std::size_t width, std::string_view s) {
  for (std::size_t i = 0; i < width; ++i) d[at + i] = i < s.size() ? static_cast<std::uint8_t>(s[i]) : ' ';
}

}  // namespace

N2kMessage blankMessage(std::uint32_t pgn, std::uint8_t priority, std::uint8_t source, std::size_t len) {
  N2kMessage m;
  m.id.pgn = pgn;
  m.id.priority = priority;
  m.id.source = source;
  m.data.assign(len, kNa8);
  return m;
}

std::uint32_t encodeN2kId(const N2kId& id) {
  std::uint32_t pgn = id.pgn & 0x3FFFF;
  if (isPdu1(pgn)) pgn = (pgn & 0x3FF00) | id.destination;
  return (static_cast<std::uint32_t>(id.priority & 0x7) << 26) | (pgn << 8) | id.source;
}

N2kId decodeN2kId(std::uint32_t canId) {
  N2kId id;
  id.priority = static_cast<std::uint8_t>((canId >> 26) & 0x7);
  id.source = static_cast<std::uint8_t>(canId & 0xFF);
  std::uint32_t pgn = (canId >> 8) & 0x3FFFF;
  if (isPdu1(pgn)) {
    id.destination = static_cast<std::uint8_t>(pgn & 0xFF);
    pgn &= 0x3FF00;
  }
  id.pgn = pgn;
  return id;
}

std::vector<CanFrame> toFrames(const N2kMessage& m, std::uint8_t sequence) {
  std::vector<CanFrame> out;
  auto start = [&]() -> CanFrame& {
    CanFrame f;
    f.id = encodeN2kId(m.id);
    f.extended = true;
    f.dlc = 8;
    f.data.fill(kNa8);
    out.push_back(f);
    return out.back();
  };
  if (m.data.size() <= 8) {
    CanFrame& f = start();
    f.dlc = static_cast<std::uint8_t>(m.data.size());
    std::copy(m.data.begin(), m.data.end(), f.data.begin());
    return out;
  }
  const std::uint8_t seq = static_cast<std::uint8_t>((sequence & 0x7) << 5);
  std::size_t at = 0;
  for (std::uint8_t frame = 0; at < m.data.size(); ++frame) {
    CanFrame& f = start();
    f.data[0] = static_cast<std::uint8_t>(seq | (frame & 0x1F));
    std::size_t slot = 1;
    if (frame == 0) f.data[slot++] = static_cast<std::uint8_t>(m.data.size());
    for (; slot < 8 && at < m.data.size(); ++slot) f.data[slot] = m.data[at++];
  }
  return out;
}

std::optional<N2kMessage> N2kAssembler::feed(const CanFrame& f) {
  if (!f.extended || f.error) return std::nullopt;
  N2kMessage m;
  m.id = decodeN2kId(f.id);
  if (std::find(fastPgns_.begin(), fastPgns_.end(), m.id.pgn) == fastPgns_.end()) {
    m.data.assign(f.data.begin(), f.data.begin() + f.dlc);
    return m;
  }
  if (f.dlc < 2) return std::nullopt;
  const std::uint32_t key = m.id.pgn << 8 | m.id.source;
  const std::uint8_t seq = f.data[0] >> 5, frame = f.data[0] & 0x1F;
  auto it = std::find_if(partial_.begin(), partial_.end(), [&](const Partial& p) { return p.key == key; });
  if (frame == 0) {
    if (it == partial_.end()) it = partial_.insert(partial_.end(), Partial{});
    it->key = key;
    it->sequence = seq;
    it->expected = f.data[1];
    it->nextFrame = 1;
    it->data.assign(f.data.begin() + 2, f.data.begin() + f.dlc);
  } else {
    // A frame out of order or of another sequence drops the partial message.
    if (it == partial_.end()) return std::nullopt;
    if (it->sequence != seq || it->nextFrame != frame) {
      partial_.erase(it);
      return std::nullopt;
    }
    it->data.insert(it->data.end(), f.data.begin() + 1, f.data.begin() + f.dlc);
    ++it->nextFrame;
  }
  if (it->data.size() < it->expected) return std::nullopt;
  it->data.resize(it->expected);
  m.data = std::move(it->data);
  partial_.erase(it);
  return m;
}

std::uint64_t encodeName(const N2kName& n) {
  std::uint64_t v = n.uniqueNumber & 0x1FFFFF;
  v |= static_cast<std::uint64_t>(n.manufacturerCode & 0x7FF) << 21;
  v |= static_cast<std::uint64_t>(n.deviceInstance) << 32;  // lower 3 then upper 5 bits: one byte
  v |= static_cast<std::uint64_t>(n.deviceFunction) << 40;
  v |= static_cast<std::uint64_t>(n.deviceClass & 0x7F) << 49;  // bit 48 reserved
  v |= static_cast<std::uint64_t>(n.systemInstance & 0xF) << 56;
  v |= static_cast<std::uint64_t>(n.industryGroup & 0x7) << 60;
  v |= static_cast<std::uint64_t>(n.arbitraryAddressCapable ? 1 : 0) << 63;
  return v;
}

N2kName decodeName(std::uint64_t v) {
  N2kName n;
  n.uniqueNumber = static_cast<std::uint32_t>(v & 0x1FFFFF);
  n.manufacturerCode = static_cast<std::uint16_t>((v >> 21) & 0x7FF);
  n.deviceInstance = static_cast<std::uint8_t>((v >> 32) & 0xFF);
  n.deviceFunction = static_cast<std::uint8_t>((v >> 40) & 0xFF);
  n.deviceClass = static_cast<std::uint8_t>((v >> 49) & 0x7F);
  n.systemInstance = static_cast<std::uint8_t>((v >> 56) & 0xF);
  n.industryGroup = static_cast<std::uint8_t>((v >> 60) & 0x7);
  n.arbitraryAddressCapable = (v >> 63) & 1;
  return n;
}

N2kMessage addressClaim(std::uint8_t source, const N2kName& name) {
  N2kMessage m = blankMessage(60928, 6, source, 8);
  const std::uint64_t v = encodeName(name);
  for (int i = 0; i < 8; ++i) m.data[i] = static_cast<std::uint8_t>(v >> (8 * i));
  return m;
}

N2kMessage heartbeat(std::uint8_t source, double intervalS, std::uint8_t sequence) {
  N2kMessage m = blankMessage(126993, 7, source, 8);
  putU16(m.data, 0, u16Of(intervalS, 0.01));
  m.data[2] = sequence;
  m.data[3] = 0xF0;  // controller 1/2 states 0 (error active), equipment status 0 (operational)
  return m;
}

N2kMessage productInformation(std::uint8_t source, std::uint16_t productCode, std::string_view model,
                              std::string_view software, std::string_view version, std::string_view serial) {
  N2kMessage m = blankMessage(126996, 6, source, 134);
  putU16(m.data, 0, 2100);  // NMEA 2000 database version 2.100
  putU16(m.data, 2, productCode);
  putText(m.data, 4, 32, model);
  putText(m.data, 36, 32, software);
  putText(m.data, 68, 32, version);
  putText(m.data, 100, 32, serial);
  m.data[132] = 1;  // certification level
  m.data[133] = 1;  // load equivalency (1 = 50 mA)
  return m;
}

N2kMessage dcDetailedStatus(std::uint8_t source, std::uint8_t sid, std::uint8_t instance, N2kDcType type,
                            double socPct, double sohPct) {
  N2kMessage m = blankMessage(127506, 6, source, 11);
  m.data[0] = sid;
  m.data[1] = instance;
  m.data[2] = static_cast<std::uint8_t>(type);
  m.data[3] =
      std::isfinite(socPct) ? static_cast<std::uint8_t>(std::clamp(std::lround(socPct), 0L, 100L)) : kNa8;
  m.data[4] =
      std::isfinite(sohPct) ? static_cast<std::uint8_t>(std::clamp(std::lround(sohPct), 0L, 100L)) : kNa8;
  // time remaining, ripple voltage, remaining capacity: not available (0xFF...)
  return m;
}

N2kMessage batteryStatus(std::uint8_t source, std::uint8_t instance, double voltageV, double currentA,
                         double tempC, std::uint8_t sid) {
  N2kMessage m = blankMessage(127508, 6, source, 8);
  m.data[0] = instance;
  putS16(m.data, 1, s16Of(voltageV, 0.01));
  putS16(m.data, 3, s16Of(currentA, 0.1));
  putU16(m.data, 5, std::isfinite(tempC) ? u16Of(tempC + 273.15, 0.01) : kNa16);
  m.data[7] = sid;
  return m;
}

N2kMessage converterStatus(std::uint8_t source, std::uint8_t sid, std::uint8_t connection,
                           N2kConverterState s) {
  N2kMessage m = blankMessage(127750, 6, source, 8);
  m.data[0] = sid;
  m.data[1] = connection;
  m.data[2] = static_cast<std::uint8_t>(s);
  m.data[3] = 0x00;  // temperature, overload, low DC voltage, ripple: all "good"
  return m;
}

N2kMessage dcVoltageCurrent(std::uint8_t source, std::uint8_t sid, std::uint8_t connection, double voltageV,
                            double currentA) {
  N2kMessage m = blankMessage(127751, 6, source, 8);
  m.data[0] = sid;
  m.data[1] = connection;
  putU16(m.data, 2, u16Of(voltageV, 0.1));
  const std::int32_t i =
      std::isfinite(currentA)
          ? static_cast<std::int32_t>(std::clamp(std::lround(currentA / 0.01), -8388607L, 8388605L))
          : 0x7FFFFF;
  m.data[4] = static_cast<std::uint8_t>(i & 0xFF);
  m.data[5] = static_cast<std::uint8_t>((i >> 8) & 0xFF);
  m.data[6] = static_cast<std::uint8_t>((i >> 16) & 0xFF);
  return m;
}

std::optional<EngineSpeed> decodeEngineSpeed(const N2kMessage& m) {
  if (m.id.pgn == 127488 && m.data.size() >= 3) {
    const std::uint16_t raw = getU16(m.data, 1);
    if (raw >= 0xFFFE) return std::nullopt;  // not available / error
    return EngineSpeed{m.data[0], raw * 0.25};
  }
  if (m.id.pgn == 61444 && m.data.size() >= 5) {
    const std::uint16_t raw = getU16(m.data, 3);
    if (raw >= 0xFB00) return std::nullopt;  // J1939: above 0xFAFF is error / not available
    return EngineSpeed{0, raw * 0.125};
  }
  return std::nullopt;
}

N2kMessage engineRapid(std::uint8_t source, std::uint8_t instance, double rpm) {
  N2kMessage m = blankMessage(127488, 2, source, 8);
  m.data[0] = instance;
  putU16(m.data, 1, u16Of(rpm, 0.25));
  return m;
}

}  // namespace xr::can
