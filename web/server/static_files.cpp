#include "web/server/static_files.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace xr::web {
namespace fs = std::filesystem;

std::string_view mimeType(std::string_view path) {
  const auto dot = path.rfind('.');
  const std::string_view ext = dot == std::string_view::npos ? std::string_view{} : path.substr(dot);
  if (ext == ".html" || ext == ".htm") return "text/html; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  if (ext == ".ico") return "image/x-icon";
  if (ext == ".webmanifest") return "application/manifest+json";
  if (ext == ".txt" || ext == ".md") return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

std::optional<std::string> resolveStaticPath(const std::string& root, std::string_view urlPath) {
  if (root.empty() || urlPath.empty() || urlPath.front() != '/') return std::nullopt;
  const auto q = urlPath.find_first_of("?#");
  if (q != std::string_view::npos) urlPath = urlPath.substr(0, q);
  // Reject encodings and characters that could hide a traversal.
  for (char c : urlPath)
    if (c == '\0' || c == '%' || c == '\\') return std::nullopt;
  std::string rel(urlPath.substr(1));
  // Every segment must be a plain name: not starting with "." (so no "." or
  // "..") and no empty middle segment.
  std::size_t start = 0;
  while (start <= rel.size()) {
    const auto end = rel.find('/', start);
    const std::string_view seg =
        std::string_view(rel).substr(start, end == std::string::npos ? std::string::npos : end - start);
    // No dotfiles either (docs/security.md): .git, .env, editor swap
    // files left in www_root are not the dashboard's.
    if (!seg.empty() && seg.front() == '.') return std::nullopt;
    if (seg.empty() && end != std::string::npos) return std::nullopt;  // "//"
    if (end == std::string::npos) break;
    start = end + 1;
  }
  std::error_code ec;
  const fs::path base = fs::weakly_canonical(fs::path(root), ec);
  if (ec) return std::nullopt;
  fs::path p = base / rel;
  if (rel.empty() || rel.back() == '/' || fs::is_directory(p, ec)) p /= "index.html";
  const fs::path real = fs::weakly_canonical(p, ec);
  if (ec) return std::nullopt;
  // Symlinks must not lead out of the root either.
  const auto rs = real.native();
  const auto bs = base.native();
  if (rs.size() <= bs.size() || rs.compare(0, bs.size(), bs) != 0 || rs[bs.size()] != '/')
    return std::nullopt;
  if (!fs::is_regular_file(real, ec)) return std::nullopt;
  return real.string();
}

std::optional<std::string> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return std::move(ss).str();
}

}  // namespace xr::web
