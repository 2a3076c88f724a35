// CAN status for /api/system (see can_status.h).
#include "app/can_status.h"

#include <cmath>

#include "can/bms_codec.h"

namespace xr::app {

web::CanState canStateOf(const rt::CanStatusHandoff& st, bool followBms) {
  web::CanState c;
  if (st.bmsConfigured) {
    auto& b = c.bms;
    b.follow = followBms;
    b.protocol = std::string(can::toString(static_cast<can::BmsProtocol>(st.bmsProtocol)));
    if (!st.bmsBusUp)
      b.state = "bus_error";
    else if (st.bmsLastFrame != 0 && st.now - st.bmsLastFrame <= fromSec(kBmsSilentS))
      b.state = "talking";
    else
      b.state = "silent";
    // The last values the BMS sent and the decoder accepted; NaN (null) when
    // it has sent none.
    b.cvl_v = st.bmsLimits.cvlV;
    b.ccl_a = st.bmsLimits.cclA;
    b.soc_pct = st.bmsLimits.socPct;
    b.cell_max_v = st.bmsLimits.cellMaxV;
    if (st.bmsLimits.stamp != 0) b.age_s = toSec(st.now - st.bmsLimits.stamp);
    b.frames = st.bmsFrames;
    b.bad_frames = st.bmsBadFrames;
    b.error_frames = st.bmsErrorFrames;
    b.open_failures = st.bmsOpenFailures;
  }
  if (st.n2kConfigured) {
    auto& n = c.n2k;
    n.state = !st.n2kBusUp ? "bus_error" : (st.n2kClaimed ? "claimed" : "no_address");
    n.claimed = st.n2kBusUp && st.n2kClaimed;
    if (n.claimed) n.address = st.n2kAddress;
    n.tx_frames = st.n2kTxFrames;
    n.rx_frames = st.n2kRxFrames;
    n.error_frames = st.n2kErrorFrames;
    n.open_failures = st.n2kOpenFailures;
  }
  return c;
}

}  // namespace xr::app
