#pragma once
// Static dashboard files from a configured root: MIME types by extension and
// no way out of the root (no "..", no absolute paths, no symlink escapes).
#include <optional>
#include <string>
#include <string_view>

namespace xr::web {

std::string_view mimeType(std::string_view path);

// Resolves a URL path ("/", "/app.js", "/vendor/uPlot.min.css") under root.
// "/" and directories map to index.html. Returns nullopt for anything that
// would leave the root, contains NUL or a percent-encoded byte we do not
// accept, or does not exist as a regular file.
std::optional<std::string> resolveStaticPath(const std::string& root, std::string_view urlPath);

// Reads a whole file (dashboard assets are small); nullopt on error.
std::optional<std::string> readFile(const std::string& path);

}  // namespace xr::web
