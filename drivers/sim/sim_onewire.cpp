#include "drivers/sim/sim_onewire.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <string>
#include <system_error>

namespace xr::sim {
namespace fs = std::filesystem;

namespace {
constexpr TimeNs kConversion = fromMs(750);  // 12-bit conversion time
}

SimOneWire::SimOneWire(fs::path root, std::string id) : root_(std::move(root)), id_(std::move(id)) {
  std::error_code ec;
  fs::create_directories(root_ / id_, ec);
}

SimOneWire::~SimOneWire() { closeFile(); }

std::uint8_t SimOneWire::crc8(const std::uint8_t* p, std::size_t n) {
  // Dallas/Maxim CRC8: x^8 + x^5 + x^4 + 1, LSB first (reflected 0x8C).
  std::uint8_t crc = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t b = p[i];
    for (int k = 0; k < 8; ++k) {
      const bool mix = (crc ^ b) & 1;
      crc >>= 1;
      if (mix) crc ^= 0x8C;
      b >>= 1;
    }
  }
  return crc;
}

std::string SimOneWire::formatW1Slave(std::int16_t raw, bool corrupt) {
  std::uint8_t sp[9] = {
      std::uint8_t(raw & 0xFF), std::uint8_t((raw >> 8) & 0xFF), 0x4B, 0x46, 0x7F, 0xFF, 0x0C, 0x10, 0};
  const std::uint8_t crc = crc8(sp, 8);
  sp[8] = corrupt ? std::uint8_t(crc ^ 0x5A) : crc;
  // Formatted by hand (what "%02x " x 9, ": crc=%02x YES|NO" and "t=%d"
  // give; the unit test holds it to snprintf): one string, no printf parsing.
  static constexpr char kHex[] = "0123456789abcdef";
  char bytes[27];
  for (int i = 0; i < 9; ++i) {
    bytes[3 * i] = kHex[sp[i] >> 4];
    bytes[3 * i + 1] = kHex[sp[i] & 15];
    bytes[3 * i + 2] = ' ';
  }
  // The kernel computes t= from the 16-bit reading: raw * 1000 / 16 (C division).
  const int milli = int(raw) * 1000 / 16;
  std::string out;
  out.reserve(96);
  out.append(bytes, sizeof bytes);
  out += ": crc=";
  out += kHex[crc >> 4];
  out += kHex[crc & 15];
  out += sp[8] == crc ? " YES\n" : " NO\n";
  out.append(bytes, sizeof bytes);
  out += "t=";
  out += std::to_string(milli);
  out += '\n';
  return out;
}

void SimOneWire::openFile() {
  std::error_code ec;
  fs::create_directories(root_ / id_, ec);  // first write, or after a reconnect
  if (slavePath_.empty()) slavePath_ = slavePath().string();
  fd_ = ::open(slavePath_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  size_ = 0;
  if (fd_ < 0) return;
  // The file's page, shared with the page cache that the reader's pread
  // copies from: a new reading is a memcpy instead of a system call.
  void* m = ::mmap(nullptr, kMapBytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
  map_ = m == MAP_FAILED ? nullptr : static_cast<char*>(m);
}

void SimOneWire::writeFile(const std::string& content) {
  ++writes_;
  if (fd_ < 0) openFile();
  if (fd_ < 0) return;
  if (map_ != nullptr && content.size() <= kMapBytes) {
    // The size first: a shorter file must not keep the old tail, and the
    // mapping may only be touched below the end of the file.
    if (content.size() != size_ && ::ftruncate(fd_, off_t(content.size())) != 0) {
      closeFile();
      return;
    }
    std::memcpy(map_, content.data(), content.size());
    size_ = content.size();
    return;
  }
  // No mapping: write the bytes, then cut what is left of a longer reading.
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::pwrite(fd_, content.data() + done, content.size() - done, off_t(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += std::size_t(n);
  }
  if (done < size_ && ::ftruncate(fd_, off_t(done)) != 0) {
    closeFile();
    return;
  }
  size_ = done;
}

void SimOneWire::closeFile() noexcept {
  if (map_ != nullptr) ::munmap(map_, kMapBytes);
  map_ = nullptr;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void SimOneWire::setPresent(bool present) {
  if (present == present_) return;
  present_ = present;
  std::error_code ec;
  if (!present) {
    if (fd_ >= 0) {
      const int rc = ::ftruncate(fd_, 0);  // a reader holding it open reads nothing
      (void)rc;                            // the unlink below follows either way
    }
    closeFile();
    fs::remove_all(root_ / id_, ec);
    written_ = false;
  } else {
    nextConversion_ = 0;  // a fresh file at the next update
  }
}

void SimOneWire::update(TimeNs t, double tempC) {
  if (!present_ || t < nextConversion_) return;
  nextConversion_ = t + kConversion;
  double r = std::nearbyint(tempC * 16.0);
  if (!(r == r)) r = 85.0 * 16.0;  // power-on value when nothing sensible converted
  r = std::fmax(-55.0 * 16.0, std::fmin(125.0 * 16.0, r));
  const auto raw = static_cast<std::int16_t>(r);
  if (written_ && raw == lastRaw_ && corrupt_ == lastCorrupt_) return;
  writeFile(formatW1Slave(raw, corrupt_));
  written_ = true;
  lastRaw_ = raw;
  lastCorrupt_ = corrupt_;
}

}  // namespace xr::sim
