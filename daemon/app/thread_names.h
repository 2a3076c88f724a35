#pragma once
// Thread names shown by top -H / ps -L (15 characters at most).
#include "runtime/rt_setup.h"

namespace xr::app {
inline void nameThisThread(const char* name) { rt::setThreadName(name); }
}  // namespace xr::app
