#pragma once
// A VE.Direct device for tests: text blocks with their checksum, and a
// pseudo-terminal the reader opens as its serial port.
#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <string>
#include <utility>
#include <vector>

namespace xr::test {

// One text block with a correct checksum byte (sum of all bytes = 0 mod 256).
inline std::string block(const std::vector<std::pair<std::string, std::string>>& fields, int corruptBy = 0) {
  std::string s;
  for (const auto& [l, v] : fields) s += "\r\n" + l + "\t" + v;
  s += "\r\nChecksum\t";
  unsigned sum = 0;
  for (unsigned char c : s) sum += c;
  s += static_cast<char>(((256 - sum % 256) + corruptBy) % 256);
  return s;
}
inline const std::vector<std::pair<std::string, std::string>> kFields = {
    {"PID", "0xA053"}, {"V", "13250"}, {"I", "-1500"}, {"VPV", "36010"}, {"PPV", "120"}, {"CS", "3"}};

class Pty {
 public:
  Pty() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master_ >= 0 && ::grantpt(master_) == 0 && ::unlockpt(master_) == 0) name_ = ::ptsname(master_);
  }
  ~Pty() { closeMaster(); }
  const std::string& slave() const { return name_; }
  bool write(const std::string& s) {
    return ::write(master_, s.data(), s.size()) == static_cast<ssize_t>(s.size());
  }
  void closeMaster() {
    if (master_ >= 0) ::close(master_);
    master_ = -1;
  }

 private:
  int master_ = -1;
  std::string name_;
};

}  // namespace xr::test
