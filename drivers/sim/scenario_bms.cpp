// The simulated CAN devices in a scenario file (docs/integrations.md): the [bms] table,
// the bms_* event keys and the engine ECU's ecu key. Errors name file:line: like every other scenario key.
#include "drivers/sim/scenario_toml.h"

namespace xr::sim::scenario_toml {

namespace {

// A forced limit: a number within [lo, hi], or "auto" (< 0: the BMS's own).
double forcedLimit(const Ctx& c, const toml::key& k, const toml::node& v, double lo, double hi) {
  if (v.is_string()) {
    if (*v.value<std::string>() == "auto") return -1.0;
    c.fail(lineOf(v), std::string(k.str()) + " must be a number or \"auto\"");
  }
  return number(c, k, v, lo, hi);
}

}  // namespace

void parseBms(const Ctx& c, const toml::table& t, ScenarioBms& b) {
  for (auto&& [k, v] : t) {
    const auto n = k.str();
    if (n == "can") {
      if (!v.is_boolean()) c.fail(lineOf(v), "[bms] can must be true or false");
      b.can = *v.value<bool>();
    } else if (n == "protocol") {
      const auto s = text(c, k, v);
      if (s != "victron" && s != "pylontech" && s != "rec")
        c.fail(lineOf(v), "[bms] protocol must be \"victron\", \"pylontech\" or \"rec\"");
      b.protocol = s;
    } else if (n == "cells") {
      b.cells = static_cast<int>(number(c, k, v, 1.0, 32.0));
      if (b.cells != *v.value<double>()) c.fail(lineOf(v), "[bms] cells must be a whole number");
    } else if (n == "cvl_v") {
      b.cvl_v = number(c, k, v, 8.0, 70.0);
    } else if (n == "ccl_max_a") {
      b.ccl_max_a = number(c, k, v, 0.0, 2000.0);
    } else if (n == "open_after_s") {
      b.open_after_s = number(c, k, v, 0.1, 600.0);
    } else if (n == "cell_spread_v") {
      b.cell_spread_v = number(c, k, v, 0.0, 0.5);
    } else {
      unknownKey(c, k, "[bms]");
    }
  }
}

bool parseBmsEventKey(const Ctx& c, const toml::key& k, const toml::node& v, ScenarioEvent& e) {
  const auto n = k.str();
  if (n == "bms_can") {
    const auto s = text(c, k, v);
    if (s == "talking")
      e.bms_can = BmsCanMode::Talking;
    else if (s == "silent")
      e.bms_can = BmsCanMode::Silent;
    else if (s == "short_frames")
      e.bms_can = BmsCanMode::ShortFrames;
    else
      c.fail(lineOf(v), "bms_can must be \"talking\", \"silent\" or \"short_frames\"");
  } else if (n == "bms_ccl_a") {
    // Up to 6000 A on purpose: the daemon must reject a CCL its decoder
    // finds implausible (bms_codec.h kMaxCclA), and a scenario proves it.
    e.bms_ccl_a = forcedLimit(c, k, v, 0.0, 6000.0);
  } else if (n == "bms_cvl_v") {
    e.bms_cvl_v = forcedLimit(c, k, v, 0.0, 100.0);
  } else if (n == "ecu") {
    const auto s = text(c, k, v);
    if (s != "talking" && s != "silent") c.fail(lineOf(v), "ecu must be \"talking\" or \"silent\"");
    e.ecu_talking = s == "talking";
  } else if (n == "bms_warn") {
    const auto s = text(c, k, v);
    if (s != "high_voltage" && s != "none")
      c.fail(lineOf(v), "bms_warn must be \"high_voltage\" or \"none\"");
    e.bms_warn = s == "high_voltage";
  } else {
    return false;
  }
  return true;
}

void checkBmsEvents(const Ctx& c, const Scenario& s) {
  for (const auto& e : s.events) {
    if (!s.bms.can && (e.bms_can || e.bms_ccl_a || e.bms_cvl_v || e.bms_warn))
      c.fail(e.line, "bms_* events need a simulated BMS on CAN ([bms] can = true)");
    if (!s.engine_ecu && e.ecu_talking)
      c.fail(e.line, "ecu events need a simulated engine ECU ([engine] ecu = true)");
  }
}

}  // namespace xr::sim::scenario_toml
