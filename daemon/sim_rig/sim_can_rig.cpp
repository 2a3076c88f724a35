// SimCanRig (see sim_can_rig.h).
#include "sim_rig/sim_can_rig.h"

#include <utility>

#include "can/n2k_position.h"

namespace xr::sim {
namespace {
constexpr double kEcuPeriodS = 0.1;  // 127488 is a rapid-update PGN
constexpr double kGpsPeriodS = 1.0;  // 129029's default interval in the canboat database
constexpr std::uint8_t kGpsSource = 1;
}  // namespace

SimCanRig::SimCanRig(const Scenario& scenario, const CanSettings& settings, rt::Handoffs& handoffs,
                     TimeNs start, std::ostream* log, Report report, bool bmsBatteryTemp)
    : bmsNode_(bmsSegment_.attach()),
      ourNode_(bmsSegment_.attach()),
      ourN2kNode_(n2kSegment_.attach()),
      ecuNode_(n2kSegment_.attach()),
      gpsNode_(n2kSegment_.attach()),
      ecu_(scenario.engine_ecu),
      gps_(scenario.gps),
      simBms_(scenario.bms.can),
      service_(handoffs, std::move(report)),
      nextStep_(start),
      start_(start) {
  // The BMS follows the bank (docs/simulator.md "[bms]"): its cells from
  // [bms] cells, else the plant's (resolved at the first step), its CVL
  // from its cells unless the scenario sets one.
  bms_.cells = scenario.bms.cells;
  bms_.cvlV = scenario.bms.cvl_v;
  bms_.cclMaxA = scenario.bms.ccl_max_a;
  bms_.openAfterS = scenario.bms.open_after_s;
  bms_.pylontech = scenario.bms.protocol == "pylontech";
  bms_.rec = scenario.bms.protocol == "rec";
  bms_.cellSpreadV = scenario.bms.cell_spread_v;
  if (log) {
    // Virtual time since the start of the run: the same seed writes the
    // same log.
    sink_ = std::make_unique<can::CandumpSink>(*log, [this] { return toSec(now_ - start_); });
    service_.setLog(sink_.get());
  }
  if (simBms_)
    service_.setBmsBus(std::make_unique<canlink::BusSlot>(kSimBmsInterface, ourNode_),
                       can::parseBmsProtocol(scenario.bms.protocol).value_or(can::BmsProtocol::Victron),
                       bmsBatteryTemp);
  if (!settings.n2k_interface.empty())
    service_.setN2kBus(std::make_unique<canlink::BusSlot>(kSimN2kInterface, ourN2kNode_),
                       static_cast<std::uint8_t>(settings.n2k_preferred_address), "simulation");
}

void SimCanRig::apply(const ScenarioEvent& e) {
  if (e.bms_can) {
    bms_.talking = *e.bms_can != BmsCanMode::Silent;
    bms_.shortFrames = *e.bms_can == BmsCanMode::ShortFrames;
  }
  if (e.bms_ccl_a) bms_.forcedCclA = *e.bms_ccl_a;
  if (e.bms_cvl_v) bms_.forcedCvlV = *e.bms_cvl_v;
  if (e.bms_warn) bms_.forcedWarning = *e.bms_warn;
  if (e.ecu_talking) ecuTalking_ = *e.ecu_talking;
}

void SimCanRig::step(TimeNs now, Plant& plant) {
  if (now < nextStep_) return;
  now_ = now;
  while (nextStep_ <= now) nextStep_ += fromSec(canlink::CanService::kPollPeriodS);
  if (simBms_) {
    if (bms_.cells <= 0) bms_.cells = plant.battery().cells();
    if (bms_.cvlV <= 0.0) bms_.cvlV = bms_.cells * ScenarioBms::kCellCvlV;
    const PlantTruth& t = plant.truth();
    // A scenario's bms = "connect" closes what the BMS opened.
    if (bms_.contactorOpen() && t.bms_connected) bms_.closeContactor();
    SimBmsTruth truth;
    truth.batteryV = t.battery_v;
    truth.batteryA = t.bms_connected ? t.battery_a : 0.0;
    truth.socPct = t.soc_pct;
    truth.tempC = t.battery_temp_c;
    for (const CanFrame& f : bms_.step(now, truth)) bmsNode_.send(f);
    if (bms_.contactorOpen() && t.bms_connected) plant.setBmsConnected(false);
  }
  if (ecu_ && ecuTalking_ && now >= nextEcu_) {
    nextEcu_ = now + fromSec(kEcuPeriodS);
    for (const CanFrame& f : can::toFrames(can::engineRapid(0, 0, plant.rpm()), 0)) ecuNode_.send(f);
  }
  if (gps_.enabled && now >= nextGps_) {
    nextGps_ = now + fromSec(kGpsPeriodS);
    const can::N2kMessage m = gps_.pgn == 129025
                                  ? can::positionRapid(kGpsSource, gps_.latitude, gps_.longitude)
                                  : can::gnssPosition(kGpsSource, gpsSid_++, gps_.latitude, gps_.longitude);
    for (const CanFrame& f : can::toFrames(m, gpsSid_ & 0x7)) gpsNode_.send(f);
  }
  service_.poll(now);
}

}  // namespace xr::sim
