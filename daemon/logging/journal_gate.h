#pragma once
// Which events reach the journal (docs/operations.md "The journal"): the
// journal says what changed, once. The store and the dashboard still get
// every event; only the repeats of a condition that has not changed stay out
// of the journal:
//   - AlarmCondition, which the core repeats every 30 s per buzzer row while
//     the row holds: the first of each row per alarm episode (AlarmOn ..
//     AlarmOff), so a fault gives one alarm line per row, not one a second at
//     a simulated speed or 120 an hour at speed 1;
//   - LimpHomeActive, repeated every 30 s: the first until the mode changes.
//   - AlarmOn, which comes in the tick of the row's first "ALARM:" line;
//   - the FieldOff that follows an immediate cut for the same reason.
// Everything else passes. One gate per journal sink, used on the event
// thread only.
#include <bitset>

#include "core/events.h"

namespace xr::logging {

class JournalGate {
 public:
  static constexpr std::size_t kRows = 32;  // more than any AlarmRow
  bool pass(const Event& e);

 private:
  std::bitset<kRows> alarmRowsSaid_;
  bool limpHomeSaid_ = false;
  Reason cutReason_ = Reason::NONE;  // the last immediate cut, until its FieldOff
};

}  // namespace xr::logging
