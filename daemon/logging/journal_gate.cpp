#include "logging/journal_gate.h"

namespace xr::logging {

bool JournalGate::pass(const Event& e) {
  switch (e.code) {
    case EventCode::AlarmOn:
      return false;  // the row's own "ALARM: ..." line, written in the same tick, says it
    case EventCode::AlarmOff:
      alarmRowsSaid_.reset();  // the next episode names its rows again
      return true;
    case EventCode::ImmediateCut:
      cutReason_ = e.reason;
      return true;
    case EventCode::FieldOff: {
      // "GPIO4 immediate cut: X" already said the field went off for X.
      const bool saidByCut = e.reason != Reason::NONE && e.reason == cutReason_;
      cutReason_ = Reason::NONE;
      return !saidByCut;
    }
    case EventCode::AlarmCondition: {
      if (e.detail < 0 || static_cast<std::size_t>(e.detail) >= kRows) return true;
      const auto row = static_cast<std::size_t>(e.detail);
      if (alarmRowsSaid_.test(row)) return false;
      alarmRowsSaid_.set(row);
      return true;
    }
    case EventCode::ModeChanged:
      limpHomeSaid_ = false;
      return true;
    case EventCode::LimpHomeActive:
      if (limpHomeSaid_) return false;
      limpHomeSaid_ = true;
      return true;
    default:
      return true;
  }
}

}  // namespace xr::logging
