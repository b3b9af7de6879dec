// Expressions against hand-computed values (LinuxCNC semantics; the MOD, FIX/FUP, ROUND, ATAN,
// precedence and EQ-tolerance cases were checked with rs274, see docs/gcode.md).
#include "pkm/cnc/expression.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <map>
#include <random>
#include <string>

#include "pkm/cnc/gcode_error.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using pkm::test::kTolExact;

class MapSource : public ParameterSource {
 public:
  double numbered(int index) override { return num[index]; }
  double named(const std::string& name) override {
    const auto it = names.find(name);
    if (it == names.end()) throw GcodeError("undefined");
    return it->second;
  }
  bool exists(const std::string& name) override { return names.count(name) != 0; }
  std::map<int, double> num;
  std::map<std::string, double> names;
};

double eval(const std::string& text, ParameterSource& p) {
  std::size_t pos = 0;
  const Expression e = Expression::parseReal(text, pos);
  EXPECT_EQ(pos, text.size()) << text;
  return e.evaluate(p);
}

double eval(const std::string& text) {
  MapSource p;
  return eval(text, p);
}

TEST(Expression, NumbersAndConstantsNeedNoCode) {
  std::size_t pos = 0;
  const Expression e = Expression::parseReal("-12.5x", pos);
  EXPECT_TRUE(e.isConstant());
  EXPECT_EQ(pos, 5u);
  EXPECT_EQ(eval(".5"), 0.5);
  EXPECT_EQ(eval("+3."), 3.0);
}

/// Plain decimals (the fast path up to 15 digits, std::from_chars beyond) read exactly as
/// std::from_chars reads them: random digit strings with the point anywhere.
TEST(Expression, DecimalsReadAsFromChars) {
  std::mt19937_64 rng(pkm::test::kSeed);
  std::uniform_int_distribution<int> length(1, 20), digit(0, 9);
  for (int trial = 0; trial < 100000; ++trial) {
    std::string d;
    const int n = length(rng);
    for (int i = 0; i < n; ++i) d.push_back(static_cast<char>('0' + digit(rng)));
    std::uniform_int_distribution<std::size_t> at(0, d.size());
    const std::size_t split = at(rng);
    const std::string t = fmt::format("{}.{}", d.substr(0, split), d.substr(split));
    double want = 0.0;
    std::from_chars(t.data(), t.data() + t.size(), want);
    ASSERT_EQ(eval(t), want) << t;
    ASSERT_EQ(eval(fmt::format("-{}", t)), -want) << t;
  }
}

TEST(Expression, PrecedenceAndAssociativity) {
  EXPECT_NEAR(eval("[1+2*3**2]"), 19.0, kTolExact);
  EXPECT_NEAR(eval("[-2**2]"), 4.0, kTolExact);  // unary minus binds to the operand
  EXPECT_NEAR(eval("[3-2-1]"), 0.0, kTolExact);
  EXPECT_NEAR(eval("[2**3**2]"), 64.0, kTolExact);  // left to right
  EXPECT_NEAR(eval("[1or0and0]"), 0.0, kTolExact);  // AND, OR at one level, left to right
  EXPECT_NEAR(eval("[8/2/2]"), 2.0, kTolExact);
  EXPECT_NEAR(eval("[1+2eq3]"), 1.0, kTolExact);
}

TEST(Expression, ModFixFupRoundMatchLinuxcnc) {
  EXPECT_EQ(eval("[5mod-3]"), 2.0);
  EXPECT_EQ(eval("[-5mod3]"), 1.0);
  EXPECT_EQ(eval("[7mod3]"), 1.0);
  EXPECT_EQ(eval("fix[-2.5]"), -3.0);
  EXPECT_EQ(eval("fup[-2.5]"), -2.0);
  EXPECT_EQ(eval("round[2.5]"), 3.0);
  EXPECT_EQ(eval("round[-2.5]"), -3.0);
}

TEST(Expression, FunctionsInDegrees) {
  EXPECT_NEAR(eval("sin[30]"), 0.5, kTolExact);
  EXPECT_NEAR(eval("cos[60]"), 0.5, kTolExact);
  EXPECT_NEAR(eval("tan[45]"), 1.0, kTolExact);
  EXPECT_NEAR(eval("asin[0.5]"), 30.0, 1e-12);
  EXPECT_NEAR(eval("acos[0.5]"), 60.0, 1e-12);
  EXPECT_NEAR(eval("atan[1]/[-1]"), 135.0, 1e-12);
  EXPECT_NEAR(eval("sqrt[16]"), 4.0, kTolExact);
  EXPECT_NEAR(eval("abs[-2]"), 2.0, kTolExact);
  EXPECT_NEAR(eval("exp[1]"), std::exp(1.0), kTolExact);
  EXPECT_NEAR(eval("ln[1]"), 0.0, kTolExact);
}

TEST(Expression, ComparisonsAndLogic) {
  EXPECT_EQ(eval("[2eq2.00000001]"), 1.0);  // within 0.0001
  EXPECT_EQ(eval("[2ne2.001]"), 1.0);
  EXPECT_EQ(eval("[3gt2]"), 1.0);
  EXPECT_EQ(eval("[3ge3]"), 1.0);
  EXPECT_EQ(eval("[1lt2]"), 1.0);
  EXPECT_EQ(eval("[2le1]"), 0.0);
  EXPECT_EQ(eval("[1xor1]"), 0.0);
  EXPECT_EQ(eval("[2and3]"), 1.0);
}

TEST(Expression, Parameters) {
  MapSource p;
  p.num[1] = 3.0;
  p.num[3] = 7.0;
  p.num[2] = 1.0;
  p.names["a"] = 8.0;
  EXPECT_EQ(eval("#1", p), 3.0);
  EXPECT_EQ(eval("#[1+2]", p), 7.0);
  EXPECT_EQ(eval("##2", p), 3.0);
  EXPECT_EQ(eval("[#<a>*2]", p), 16.0);
  EXPECT_EQ(eval("exists[#<a>]", p), 1.0);
  EXPECT_EQ(eval("exists[#<b>]", p), 0.0);
  EXPECT_THROW(eval("#<b>", p), GcodeError);
  EXPECT_THROW(eval("#6000", p), GcodeError);
}

TEST(Expression, DomainErrorsThrow) {
  EXPECT_THROW(eval("[1/0]"), GcodeError);
  EXPECT_THROW(eval("ln[0]"), GcodeError);
  EXPECT_THROW(eval("sqrt[-1]"), GcodeError);
  EXPECT_THROW(eval("asin[2]"), GcodeError);
  EXPECT_THROW(eval("[[-8]**0.5]"), GcodeError);
  EXPECT_THROW(eval("[1mod0]"), GcodeError);
}

TEST(Expression, SyntaxErrorsThrow) {
  for (const char* bad :
       {"[1+", "[1+2", "foo[1]", "[1 2]", "atan[1]", "exists[1]", "[1$2]", "", "..", "#<x"}) {
    std::size_t pos = 0;
    EXPECT_THROW((void)Expression::parseReal(bad, pos), GcodeError) << bad;
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
