/// @file
/// @brief The active comments of LinuxCNC 2.9 (G-code overview, "Messages", "Probe Logging",
/// "Debug Messages", "Print Messages", "Abort"): `(MSG,text)`, `(DEBUG,text)`, `(PRINT,text)`,
/// `(ABORT,text)` and the LOG family; DEBUG, PRINT, ABORT and LOG text has its parameters
/// substituted when the block runs.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "pkm/cnc/expression.hpp"

namespace pkm::cnc {

/// What a comment asks for. A line's last comment is the one that counts (as in rs274).
enum class CommentKind : std::uint8_t {
  kNone,       ///< a plain comment, or none
  kMsg,        ///< show the text to the operator, as written
  kDebug,      ///< show the text with its parameters substituted
  kPrint,      ///< print the text with its parameters substituted (rs274: standard output)
  kAbort,      ///< stop the program with the substituted text as its error
  kLogOpen,    ///< open a probe log file (pkm reports it; it writes no file)
  kLogAppend,  ///< open a probe log file to append
  kLogClose,   ///< close the probe log
  kLog         ///< write the substituted text to the probe log
};

/// The keyword of `kind` as pkm reports it: "msg", "debug", "print", "abort", "logopen", ...;
/// "" for kNone.
[[nodiscard]] std::string_view commentKeyword(CommentKind kind);

/// Classifies the inside of one comment (the text between '(' and ')'): blanks before the
/// keyword are skipped, the keyword's case does not matter, and it must be followed directly by
/// ',' (`(MSG ,x)` is a plain comment), except LOGCLOSE, which takes no text. Sets `text` to
/// what follows the comma, blanks kept. Throws GcodeError for `(PY,...)`: embedded Python is not
/// supported.
[[nodiscard]] CommentKind classifyComment(std::string_view inner, std::string& text);

/// `text` with each `#n` (digits) and `#<name>` replaced by the parameter's value printed with 6
/// decimals (as rs274 prints it; "######" for a name not defined or a number outside
/// 1..5601). Other characters, '#' without a parameter after it included, are kept.
[[nodiscard]] std::string substituteParameters(std::string_view text, ParameterSource& source);

}  // namespace pkm::cnc
