#pragma once
// OperatorCommands: what the owner asked of the field from the dashboard,
// the API or MQTT (docs/operations.md "Commands"): automatic, a manual duty,
// off, Limp Home, and the weather mode's forecast. Mode selection reads them
// each tick; nothing else writes them.
#include <optional>

#include "core/commands.h"
#include "params/params.h"

namespace xr {

class OperatorCommands {
 public:
  // Applies the command when it is one of these; returns whether it was
  // legal, or nothing when the command belongs to another part.
  std::optional<bool> apply(const Command& cmd) noexcept;

  // ManualMode in the parameters or the operator's manual command.
  bool manualMode(const Params& p) const noexcept { return p.ManualMode || manual_; }
  // The duty MANUAL drives: the operator's, else ManualDutyTarget.
  double manualDuty(const Params& p) const noexcept { return manual_ ? manualDuty_ : p.ManualDutyTarget; }
  bool operatorManual() const noexcept { return manual_; }
  bool off() const noexcept { return off_; }
  bool limpHome() const noexcept { return limpHome_; }
  bool weatherMode() const noexcept { return weatherMode_; }

 private:
  bool limpHome_ = false;     // Limp Home asked (a fixed duty, no loops)
  bool manual_ = false;       // the operator's manual command holds
  double manualDuty_ = 0.0;   // ... at this duty (%)
  bool off_ = false;          // the operator turned the field off
  bool weatherMode_ = false;  // the forecast says the sun will charge (docs/integrations.md "Weather")
};

}  // namespace xr
