// The telemetry CSV tells the same SoC as every screen (docs/operations.md):
// the shown SoC, and an empty cell while it is not known, never the
// start-up guess as if it were a measurement.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "app/csv_writer.h"

namespace xr::app {
namespace {

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string c;
  while (std::getline(ss, c, ',')) out.push_back(c);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::string socCell(const rt::RuntimeSnapshot& s) {
  const auto head = cells(CsvWriter::header(false));
  std::string row = CsvWriter::row(s, false);
  while (!row.empty() && (row.back() == '\n' || row.back() == '\r')) row.pop_back();
  const auto vals = cells(row);
  for (std::size_t i = 0; i < head.size(); ++i)
    if (head[i] == "soc_pct" || head[i] == "soc_pct\n") return i < vals.size() ? vals[i] : "<missing>";
  return "<no soc_pct column>";
}

TEST(CsvSoc, TheSocCellIsEmptyWhileTheSocIsUnknown) {
  rt::RuntimeSnapshot s;
  s.telemetry.soc_pct = 100.0;  // the counter's start-up guess
  s.telemetry.battery.socSource = SocSource::Unknown;
  EXPECT_EQ(socCell(s), "");
}

TEST(CsvSoc, TheSocCellIsTheShownSoc) {
  rt::RuntimeSnapshot s;
  s.telemetry.soc_pct = 62.5;
  s.telemetry.battery.socSource = SocSource::Counted;
  EXPECT_EQ(socCell(s), "62.5");
  s.telemetry.bms_state = BmsState::OK;  // a BMS talking: its SoC is the one shown
  s.telemetry.bms_soc_pct = 40.0;
  EXPECT_EQ(socCell(s), "40");
}

}  // namespace
}  // namespace xr::app
