// AlarmPanel: the rows, the latch, the acknowledgement and the buzzer's log.
#include "protection/alarms.h"

#include <cmath>

#include "params/constants.h"
#include "params/derived.h"

namespace xr {

bool AlarmPanel::update(const AlarmInput& in, const Params& p, const ProtectionLog& log) noexcept {
  const TimeNs now = log.now();
  if (now < nextCheck_) return buzzer_;
  nextCheck_ = now + fromMs(k::ALARM_CHECK_MS);

  const Rows row = evaluate(in, p, log);
  bool gated = false;
  for (std::size_t i = 0; i < kAlarmRowCount; ++i) {
    if (row[i] && static_cast<AlarmRow>(i) != AlarmRow::TempTaskHung) gated = true;
  }
  // TempTask hang sounds regardless of AlarmActivate.
  const bool cond = gated || row[static_cast<std::size_t>(AlarmRow::TempTaskHung)];
  if (p.AlarmLatchEnabled && cond) latched_ = true;
  if (!p.AlarmLatchEnabled) latched_ = false;
  updateAcknowledgement(cond, now);
  buzzer_ = (cond || latched_) && !ackActive_;
  logBuzzer(log);
  return buzzer_;
}

// Every row of the table (AlarmActivate gates all but TempTaskHung), with
// its console message: one per row per 30 s while it holds; the rows with an
// event of their own (once per episode; a silent BMS its REASON_BMS_STALE
// trip and clear) add none: a mismatch lasting hours is one incident.
AlarmPanel::Rows AlarmPanel::evaluate(const AlarmInput& in, const Params& p,
                                      const ProtectionLog& log) noexcept {
  const TimeNs now = log.now();
  Rows counted{};
  auto set = [&](AlarmRow r, bool on, double v, double l) {
    const auto i = static_cast<std::size_t>(r);
    const bool counts = on && (r == AlarmRow::TempTaskHung || p.AlarmActivate);
    const bool ownEvent =
        r == AlarmRow::BmsMismatch || r == AlarmRow::ChargingHeld || r == AlarmRow::BmsStale;
    if (counts && !ownEvent &&
        (messageAt_[i] < 0 || now - messageAt_[i] >= fromMs(k::ALARM_MESSAGE_THROTTLE_MS))) {
      messageAt_[i] = now;
      log.push(EventCode::AlarmCondition, EventLevel::Warning, Reason::NONE, v, l, static_cast<int>(i));
    }
    counted[i] = counts;
  };
  const bool tempOk = std::isfinite(in.TempToUse) && !in.tempStale;
  const double tempAlarm = tempAlarmF(p);  // 0 = derived from TemperatureLimitF
  set(AlarmRow::TempHigh, tempOk && in.TempToUse > tempAlarm, in.TempToUse, tempAlarm);
  set(AlarmRow::TempLow, p.TempAlarmLow != 0.0 && tempOk && in.TempToUse < p.TempAlarmLow, in.TempToUse,
      p.TempAlarmLow);
  const double vHigh = voltageAlarmHighV(p), vLow = voltageAlarmLowV(p);  // 0 = derived from the bank
  set(AlarmRow::VoltageHigh, std::isfinite(in.IBV) && in.IBV > vHigh, in.IBV, vHigh);
  // "VoltageAlarmLow (11 V, > 8 V floor)": a threshold at or under the floor disables the row.
  set(AlarmRow::VoltageLow, vLow > k::VOLTAGE_ALARM_LOW_FLOOR_V && std::isfinite(in.IBV) && in.IBV < vLow,
      in.IBV, vLow);
  const double currentAlarm = currentAlarmHighAmps(p);
  set(AlarmRow::AltCurrentHigh, std::isfinite(in.MeasuredAmps) && in.MeasuredAmps > currentAlarm,
      in.MeasuredAmps, currentAlarm);
  set(AlarmRow::BatteryCurrentHigh,
      std::isfinite(in.Bcur) && std::fabs(in.Bcur) > p.MaximumAllowedBatteryAmps, in.Bcur,
      p.MaximumAllowedBatteryAmps);
  set(AlarmRow::InaOvervoltage, in.inaLatched, in.IBV, 0.0);
  set(AlarmRow::TempSensorDead, in.tempStale, in.TempToUse, k::TEMP_STALE_MS / 1000.0);
  set(AlarmRow::EfficiencyAnomaly, in.effAnomaly, 0.0, 0.0);
  set(AlarmRow::FaultMode, in.faultMode, 0.0, 0.0);
  set(AlarmRow::TempTaskHung, in.tempTaskHung, 0.0, k::TEMP_TASK_TIMEOUT / 1000.0);
  set(AlarmRow::BmsStale, control_.bmsStale, 0.0, p.BmsStaleS);
  set(AlarmRow::BmsMismatch, control_.bmsMismatch, 0.0, 0.0);
  set(AlarmRow::ChargingHeld, control_.chargingHeld, 0.0, 0.0);
  rowOn_ = counted;
  return counted;
}

// Log the buzzer's edges, but an alarm hovering on its threshold (the
// buzzer follows it check by check) is one alarm: "Alarm OFF" only after
// the buzzer stayed off for the message hold.
void AlarmPanel::logBuzzer(const ProtectionLog& log) noexcept {
  if (buzzer_) {
    buzzerOffSince_ = -1;
    if (!buzzerLogged_) {
      buzzerLogged_ = true;
      log.push(EventCode::AlarmOn, EventLevel::Warning, Reason::NONE);
    }
  } else if (buzzerLogged_) {
    if (buzzerOffSince_ < 0) buzzerOffSince_ = log.now();
    if (log.now() - buzzerOffSince_ >= fromMs(k::ALARM_MESSAGE_THROTTLE_MS)) {
      buzzerLogged_ = false;
      buzzerOffSince_ = -1;
      log.push(EventCode::AlarmOff, EventLevel::Info, Reason::NONE);
    }
  }
}

void AlarmPanel::acknowledge(TimeNs now) noexcept {
  ackRows_ = rowOn_;
  ackActive_ = true;
  ackQuietSince_ = -1;
  latched_ = false;
  nextCheck_ = now;  // quiet at the next tick, not up to 250 ms later
}

// An acknowledgement silences the rows it saw; a new row sounds again, and it
// ends once all have been quiet for the message hold (30 s: a row hovering on
// its threshold stays acknowledged), so the next alarm is heard.
void AlarmPanel::updateAcknowledgement(bool cond, TimeNs now) noexcept {
  if (!ackActive_) return;
  for (std::size_t i = 0; i < kAlarmRowCount; ++i)
    if (rowOn_[i] && !ackRows_[i]) ackActive_ = false;
  if (cond)
    ackQuietSince_ = -1;
  else if (ackQuietSince_ < 0)
    ackQuietSince_ = now;
  if (ackQuietSince_ >= 0 && now - ackQuietSince_ >= fromMs(k::ALARM_MESSAGE_THROTTLE_MS)) ackActive_ = false;
  if (ackActive_) latched_ = false;
}

}  // namespace xr
