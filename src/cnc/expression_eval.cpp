// Evaluation of compiled expressions: a stack machine over the postfix code (semantics in
// expression.cpp's header comment and docs/gcode.md).
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "pkm/cnc/expression.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// a OP b for the binary operators (kPow..kXor) and ATAN2 (a/b, degrees).
double applyBinary(ExprOp op, double a, double b) {
  switch (op) {
    case ExprOp::kPow:
      if (a < 0.0 && std::floor(b) != b)
        throw GcodeError("attempt to raise a negative number to a non-integer power");
      return std::pow(a, b);
    case ExprOp::kMul:
      return a * b;
    case ExprOp::kDiv:
      if (b == 0.0) throw GcodeError("attempt to divide by zero");
      return a / b;
    case ExprOp::kMod: {
      if (b == 0.0) throw GcodeError("attempt to divide by zero (MOD)");
      double r = std::fmod(a, b);
      if (r < 0.0) r += std::abs(b);
      return r;
    }
    case ExprOp::kAdd:
      return a + b;
    case ExprOp::kSub:
      return a - b;
    case ExprOp::kEq:
      return std::abs(a - b) < kExprEqualTolerance ? 1.0 : 0.0;
    case ExprOp::kNe:
      return std::abs(a - b) >= kExprEqualTolerance ? 1.0 : 0.0;
    case ExprOp::kGt:
      return a > b ? 1.0 : 0.0;
    case ExprOp::kGe:
      return a >= b ? 1.0 : 0.0;
    case ExprOp::kLt:
      return a < b ? 1.0 : 0.0;
    case ExprOp::kLe:
      return a <= b ? 1.0 : 0.0;
    case ExprOp::kAnd:
      return (a != 0.0 && b != 0.0) ? 1.0 : 0.0;
    case ExprOp::kOr:
      return (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
    case ExprOp::kXor:
      return ((a != 0.0) != (b != 0.0)) ? 1.0 : 0.0;
    case ExprOp::kAtan2:
      return std::atan2(a, b) * kDegPerRad;
    default:
      throw GcodeError("internal error: bad expression code");
  }
}

/// OP b for negation and the one-argument functions (angles in degrees).
double applyUnary(ExprOp op, double b) {
  switch (op) {
    case ExprOp::kNeg:
      return -b;
    case ExprOp::kAbs:
      return std::abs(b);
    case ExprOp::kAcos:
      if (b < -1.0 || b > 1.0) throw GcodeError("ACOS argument out of range [-1, 1]");
      return std::acos(b) * kDegPerRad;
    case ExprOp::kAsin:
      if (b < -1.0 || b > 1.0) throw GcodeError("ASIN argument out of range [-1, 1]");
      return std::asin(b) * kDegPerRad;
    case ExprOp::kCos:
      return std::cos(b / kDegPerRad);
    case ExprOp::kExp:
      return std::exp(b);
    case ExprOp::kFix:
      return std::floor(b);
    case ExprOp::kFup:
      return std::ceil(b);
    case ExprOp::kRound:
      return std::round(b);
    case ExprOp::kLn:
      if (b <= 0.0) throw GcodeError("LN of a zero or negative number");
      return std::log(b);
    case ExprOp::kSin:
      return std::sin(b / kDegPerRad);
    case ExprOp::kSqrt:
      if (b < 0.0) throw GcodeError("SQRT of a negative number");
      return std::sqrt(b);
    case ExprOp::kTan:
      return std::tan(b / kDegPerRad);
    default:
      throw GcodeError("internal error: bad expression code");
  }
}

}  // namespace

double Expression::run(ParameterSource& params) const {
  const std::vector<ExprInstr>& code = code_->code;
  const std::vector<std::string>& names = code_->names;
  std::vector<double> stack;
  stack.reserve(code.size());
  auto pop = [&stack]() {
    const double v = stack.back();
    stack.pop_back();
    return v;
  };
  for (const ExprInstr& in : code) {
    switch (in.op) {
      case ExprOp::kConst:
        stack.push_back(in.value);
        continue;
      case ExprOp::kNamed:
        stack.push_back(params.named(names[in.name]));
        continue;
      case ExprOp::kExists:
        stack.push_back(params.exists(names[in.name]) ? 1.0 : 0.0);
        continue;
      case ExprOp::kExistsNumbered: {
        const double idx = pop();
        const double rounded = std::round(idx);
        const bool ok =
            std::abs(idx - rounded) <= kExprEqualTolerance && rounded >= 1.0 && rounded <= 5601.0;
        stack.push_back(ok ? 1.0 : 0.0);
        continue;
      }
      case ExprOp::kParam: {
        const double idx = pop();
        const double rounded = std::round(idx);
        if (std::abs(idx - rounded) > kExprEqualTolerance || rounded < 1.0 || rounded > 5601.0)
          throw GcodeError(fmt::format("parameter number {} out of range (1..5601)", idx));
        stack.push_back(params.numbered(static_cast<int>(rounded)));
        continue;
      }
      default:
        break;
    }
    const bool binary = in.op >= ExprOp::kPow && in.op <= ExprOp::kXor;
    const bool two_args = binary || in.op == ExprOp::kAtan2;
    const double b = pop();
    const double a = two_args ? pop() : 0.0;
    const double r = two_args ? applyBinary(in.op, a, b) : applyUnary(in.op, b);
    if (!std::isfinite(r)) throw GcodeError("expression result is not a finite number");
    stack.push_back(r);
  }
  if (stack.size() != 1) throw GcodeError("internal error: unbalanced expression");
  return stack.back();
}

}  // namespace pkm::cnc
