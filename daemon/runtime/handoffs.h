#pragma once
// Every lock-free hand-off between the RT control thread and the rest of the
// daemon, in one place (docs/architecture.md "Threads"):
//   in : commands (bounded SPSC), whole Params (triple buffer), slow sensor
//        samples (seqlocks written by the 1-Wire and VE.Direct threads)
//   out: newest snapshot (seqlock: telemetry + loop statistics + sim truth),
//        events (SPSC ring), telemetry rows for the CSV writer (SPSC).
// Multi-producer callers on the non-RT side (several HTTP sessions, the
// scenario runner) go through submitCommand()/submitParams(), which take a
// mutex the RT thread never touches.
#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>

#include "battery/ledger.h"
#include "control/telemetry.h"
#include "core/commands.h"
#include "core/inputs.h"
#include "core/seqlock.h"
#include "params/derived.h"
#include "params/params.h"
#include "runtime/event_pump.h"
#include "runtime/loop_stats.h"
#include "runtime/spsc_queue.h"
#include "runtime/triple_buffer.h"

namespace xr::rt {

// The simulator's physical truth, for the CSV's sim_* columns and the tests.
struct SimTruth {
  bool valid = false;
  double sim_battery_v = 0, sim_alt_a = 0, sim_alt_temp_f = 0, sim_soc_pct = 0;
  bool sim_bms_connected = true, sim_field_on = false;
};

// Health of the runtime itself, beside the loop statistics.
struct RuntimeHealth {
  std::uint64_t sensorReadErrors = 0;   // ticks where the fast sensors reported an I/O error
  std::uint64_t outputWriteErrors = 0;  // PWM/GPIO writes that failed (safe state driven)
  std::uint64_t watchdogFeeds = 0;
  std::uint64_t commandsApplied = 0, commandsRejected = 0;
  std::uint64_t paramSwaps = 0;
  std::uint64_t eventsDropped = 0;
  std::uint64_t rowsDropped = 0;  // CSV rows lost because the writer fell behind
  std::uint64_t edgeErrors = 0;   // ALERT/RDY waits that failed
  bool adsEdgeFallback = false;   // ALERT/RDY configured but silent: single-shot pacing
  bool stopping = false;          // the controlled shutdown ramp is running
};

struct RuntimeSnapshot {
  std::uint64_t tick = 0;
  TimeNs start = 0;  // loop start (t_s = 0)
  Telemetry telemetry;
  LoopStatsSummary loop;
  RuntimeHealth health;
  SimTruth sim;
};

// Latest sample of a slow sensor thread (1 Hz DS18B20, VE.Direct frames).
struct TemperatureHandoff {
  double tempF = kNoValue;
  TimeNs stamp = 0;      // when the valid sample was taken (0 = never)
  TimeNs heartbeat = 0;  // last completed cycle of the thread (T4), valid or not
};
// The battery temperature (docs/batteries.md): from the battery DS18B20 today; a BMS or
// a Victron device posts here the same way, naming itself in `source`.
struct BatteryTempHandoff {
  double tempC = kNoValue;
  TimeNs stamp = 0;  // when the valid sample was taken (0 = none yet)
  BatteryTempSource source = BatteryTempSource::none;
};
// Engine speed from NMEA 2000 (127488) or J1939 (61444), for RpmSource = n2k
// (docs/integrations.md): posted by the CAN service on each message.
struct EngineRpmHandoff {
  double rpm = kNoValue;
  TimeNs stamp = 0;  // when it arrived (0 = never)
};
// What the CAN service sees on its buses (docs/integrations.md), for /api/system: one
// writer (the service's poll), any readers. Times on the control loop's
// clock; 0 = never.
struct CanStatusHandoff {
  TimeNs now = 0;  // when this was written
  // BMS bus
  bool bmsConfigured = false, bmsBusUp = false;
  std::uint8_t bmsProtocol = 0;  // can::BmsProtocol
  TimeNs bmsLastFrame = 0;       // the last frame the decoder accepted
  BmsLimits bmsLimits;           // the decoder's last good values (NaN = none)
  std::uint64_t bmsFrames = 0, bmsBadFrames = 0, bmsErrorFrames = 0, bmsOpenFailures = 0;
  // NMEA 2000 bus
  bool n2kConfigured = false, n2kBusUp = false, n2kClaimed = false;
  std::uint8_t n2kAddress = 0xFF;
  std::uint64_t n2kTxFrames = 0, n2kRxFrames = 0, n2kErrorFrames = 0, n2kOpenFailures = 0;
};
// The boat's position from NMEA 2000 (129025 / 129029), for the weather
// forecast (docs/integrations.md "Weather"): posted by the CAN service,
// stamped on its clock, so its age is CanStatusHandoff::now - stamp.
struct PositionHandoff {
  double latitudeDeg = kNoValue, longitudeDeg = kNoValue;
  TimeNs stamp = 0;  // when it arrived (0 = never)
};
struct VictronHandoff {
  double currentA = kNoValue, voltageV = kNoValue, solarW = kNoValue;
  TimeNs stamp = 0;
};

// Whether the regulator applied or refused a command, per Command::ackId
// (docs/security.md). The control thread posts with one release store into
// a slot; any number of readers poll their own id. Never blocks the control
// thread. A slot is reused after kSlots later acknowledged commands, so a
// reader checks the id in it, and a late reader sees "unknown" not a wrong
// answer.
class CommandAcks {
 public:
  static constexpr std::size_t kSlots = 128;  // > the command queue (64): no slot is reused while queued
  void post(std::uint32_t id, bool applied) noexcept {
    slots_[id % kSlots].store((static_cast<std::uint64_t>(id) << 1) | (applied ? 1u : 0u),
                              std::memory_order_release);
  }
  // 1 applied, 0 refused, -1 not (yet) known.
  int find(std::uint32_t id) const noexcept {
    const std::uint64_t v = slots_[id % kSlots].load(std::memory_order_acquire);
    return (v >> 1) == id ? static_cast<int>(v & 1u) : -1;
  }

 private:
  std::array<std::atomic<std::uint64_t>, kSlots> slots_{};
};

class Handoffs {
 public:
  explicit Handoffs(const Params& initial) : params(initial), acceptedParams_(initial) {}

  // ---- non-RT side (any thread) ----
  // False when the queue is full (the caller reports 503 / retries).
  bool submitCommand(const Command& c) {
    std::lock_guard lock(producerMutex_);
    return commands.push(c);
  }
  // Queues c with a fresh ackId; returns it, or 0 when the queue is full.
  std::uint32_t submitCommandForAck(Command c) {
    std::lock_guard lock(producerMutex_);
    if (++lastAckId_ == 0) ++lastAckId_;  // 0 means "no acknowledgement wanted"
    c.ackId = lastAckId_;
    return commands.push(c) ? c.ackId : 0;
  }
  // Publish a validated whole Params; the RT thread applies it between ticks.
  void submitParams(const Params& p) {
    std::lock_guard lock(producerMutex_);
    acceptedParams_ = p;
    params.write(p);
  }
  // The newest Params handed to the RT thread (what GET /api/params shows).
  Params acceptedParams() const {
    std::lock_guard lock(producerMutex_);
    return acceptedParams_;
  }
  RuntimeSnapshot latest() const { return snapshot.load(); }
  // Not set up: the core scaled its set to the bank class it read from the
  // battery (control/bank_reading.cpp); the accepted copy follows, so the
  // API shows what runs. Not handed to the RT thread again (it has it). A
  // set submitted since (no longer reading the bank) is left alone. True
  // when the copy changed.
  bool followBankClass(const Telemetry::SetupBank& bank) {
    std::lock_guard lock(producerMutex_);
    if (!bank.fromBattery || !acceptedParams_.SetupBankFromBattery) return false;
    acceptedParams_ = withBankClass(acceptedParams_, bankClassOfVoltage(bank.classV));
    return true;
  }

  // ---- the hand-offs themselves ----
  SpscQueue<Command, 64> commands;
  TripleBuffer<Params> params;
  SeqLock<RuntimeSnapshot> snapshot;
  EventRing events;
  SideEvents sideEvents;                 // events of the non-RT threads (CAN), drained by the EventPump
  SpscQueue<RuntimeSnapshot, 512> rows;  // telemetry rows at --telemetry-rate
  SeqLock<TemperatureHandoff> temperature;
  SeqLock<VictronHandoff> victron;
  SeqLock<BmsLimits> bms;   // a BMS's limits (CAN link or another source), posted on each change
  SeqLock<BmsLimits> dvcc;  // a Victron GX's DVCC limits (POST /api/dvcc), beside the BMS's
  SeqLock<EngineRpmHandoff> engineRpm;
  SeqLock<BatteryTempHandoff> batteryTemp;
  SeqLock<CanStatusHandoff> canStatus;   // written by the CAN service's poll
  SeqLock<PositionHandoff> n2kPosition;  // the newest position heard on NMEA 2000
  SeqLock<BatteryLedger> ledger;         // the core's ledger, copied out ~4 times a second
  CommandAcks acks;
  // A battery type is chosen (docs/configuration.md "Not set up"): written by
  // the web API when it changes, read by the owner model of the integrations.
  std::atomic<bool> setUp{true};

 private:
  mutable std::mutex producerMutex_;
  Params acceptedParams_;
  std::uint32_t lastAckId_ = 0;
};

}  // namespace xr::rt
