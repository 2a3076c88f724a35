// CanService (see can_service.h).
#include "canlink/can_service.h"

#include <cmath>

#include "can/n2k_position.h"

namespace xr::canlink {

namespace {
constexpr int kBmsBus = 0, kN2kBus = 1;  // the CAN events' detail
}  // namespace

BusSlot::Fault CanService::faultEvents(int bus) {
  return [this, bus](bool back, std::uint64_t failures, double retryS, TimeNs now) {
    h_.sideEvents.post(makeEvent(now, back ? EventLevel::Info : EventLevel::Error,
                                 back ? EventCode::CanBusBack : EventCode::CanBusDown, Reason::NONE,
                                 static_cast<double>(failures), retryS, bus));
  };
}

void CanService::setBmsBus(std::unique_ptr<BusSlot> slot, can::BmsProtocol protocol, bool batteryTemp) {
  bms_ = std::move(slot);
  if (bms_) bms_->onFault(faultEvents(kBmsBus));
  protocol_ = protocol;
  batteryTemp_ = batteryTemp;
  bmsLink_.reset();
  // Configured, not heard yet: the control law follows this source from now
  // on, so its silence goes stale after BmsStaleS (docs/integrations.md).
  if (bms_) {
    BmsLimits configured;
    configured.source = BmsSource::Can;
    h_.bms.store(configured);
  }
  bmsRecorded_.reset();
}

void CanService::setN2kBus(std::unique_ptr<BusSlot> slot, std::uint8_t preferredAddress,
                           std::string version) {
  n2k_ = std::move(slot);
  if (n2k_) n2k_->onFault(faultEvents(kN2kBus));
  n2kAddress_ = preferredAddress;
  version_ = std::move(version);
  n2kNode_.reset();
  n2kRecorded_.reset();
}

void CanService::poll(TimeNs now) {
  pollNow_ = now;
  if (bms_) {
    CanBus* bus = bms_->get(now);
    if (bms_->takeOpened() && bus) {
      // A (re)opened bus: the decoder starts over. The limits posted before
      // keep their stamp in the hand-off and go stale on their own.
      if (sink_) {
        bmsRecorded_ = std::make_unique<can::RecordingCanBus>(*bus, bms_->interface(), *sink_);
        bus = bmsRecorded_.get();
      }
      bmsLink_ = std::make_unique<BmsCanLink>(
          *bus, protocol_, bms_->interface(),
          [this](const BmsLimits& l) {
            h_.bms.store(l);
            if (batteryTemp_ && std::isfinite(l.tempC)) {
              rt::BatteryTempHandoff t;
              t.tempC = l.tempC;
              t.stamp = pollNow_;  // posted in the poll the frames arrived in
              t.source = BatteryTempSource::bms;
              h_.batteryTemp.store(t);
            }
          },
          report_);
      bmsLink_->setPostEvent([this](const Event& e) { h_.sideEvents.post(e); });
    }
    if (bus && bmsLink_) bmsLink_->poll(now);
  }
  if (n2k_) {
    CanBus* bus = n2k_->get(now);
    if (n2k_->takeOpened() && bus) {
      // A (re)opened bus: claim an address again before anything else.
      if (sink_) {
        n2kRecorded_ = std::make_unique<can::RecordingCanBus>(*bus, n2k_->interface(), *sink_);
        bus = n2kRecorded_.get();
      }
      n2kNode_ = std::make_unique<N2kNode>(*bus, n2kAddress_, h_, version_);
      // Engine speed (127488 or J1939 61444) for RpmSource = n2k; engine
      // instance 0 (the single or port engine).
      n2kNode_->onMessage([this](const can::N2kMessage& m, TimeNs at) {
        if (auto s = can::decodeEngineSpeed(m); s && s->instance == 0) h_.engineRpm.store({s->rpm, at});
        // The position, for the weather forecast; any GNSS on the bus.
        if (auto p = can::decodePosition(m)) h_.n2kPosition.store({p->latitudeDeg, p->longitudeDeg, at});
      });
    }
    if (bus && n2kNode_) {
      n2kNode_->poll(now);
      if (const std::uint64_t n = n2kErrorGate_.due(n2kNode_->errorFrames(), now))
        h_.sideEvents.post(makeEvent(now, EventLevel::Warning, EventCode::CanErrorFrames, Reason::NONE,
                                     static_cast<double>(n), n2kNode_->lastErrorClass(), kN2kBus));
    }
  }
  publishStatus(now);
}

void CanService::publishStatus(TimeNs now) {
  rt::CanStatusHandoff st;
  st.now = now;
  if (bms_) {
    st.bmsConfigured = true;
    st.bmsBusUp = bms_->up();
    st.bmsProtocol = static_cast<std::uint8_t>(protocol_);
    st.bmsOpenFailures = bms_->failures();
    if (bmsLink_) {
      st.bmsLastFrame = bmsLink_->lastAccepted();
      st.bmsLimits = bmsLink_->decoder().limits();
      st.bmsFrames = bmsLink_->decoder().accepted();
      st.bmsBadFrames = bmsLink_->decoder().rejected();
      st.bmsErrorFrames = bmsLink_->errorFrames();
    }
  }
  if (n2k_) {
    st.n2kConfigured = true;
    st.n2kBusUp = n2k_->up();
    st.n2kOpenFailures = n2k_->failures();
    if (n2kNode_) {
      st.n2kClaimed = n2kNode_->claimed();
      st.n2kAddress = n2kNode_->address();
      st.n2kTxFrames = n2kNode_->txFrames();
      st.n2kRxFrames = n2kNode_->rxFrames();
      st.n2kErrorFrames = n2kNode_->errorFrames();
    }
  }
  h_.canStatus.store(st);
}

}  // namespace xr::canlink
