#include "integrations/mqtt_link.h"

#include <mosquitto.h>
#include <poll.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "integrations/clock_wait.h"

namespace xr::integrations {

namespace {

using namespace std::chrono_literals;
constexpr auto kPollPeriod = 50ms;
constexpr auto kConnectTimeout = 10s;  // a host that never answers the SYN or the CONNECT
// libmosquitto reads one packet per loop call when nothing of QoS > 0 is in
// flight (lib/loop.c mosquitto_loop_read): without draining, a link took at
// most 20 messages a second, and a burst beyond that (a GX answering read
// requests faster, a keepalive that republishes every value) queued up in
// the socket and was handed on seconds later as if fresh, so a GX that had
// gone silent was not stale until its backlog was read. Bounded, so a flood
// cannot hold the integrations thread.
constexpr int kMaxPacketsPerPoll = 256;

bool readable(int fd) {
  if (fd < 0) return false;
  pollfd p{fd, POLLIN, 0};
  return ::poll(&p, 1, 0) == 1 && (p.revents & POLLIN) != 0;
}

void initLibraryOnce() {
  static std::once_flag once;
  std::call_once(once, [] { mosquitto_lib_init(); });
}

std::string errorText(int rc) {
  if (rc == MOSQ_ERR_ERRNO) return std::strerror(errno);
  return mosquitto_strerror(rc);
}

}  // namespace

MqttLink::MqttLink(boost::asio::io_context& io, MqttOptions opts, IntegrationHealth& health,
                   const rt::WallClock& clock)
    : io_(io), opts_(std::move(opts)), health_(health), clock_(clock), pollTimer_(io), retryTimer_(io) {
  initLibraryOnce();
  mosq_ = mosquitto_new(opts_.clientId.empty() ? nullptr : opts_.clientId.c_str(), true, this);
  if (!mosq_) throw std::runtime_error("mqtt: cannot create a client: " + std::string(std::strerror(errno)));
  mosquitto_int_option(mosq_, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V311);
  if (!opts_.username.empty())
    mosquitto_username_pw_set(mosq_, opts_.username.c_str(),
                              opts_.password.empty() ? nullptr : opts_.password.c_str());
  if (!opts_.willTopic.empty())
    mosquitto_will_set(mosq_, opts_.willTopic.c_str(), static_cast<int>(opts_.willPayload.size()),
                       opts_.willPayload.data(), 1, opts_.willRetain);
  if (opts_.tls) {
    // Without a CA file the system store (/etc/ssl/certs) verifies the broker.
    const int rc = opts_.caFile.empty()
                       ? mosquitto_tls_set(mosq_, nullptr, "/etc/ssl/certs", nullptr, nullptr, nullptr)
                       : mosquitto_tls_set(mosq_, opts_.caFile.c_str(), nullptr, nullptr, nullptr, nullptr);
    if (rc != MOSQ_ERR_SUCCESS) {
      mosquitto_destroy(mosq_);
      throw std::runtime_error("mqtt: TLS set-up failed: " + errorText(rc));
    }
  }
  mosquitto_connect_callback_set(mosq_, &MqttLink::onConnectCb);
  mosquitto_disconnect_callback_set(mosq_, &MqttLink::onDisconnectCb);
  mosquitto_message_callback_set(mosq_, &MqttLink::onMessageCb);
  mosquitto_publish_callback_set(mosq_, &MqttLink::onPublishCb);
}

MqttLink::~MqttLink() {
  if (mosq_) mosquitto_destroy(mosq_);
}

void MqttLink::start(OnConnected onConnected, OnMessage onMessage, OnRefused onRefused) {
  onConnected_ = std::move(onConnected);
  onMessage_ = std::move(onMessage);
  onRefused_ = std::move(onRefused);
  started_ = true;
  connectNow();
  poll();
}

void MqttLink::stop(const std::string& finalTopic, const std::string& finalPayload) {
  stopping_ = true;
  pollTimer_.cancel();
  retryTimer_.cancel();
  if (connected_) {
    if (!finalTopic.empty())
      mosquitto_publish(mosq_, nullptr, finalTopic.c_str(), static_cast<int>(finalPayload.size()),
                        finalPayload.data(), 1, true);
    // Flush what is queued (bounded: at most a few loops), then say goodbye.
    for (int i = 0; i < 20 && mosquitto_want_write(mosq_); ++i) mosquitto_loop(mosq_, 10, 1);
    mosquitto_disconnect(mosq_);
    mosquitto_loop(mosq_, 10, 1);
  }
  connected_ = false;
}

void MqttLink::connectNow() {
  if (stopping_) return;
  health_.attempt();
  connecting_ = true;
  connectStarted_ = clock_.steadyNow();
  inFlight_ = 0;
  // Non-blocking TCP connect; the CONNACK arrives through poll(). Only the
  // name lookup can block, and only this thread.
  const int rc = mosquitto_connect_async(mosq_, opts_.host.c_str(), opts_.port, opts_.keepaliveS);
  if (rc != MOSQ_ERR_SUCCESS) lost(opts_.host + ":" + std::to_string(opts_.port) + ": " + errorText(rc));
}

void MqttLink::scheduleConnect() {
  if (stopping_) return;
  afterOnClock(clock_, retryTimer_, backoff_.next(), [this] { connectNow(); });
}

void MqttLink::lost(const std::string& why) {
  connecting_ = false;
  connected_ = false;
  health_.failed(why);
  mosquitto_disconnect(mosq_);  // the next connect closes whatever socket is left
  scheduleConnect();
}

void MqttLink::poll() {
  if (stopping_) return;
  if (connecting_ || connected_) {
    int rc = mosquitto_loop(mosq_, 0, 1);
    for (int i = 1;
         i < kMaxPacketsPerPoll && rc == MOSQ_ERR_SUCCESS && connected_ && readable(mosquitto_socket(mosq_));
         ++i)
      rc = mosquitto_loop(mosq_, 0, 1);
    if (rc != MOSQ_ERR_SUCCESS && (connecting_ || connected_))
      lost(opts_.host + ":" + std::to_string(opts_.port) + ": " + errorText(rc));
    else if (connecting_ && clock_.steadyNow() - connectStarted_ > kConnectTimeout)
      lost(opts_.host + ":" + std::to_string(opts_.port) + ": no answer within 10 s");
  }
  pollTimer_.expires_after(kPollPeriod);
  pollTimer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) poll();
  });
}

bool MqttLink::publish(const std::string& topic, std::string_view payload, bool retain, int qos) {
  if (!connected_ || inFlight_ >= kMaxInFlight) {
    health_.dropped();
    return false;
  }
  const int rc = mosquitto_publish(mosq_, nullptr, topic.c_str(), static_cast<int>(payload.size()),
                                   payload.data(), qos, retain);
  if (rc != MOSQ_ERR_SUCCESS) {
    health_.dropped();
    return false;
  }
  ++inFlight_;
  health_.sent();
  return true;
}

void MqttLink::subscribe(const std::string& pattern, int qos) {
  if (connected_) mosquitto_subscribe(mosq_, nullptr, pattern.c_str(), qos);
}

void MqttLink::onConnectCb(mosquitto*, void* self, int rc) {
  auto* l = static_cast<MqttLink*>(self);
  if (rc != 0) {
    // The broker answered and refused (bad credentials, not authorised).
    if (l->onRefused_) l->onRefused_(rc);  // may stop the link: a refusal can be the answer wanted
    if (!l->stopping_) l->lost("broker refused the connection: " + std::string(mosquitto_connack_string(rc)));
    return;
  }
  l->connecting_ = false;
  l->connected_ = true;
  l->backoff_.reset();
  l->health_.connected();
  if (l->onConnected_) l->onConnected_();
}

void MqttLink::onDisconnectCb(mosquitto*, void* self, int rc) {
  auto* l = static_cast<MqttLink*>(self);
  if (rc == 0 || l->stopping_) return;  // our own disconnect
  if (l->connected_ || l->connecting_) l->lost("connection lost: " + errorText(rc));
}

void MqttLink::onMessageCb(mosquitto*, void* self, const mosquitto_message* m) {
  auto* l = static_cast<MqttLink*>(self);
  l->health_.received();
  if (l->onMessage_ && m && m->topic)
    l->onMessage_(m->topic,
                  std::string_view(static_cast<const char*>(m->payload),
                                   m->payload ? static_cast<std::size_t>(m->payloadlen) : 0),
                  m->retain);
}

void MqttLink::onPublishCb(mosquitto*, void* self, int) {
  auto* l = static_cast<MqttLink*>(self);
  if (l->inFlight_ > 0) --l->inFlight_;
}

}  // namespace xr::integrations
