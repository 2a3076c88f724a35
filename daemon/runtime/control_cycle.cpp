#include "runtime/control_cycle.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/dvcc_limits.h"
#include "core/freshness.h"
#include "runtime/fatal_guard.h"

namespace xr::rt {

ControlCycle::ControlCycle(ControlCore& core, const CycleDevices& devices, Handoffs& handoffs,
                           LoopStats& stats, const Clock& timing, CycleConfig config)
    : core_(core), dev_(devices), h_(handoffs), stats_(stats), timing_(timing), cfg_(config) {}

bool ControlCycle::onEvery(int ticks) const noexcept {
  return ticks <= 1 || tick_ % std::uint64_t(ticks) == 0;
}

void ControlCycle::applyPending() noexcept {
  // docs/architecture.md "Threads": Params are swapped whole between ticks, never mid-tick.
  if (h_.params.update()) {
    core_.setParams(h_.params.current());
    ++health_.paramSwaps;
  }
  Command c;
  for (int i = 0; i < cfg_.maxCommandsPerTick && h_.commands.pop(c); ++i) {
    const bool applied = core_.command(c);
    if (applied)
      ++health_.commandsApplied;
    else
      ++health_.commandsRejected;
    if (c.ackId != 0) h_.acks.post(c.ackId, applied);
  }
}

void ControlCycle::mergeSlowInputs() noexcept {
  mergeTemperature();
  mergeBatteryTemp();
  mergeVictron();
  mergeEngineRpm();
  // A BMS's limits: copied whole when posted; their stamp carries staleness.
  // A GX's DVCC limits join them, the lower of each winning (core/dvcc_limits.h).
  h_.bms.load(in_.bms);
  BmsLimits dvcc;
  h_.dvcc.load(dvcc);
  in_.bms = withDvcc(in_.bms, dvcc);
}

void ControlCycle::mergeTemperature() noexcept {
  TemperatureHandoff t;
  h_.temperature.load(t);
  in_.AlternatorTemperatureF.fresh = t.stamp != 0 && t.stamp != lastTempStamp_;
  if (t.stamp != 0) {
    in_.AlternatorTemperatureF.value = t.tempF;
    in_.AlternatorTemperatureF.stamp = t.stamp;
  }
  lastTempStamp_ = t.stamp;
  in_.tempTaskHeartbeat = t.heartbeat;
}

void ControlCycle::mergeBatteryTemp() noexcept {
  BatteryTempHandoff b;
  h_.batteryTemp.load(b);
  in_.batteryTempSource = b.source;
  in_.batteryTempC.fresh = b.stamp != 0 && b.stamp != lastBatteryTempStamp_;
  if (b.stamp != 0) {
    in_.batteryTempC.value = b.tempC;
    in_.batteryTempC.stamp = b.stamp;
  }
  lastBatteryTempStamp_ = b.stamp;
}

void ControlCycle::mergeVictron() noexcept {
  VictronHandoff v;
  h_.victron.load(v);
  const bool fresh = v.stamp != 0 && v.stamp != lastVictronStamp_;
  if (v.stamp != 0) {
    in_.VictronCurrent = Reading{v.currentA, v.stamp, fresh};
    in_.VictronVoltage = Reading{v.voltageV, v.stamp, fresh};
    in_.solarPowerW = Reading{v.solarW, v.stamp, fresh};
  }
  lastVictronStamp_ = v.stamp;
}

void ControlCycle::mergeEngineRpm() noexcept {
  EngineRpmHandoff r;
  h_.engineRpm.load(r);
  // The engine's speed as last heard, for the belt-slip check; the core judges its age.
  if (r.stamp != 0) in_.engineRpm = Reading{r.rpm, r.stamp, r.stamp != lastEngineRpmStamp_};
  if (cfg_.rpmFromN2k) {
    const bool heard = fresh::engineRpm(Reading{r.rpm, r.stamp, false}, in_.now);
    // A silent ECU reads like a tach with no pulses: 0 rpm, fresh each tick.
    in_.rpm = heard ? Reading{r.rpm, r.stamp, r.stamp != lastEngineRpmStamp_} : Reading{0.0, in_.now, true};
  }
  lastEngineRpmStamp_ = r.stamp;
}

void ControlCycle::readDiscreteInputs() noexcept {
  // A read error counts as the safe level: charging disabled / ignition off.
  in_.bmsChargeEnabled = dev_.bms ? dev_.bms->get() == 0 : true;
  in_.ignitionOn = dev_.ignition ? dev_.ignition->get() == 1 : true;
}

bool ControlCycle::writeOutputs(const Outputs& out) noexcept {
  const bool dying = fatal::dying();
  const bool enable = out.fieldEnable && !dying;
  double duty = dying ? 0.0 : out.dutyPct;
  if (!std::isfinite(duty)) duty = 0.0;
  duty = std::clamp(duty, 0.0, 100.0);
  bool ok = true;
  // Turning off: enable LOW before the duty. Turning on: duty before enable.
  if (!enable && (!outputsKnown_ || lastEnable_)) {
    if (dev_.fieldEnable->set(false))
      lastEnable_ = false;
    else
      ok = false;
  }
  if (!outputsKnown_ || duty != lastDuty_) {
    if (dev_.pwm->setDutyPercent(duty))
      lastDuty_ = duty;
    else
      ok = false;
  }
  if (enable && ok && (!outputsKnown_ || !lastEnable_)) {
    if (dev_.fieldEnable->set(true))
      lastEnable_ = true;
    else
      ok = false;
  }
  if (dev_.buzzer && (!outputsKnown_ || out.buzzer != lastBuzzer_)) {
    if (dev_.buzzer->set(out.buzzer)) lastBuzzer_ = out.buzzer;
    // A buzzer failure does not endanger the alternator: not a fault.
  }
  outputsKnown_ = ok;
  if (!ok) {
    ++health_.outputWriteErrors;
    driveSafeState();
  }
  return ok;
}

ControlCycle::PublishPlan ControlCycle::planPublish(TimeNs now) const noexcept {
  // The snapshot is stored on the tick's thinning grid (every tick while
  // stopping); a row is due on the row grid.
  PublishPlan p;
  p.store = onEvery(cfg_.publishEveryTicks) || stopping_;
  p.row = cfg_.rowPeriod > 0 && (!rowsStarted_ || now - lastRow_ >= cfg_.rowPeriod);
  p.summary = onEvery(kSummaryEveryTicks);
  return p;
}

void ControlCycle::storeSnapshot(const Outputs& out, TimeNs now) noexcept {
  if (dev_.truth) dev_.truth->fill(truth_);
  health_.eventsDropped = h_.events.dropped();
  health_.stopping = stopping_;
  RuntimeSnapshot& snap = scratch_;
  snap.tick = tick_;
  snap.start = start_;
  snap.telemetry = out.telemetry;
  snap.telemetry.now = now;
  snap.loop = summary_;
  snap.health = health_;
  snap.sim = truth_;
  h_.snapshot.store(snap);
}

void ControlCycle::publishLatest() noexcept {
  if (!lastOut_) return;
  summary_ = stats_.summary();
  storeSnapshot(*lastOut_, lastNow_);
}

void ControlCycle::publish(const Outputs& out, TimeNs now, PublishPlan plan) noexcept {
  lastOut_ = &out;
  lastNow_ = now;
  if (plan.summary) summary_ = stats_.summary();  // every kSummaryEveryTicks
  // The row carries this tick's state: it needs the snapshot even when the
  // thinned store would skip this tick.
  if (plan.store || plan.row) storeSnapshot(out, now);
  if (plan.row) publishRow(now);
}

void ControlCycle::publishRow(TimeNs now) noexcept {
  // Rows sit on the grid start + k·rowPeriod so t_s is regular.
  lastRow_ = rowsStarted_ ? lastRow_ + cfg_.rowPeriod * ((now - lastRow_) / cfg_.rowPeriod) : now;
  rowsStarted_ = true;
  RuntimeSnapshot snap = scratch_;
  snap.loop = stats_.summary();
  while (!h_.rows.push(snap)) {
    if (!cfg_.blockOnFullRows) {
      ++health_.rowsDropped;
      break;
    }
    std::this_thread::yield();  // --speed max only: not real time, the writer sets the pace
  }
}

bool ControlCycle::tick(TimeNs now) {
  if (dev_.hook) dev_.hook->beforeTick(now);
  applyPending();

  const bool timed = timedTick();
  const TimeNs t0 = timed ? timing_.now() : 0;
  in_.now = now;
  const bool sensorsOk = dev_.sensors->read(now, in_);
  if (!sensorsOk) ++health_.sensorReadErrors;
  mergeSlowInputs();
  readDiscreteInputs();
  const PublishPlan plan = planPublish(now);
  const TimeNs t1 = timed ? timing_.now() : 0;

  const Outputs& out = core_.step(in_);
  const TimeNs t2 = timed ? timing_.now() : 0;

  bool healthy = writeOutputs(out);
  dev_.sensors->apply(out);
  if (timed) {
    const TimeNs t3 = timing_.now();
    stats_.onIo((t1 - t0) + (t3 - t2));
    stats_.onCompute(t2 - t1);
  }
  stats_.onTick();
  if (const SampleCounts* counts = dev_.sensors->sampleCounts()) {
    health_.adsEdgeFallback = counts->readyEdgeFallback;
    stats_.onSampleTotals(now, counts->ads, in_.IBV.fresh);
  } else {
    freshTotals_[0] += in_.BatteryV.fresh;
    freshTotals_[1] += in_.altCurrentRaw.fresh;
    freshTotals_[2] += in_.rpm.fresh;
    freshTotals_[3] += in_.thermistorF.fresh;
    stats_.onSampleTotals(now, freshTotals_, in_.IBV.fresh);
  }

  // A stalled or failing loop must lead to a reset: feed only when healthy.
  if (healthy && dev_.watchdog) {
    if (dev_.watchdog->keepAlive()) ++health_.watchdogFeeds;
  }
  h_.events.pushBatch(out.events);
  const bool ledgerDue = onEvery(kLedgerEveryTicks);
  ++tick_;
  if (ledgerDue) {
    BatteryLedger l;
    if (core_.ledger(l)) h_.ledger.store(l);
  }
  publish(out, now, plan);
  return healthy && sensorsOk;
}

void ControlCycle::serviceEdges(TimeNs deadline) noexcept {
  if (!dev_.adsReady) return;
  const bool timed = timedTick();
  // Bounded: at 860 SPS a 2.5 ms period holds 2-3 edges; a storm of
  // spurious edges must not starve the tick.
  for (int i = 0; i < kMaxEdgesPerPeriod; ++i) {
    TimeNs stamp = 0;
    const int rc = dev_.adsReady->waitEdge(deadline, &stamp);
    if (rc < 0) ++health_.edgeErrors;
    if (rc != 1) return;
    stats_.onEdge();
    if (timed) {
      const TimeNs t0 = timing_.now();
      dev_.sensors->onReadyEdge(stamp);
      stats_.onEdgeIo(timing_.now() - t0);
    } else {
      dev_.sensors->onReadyEdge(stamp);
    }
  }
}

void ControlCycle::beginShutdown() noexcept {
  stopping_ = true;
  Command off;
  off.type = CommandType::Off;
  core_.command(off);
}

void ControlCycle::driveSafeState() noexcept {
  // Enable LOW first: it cuts the field even when the PWM write fails.
  const bool enOk = dev_.fieldEnable->set(false);
  const bool pwmOk = dev_.pwm->setDutyPercent(0.0);
  if (dev_.buzzer) dev_.buzzer->set(false);
  lastEnable_ = !enOk;  // unknown → assume still on so we retry
  lastDuty_ = pwmOk ? 0.0 : 100.0;
  lastBuzzer_ = false;
  outputsKnown_ = enOk && pwmOk;
}

}  // namespace xr::rt
