// The front end's files, embedded at build time from web/app (docs/web.md): served by
// Api::asset.
#include <string_view>
#include <utility>
#include <vector>

#include "pkm/server/api.hpp"

namespace pkm::io::detail {
const std::vector<std::pair<std::string_view, std::string_view>>& appIndexHtml();
const std::vector<std::pair<std::string_view, std::string_view>>& appJs();
const std::vector<std::pair<std::string_view, std::string_view>>& appCss();
}  // namespace pkm::io::detail

namespace pkm::server {
namespace {

Response embedded(const std::vector<std::pair<std::string_view, std::string_view>>& files,
                  const char* type) {
  return {200, type, files.empty() ? std::string() : std::string(files.front().second)};
}

}  // namespace

const Response* Api::asset(const std::string& path) {
  static const Response index = embedded(io::detail::appIndexHtml(), "text/html; charset=utf-8");
  static const Response js = embedded(io::detail::appJs(), "text/javascript; charset=utf-8");
  static const Response css = embedded(io::detail::appCss(), "text/css; charset=utf-8");
  if (path == "/" || path == "/index.html") return &index;
  if (path == "/app.js") return &js;
  if (path == "/app.css") return &css;
  return nullptr;
}

}  // namespace pkm::server
