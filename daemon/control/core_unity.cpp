// The whole pure core (control law, protections, battery monitor) as ONE
// translation unit: Regulator::step calls into every part each tick, and
// without LTO GCC can only inline across these calls when it sees their
// bodies. xr_protection and xr_battery stay separate libraries for their own
// tests; xr_control does not link them (it contains them).
#include "battery/battery_auto_zero.cpp"
#include "battery/battery_monitor.cpp"
#include "battery/battery_soc.cpp"
#include "control/charging_stage.cpp"
#include "control/control_law.cpp"
#include "control/cv_loop.cpp"
#include "control/cv_tuning_mode.cpp"
#include "control/governor.cpp"
#include "control/pid.cpp"
#include "control/regulator.cpp"
#include "control/system_id.cpp"
#include "control/thermal_derate.cpp"
#include "control/tuning_mode.cpp"
#include "protection/alarms.cpp"
#include "protection/detectors.cpp"
#include "protection/fast_ov.cpp"
#include "protection/mode_selection.cpp"
#include "protection/protection_supervisor.cpp"
#include "protection/shutdown_sequencer.cpp"
