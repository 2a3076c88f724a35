#pragma once
// Pairing: how a phone on the boat's Wi-Fi gets the right to change things
// (docs/security.md "Pairing"). Reads stay open on the LAN (unless
// [web] reads_require_token); every write needs a token in the Authorization
// header: the configured or generated static token (installers' scripts), or
// a per-device token handed out by POST /api/pair for a short code.
//
// The code: 6 digits, valid for kCodeLifetime, single use. It is shown in the
// journal at start and handed out to an already paired device (or to
// `xregulatord --pair`, which asks the running daemon with the static token).
// kMaxWrongTries wrong codes in a row burn the code and lock /api/pair for
// kLockout: a guesser on the marina Wi-Fi gets 5 tries in 1,000,000 per code
// the owner makes.
//
// The owner (docs/security.md "Owner and devices"): the installer token and
// the first device paired (the oldest still paired) may revoke any device;
// any other device may revoke only itself. A revocation is durable or it is
// refused: the in-memory list changes only after the store has saved it.
//
// Device tokens are 256 random bits; only their SHA-256 is kept (AuthStore,
// the state database in the daemon), so a copy of the database does not give
// write access, and revoking a device forgets its hash.
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace xr::web {

inline constexpr std::int64_t kCodeLifetimeMs = 10 * 60 * 1000;
inline constexpr int kMaxWrongTries = 5;
inline constexpr std::int64_t kLockoutMs = 5 * 60 * 1000;
inline constexpr std::size_t kMaxPairedDevices = 32;
inline constexpr std::size_t kMaxDeviceNameLength = 40;
// The QR code a paired phone shows for the next one (docs/security.md
// "Pairing without a terminal"): 128 random bits as 32 hex digits, too many
// to guess, so the URL alone pairs; valid for kCodeLifetimeMs, single use.
inline constexpr std::size_t kQrCodeLength = 32;

// SHA-256 of text as 64 lowercase hex digits (OpenSSL).
std::string sha256Hex(std::string_view text);
// `digits` random decimal digits from /dev/urandom (uniform: rejection sampling).
std::string randomDigits(int digits);

struct PairedDevice {
  std::string id;    // 8 hex digits of the token's hash: names the device in lists and DELETE
  std::string name;  // what the phone called itself, printable ASCII, at most 40 characters
  std::string hash;  // sha256Hex(token)
  std::int64_t createdMs = 0;
};

// Where paired devices survive a restart. Implementations must be
// thread-safe (the web threads call them) and never block for long.
class AuthStore {
 public:
  virtual ~AuthStore() = default;
  virtual std::vector<PairedDevice> loadDevices() = 0;
  // false: not saved (read-only database...): the pairing is refused.
  virtual bool saveDevice(const PairedDevice& d) = 0;
  virtual bool removeDevice(const std::string& id) = 0;
};

// For tests and for a daemon without a state database: forgotten at exit.
class MemoryAuthStore final : public AuthStore {
 public:
  std::vector<PairedDevice> loadDevices() override;
  bool saveDevice(const PairedDevice& d) override;
  bool removeDevice(const std::string& id) override;

 private:
  std::mutex m_;
  std::vector<PairedDevice> devices_;
};

class Pairing {
 public:
  using Clock = std::function<std::int64_t()>;  // ms; injectable for tests
  // wall: Unix ms, only for the dates shown (a device's "paired at").
  // elapsed: a monotonic ms count for the rules about elapsed time (a code's
  // lifetime, the lock-out), which a wall clock set by GPS or NTP must not
  // stretch or cut (docs/security.md "The clock"). One clock given: both.
  explicit Pairing(std::shared_ptr<AuthStore> store, Clock wall = {}, Clock elapsed = {});

  struct Code {
    std::string code;
    std::int64_t expiresMs = 0;
  };
  // A fresh code; replaces the previous one and ends a lock-out.
  Code newCode();
  // A fresh QR code (kQrCodeLength hex digits), for a paired device only;
  // `by` names who made it (the pairing's event says so). Replaces the
  // previous QR code, not the 6-digit one, and ends a lock-out.
  Code newQrCode(std::string_view by);

  struct Outcome {
    enum Kind { Paired, WrongCode, LockedOut, NotSaved, Full, NoWindow, WindowClaimed } kind = WrongCode;
    std::string token;              // Paired: the device's write token (shown once)
    PairedDevice device;            // Paired
    int triesLeft = 0;              // WrongCode
    std::int64_t retryAfterMs = 0;  // LockedOut
    std::string claimedBy;          // WindowClaimed: who paired in this window
    std::string qrMadeBy;           // Paired with a QR code: who made it
  };
  Outcome pair(std::string_view code, std::string_view name);

  // Pairing without a terminal (docs/security.md "Pairing without a
  // terminal"): on a regulator that is new and has nothing paired, the first
  // device pairs without a code for durationMs of elapsed time. The window
  // closes at the first pairing and never opens while a device is paired.
  void openFirstStartWindow(std::int64_t durationMs);
  // A person on board proved presence (the ignition turned off-on-off-on):
  // one device, paired or not before, may pair without a code for durationMs.
  void openPresenceWindow(std::int64_t durationMs);
  struct Window {
    bool open = false;
    std::int64_t closesInMs = 0;
  };
  Window window() const;
  // `from`: the client's address, kept with the claim. A device that comes
  // after another claimed the window (before it would have closed) is told
  // WindowClaimed and by whom, not merely NoWindow.
  Outcome pairInWindow(std::string_view name, std::string_view from = {});
  // Who claimed the last window ("device \"phone\" (1a2b3c4d) from
  // 192.168.4.20"); empty when no window was claimed.
  std::string windowClaim() const;

  // True when token is one of the paired devices' tokens.
  bool isDeviceToken(std::string_view token) const;
  // The paired device that token belongs to (events name who changed what).
  std::optional<PairedDevice> deviceFor(std::string_view token) const;
  std::vector<PairedDevice> devices() const;
  // Who asks for a revocation: the installer token, or a paired device.
  struct Caller {
    bool installer = false;
    std::string deviceId;
  };
  enum class Revoke { Revoked, NoSuchDevice, NotAllowed, NotSaved };
  Revoke revoke(const std::string& id, const Caller& by);
  struct RevokeAll {
    Revoke result = Revoke::Revoked;
    std::size_t revoked = 0;  // saved and forgotten (also on NotSaved: the part that was)
  };
  // Owner only; every device, the owner's too (a lost phone: start again).
  RevokeAll revokeAll(const Caller& by);
  // The owner device's id: the oldest paired device; empty when none.
  std::string ownerId() const;
  bool isOwner(const Caller& c) const;

 private:
  std::int64_t now() const;      // wall
  std::int64_t elapsed() const;  // monotonic
  std::string ownerIdLocked() const;
  bool windowOpenLocked(std::int64_t t) const {
    return t < windowUntilMs_ && (!windowNeedsNoDevice_ || devices_.empty());
  }
  void addDeviceLocked(std::string_view name, std::int64_t wallNow, Outcome& out);

  std::shared_ptr<AuthStore> store_;
  Clock clock_, elapsedClock_;
  mutable std::mutex m_;
  std::string codeHash_;            // empty: no code in force
  std::int64_t codeExpiresMs_ = 0;  // on the elapsed clock, like lockedUntilMs_
  std::string qrHash_;              // the QR code's; empty: none in force
  std::int64_t qrExpiresMs_ = 0;
  std::string qrMadeBy_;
  int wrongTries_ = 0;
  std::int64_t lockedUntilMs_ = 0;
  std::int64_t windowUntilMs_ = 0;       // elapsed clock; 0: never opened
  bool windowNeedsNoDevice_ = true;      // the first-start window: only while nothing is paired
  std::string windowClaim_;              // who paired in the last window
  std::int64_t windowClaimUntilMs_ = 0;  // when that window would have closed
  std::vector<PairedDevice> devices_;
};

// Keeps a device name printable and short; empty becomes "device".
std::string cleanDeviceName(std::string_view name);

}  // namespace xr::web
