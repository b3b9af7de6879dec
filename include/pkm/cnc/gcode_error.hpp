/// @file
/// @brief The error the G-code reader and interpreter throw internally; the interpreter turns it
/// into pkm::IoError "FILE:LINE: message" (docs/conventions.md, "Errors").
#pragma once

#include <stdexcept>

namespace pkm::cnc {

/// An error in a G-code block without file or line (they are added by the caller that knows
/// them). Never escapes the public entry points Program::parse and Interpreter::run.
class GcodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pkm::cnc
