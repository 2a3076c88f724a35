#pragma once
// Events the core emits (trips, clears, lockouts, cuts, stage changes...).
// The RT thread only copies these plain structs into a ring; a non-RT thread
// formats them with the specification's console wording (describe()) for the journal,
// the store and the dashboard.
#include <array>
#include <cstddef>
#include <string>

#include "core/modes.h"
#include "core/time.h"

namespace xr {

enum class EventLevel { Debug, Info, Warning, Error, Critical };

enum class EventCode {
  ModeChanged,      // "Entering normal mode" / "Exiting normal mode: <reason>"
  ProtectionTrip,   // a protection fired (reason)
  ProtectionClear,  // a protection cleared (reason)
  ImmediateCut,     // "GPIO4 immediate cut: <reason>"
  CutAfterSettle,   // "GPIO4 cut after settle: <reason>"
  LockoutStarted,   // "Field lockout started: Xs cooldown before restart allowed"
  LockoutExpired,   // "Field lockout expired - normal operation resumed"
  StageChanged,     // "CHARGING: ..." (a = from stage, b = to stage)
  FieldOn,          // field enable rising edge
  FieldOff,         // field enable falling edge (store checkpoint + 5 s)
  InaLatchSet,
  InaLatchCleared,
  VoltageDisagreement,  // "Battery Voltage disagreement! BatteryV=X V, IBV=Y V. Field shut off for safety!"
  TempSensorStale,      // "OneWire sensor stale, sensor dead or disconnected"
  TempTaskHung,
  AlarmOn,
  AlarmOff,
  LimpHomeActive,  // one per 30 s
  FullChargeDetected,
  ShuntGainCorrected,
  AutoZeroStarted,
  AutoZeroDone,
  SystemIdDone,
  TuningCommitted,
  CommandApplied,
  CommandRejected,
  Message,         // generic; text chosen by detail code
  AlarmCondition,  // one buzzer-table row holds (detail = AlarmRow, a = value, b = threshold); 30 s throttled
  BatteryTempMissing,  // battery temperature missing or stale (detail 1: current capped at C/10, a = cap A;
                       // detail 0: charging uncompensated); once per episode (docs/batteries.md "Temperature
                       // rules")
  BatteryTempBack,     // a fresh battery temperature again (a = degC)
  // The CAN side (docs/integrations.md), posted by the xr-can thread through SideEvents,
  // each at most once per 30 s. detail = the bus: 0 BMS, 1 NMEA 2000.
  BmsBadFrames,    // bad BMS frames dropped (a = how many since the last, b = last id, detail = BmsReject)
  CanBusDown,      // a bus cannot be opened (a = failed attempts, b = retry in s)
  CanBusBack,      // open again (a = failed attempts before)
  CanErrorFrames,  // error frames on a bus (a = how many since the last, b = last error class bits)
  // The weather forecast (docs/integrations.md "Weather"), posted by the
  // integrations thread through SideEvents, once per outage.
  WeatherForecastMissing,  // cannot be read (detail: WeatherMissing; a = HTTP status or 0, b = next try in s)
  WeatherForecastBack,     // read again after an outage
  // What the regulator learns (docs/batteries.md, docs/operations.md "Alternator wear").
  CapacityMeasured,  // a swing measured the capacity (a = this swing's Ah, b = swing %, detail = swings so
                     // far)
  BeltSlip,          // the belt slips (detail 1: tach against engine speed, a = slip %, b = engine rpm;
                     // detail 2: current falling while the duty rises, a = current drop A, b = duty rise %)
  // The BMS's values do not fit the bank (docs/protections.md "BMS plausibility"), once per episode:
  // detail bits 0-3 = BmsMismatch (0 = everything fits again, a = the kind that was reported), bits 4-9 =
  // the bank's cells, from bit 10 = its nominal V; a, b = the value that does not fit and what it meets.
  BmsMismatch,
  // Charging held with the engine running and the bank not full (docs/protections.md "Charging held"):
  // level Warning once when it reaches the limit, Info when it ends; a = minutes held, detail = ChargeHold.
  ChargingHeld,
};
// Why the weather forecast cannot be read (WeatherForecastMissing's detail).
enum class WeatherMissing { NoPosition = 0, ServerError = 1, NoAnswer = 2, AnswerRefused = 3 };
// How many codes there are (keep it after the last one): parsing a stored
// code name tries each.
inline constexpr int kEventCodeCount = static_cast<int>(EventCode::ChargingHeld) + 1;

struct Event {
  TimeNs t = 0;
  EventLevel level = EventLevel::Info;
  EventCode code = EventCode::Message;
  Reason reason = Reason::NONE;
  FieldControlMode mode = FieldControlMode::MODE_NORMAL_AUTO_PID;  // ModeChanged: the mode entered
  double a = 0.0;  // values; meaning depends on code (documented in describe())
  double b = 0.0;
  int detail = 0;
};

// Fixed-capacity per-tick batch: no allocation on the RT path.
struct EventBatch {
  static constexpr std::size_t kCapacity = 16;
  std::array<Event, kCapacity> items{};
  std::size_t count = 0;
  std::size_t dropped = 0;
  void clear() {
    count = 0;
    dropped = 0;
  }
  void push(const Event& e) {
    if (count < kCapacity)
      items[count++] = e;
    else
      ++dropped;
  }
};

// The one way the core builds an event (battery, protection and control all
// emit them).
inline Event makeEvent(TimeNs t, EventLevel level, EventCode code, Reason reason = Reason::NONE,
                       double a = 0.0, double b = 0.0, int detail = 0,
                       FieldControlMode mode = FieldControlMode::MODE_NORMAL_AUTO_PID) {
  Event e;
  e.t = t;
  e.level = level;
  e.code = code;
  e.reason = reason;
  e.mode = mode;
  e.a = a;
  e.b = b;
  e.detail = detail;
  return e;
}

std::string_view toString(EventLevel l);
std::string_view toString(EventCode c);
// Human text with the specification's console wording. Allocates: never call on the RT thread.
std::string describe(const Event& e);

}  // namespace xr
