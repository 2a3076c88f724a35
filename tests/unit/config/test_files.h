#pragma once
// A temporary file that removes itself: checkConfigMain takes a path.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace xr::testing {

class TempFile {
 public:
  explicit TempFile(std::string_view content, std::string_view stem = "xr-config-test") {
    static int counter = 0;
    path_ = (std::filesystem::temp_directory_path() /
             (std::string(stem) + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".toml"))
                .string();
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempFile() { std::filesystem::remove(path_); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace xr::testing
