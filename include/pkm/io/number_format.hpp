/// @file
/// @brief Number output that round-trips: the shortest decimal form that parses back to the same
/// double.
#pragma once

#include <string>

namespace pkm::io {

/// Appends the shortest round-trip decimal representation of `value` ("nan"/"inf" for non-finite;
/// -0 is written as 0).
void appendNumber(std::string& out, double value);

/// appendNumber into a new string.
[[nodiscard]] std::string formatNumber(double value);

}  // namespace pkm::io
