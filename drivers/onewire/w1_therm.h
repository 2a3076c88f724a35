#pragma once
// Linux w1_therm sysfs (docs/sources.md D3): parse the two-line `w1_slave`
// format and find DS18B20 (family 28) sensors under a configurable root.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace xr::w1 {

enum class ParseError { None, Empty, Malformed, CrcNo, PowerOnValue };
const char* toString(ParseError e) noexcept;

struct W1Reading {
  ParseError error = ParseError::None;
  int milliC = 0;  // valid when error == None
};

// Accepts a reading only when line 1 ends in "crc=XX YES" and line 2 carries
// "t=<int>". 85000 (the DS18B20 power-on value: no conversion happened) is
// rejected as PowerOnValue.
W1Reading parseW1Slave(std::string_view text) noexcept;

// "28-..." device directories under `root`, sorted. Not RT.
std::vector<std::string> listDs18b20(const std::string& root);

}  // namespace xr::w1
