#pragma once
// The daemon's side of the web API (app/web_api.cpp) with its hand-offs, an
// optional store and the recent-events ring, as daemon.cpp wires them; shared
// by the app tests that drive WebApi directly.
#include <memory>
#include <string>

#include "app/store_service.h"
#include "app/web_api.h"

namespace xr::app::test {

struct WebApiRig {
  Params params;
  rt::Handoffs handoffs{params};
  std::unique_ptr<StoreService> store;
  RecentEvents recent;
  std::unique_ptr<WebApi> api;
  // setUp: as a file that names the battery type (most tests); false: a
  // fresh install, whose PATCHes start from `params` unlowered, as in the
  // daemon (docs/configuration.md "Not set up").
  explicit WebApiRig(const std::string& db = {}, bool setUp = true) {
    if (!db.empty()) store = std::make_unique<StoreService>(db, 300);
    WebApiContext ctx;
    ctx.origins.assumeSetUp = setUp;
    if (!setUp) {
      ctx.configured = params;
      handoffs.submitParams(runningParams(params, ctx.origins));
    }
    ctx.handoffs = &handoffs;
    ctx.store = store.get();
    ctx.events = &recent;
    api = std::make_unique<WebApi>(ctx);
  }
  ~WebApiRig() {
    if (store) store->stop(BatteryLedger{}, false);
  }
};

}  // namespace xr::app::test
