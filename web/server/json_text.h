#pragma once
// The one JSON writer of the web API. Boost.JSON writes every double in
// exponent form ("1.301E1"); an owner reading /api/status in a browser, a
// shell script with jq or a spreadsheet import wants "13.01". Every JSON
// route (api_reply.cpp) and the WebSocket frames (serializeStatus) go through
// jsonText, so no route can forget (docs/dashboard.md, "Numbers").
#include <boost/json.hpp>
#include <string>

namespace xr::web {

// `v` as compact JSON text, doubles as plain decimals (the shortest text that
// reads back as the same double, never an exponent); non-finite doubles,
// which JSON cannot carry, as null.
std::string jsonText(const boost::json::value& v);

// Appends one double as jsonText writes it.
void appendJsonNumber(std::string& out, double v);

}  // namespace xr::web
