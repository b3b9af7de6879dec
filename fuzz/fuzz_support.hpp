// Helpers shared by the libFuzzer harnesses (docs/fuzzing.md). A harness feeds its input to a
// reader; the reader must return or throw one of the project's documented exceptions
// (pkm::IoError, pkm::InvalidArgument). Anything else — another exception, a crash, a sanitizer
// report, a hang or an allocation beyond libFuzzer's -rss_limit_mb — is a finding, as is a
// violated invariant (fuzz::check).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "pkm/core/error.hpp"

namespace pkm::fuzz {

/// The input as text.
inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Runs `f`; returns true when it returned, false when it threw a documented exception.
template <typename F>
bool accepts(F&& f) {
  try {
    f();
    return true;
  } catch (const IoError&) {
  } catch (const InvalidArgument&) {
  }
  return false;
}

/// Aborts with `what` (a finding) when `ok` is false.
inline void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz invariant violated: %s\n", what);
  std::abort();
}

/// Splits `text` at the first line that is exactly `marker` (e.g. "%%ini"): what comes before,
/// and what comes after (empty and `found` false without such a line). Lets one input carry
/// two files.
struct Split {
  std::string first, second;
  bool found = false;
};
inline Split splitAt(std::string_view text, std::string_view marker) {
  Split s;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    if (text.substr(pos, end - pos) == marker) {
      s.first = std::string(text.substr(0, pos));
      s.second = std::string(text.substr(std::min(end + 1, text.size())));
      s.found = true;
      return s;
    }
    pos = end + 1;
  }
  s.first = std::string(text);
  return s;
}

}  // namespace pkm::fuzz
