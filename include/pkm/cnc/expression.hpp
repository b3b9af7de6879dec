/// @file
/// @brief RS274NGC real values and expressions as LinuxCNC 2.9 reads them (docs "Numbered
/// Parameters", "Expressions", "Binary Operators", "Functions" of the LinuxCNC G-code
/// overview): numbers, `#n`/`#<name>` parameters, `[ ]` expressions with ** * / MOD + - EQ NE GT
/// GE LT LE AND OR XOR and the functions ABS ACOS ASIN ATAN[y]/[x] COS EXP FIX FUP ROUND LN SIN
/// SQRT TAN EXISTS. Parsed once into postfix code, evaluated many times.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace pkm::cnc {

/// Where an expression reads parameter values. Implementations throw GcodeError for a parameter
/// that is out of range or undefined.
class ParameterSource {
 public:
  virtual ~ParameterSource() = default;
  /// Value of numbered parameter `#index` (1..5601), in program units where it is a length.
  virtual double numbered(int index) = 0;
  /// Value of named parameter `#<name>` (`name` lower-case, without the brackets).
  virtual double named(const std::string& name) = 0;
  /// True when `#<name>` is defined in the current scope (EXISTS).
  virtual bool exists(const std::string& name) = 0;
};

/// Operations of the postfix code (stack machine).
enum class ExprOp : std::uint8_t {
  kConst,
  kParam,
  kNamed,
  kExists,
  kExistsNumbered,  ///< pops a number: 1 when it is a parameter number (1..5601), else 0
  kNeg,
  kPow,
  kMul,
  kDiv,
  kMod,
  kAdd,
  kSub,
  kEq,
  kNe,
  kGt,
  kGe,
  kLt,
  kLe,
  kAnd,
  kOr,
  kXor,
  kAbs,
  kAcos,
  kAsin,
  kAtan2,
  kCos,
  kExp,
  kFix,
  kFup,
  kRound,
  kLn,
  kSin,
  kSqrt,
  kTan
};

/// One instruction: an operation and its operand (constant value or name index).
struct ExprInstr {
  ExprOp op = ExprOp::kConst;
  std::uint32_t name = 0;  ///< index into Expression::names for kNamed / kExists
  double value = 0.0;      ///< the constant of kConst
};

/// Postfix code of a non-constant value.
struct ExprCode {
  std::vector<ExprInstr> code;
  std::vector<std::string> names;  ///< named parameters referred to by kNamed / kExists
};

/// A compiled real value. Constants keep no code (the common case is cheap to store and read:
/// 24 bytes, no allocation).
class Expression {
 public:
  Expression() = default;
  /// The constant `value`.
  explicit Expression(double value) : constant_(value) {}
  /// True when the value needs no parameters.
  [[nodiscard]] bool isConstant() const { return !code_; }
  /// The value; `params` is read only when the expression refers to parameters.
  /// Throws GcodeError on a domain error (division by zero, LN of a non-positive number, SQRT of
  /// a negative number, ASIN/ACOS outside [-1, 1], a non-finite result).
  [[nodiscard]] double evaluate(ParameterSource& params) const {
    return code_ ? run(params) : constant_;
  }
  /// The value of a constant expression (precondition: isConstant()).
  [[nodiscard]] double constantValue() const { return constant_; }

  /// Parses one real value of `text` (lower-case, no blanks) starting at `pos`, which is advanced
  /// past it: a number with optional sign, `[expression]`, `#n`, `#<name>`, `#[expr]`, or a
  /// function call such as `sin[30]`, `atan[1]/[2]`, `exists[#<x>]`. Throws GcodeError.
  static Expression parseReal(std::string_view text, std::size_t& pos);
  /// Parses a whole `[ ... ]` expression starting at `text[pos] == '['`.
  static Expression parseBracketed(std::string_view text, std::size_t& pos);

 private:
  [[nodiscard]] double run(ParameterSource& params) const;
  std::shared_ptr<const ExprCode> code_;
  double constant_ = 0.0;
  friend class ExprCompiler;
};

/// LinuxCNC's tolerance of EQ and NE (rs274ngc TOLERANCE_EQUAL).
inline constexpr double kExprEqualTolerance = 0.0001;

}  // namespace pkm::cnc
