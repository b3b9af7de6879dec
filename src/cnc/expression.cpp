// RS274NGC expressions: recursive-descent parse into postfix code, stack evaluation. Semantics
// from the LinuxCNC 2.9 G-code overview ("Expressions", "Binary Operators", "Functions"):
// precedence ** > * / MOD > + - > EQ NE GT GE LT LE > AND OR XOR, left to right within a level;
// angles of the trigonometric functions in degrees; FIX rounds down, FUP up; EQ/NE compare within
// 0.0001; MOD's result takes the sign of the divisor's magnitude (checked against rs274:
// -5 MOD 3 = 1, 5 MOD -3 = 2).
#include "pkm/cnc/expression.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>

#include "pkm/cnc/gcode_error.hpp"
#include "plain_number.hpp"

namespace pkm::cnc {

namespace {

constexpr int kMaxNesting = 64;  // brackets/parameter indirections per value

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlpha(char c) { return c >= 'a' && c <= 'z'; }

int precedence(ExprOp op) {
  switch (op) {
    case ExprOp::kPow:
      return 4;
    case ExprOp::kMul:
    case ExprOp::kDiv:
    case ExprOp::kMod:
      return 3;
    case ExprOp::kAdd:
    case ExprOp::kSub:
      return 2;
    case ExprOp::kEq:
    case ExprOp::kNe:
    case ExprOp::kGt:
    case ExprOp::kGe:
    case ExprOp::kLt:
    case ExprOp::kLe:
      return 1;
    default:
      return 0;
  }
}

}  // namespace

/// Builds the postfix code of one value.
class ExprCompiler {
 public:
  explicit ExprCompiler(std::string_view text) : text_(text) {}

  void real(std::size_t& pos, int depth) {
    if (depth > kMaxNesting) throw GcodeError("expression nested too deeply");
    if (pos >= text_.size()) throw GcodeError("missing value at end of line");
    const char c = text_[pos];
    if (c == '[') {
      bracketed(pos, depth + 1);
    } else if (c == '#') {
      ++pos;
      if (pos < text_.size() && text_[pos] == '<') {
        const std::size_t close = text_.find('>', pos);
        if (close == std::string_view::npos) throw GcodeError("named parameter not terminated");
        const std::string name(text_.substr(pos + 1, close - pos - 1));
        if (name.empty()) throw GcodeError("empty parameter name");
        pos = close + 1;
        emit(ExprOp::kNamed, addName(name));
      } else {
        real(pos, depth + 1);
        emit(ExprOp::kParam);
      }
    } else if (c == '-' || c == '+') {
      ++pos;
      if (pos < text_.size() && (isDigit(text_[pos]) || text_[pos] == '.')) {
        const double v = number(pos);
        constant(c == '-' ? -v : v);
      } else {
        real(pos, depth + 1);
        if (c == '-') emit(ExprOp::kNeg);
      }
    } else if (isDigit(c) || c == '.') {
      constant(number(pos));
    } else if (isAlpha(c)) {
      function(pos, depth);
    } else {
      throw GcodeError(fmt::format("bad character '{}' where a value was expected", c));
    }
  }

  void bracketed(std::size_t& pos, int depth) {
    if (depth > kMaxNesting) throw GcodeError("expression nested too deeply");
    if (pos >= text_.size() || text_[pos] != '[') throw GcodeError("expected '['");
    ++pos;
    // Shunting-yard over left-associative binary operators.
    std::array<ExprOp, kMaxNesting> ops{};
    std::size_t n_ops = 0;
    real(pos, depth);
    while (true) {
      if (pos >= text_.size()) throw GcodeError("unclosed bracket in expression");
      if (text_[pos] == ']') {
        ++pos;
        break;
      }
      const ExprOp op = binaryOperator(pos);
      while (n_ops > 0 && precedence(ops[n_ops - 1]) >= precedence(op)) emit(ops[--n_ops]);
      if (n_ops == ops.size()) throw GcodeError("expression too long");
      ops[n_ops++] = op;
      real(pos, depth);
    }
    while (n_ops > 0) emit(ops[--n_ops]);
  }

  Expression finish() {
    Expression e;
    if (code_.size() == 1 && code_[0].op == ExprOp::kConst) {
      e.constant_ = code_[0].value;
    } else {
      auto c = std::make_shared<ExprCode>();
      c->code = std::move(code_);
      c->names = std::move(names_);
      e.code_ = std::move(c);
    }
    return e;
  }

 private:
  double number(std::size_t& pos) {
    const std::size_t start = pos;
    bool dot = false;
    while (pos < text_.size() && (isDigit(text_[pos]) || (text_[pos] == '.' && !dot))) {
      if (text_[pos] == '.') dot = true;
      ++pos;
    }
    if (pos == start || (pos == start + 1 && text_[start] == '.'))
      throw GcodeError("bad number format");
    double v = 0.0;
    const auto r = std::from_chars(text_.data() + start, text_.data() + pos, v);
    if (r.ec != std::errc() || r.ptr != text_.data() + pos || !std::isfinite(v))
      throw GcodeError("bad number format");
    return v;
  }

  ExprOp binaryOperator(std::size_t& pos) {
    const std::string_view rest = text_.substr(pos);
    auto take = [&](std::string_view s, ExprOp op) {
      if (rest.substr(0, s.size()) != s) return false;
      pos += s.size();
      found_ = op;
      return true;
    };
    if (take("**", ExprOp::kPow) || take("*", ExprOp::kMul) || take("/", ExprOp::kDiv) ||
        take("+", ExprOp::kAdd) || take("-", ExprOp::kSub) || take("mod", ExprOp::kMod) ||
        take("eq", ExprOp::kEq) || take("ne", ExprOp::kNe) || take("gt", ExprOp::kGt) ||
        take("ge", ExprOp::kGe) || take("lt", ExprOp::kLt) || take("le", ExprOp::kLe) ||
        take("and", ExprOp::kAnd) || take("or", ExprOp::kOr) || take("xor", ExprOp::kXor))
      return found_;
    throw GcodeError(fmt::format("unknown operator at '{}'", rest.substr(0, 8)));
  }

  void function(std::size_t& pos, int depth) {
    const std::size_t start = pos;
    while (pos < text_.size() && isAlpha(text_[pos])) ++pos;
    const std::string_view name = text_.substr(start, pos - start);
    if (pos >= text_.size() || text_[pos] != '[')
      throw GcodeError(fmt::format("unknown word '{}' where a value was expected", name));
    if (name == "exists" && pos + 2 < text_.size() && text_[pos + 1] == '#' &&
        text_[pos + 2] != '<') {
      // EXISTS[#n]: whether #n is a parameter number (1..5601); n may itself be #m (rs274).
      pos += 2;
      real(pos, depth + 1);
      if (pos >= text_.size() || text_[pos] != ']')
        throw GcodeError("EXISTS takes one parameter: exists[#<name>] or exists[#n]");
      ++pos;
      emit(ExprOp::kExistsNumbered);
      return;
    }
    if (name == "exists") {
      // The name may hold brackets itself (#<_ini[section]name>): it ends at its '>'.
      const std::size_t gt = text_.find('>', pos);
      if (text_.substr(pos, 3) != "[#<" || gt == std::string_view::npos || gt == pos + 3 ||
          gt + 1 >= text_.size() || text_[gt + 1] != ']')
        throw GcodeError("EXISTS takes one parameter: exists[#<name>] or exists[#n]");
      emit(ExprOp::kExists, addName(std::string(text_.substr(pos + 3, gt - pos - 3))));
      pos = gt + 2;
      return;
    }
    if (name == "atan") {
      bracketed(pos, depth + 1);
      if (pos >= text_.size() || text_[pos] != '/')
        throw GcodeError("ATAN needs two arguments: atan[y]/[x]");
      ++pos;
      bracketed(pos, depth + 1);
      emit(ExprOp::kAtan2);
      return;
    }
    static constexpr std::array<std::pair<std::string_view, ExprOp>, 12> kUnary{{
        {"abs", ExprOp::kAbs},
        {"acos", ExprOp::kAcos},
        {"asin", ExprOp::kAsin},
        {"cos", ExprOp::kCos},
        {"exp", ExprOp::kExp},
        {"fix", ExprOp::kFix},
        {"fup", ExprOp::kFup},
        {"round", ExprOp::kRound},
        {"ln", ExprOp::kLn},
        {"sin", ExprOp::kSin},
        {"sqrt", ExprOp::kSqrt},
        {"tan", ExprOp::kTan},
    }};
    for (const auto& [n, op] : kUnary) {
      if (n == name) {
        bracketed(pos, depth + 1);
        emit(op);
        return;
      }
    }
    throw GcodeError(fmt::format("unknown function '{}'", name));
  }

  void constant(double v) {
    ExprInstr i;
    i.op = ExprOp::kConst;
    i.value = v;
    code_.push_back(i);
  }
  void emit(ExprOp op, std::uint32_t name = 0) {
    ExprInstr i;
    i.op = op;
    i.name = name;
    code_.push_back(i);
  }
  std::uint32_t addName(const std::string& name) {
    names_.push_back(name);
    return static_cast<std::uint32_t>(names_.size() - 1);
  }

  std::string_view text_;
  std::vector<ExprInstr> code_;
  std::vector<std::string> names_;
  ExprOp found_ = ExprOp::kAdd;
};

Expression Expression::parseReal(std::string_view text, std::size_t& pos) {
  // Fast path for a plain number (the common word value): no code, no allocation.
  double v = 0.0;
  if (pos < text.size()) {
    const char* end = detail::scanPlainNumber(text.data() + pos, text.data() + text.size(), v);
    if (end != nullptr) {
      pos = static_cast<std::size_t>(end - text.data());
      return Expression(v);
    }
  }
  ExprCompiler c(text);
  c.real(pos, 0);
  return c.finish();
}

Expression Expression::parseBracketed(std::string_view text, std::size_t& pos) {
  ExprCompiler c(text);
  c.bracketed(pos, 0);
  return c.finish();
}

}  // namespace pkm::cnc
