// Errors of an analysis that come from the data, not the parser, named by the data's files.
#pragma once

#include <initializer_list>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::workflow::detail {

/// The inputs' names, comma-separated ("a.csv, b.csv").
[[nodiscard]] std::string dataNames(std::initializer_list<std::span<const io::NamedText>> groups);

/// Runs f() and returns its result. A pkm::InvalidArgument from it (an analysis refusing what the
/// data say, e.g. "ISO 230-2: target 1 has only 1 run in the + direction (needs 2)") is thrown
/// again with the inputs' names in front, "a.csv: ISO 230-2: ...", so that the user knows which
/// file to look at. Validate the request before: its own errors are not the files'.
template <class F>
decltype(auto) namingData(std::initializer_list<std::span<const io::NamedText>> groups, F&& f) {
  const std::string names = dataNames(groups);
  try {
    return std::forward<F>(f)();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(names + ": " + e.what());
  }
}

}  // namespace pkm::workflow::detail
