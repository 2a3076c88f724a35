// CheckAlarms(): the GPIO21 buzzer of docs/protections.md "Protections". Evaluated every ALARM_CHECK_MS (250
// ms); holds between.
#include <cmath>

#include "params/constants.h"
#include "params/derived.h"
#include "protection/alarm_rows.h"
#include "protection/protection_supervisor.h"

namespace xr {

bool ProtectionSupervisor::checkAlarms(bool effAnomalyAlarmActive, EventBatch& ev) noexcept {
  if (now_ < nextAlarmCheck_) return buzzer_;
  nextAlarmCheck_ = now_ + fromMs(k::ALARM_CHECK_MS);

  const bool tempOk = std::isfinite(TempToUse_) && !tempStaleRaw_;
  std::array<bool, kAlarmRowCount> row{};
  std::array<double, kAlarmRowCount> val{};
  std::array<double, kAlarmRowCount> lim{};
  auto set = [&](AlarmRow r, bool on, double v, double l) {
    row[static_cast<std::size_t>(r)] = on;
    val[static_cast<std::size_t>(r)] = v;
    lim[static_cast<std::size_t>(r)] = l;
  };
  const double tempAlarm = tempAlarmF(p_);  // 0 = derived from TemperatureLimitF
  set(AlarmRow::TempHigh, tempOk && TempToUse_ > tempAlarm, TempToUse_, tempAlarm);
  set(AlarmRow::TempLow, p_.TempAlarmLow != 0.0 && tempOk && TempToUse_ < p_.TempAlarmLow, TempToUse_,
      p_.TempAlarmLow);
  const double vHigh = voltageAlarmHighV(p_), vLow = voltageAlarmLowV(p_);  // 0 = derived from the bank
  set(AlarmRow::VoltageHigh, std::isfinite(IBV_) && IBV_ > vHigh, IBV_, vHigh);
  // "VoltageAlarmLow (11 V, > 8 V floor)": a threshold at or under the floor disables the row.
  set(AlarmRow::VoltageLow, vLow > k::VOLTAGE_ALARM_LOW_FLOOR_V && std::isfinite(IBV_) && IBV_ < vLow, IBV_,
      vLow);
  const double currentAlarm = currentAlarmHighAmps(p_);
  set(AlarmRow::AltCurrentHigh, std::isfinite(MeasuredAmps_) && MeasuredAmps_ > currentAlarm, MeasuredAmps_,
      currentAlarm);
  set(AlarmRow::BatteryCurrentHigh, std::isfinite(Bcur_) && std::fabs(Bcur_) > p_.MaximumAllowedBatteryAmps,
      Bcur_, p_.MaximumAllowedBatteryAmps);
  set(AlarmRow::InaOvervoltage, flags_.inaOvervoltageLatched, IBV_, 0.0);
  set(AlarmRow::TempSensorDead, tempStaleRaw_, TempToUse_, k::TEMP_STALE_MS / 1000.0);
  set(AlarmRow::EfficiencyAnomaly, effAnomalyAlarmActive, 0.0, 0.0);
  set(AlarmRow::FaultMode, faultAlarm_, 0.0, 0.0);
  set(AlarmRow::TempTaskHung, flags_.tempTaskAlarm, 0.0, k::TEMP_TASK_TIMEOUT / 1000.0);
  set(AlarmRow::BmsStale, bmsStale_, 0.0, p_.BmsStaleS);
  set(AlarmRow::BmsMismatch, bmsMismatch_, 0.0, 0.0);
  set(AlarmRow::ChargingHeld, chargingHeld_, 0.0, 0.0);

  bool gated = false;
  for (std::size_t i = 0; i < kAlarmRowCount; ++i) {
    const auto r = static_cast<AlarmRow>(i);
    const bool counts = row[i] && (r == AlarmRow::TempTaskHung || p_.AlarmActivate);
    if (counts && r != AlarmRow::TempTaskHung) gated = true;
    // One console message per row per 30 s while it holds; the rows with an
    // event of their own (once per episode; a silent BMS its REASON_BMS_STALE
    // trip and clear) add none: a mismatch lasting hours is one incident.
    const bool ownEvent =
        r == AlarmRow::BmsMismatch || r == AlarmRow::ChargingHeld || r == AlarmRow::BmsStale;
    if (counts && !ownEvent &&
        (alarmMsgAt_[i] < 0 || now_ - alarmMsgAt_[i] >= fromMs(k::ALARM_MESSAGE_THROTTLE_MS))) {
      alarmMsgAt_[i] = now_;
      push(ev, EventCode::AlarmCondition, EventLevel::Warning, Reason::NONE, val[i], lim[i],
           static_cast<int>(i));
    }
    alarmRowOn_[i] = counts;
  }
  // TempTask hang sounds regardless of AlarmActivate.
  const bool cond = gated || row[static_cast<std::size_t>(AlarmRow::TempTaskHung)];
  if (p_.AlarmLatchEnabled && cond) alarmLatched_ = true;
  if (!p_.AlarmLatchEnabled) alarmLatched_ = false;
  updateAcknowledgement(cond);
  buzzer_ = (cond || alarmLatched_) && !ackActive_;
  // Log the buzzer's edges, but an alarm hovering on its threshold (the
  // buzzer follows it check by check) is one alarm: "Alarm OFF" only after
  // the buzzer stayed off for kEventClearHold.
  if (buzzer_) {
    buzzerOffSince_ = -1;
    if (!lastBuzzerEvent_) {
      lastBuzzerEvent_ = true;
      push(ev, EventCode::AlarmOn, EventLevel::Warning, Reason::NONE);
    }
  } else if (lastBuzzerEvent_) {
    if (buzzerOffSince_ < 0) buzzerOffSince_ = now_;
    if (now_ - buzzerOffSince_ >= fromMs(k::ALARM_MESSAGE_THROTTLE_MS)) {
      lastBuzzerEvent_ = false;
      buzzerOffSince_ = -1;
      push(ev, EventCode::AlarmOff, EventLevel::Info, Reason::NONE);
    }
  }
  return buzzer_;
}

// An acknowledgement silences the rows it saw; a new row sounds again, and it
// ends once all have been quiet for the message hold (30 s: a row hovering on
// its threshold stays acknowledged), so the next alarm is heard.
void ProtectionSupervisor::updateAcknowledgement(bool cond) noexcept {
  if (!ackActive_) return;
  for (std::size_t i = 0; i < kAlarmRowCount; ++i)
    if (alarmRowOn_[i] && !ackRows_[i]) ackActive_ = false;
  if (cond)
    ackQuietSince_ = -1;
  else if (ackQuietSince_ < 0)
    ackQuietSince_ = now_;
  if (ackQuietSince_ >= 0 && now_ - ackQuietSince_ >= fromMs(k::ALARM_MESSAGE_THROTTLE_MS))
    ackActive_ = false;
  if (ackActive_) alarmLatched_ = false;
}

}  // namespace xr
