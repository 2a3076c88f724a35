#pragma once
// The chart sample the runtime appends once a second: telemetry values in
// defaultHistorySeries() order (ibv_v, bcur_a, alt_a, soc_pct, temp_f,
// duty_pct, rpm, target_v).
#include <array>

#include "core/telemetry.h"

namespace xr {

inline std::array<double, 8> historyValues(const Telemetry& t) {
  return {t.ibv_v, t.bcur_a, t.alt_a, t.soc_pct, t.temp_f, t.duty_pct, t.rpm, t.target_v};
}

}  // namespace xr
