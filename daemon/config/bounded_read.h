#pragma once
// Reading a configuration-like file safely (docs/security.md): only a regular
// file is read, and only up to a size bound. A directory, a FIFO, a socket or
// a character device such as /dev/zero is refused before any byte is read, so
// a mistyped --config can neither look "OK" (a directory read as empty text)
// nor hang or exhaust memory (a FIFO with no writer, an endless device).
#include <cstddef>
#include <string>

namespace xr {

// Far above any real configuration (the commented default is ~50 KiB).
inline constexpr std::size_t kMaxConfigBytes = 1024 * 1024;

// Reads path into text. Returns an empty string on success, otherwise the
// reason, worded for the user ("is a directory, not a configuration file").
std::string readConfigText(const std::string& path, std::string& text,
                           std::size_t maxBytes = kMaxConfigBytes);

}  // namespace xr
