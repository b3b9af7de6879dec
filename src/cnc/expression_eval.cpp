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
    double r = 0.0;
    switch (in.op) {
      case ExprOp::kNeg:
        r = -b;
        break;
      case ExprOp::kPow:
        if (a < 0.0 && std::floor(b) != b)
          throw GcodeError("attempt to raise a negative number to a non-integer power");
        r = std::pow(a, b);
        break;
      case ExprOp::kMul:
        r = a * b;
        break;
      case ExprOp::kDiv:
        if (b == 0.0) throw GcodeError("attempt to divide by zero");
        r = a / b;
        break;
      case ExprOp::kMod:
        if (b == 0.0) throw GcodeError("attempt to divide by zero (MOD)");
        r = std::fmod(a, b);
        if (r < 0.0) r += std::abs(b);
        break;
      case ExprOp::kAdd:
        r = a + b;
        break;
      case ExprOp::kSub:
        r = a - b;
        break;
      case ExprOp::kEq:
        r = std::abs(a - b) < kExprEqualTolerance ? 1.0 : 0.0;
        break;
      case ExprOp::kNe:
        r = std::abs(a - b) >= kExprEqualTolerance ? 1.0 : 0.0;
        break;
      case ExprOp::kGt:
        r = a > b ? 1.0 : 0.0;
        break;
      case ExprOp::kGe:
        r = a >= b ? 1.0 : 0.0;
        break;
      case ExprOp::kLt:
        r = a < b ? 1.0 : 0.0;
        break;
      case ExprOp::kLe:
        r = a <= b ? 1.0 : 0.0;
        break;
      case ExprOp::kAnd:
        r = (a != 0.0 && b != 0.0) ? 1.0 : 0.0;
        break;
      case ExprOp::kOr:
        r = (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
        break;
      case ExprOp::kXor:
        r = ((a != 0.0) != (b != 0.0)) ? 1.0 : 0.0;
        break;
      case ExprOp::kAtan2:
        r = std::atan2(a, b) * kDegPerRad;
        break;
      case ExprOp::kAbs:
        r = std::abs(b);
        break;
      case ExprOp::kAcos:
        if (b < -1.0 || b > 1.0) throw GcodeError("ACOS argument out of range [-1, 1]");
        r = std::acos(b) * kDegPerRad;
        break;
      case ExprOp::kAsin:
        if (b < -1.0 || b > 1.0) throw GcodeError("ASIN argument out of range [-1, 1]");
        r = std::asin(b) * kDegPerRad;
        break;
      case ExprOp::kCos:
        r = std::cos(b / kDegPerRad);
        break;
      case ExprOp::kExp:
        r = std::exp(b);
        break;
      case ExprOp::kFix:
        r = std::floor(b);
        break;
      case ExprOp::kFup:
        r = std::ceil(b);
        break;
      case ExprOp::kRound:
        r = std::round(b);
        break;
      case ExprOp::kLn:
        if (b <= 0.0) throw GcodeError("LN of a zero or negative number");
        r = std::log(b);
        break;
      case ExprOp::kSin:
        r = std::sin(b / kDegPerRad);
        break;
      case ExprOp::kSqrt:
        if (b < 0.0) throw GcodeError("SQRT of a negative number");
        r = std::sqrt(b);
        break;
      case ExprOp::kTan:
        r = std::tan(b / kDegPerRad);
        break;
      default:
        throw GcodeError("internal error: bad expression code");
    }
    if (!std::isfinite(r)) throw GcodeError("expression result is not a finite number");
    stack.push_back(r);
  }
  if (stack.size() != 1) throw GcodeError("internal error: unbalanced expression");
  return stack.back();
}

}  // namespace pkm::cnc
