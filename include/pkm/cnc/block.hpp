/// @file
/// @brief One line of an RS274NGC program as LinuxCNC 2.9 reads it ("Format of a line" of the
/// LinuxCNC G-code overview): optional `/` block delete, optional N number, words whose values
/// are expressions, parameter settings, an O-word statement, comments `( )` and `;` (dropped, but
/// for the active comments of comment_message.hpp).
/// Case and blanks outside comments do not matter.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/cnc/comment_message.hpp"
#include "pkm/cnc/expression.hpp"

namespace pkm::cnc {

/// O-word statement kind (LinuxCNC "O Codes").
enum class OKind : std::uint8_t {
  kNone,
  kSub,
  kEndSub,
  kCall,
  kReturn,
  kIf,
  kElseIf,
  kElse,
  kEndIf,
  kWhile,
  kEndWhile,
  kDo,
  kRepeat,
  kEndRepeat,
  kBreak,
  kContinue,
  kProgram  ///< `O1000` alone: the label of a main program or of an M98 subprogram (Fanuc style)
};

/// The polar-coordinate words `@` (distance) and `^` (angle, degrees) as Word letters: the two
/// characters after 'z', so that words index letters 'a'..'z' + 2 alike.
inline constexpr char kPolarRadius = '{';
inline constexpr char kPolarAngle = '|';

/// The letter of word `letter` as written: 'X' for 'x', '@' for kPolarRadius, '^' for
/// kPolarAngle.
[[nodiscard]] char writtenLetter(char letter);

/// A word: a letter (lower-case; kPolarRadius, kPolarAngle for @ ^) and its value.
struct Word {
  char letter = 0;
  Expression value;
};

/// A parameter setting `#n = value` or `#<name> = value`.
struct Assignment {
  bool named = false;
  std::string name;  ///< named parameter (lower-case), when `named`
  Expression index;  ///< parameter number, when not `named`
  Expression value;
};

/// "No block" for the jump fields.
inline constexpr std::size_t kNoBlock = std::numeric_limits<std::size_t>::max();

/// One parsed line.
struct Block {
  std::size_t line = 0;                 ///< 1-based source line
  bool block_delete = false;            ///< the line starts with `/`
  std::vector<Word> words;              ///< words in source order (N dropped)
  std::vector<Assignment> assignments;  ///< parameter settings in source order
  OKind o_kind = OKind::kNone;          ///< O-word statement, if any
  std::string o_name;                   ///< its label: "100" for o100, "name" for o<name>
  std::vector<Expression> o_args;       ///< call arguments, or the condition / count / value
  /// `O[expression] call`: the sub's number, evaluated when the call runs (o_name is then "").
  std::optional<Expression> o_label;
  /// Control flow resolved by Program: for sub, the endsub; for if/elseif, the next branch; for
  /// while/do/repeat, the closing statement; for call, the sub (kNoBlock when undefined).
  std::size_t jump = kNoBlock;
  /// For elseif/else, the endif; for endwhile/endrepeat/do-while/break/continue, the opening
  /// statement of the loop.
  std::size_t partner = kNoBlock;
  /// True for the `while` that closes a `do` loop.
  bool closes_do = false;
  /// The line's last comment when it is an active one (MSG, DEBUG, PRINT, ABORT, LOG...), and
  /// its text after the comma (comment_message.hpp).
  CommentKind comment = CommentKind::kNone;
  std::string comment_text;
  /// A line that could not be parsed after the program's end (LineReader::setLenient): the
  /// message, reported only if the line is ever executed (LinuxCNC never reads past M2).
  std::string deferred_error;
  /// Resets every field to its default, keeping the storage of the vectors and of `o_name` (a
  /// reader reuses one Block for every line). Keep it in step with the fields above.
  void clear();
  /// True when the line holds nothing to execute.
  [[nodiscard]] bool empty() const {
    return words.empty() && assignments.empty() && o_kind == OKind::kNone &&
           comment == CommentKind::kNone && deferred_error.empty();
  }
};

/// The label as written: "o100" for a number, "o<name>" for a name (for messages).
[[nodiscard]] std::string oLabel(const std::string& name);

/// What parseLine found besides the block.
enum class LineMark { kNormal, kPercent };

/// Parses one source line (without its newline) into `block` (which is cleared first; its `line`
/// is left to the caller). Throws GcodeError for a malformed line: unclosed comment, bad
/// character, bad number or expression, a word letter LinuxCNC does not know, two words with
/// the same letter other than G and M, N not first, polar coordinates (`@`, `^`, unsupported).
LineMark parseLine(std::string_view text, Block& block);

}  // namespace pkm::cnc
