#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "params/params.h"

namespace xr {
namespace {

TEST(Catalogue, NamesAreUnique) {
  std::set<std::string> names;
  for (const auto& s : catalogue()) EXPECT_TRUE(names.insert(std::string(s.name)).second) << s.name;
}

TEST(Catalogue, DefaultsFitTheirOwnRange) {
  const Params p;
  for (const auto& s : catalogue()) {
    if (s.kind == ParamKind::Table) {
      for (std::size_t i = 0; i < RPM_TABLE_SIZE; ++i) {
        EXPECT_TRUE(valueFits(s, s.tableDefault[i])) << s.name << "[" << i << "]";
        EXPECT_EQ(s.get(p, i), s.tableDefault[i]) << s.name;
      }
    } else {
      EXPECT_TRUE(valueFits(s, s.defaultValue)) << s.name;
      EXPECT_EQ(s.get(p, 0), s.defaultValue) << s.name;
    }
  }
}

TEST(Catalogue, SetterWritesTheNamedField) {
  Params p;
  findParam("BulkVoltage")->set(p, 0, 28.8);
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 28.8);
  findParam("rpmCapCurrentTable")->set(p, 3, 77.0);
  EXPECT_DOUBLE_EQ(p.rpmCapCurrentTable[3], 77.0);
  EXPECT_EQ(findParam("NoSuchParameter"), nullptr);
}

TEST(Catalogue, ValueFitsRejectsFractionsForIntsAndOutOfRange) {
  const auto& interval = *findParam("VoltageLoopInterval");
  EXPECT_TRUE(valueFits(interval, 100));
  EXPECT_FALSE(valueFits(interval, 100.5));
  EXPECT_FALSE(valueFits(interval, 1e9));
  EXPECT_FALSE(valueFits(*findParam("UseFloat"), 2));
  EXPECT_FALSE(valueFits(*findParam("BulkVoltage"), std::nan("")));
}

}  // namespace
}  // namespace xr
