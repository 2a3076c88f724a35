#pragma once
// The CAN service's status (Handoffs::canStatus) in the words /api/system
// uses (docs/integrations.md). Pure: no clock is read, `st.now` is when it was written.
//   bms.state  off        no BMS bus configured
//              bus_error  configured, but the interface is not open
//              silent     open, no good frame for kSilentS
//              talking    a good frame within kSilentS
//   n2k.state  off | bus_error | no_address (every address lost) | claimed
#include "runtime/handoffs.h"
#include "web/server/daemon_api.h"

namespace xr::app {

// The BMS sends every 0.5-1 s; 5 s without one is BmsStaleS's default.
inline constexpr double kBmsSilentS = 5.0;

// followBms: BmsLimitsEnabled in force (false = monitor only).
web::CanState canStateOf(const rt::CanStatusHandoff& st, bool followBms);

}  // namespace xr::app
