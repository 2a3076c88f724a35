// Pairing codes and per-device write tokens (pairing.h).
#include "web/server/pairing.h"

#include <openssl/evp.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>

#include "web/server/auth.h"
#include "web/server/web_server.h"

namespace xr::web {

std::string sha256Hex(std::string_view text) {
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (EVP_Digest(text.data(), text.size(), md, &len, EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("SHA-256 failed");
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(2 * len);
  for (unsigned int i = 0; i < len; ++i) {
    out.push_back(kHex[md[i] >> 4]);
    out.push_back(kHex[md[i] & 15]);
  }
  return out;
}

std::string randomDigits(int digits) {
  std::ifstream in("/dev/urandom", std::ios::binary);
  std::string out;
  while (static_cast<int>(out.size()) < digits) {
    unsigned char b = 0;
    if (!in.read(reinterpret_cast<char*>(&b), 1)) throw std::runtime_error("cannot read /dev/urandom");
    if (b < 250) out.push_back(static_cast<char>('0' + b % 10));  // 250 = 25 * 10: no bias
  }
  return out;
}

std::string cleanDeviceName(std::string_view name) {
  std::string out;
  for (char c : name) {
    if (out.size() >= kMaxDeviceNameLength) break;
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f && c != '"' && c != '\\') out.push_back(c);
  }
  return out.empty() ? "device" : out;
}

std::vector<PairedDevice> MemoryAuthStore::loadDevices() {
  std::lock_guard lock(m_);
  return devices_;
}

bool MemoryAuthStore::saveDevice(const PairedDevice& d) {
  std::lock_guard lock(m_);
  devices_.push_back(d);
  return true;
}

bool MemoryAuthStore::removeDevice(const std::string& id) {
  std::lock_guard lock(m_);
  return std::erase_if(devices_, [&](const PairedDevice& d) { return d.id == id; }) > 0;
}

Pairing::Pairing(std::shared_ptr<AuthStore> store, Clock wall, Clock elapsed)
    : store_(store ? std::move(store) : std::make_shared<MemoryAuthStore>()),
      clock_(std::move(wall)),
      elapsedClock_(elapsed ? std::move(elapsed) : clock_) {
  devices_ = store_->loadDevices();
}

std::int64_t Pairing::elapsed() const {
  if (elapsedClock_) return elapsedClock_();
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::int64_t Pairing::now() const {
  if (clock_) return clock_();
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

Pairing::Code Pairing::newCode() {
  Code c{randomDigits(6), now() + kCodeLifetimeMs};
  const std::int64_t t = elapsed();
  std::lock_guard lock(m_);
  codeHash_ = sha256Hex(c.code);
  codeExpiresMs_ = t + kCodeLifetimeMs;
  wrongTries_ = 0;
  lockedUntilMs_ = 0;
  return c;
}

Pairing::Code Pairing::newQrCode(std::string_view by) {
  Code c{generateToken().substr(0, kQrCodeLength), now() + kCodeLifetimeMs};
  const std::int64_t t = elapsed();
  std::lock_guard lock(m_);
  qrHash_ = sha256Hex(c.code);
  qrExpiresMs_ = t + kCodeLifetimeMs;
  qrMadeBy_ = by;
  wrongTries_ = 0;
  lockedUntilMs_ = 0;
  return c;
}

Pairing::Outcome Pairing::pair(std::string_view code, std::string_view name) {
  Outcome out;
  const std::int64_t t = elapsed();
  const std::int64_t wallNow = now();
  std::lock_guard lock(m_);
  if (t < lockedUntilMs_) {
    out.kind = Outcome::LockedOut;
    out.retryAfterMs = lockedUntilMs_ - t;
    return out;
  }
  // Which code this is by its length: 6 digits typed, or the QR code's 32.
  const bool qr = code.size() == kQrCodeLength;
  const std::string& hash = qr ? qrHash_ : codeHash_;
  const bool valid = !hash.empty() && t < (qr ? qrExpiresMs_ : codeExpiresMs_);
  if (!valid || !constantTimeEquals(sha256Hex(code), hash)) {
    // An expired or absent code counts too: otherwise a guesser could probe
    // freely while no code is in force and learn nothing, but still load us.
    if (++wrongTries_ >= kMaxWrongTries) {
      codeHash_.clear();  // burnt: the owner makes a new one
      qrHash_.clear();
      wrongTries_ = 0;
      lockedUntilMs_ = t + kLockoutMs;
      out.kind = Outcome::LockedOut;
      out.retryAfterMs = kLockoutMs;
      return out;
    }
    out.kind = Outcome::WrongCode;
    out.triesLeft = kMaxWrongTries - wrongTries_;
    return out;
  }
  addDeviceLocked(name, wallNow, out);
  if (out.kind == Outcome::Paired) {
    (qr ? qrHash_ : codeHash_).clear();  // single use
    if (qr) out.qrMadeBy = qrMadeBy_;
    wrongTries_ = 0;
  }
  return out;
}

void Pairing::addDeviceLocked(std::string_view name, std::int64_t wallNow, Outcome& out) {
  if (devices_.size() >= kMaxPairedDevices) {
    out.kind = Outcome::Full;
    return;
  }
  const std::string token = generateToken();
  PairedDevice d;
  d.hash = sha256Hex(token);
  d.id = d.hash.substr(0, 8);
  d.name = cleanDeviceName(name);
  // Later than every device already paired even when the wall clock went
  // back: the order of pairing decides who the owner is.
  std::int64_t newest = 0;
  for (const auto& p : devices_) newest = std::max(newest, p.createdMs);
  d.createdMs = std::max(wallNow, newest + 1);
  if (!store_->saveDevice(d)) {
    out.kind = Outcome::NotSaved;  // the code (or the window) stays: the owner may retry
    return;
  }
  devices_.push_back(d);
  out.kind = Outcome::Paired;
  out.token = token;
  out.device = d;
}

void Pairing::openFirstStartWindow(std::int64_t durationMs) {
  const std::int64_t t = elapsed();
  std::lock_guard lock(m_);
  if (!devices_.empty()) return;
  windowUntilMs_ = t + durationMs;
  windowNeedsNoDevice_ = true;
  windowClaim_.clear();
}

void Pairing::openPresenceWindow(std::int64_t durationMs) {
  const std::int64_t t = elapsed();
  std::lock_guard lock(m_);
  windowUntilMs_ = t + durationMs;
  windowNeedsNoDevice_ = false;
  windowClaim_.clear();
}

Pairing::Window Pairing::window() const {
  const std::int64_t t = elapsed();
  std::lock_guard lock(m_);
  Window w;
  w.open = windowOpenLocked(t);
  if (w.open) w.closesInMs = windowUntilMs_ - t;
  return w;
}

Pairing::Outcome Pairing::pairInWindow(std::string_view name, std::string_view from) {
  Outcome out;
  const std::int64_t t = elapsed();
  const std::int64_t wallNow = now();
  std::lock_guard lock(m_);
  if (!windowOpenLocked(t)) {
    // Told who took it, so the second phone (perhaps the owner's) knows
    // the window was used, not that it never opened.
    const bool claimed = !windowClaim_.empty() && t < windowClaimUntilMs_;
    out.kind = claimed ? Outcome::WindowClaimed : Outcome::NoWindow;
    if (claimed) out.claimedBy = windowClaim_;
    return out;
  }
  addDeviceLocked(name, wallNow, out);
  if (out.kind == Outcome::Paired) {
    windowClaimUntilMs_ = windowUntilMs_;
    windowUntilMs_ = 0;  // one device: the owner
    windowClaim_ = "device \"" + out.device.name + "\" (" + out.device.id + ")";
    if (!from.empty()) windowClaim_ += " from " + std::string(from);
  }
  return out;
}

std::string Pairing::windowClaim() const {
  std::lock_guard lock(m_);
  return windowClaim_;
}

bool Pairing::isDeviceToken(std::string_view token) const {
  if (token.empty()) return false;
  const std::string h = sha256Hex(token);
  std::lock_guard lock(m_);
  bool found = false;
  for (const auto& d : devices_) found |= constantTimeEquals(h, d.hash);
  return found;
}

std::optional<PairedDevice> Pairing::deviceFor(std::string_view token) const {
  if (token.empty()) return std::nullopt;
  const std::string h = sha256Hex(token);
  std::lock_guard lock(m_);
  for (const auto& d : devices_)
    if (constantTimeEquals(h, d.hash)) return d;
  return std::nullopt;
}

std::vector<PairedDevice> Pairing::devices() const {
  std::lock_guard lock(m_);
  return devices_;
}

std::string Pairing::ownerIdLocked() const {
  const PairedDevice* owner = nullptr;
  for (const auto& d : devices_)
    if (!owner || d.createdMs < owner->createdMs || (d.createdMs == owner->createdMs && d.id < owner->id))
      owner = &d;
  return owner ? owner->id : std::string{};
}

std::string Pairing::ownerId() const {
  std::lock_guard lock(m_);
  return ownerIdLocked();
}

bool Pairing::isOwner(const Caller& c) const {
  if (c.installer) return true;
  std::lock_guard lock(m_);
  return !c.deviceId.empty() && c.deviceId == ownerIdLocked();
}

Pairing::Revoke Pairing::revoke(const std::string& id, const Caller& by) {
  std::lock_guard lock(m_);
  const auto it = std::find_if(devices_.begin(), devices_.end(), [&](const auto& d) { return d.id == id; });
  if (it == devices_.end()) return Revoke::NoSuchDevice;
  const bool owner = by.installer || (!by.deviceId.empty() && by.deviceId == ownerIdLocked());
  if (!owner && by.deviceId != id) return Revoke::NotAllowed;
  // Forget it only once the store has: a revocation that a restart undoes
  // would give the phone back its write access.
  if (!store_->removeDevice(id)) return Revoke::NotSaved;
  devices_.erase(it);
  return Revoke::Revoked;
}

Pairing::RevokeAll Pairing::revokeAll(const Caller& by) {
  std::lock_guard lock(m_);
  RevokeAll r;
  if (!by.installer && (by.deviceId.empty() || by.deviceId != ownerIdLocked())) {
    r.result = Revoke::NotAllowed;
    return r;
  }
  // Each device stays in memory until its row is gone, so memory and disk agree.
  std::erase_if(devices_, [&](const PairedDevice& d) {
    if (!store_->removeDevice(d.id)) {
      r.result = Revoke::NotSaved;
      return false;
    }
    ++r.revoked;
    return true;
  });
  return r;
}

}  // namespace xr::web
