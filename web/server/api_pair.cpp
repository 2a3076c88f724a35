// Pairing routes (pairing.h): POST /api/pair for a code, and for a device
// that may write already: POST /api/pair/code, POST /api/pair/qr, GET /api/pair/devices,
// DELETE /api/pair/devices[/<id>].
#include <boost/json.hpp>
#include <optional>
#include <string>

#include "web/server/api_handler.h"
#include "web/server/api_reply.h"
#include "web/server/auth.h"
#include "web/server/on_board.h"

namespace xr::web {

using namespace api;

unsigned ApiHandler::checkWrite(std::string_view authorization) const {
  // Header only: a token in a URL ends up in browser history and proxy logs.
  switch (checkBearer(authorization, "", opts_.token)) {
    case AuthResult::Ok:
      return 0;
    case AuthResult::Missing:
      return 401;
    case AuthResult::Forbidden:
      break;
  }
  return pairing_.isDeviceToken(bearerToken(authorization)) ? 0 : 403;
}

std::string ApiHandler::writerName(std::string_view authorization) const {
  if (auto d = pairing_.deviceFor(bearerToken(authorization))) return "device \"" + d->name + "\"";
  return "the installer token";
}

Pairing::Caller ApiHandler::callerOf(std::string_view authorization) const {
  Pairing::Caller c;
  c.installer = checkBearer(authorization, "", opts_.token) == AuthResult::Ok;
  if (!c.installer)
    if (auto d = pairing_.deviceFor(bearerToken(authorization))) c.deviceId = d->id;
  return c;
}

namespace {
std::string deviceText(const PairedDevice& d) { return "device \"" + d.name + "\" (" + d.id + ")"; }
}  // namespace

// At most this many off-board refusals go to the event list per run: a
// neighbour's script must not bury the owner's events (the journal's rate
// limit covers the rest).
constexpr int kMaxOffBoardEvents = 5;

std::string ApiHandler::offBoardRefusal(const Peer& peer) {
  if (peer && onBoard(*peer, boardSubnets())) return "";
  const std::string from = peer ? addressText(*peer) : std::string("an unknown address");
  if (offBoardEvents_.fetch_add(1) < kMaxOffBoardEvents)
    api_.securityEvent("Refused a pairing without a code from " + from +
                       ": not on the boat's own networks (loopback, link-local or the board's subnets)");
  return "pairing without a code is only for a device on the boat's own network (" + from +
         " is not); pair with the 6-digit code from the journal or from a paired phone";
}

Response ApiHandler::postPair(const Request& req, const Peer& peer) {
  std::string err;
  auto body = parseBody(req, err);
  if (!body) return error(req, http::status::bad_request, err);
  const auto* o = body->if_object();
  const auto* code = o ? o->if_contains("code") : nullptr;
  // No code at all: the first device of a new regulator, in its first-start
  // window (pairing.h); a code that is there must be a string.
  const bool windowed = o && (!code || code->is_null());
  if (!o || (!windowed && (!code->is_string() || code->get_string().size() > kQrCodeLength)))
    return error(req, http::status::bad_request, "expected {\"code\": \"123456\", \"name\": \"...\"}");
  std::string name;
  if (const auto* n = o->if_contains("name"); n && n->is_string()) name = std::string(n->get_string());
  // A code-less window is for someone on board only (on_board.h); the check
  // comes only when a window is open, so the answer without one is unchanged.
  if (windowed && pairing_.window().open)
    if (std::string why = offBoardRefusal(peer); !why.empty())
      return error(req, http::status::forbidden, why);
  const std::string from = peer ? addressText(*peer) : std::string();
  const auto r = windowed ? pairing_.pairInWindow(name, from)
                          : pairing_.pair(std::string_view(code->get_string()), name);
  json::object out;
  switch (r.kind) {
    case Pairing::Outcome::NoWindow:
      return error(req, http::status::forbidden, "a pairing code is needed: no pairing window is open");
    case Pairing::Outcome::WindowClaimed:
      // Who claimed it is for people on board; a stranger learns nothing.
      if (!peer || !onBoard(*peer, boardSubnets()))
        return error(req, http::status::forbidden, "a pairing code is needed: no pairing window is open");
      api_.securityEvent("Refused a pairing without a code of \"" + cleanDeviceName(name) + "\"" +
                         (from.empty() ? "" : " from " + from) + ": the window was already used by " +
                         r.claimedBy);
      out["error"] = "a pairing code is needed: the pairing window was already used by " + r.claimedBy +
                     "; if that was not you, ask the owner for a code";
      out["claimed_by"] = r.claimedBy;
      return jsonReply(req, http::status::forbidden, out);
    case Pairing::Outcome::Paired:
      api_.securityEvent("Paired " + deviceText(r.device) +
                         (pairing_.ownerId() == r.device.id ? " as the owner" : "") +
                         (windowed ? " without a code, in a pairing window" : "") +
                         (r.qrMadeBy.empty() ? "" : " with a QR code made by " + r.qrMadeBy) +
                         (from.empty() ? "" : " from " + from));
      out["token"] = r.token;
      out["id"] = r.device.id;
      out["name"] = r.device.name;
      return jsonReply(req, http::status::ok, out);
    case Pairing::Outcome::WrongCode:
      out["error"] = "wrong or expired pairing code";
      out["tries_left"] = r.triesLeft;
      return jsonReply(req, http::status::forbidden, out);
    case Pairing::Outcome::LockedOut: {
      if (r.retryAfterMs == kLockoutMs)  // this request locked it: one event per lock-out
        api_.securityEvent("Pairing locked for " + std::to_string(kLockoutMs / 60000) + " min after " +
                           std::to_string(kMaxWrongTries) + " wrong codes");
      out["error"] = "too many wrong codes: pairing is locked and the code is void; make a new code";
      const auto s = (r.retryAfterMs + 999) / 1000;
      out["retry_after_s"] = s;
      auto res = jsonReply(req, http::status::too_many_requests, out);
      res.set(http::field::retry_after, std::to_string(s));
      return res;
    }
    case Pairing::Outcome::NotSaved:
      return error(req, http::status::service_unavailable, "the pairing cannot be saved (see /api/system)");
    case Pairing::Outcome::Full:
      return error(req, http::status::conflict, "too many paired devices: revoke one first");
  }
  return error(req, http::status::internal_server_error, "pairing");
}

Response ApiHandler::pairRoutes(const Request& req, std::string_view path, const Peer& peer) {
  const auto method = req.method();
  if (path == "/api/pair") {
    if (method != http::verb::post) {
      auto r = error(req, http::status::method_not_allowed, "method not allowed");
      r.set(http::field::allow, "POST");
      return r;
    }
    return postPair(req, peer);
  }
  if (path == "/api/pair/window") {  // open: a new phone asks whether it needs a code
    if (method != http::verb::get && method != http::verb::head)
      return error(req, http::status::method_not_allowed, "method not allowed");
    const auto w = pairing_.window();
    json::object out;
    out["open"] = w.open;
    out["closes_in_s"] = (w.closesInMs + 999) / 1000;
    return jsonReply(req, http::status::ok, out);
  }
  if (auto code = checkWrite(req[http::field::authorization])) return authError(req, code);
  if (path == "/api/pair/code") {
    if (method != http::verb::post) return error(req, http::status::method_not_allowed, "method not allowed");
    const auto c = pairing_.newCode();
    json::object out;
    out["code"] = c.code;
    out["expires_in_s"] = kCodeLifetimeMs / 1000;
    return jsonReply(req, http::status::ok, out);
  }
  if (path == "/api/pair/qr") {
    if (method != http::verb::post) return error(req, http::status::method_not_allowed, "method not allowed");
    return postQrCode(req);
  }
  if (path == "/api/pair/devices") {
    if (method == http::verb::get || method == http::verb::head) return listDevices(req);
    if (method == http::verb::delete_) return revokeAllDevices(req);
    return error(req, http::status::method_not_allowed, "method not allowed");
  }
  constexpr std::string_view kDevice = "/api/pair/devices/";
  if (path.starts_with(kDevice) && method == http::verb::delete_)
    return revokeDevice(req, std::string(path.substr(kDevice.size())));
  return error(req, http::status::not_found, "no such endpoint");
}

// A paired phone's QR code for the next phone (pairing.h): the phone draws
// it from the code; the code, not the URL, is what pairs, so the phone puts
// its own address in front (the one the next phone can reach too).
Response ApiHandler::postQrCode(const Request& req) {
  const auto auth = req[http::field::authorization];
  std::string by = writerName(auth);
  if (auto d = pairing_.deviceFor(bearerToken(auth))) by = deviceText(*d);
  const auto c = pairing_.newQrCode(by);
  api_.securityEvent("QR code for pairing another device made by " + by + " (" +
                     std::to_string(kCodeLifetimeMs / 60000) + " min, once)");
  json::object out;
  out["code"] = c.code;
  out["expires_in_s"] = kCodeLifetimeMs / 1000;
  return jsonReply(req, http::status::ok, out);
}

Response ApiHandler::listDevices(const Request& req) {
  const auto caller = callerOf(req[http::field::authorization]);
  const std::string owner = pairing_.ownerId();
  json::array list;
  for (const auto& d : pairing_.devices()) {
    json::object j;
    j["id"] = d.id;
    j["name"] = d.name;
    j["created"] = static_cast<double>(d.createdMs) / 1000.0;
    j["owner"] = d.id == owner;
    j["this_device"] = d.id == caller.deviceId;
    list.push_back(std::move(j));
  }
  json::object out;
  out["devices"] = std::move(list);
  out["you_are_owner"] = pairing_.isOwner(caller);
  // Who paired without a code in this run's window (the owner checks it was them).
  if (const std::string claim = pairing_.windowClaim(); !claim.empty()) out["window_claimed_by"] = claim;
  return jsonReply(req, http::status::ok, out);
}

Response ApiHandler::revokeDevice(const Request& req, const std::string& id) {
  const auto auth = req[http::field::authorization];
  std::optional<PairedDevice> target;
  for (const auto& d : pairing_.devices())
    if (d.id == id) target = d;
  switch (pairing_.revoke(id, callerOf(auth))) {
    case Pairing::Revoke::NoSuchDevice:
      return error(req, http::status::not_found, "no such device");
    case Pairing::Revoke::NotAllowed:
      return error(req, http::status::forbidden, "only the owner may revoke another device");
    case Pairing::Revoke::NotSaved:
      return error(req, http::status::service_unavailable,
                   "the revocation cannot be saved (state database not writable, see /api/system); "
                   "the device keeps its access");
    case Pairing::Revoke::Revoked:
      break;
  }
  api_.securityEvent("Revoked " + (target ? deviceText(*target) : "device " + id) + " by " +
                     writerName(auth));
  json::object out;
  out["revoked"] = 1;
  return jsonReply(req, http::status::ok, out);
}

Response ApiHandler::revokeAllDevices(const Request& req) {
  const auto auth = req[http::field::authorization];
  const std::string by = writerName(auth);  // before: the owner's own token goes too
  const auto r = pairing_.revokeAll(callerOf(auth));
  if (r.result == Pairing::Revoke::NotAllowed)
    return error(req, http::status::forbidden, "only the owner may revoke every device");
  if (r.revoked > 0)
    api_.securityEvent("Revoked " + std::to_string(r.revoked) + " device(s) at once by " + by);
  if (r.result == Pairing::Revoke::NotSaved)
    return error(req, http::status::service_unavailable,
                 "only " + std::to_string(r.revoked) +
                     " revocation(s) could be saved (state database not writable, see /api/system); "
                     "the other devices keep their access");
  json::object out;
  out["revoked"] = r.revoked;
  return jsonReply(req, http::status::ok, out);
}

}  // namespace xr::web
