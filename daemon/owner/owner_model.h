#pragma once
// The owner model (docs/dashboard.md "Owner model"): what the regulator is
// doing, the one number that matters now, the state of charge with its
// source, the BMS's state, and every limit acting now with its amps and its
// cause in plain words. Computed once per frame from the telemetry, by this
// one function, for every reader: /api/status and the WebSocket frame, Home
// Assistant and Signal K. No page re-derives it.
//
// Pure: a function of the telemetry and what the daemon knows beside it
// (whether a battery type was chosen). Off the control thread (it makes text).
#include <string>
#include <string_view>
#include <vector>

#include "control/telemetry.h"

namespace xr::owner {

// What the telemetry does not carry.
struct OwnerContext {
  bool setUp = true;        // a battery type is chosen (docs/configuration.md "Not set up")
  std::string setupLimits;  // the limits while not set up, "at most 14.0 V, float 13.4 V, ..."
};

// One limit acting now. amps: the cap in amps (NaN when the limit is not a
// current, e.g. manual mode or the not-set-up voltages); id: a stable name
// for programs ("battery_temp_required"); what/why: the owner's words.
struct OwnerLimit {
  std::string id;
  std::string what;
  double amps = kNoValue;
  std::string why;
};

struct OwnerSoc {
  double pct = kNoValue;                // NaN while unknown
  std::string_view source = "unknown";  // bms | counted | ocv_estimate | unknown
};

struct OwnerHero {
  double value = kNoValue;
  std::string unit;
  std::string label;
};

struct OwnerBms {
  std::string_view state = "none";  // none | talking | warning | no_charge | silent
  std::string words;                // "talking (CAN)", "no BMS"
};

struct OwnerModel {
  std::string state;  // "Charging · Bulk", "Not charging · Engine stopped or idling"
  OwnerHero hero;
  OwnerSoc soc;
  OwnerBms bms;
  std::vector<OwnerLimit> limits;  // most restrictive first
  // One calm notice beside the state, "" when none: not set up, what the
  // bank reads and which size to choose (setupBankNotice).
  std::string notice;
};

OwnerModel ownerModel(const Telemetry& t, const OwnerContext& ctx = {});

// The one SoC rule: a talking BMS's SoC, else the counted SoC, else the
// rested-voltage estimate, else unknown (no number).
OwnerSoc ownerSoc(const Telemetry& t);

// Not set up, the bank class read from the battery (docs/configuration.md
// "Not set up"): "The bank reads 26.1 V: choose 24 V on the set-up page.";
// a reading that fits no bank says the 12 V limits stay. "" when the class
// was not read.
std::string setupBankNotice(const Telemetry::SetupBank& b);

// "Battery too cold to charge" for REASON_BATTERY_COLD; "" for NONE.
std::string_view reasonTitle(Reason r);

// "Bulk", "Absorption", "Float", "Resting".
std::string_view stageWord(ChargeStage s);

// Every limit acting now, most restrictive first (owner_limits.cpp).
std::vector<OwnerLimit> ownerLimits(const Telemetry& t, const OwnerContext& ctx);

// The first limit's words for one-line readers ("C/10 without a battery
// probe: 28 A"), or "nothing" when none acts.
std::string limitedByText(const OwnerModel& m);

}  // namespace xr::owner
