/// @file
/// @brief The project's exception types and precondition-check macro (docs/conventions.md,
/// "Errors").
#pragma once

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace pkm {

/// A violated precondition of a public function (bad sizes, NaN inputs, degenerate geometry).
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Malformed or unreadable input: the message names the file and, where known, the line.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Builds an IoError message of the form "FILE:LINE: what" (line omitted when 0).
[[nodiscard]] std::string locate(const std::string& file,
                                 std::size_t line,
                                 const std::string& what);

}  // namespace pkm

/// Throws pkm::InvalidArgument with a fmt-formatted message when `cond` is false.
#define PKM_CHECK(cond, ...)                                             \
  do {                                                                   \
    if (!(cond)) throw ::pkm::InvalidArgument(fmt::format(__VA_ARGS__)); \
  } while (false)
