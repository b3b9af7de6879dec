// The front end's files, embedded at build time from web/app (docs/web.md): served by
// Api::asset.
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pkm/server/api.hpp"

namespace pkm::io::detail {
const std::vector<std::pair<std::string_view, std::string_view>>& appIndexHtml();
const std::vector<std::pair<std::string_view, std::string_view>>& appJs();
const std::vector<std::pair<std::string_view, std::string_view>>& appCss();
const std::vector<std::pair<std::string_view, std::string_view>>& appMedia();
}  // namespace pkm::io::detail

namespace pkm::server {
namespace {

Response embedded(const std::vector<std::pair<std::string_view, std::string_view>>& files,
                  const char* type) {
  return {200, type, files.empty() ? std::string() : std::string(files.front().second), "", ""};
}

}  // namespace

const Response* Api::asset(const std::string& path) {
  static const Response index = embedded(io::detail::appIndexHtml(), "text/html; charset=utf-8");
  static const Response js = embedded(io::detail::appJs(), "text/javascript; charset=utf-8");
  static const Response css = embedded(io::detail::appCss(), "text/css; charset=utf-8");
  if (path == "/" || path == "/index.html") return &index;
  if (path == "/app.js") return &js;
  if (path == "/app.css") return &css;
  static const std::map<std::string, Response> media = [] {
    std::map<std::string, Response> m;
    for (const auto& [name, bytes] : io::detail::appMedia()) {
      const std::string n(name);
      const std::string type = n.ends_with(".svg")   ? "image/svg+xml"
                               : n.ends_with(".png") ? "image/png"
                               : n.ends_with(".gif") ? "image/gif"
                                                     : "application/octet-stream";
      m["/media/" + n] = Response{200, type, std::string(bytes), "", ""};
    }
    return m;
  }();
  const auto it = media.find(path);
  return it == media.end() ? nullptr : &it->second;
}

}  // namespace pkm::server
