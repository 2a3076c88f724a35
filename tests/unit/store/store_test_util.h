#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>

namespace xr::test {

// A fresh directory under /tmp, removed at the end of the test.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    char tmpl[] = "/tmp/xr-store-test-XXXXXX";
    path = mkdtemp(tmpl);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::permissions(path, std::filesystem::perms::owner_all, ec);
    std::filesystem::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

inline constexpr std::int64_t kT0 = 1'700'000'000'000;  // a UTC ms timestamp

}  // namespace xr::test
