#pragma once
// FastOvVerdict: what the fast over-voltage supervisors ask of the control
// law on one AUTO tick (docs/protections.md "Fast over-voltage"). Protection
// decides it, control applies it as it stands; the type sits here so that
// neither layer needs the other's types.
namespace xr {

// What to do with the CV integrator cv_I this tick.
enum class CvIAction { None, Snap, Bleed, Reseed };

struct FastOvVerdict {
  double fastOvCurrentCap = 1e300;        // clamp on uTargetAmps (1e300: no clamp asked)
  bool fastOvClampActive = false;         // a supervisor clamps the request this tick
  CvIAction cvIAction = CvIAction::None;  // Snap, Bleed or Reseed cv_I ...
  double cv_I = 0.0;                      // ... to this value
  bool forceBypassSlew = false;           // govMode = GOV_BYPASS_SLEW this tick
  bool zeroSetpointLimited = false;       // load dump: setpointLimited = 0
};

}  // namespace xr
