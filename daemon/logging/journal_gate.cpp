#include "logging/journal_gate.h"

namespace xr::logging {

bool JournalGate::pass(const Event& e) {
  switch (e.code) {
    case EventCode::AlarmOn:
    case EventCode::AlarmOff:
      alarmRowsSaid_.reset();  // a new episode names its rows again
      return true;
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
