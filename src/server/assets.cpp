// The front end's files, embedded at build time from web/app (docs/web.md): served by
// Api::asset.
#include <cstdint>
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
  return {200, type, files.empty() ? std::string() : std::string(files.front().second), "", "", ""};
}

/// 16 hex digits of FNV-1a over `bytes`: the bundle's name changes with its content.
std::string contentHash(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  static const char* digits = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, h >>= 4) out[static_cast<std::size_t>(i)] = digits[h & 15u];
  return out;
}

/// `text` with every `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

/// The bundle under its content-hashed name, kept by the browser for a year (a new build is a
/// new name, and the page, never cached, names it).
struct Bundle {
  Response js, css, index;
  std::string js_path, css_path;
};

const Bundle& bundle() {
  static const Bundle b = [] {
    Bundle out;
    out.js = embedded(io::detail::appJs(), "text/javascript; charset=utf-8");
    out.css = embedded(io::detail::appCss(), "text/css; charset=utf-8");
    out.js_path = "/app." + contentHash(out.js.body) + ".js";
    out.css_path = "/app." + contentHash(out.css.body) + ".css";
    out.index = embedded(io::detail::appIndexHtml(), "text/html; charset=utf-8");
    out.index.body = replaced(replaced(out.index.body, "\"/app.js\"", '"' + out.js_path + '"'),
                              "\"/app.css\"",
                              '"' + out.css_path + '"');
    out.js.cache_control = out.css.cache_control = "public, max-age=31536000, immutable";
    return out;
  }();
  return b;
}

}  // namespace

const Response* Api::asset(const std::string& path) {
  const Bundle& b = bundle();
  if (path == "/" || path == "/index.html") return &b.index;
  if (path == b.js_path) return &b.js;
  if (path == b.css_path) return &b.css;
  static const std::map<std::string, Response> media = [] {
    std::map<std::string, Response> m;
    for (const auto& [name, bytes] : io::detail::appMedia()) {
      const std::string n(name);
      const std::string type = n.ends_with(".svg")   ? "image/svg+xml"
                               : n.ends_with(".png") ? "image/png"
                               : n.ends_with(".gif") ? "image/gif"
                                                     : "application/octet-stream";
      m["/media/" + n] = Response{200, type, std::string(bytes), "", "", ""};
    }
    return m;
  }();
  const auto it = media.find(path);
  return it == media.end() ? nullptr : &it->second;
}

}  // namespace pkm::server
