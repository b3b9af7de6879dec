/// @file
/// @brief Number output that round-trips: the shortest decimal form that parses back to the same
/// double.
#pragma once

#include <cstddef>
#include <string>

namespace pkm::io {

/// Room writeNumber needs at `out`: the longest text it writes ("-1.2345678901234567e-308") is 24
/// bytes; it may also write (and leave undefined) bytes up to out + kMaxNumberChars, as slack for
/// fixed-size copies.
inline constexpr std::size_t kMaxNumberChars = 48;

/// Writes the text appendNumber appends to [out, out + kMaxNumberChars) and returns its end
/// (no terminating NUL).
char* writeNumber(char* out, double value);

/// Appends the shortest round-trip decimal representation of `value` ("nan"/"inf" for non-finite;
/// -0 is written as 0).
void appendNumber(std::string& out, double value);

/// appendNumber into a new string.
[[nodiscard]] std::string formatNumber(double value);

}  // namespace pkm::io
