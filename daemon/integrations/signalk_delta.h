#pragma once
// Signal K deltas (docs/integrations.md; Signal K specification 1.7, "Delta format" and
// the electrical.alternators / electrical.batteries schema). Pure: the paths,
// SI units and the JSON text, from one sample, so tests can check them
// without a server.
//
//   electrical.alternators.<id>.{voltage V, current A, temperature K,
//     revolutions Hz, fieldDrive ratio, chargingMode, setpointVoltage V,
//     setpointCurrent A}
//   electrical.batteries.<id>.{voltage V, current A, temperature K,
//     capacity.stateOfCharge ratio, capacity.timeRemaining s}
#include <string>
#include <vector>

#include "integrations/integration_sample.h"

namespace xr::integrations {

struct SignalKValue {
  std::string path;
  double number = 0.0;  // when text is empty
  std::string text;     // chargingMode
  bool isText = false;
};

struct SignalKMeta {
  std::string path, units, displayName, description;
};

// The values of one sample in SI units. A value that is not known (NaN, a
// temperature that is not measured) is left out rather than sent as 0.
std::vector<SignalKValue> signalKValues(const IntegrationSample& s, const std::string& alternatorId,
                                        const std::string& batteryId);

// Units and display names, sent once per connection.
std::vector<SignalKMeta> signalKMeta(const std::string& alternatorId, const std::string& batteryId);

// Delta documents ({"context":"vessels.self","updates":[...]}).
std::string signalKDelta(const std::vector<SignalKValue>& values, const std::string& isoTime);
std::string signalKMetaDelta(const std::vector<SignalKMeta>& meta);

// "2026-12-03T14:05:00.123Z" for a Unix time in milliseconds.
std::string isoTimeUtc(long long unixMs);

}  // namespace xr::integrations
