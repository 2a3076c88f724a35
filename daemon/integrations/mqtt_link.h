#pragma once
// One MQTT connection (libmosquitto) driven from the integrations' Asio
// thread: no libmosquitto thread, no blocking connect. A 50 ms timer runs
// mosquitto_loop() with a zero timeout; the connection is made with
// mosquitto_connect_async and retried with exponential backoff; every
// outcome goes to the integration's health record.
//
// Newest wins: publish() refuses (and counts as dropped) when the link is
// down or more than kMaxInFlight messages wait to be written, so a slow or
// dead broker never grows a queue; the next sample replaces the lost one.
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "integrations/backoff.h"
#include "integrations/integration_health.h"

struct mosquitto;
struct mosquitto_message;

namespace xr::integrations {

struct MqttOptions {
  std::string host = "localhost";
  int port = 1883;
  std::string clientId;
  std::string username, password;  // empty: anonymous
  bool tls = false;
  std::string caFile;                  // empty: the system trust store
  std::string willTopic, willPayload;  // empty topic: no last will
  bool willRetain = true;
  int keepaliveS = 30;
};

class MqttLink {
 public:
  static constexpr int kMaxInFlight = 64;
  using OnConnected = std::function<void()>;
  // `retained`: the broker stored this message and replays it to every new
  // subscriber; it was published some time before, maybe before our start.
  using OnMessage = std::function<void(const std::string& topic, std::string_view payload, bool retained)>;
  // The broker answered the CONNECT and refused it (bad or missing credentials).
  using OnRefused = std::function<void(int connackCode)>;

  // clock: the backoff and the connect timeout run on it (clock_wait.h).
  MqttLink(boost::asio::io_context& io, MqttOptions opts, IntegrationHealth& health,
           const rt::WallClock& clock);
  ~MqttLink();
  MqttLink(const MqttLink&) = delete;
  MqttLink& operator=(const MqttLink&) = delete;

  // Both on the io_context's thread.
  void start(OnConnected onConnected, OnMessage onMessage, OnRefused onRefused = {});
  // Publishes finalTopic/finalPayload (retained) first when given: a clean
  // stop says "offline" itself instead of leaving it to the broker's will.
  void stop(const std::string& finalTopic = {}, const std::string& finalPayload = {});

  bool connected() const { return connected_; }
  bool publish(const std::string& topic, std::string_view payload, bool retain, int qos = 0);
  void subscribe(const std::string& pattern, int qos = 0);

 private:
  static void onConnectCb(mosquitto*, void* self, int rc);
  static void onDisconnectCb(mosquitto*, void* self, int rc);
  static void onMessageCb(mosquitto*, void* self, const mosquitto_message* m);
  static void onPublishCb(mosquitto*, void* self, int mid);

  void connectNow();
  void scheduleConnect();
  void poll();
  void lost(const std::string& why);

  boost::asio::io_context& io_;
  MqttOptions opts_;
  IntegrationHealth& health_;
  const rt::WallClock& clock_;
  mosquitto* mosq_ = nullptr;
  boost::asio::steady_timer pollTimer_, retryTimer_;
  Backoff backoff_;
  OnConnected onConnected_;
  OnMessage onMessage_;
  OnRefused onRefused_;
  bool started_ = false, connecting_ = false, connected_ = false, stopping_ = false;
  std::chrono::steady_clock::time_point connectStarted_{};
  int inFlight_ = 0;
};

}  // namespace xr::integrations
