// The per-launch token of a server reachable from other machines (pkm/server/api.hpp,
// Api::token; docs/web.md, "Security").
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string_view>

#include "api_state.hpp"

namespace pkm::server {
namespace {

/// a == b without an early exit: the time does not tell how many leading characters matched.
bool sameSecret(std::string_view a, std::string_view b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  const std::string_view ref = a.size() == b.size() ? b : a;  // compare a with itself if unequal
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ ref[i]);
  return diff == 0 && !a.empty();
}

/// The value of cookie `name` in a Cookie header ("a=1; b=2"), "" when absent.
std::string cookieValue(std::string_view header, std::string_view name) {
  while (!header.empty()) {
    const std::size_t end = std::min(header.find(';'), header.size());
    std::string_view pair = header.substr(0, end);
    header.remove_prefix(std::min(end + 1, header.size()));
    while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
    if (pair.size() > name.size() && pair.starts_with(name) && pair[name.size()] == '=')
      return std::string(pair.substr(name.size() + 1));
  }
  return "";
}

}  // namespace

bool isLoopbackHost(const std::string& host) {
  if (host == "localhost" || host == "::1" || host == "[::1]") return true;
  unsigned a = 0, b = 0, c = 0, d = 0;
  char tail = 0;
  return std::sscanf(host.c_str(), "%u.%u.%u.%u%c", &a, &b, &c, &d, &tail) == 4 && a == 127 &&
         b < 256 && c < 256 && d < 256;
}

namespace detail {

std::string newToken() {
  std::random_device source;  // getrandom(2) on Linux
  std::string out;
  for (int i = 0; i < 8; ++i) out += fmt::format("{:08x}", source());
  return out;
}

TokenUse tokenUse(const Request& r, const std::string& token) {
  if (token.empty()) return TokenUse::kNotNeeded;
  if (!r.token.empty()) return sameSecret(r.token, token) ? TokenUse::kQuery : TokenUse::kWrong;
  const std::string cookie = cookieValue(r.cookie, kTokenCookie);
  if (cookie.empty()) return TokenUse::kMissing;
  return sameSecret(cookie, token) ? TokenUse::kCookie : TokenUse::kWrong;
}

void requireCommandToken(const Request& r, const Api::State& s) {
  const TokenUse use = tokenUse(r, s.token);
  if (use == TokenUse::kQuery || use == TokenUse::kCookie) return;
  throw HttpError(401,
                  use == TokenUse::kWrong
                      ? "wrong token: this server was started again, or the link is not the one "
                        "`pkm serve` printed; nothing was sent to the machine; open the URL it "
                        "printed"
                      : "commanding the machine needs this launch's token: open the URL `pkm "
                        "serve` printed (…/?token=…); nothing was sent to the machine");
}

std::string tokenCookie(const std::string& token) {
  return fmt::format("{}={}; Path=/; HttpOnly; SameSite=Strict", kTokenCookie, token);
}

}  // namespace detail
}  // namespace pkm::server
