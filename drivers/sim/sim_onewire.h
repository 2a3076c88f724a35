#pragma once
// A simulated DS18B20 on a simulated Linux w1 sysfs tree, so the real w1
// reader runs on it unchanged: <root>/28-xxxxxxxxxxxx/w1_slave in the kernel's
// two-line format (docs/sources.md D3):
//   "2c 01 4b 46 7f ff 0c 10 61 : crc=61 YES"
//   "2c 01 4b 46 7f ff 0c 10 61 t=18750"
// The file is refreshed once per conversion (750 ms at 12 bits) and only
// rewritten when its content changes. It is rewritten in place through a
// shared mapping of the file held open (a memcpy per new reading, an
// ftruncate when its length changes): the simulator and the reader it feeds
// run on the same thread, so no reader ever sees half a file.
// Disconnecting empties the file first, then removes the device directory:
// a reader holding the file open reads nothing, as a removed sysfs attribute
// fails to read, and opens the path afresh.
#include <cstdint>
#include <filesystem>
#include <string>

#include "core/time.h"

namespace xr::sim {

class SimOneWire {
 public:
  // Creates root/ (and the device) if needed.
  SimOneWire(std::filesystem::path root, std::string deviceId = "28-00000a1b2c3d");
  ~SimOneWire();
  SimOneWire(const SimOneWire&) = delete;
  SimOneWire& operator=(const SimOneWire&) = delete;

  // Bring the sensor to time t with the true temperature (degC).
  void update(TimeNs t, double tempC);
  void setPresent(bool present);
  // The next update() converts at once (what the sensor sees changed: a
  // fault), instead of waiting for the running 750 ms conversion.
  void convertNow() { nextConversion_ = 0; }
  // Next files carry a scratchpad whose CRC does not match ("crc=.. NO").
  void setCorrupt(bool corrupt) { corrupt_ = corrupt; }
  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path slavePath() const { return root_ / id_ / "w1_slave"; }
  const std::string& deviceId() const { return id_; }
  std::uint64_t writes() const { return writes_; }
  // update() before this time is a no-op (the sensor is still converting);
  // lets the caller skip computing the temperature.
  TimeNs nextConversion() const { return present_ ? nextConversion_ : INT64_MAX; }

  // The two lines for a raw 12-bit reading (1/16 degC); exposed for tests.
  static std::string formatW1Slave(std::int16_t raw, bool corrupt);
  static std::uint8_t crc8(const std::uint8_t* p, std::size_t n);

 private:
  void writeFile(const std::string& content);
  std::filesystem::path root_;
  std::string id_;
  void openFile();
  void closeFile() noexcept;
  static constexpr std::size_t kMapBytes = 4096;  // one page; a reading is < 100 bytes
  std::string slavePath_;                         // built at the first write
  int fd_ = -1;                                   // slavePath_, held open between writes
  char* map_ = nullptr;                           // its first page, MAP_SHARED (null: pwrite instead)
  std::size_t size_ = 0;                          // bytes in the file
  bool present_ = true;
  bool corrupt_ = false;
  bool written_ = false;
  std::int16_t lastRaw_ = 0;
  bool lastCorrupt_ = false;
  TimeNs nextConversion_ = 0;
  std::uint64_t writes_ = 0;
};

}  // namespace xr::sim
