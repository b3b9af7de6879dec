// The pkmexechonkins parameter file (io::linuxcncExechonParameters): every model value on its named
// line, exactly (the C parser and the comparison with the C++ kinematics are in
// tests/linuxcnc/exechon_core_test.cpp).
#include "pkm/io/linuxcnc_exechon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "support/tolerances.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

/// The numbers on the line that starts with `name` (empty when there is none).
std::vector<double> valuesOf(const std::string& text, const std::string& name) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word != name) continue;
    std::vector<double> out;
    while (words >> word) out.push_back(std::strtod(word.c_str(), nullptr));
    return out;
  }
  return {};
}

TEST(LinuxcncExechon, WritesEveryValueOnItsLine) {
  const ExechonMachine machine = loadExechonMachine("mxt700s-like");
  const kinematics::ExechonModel& m = machine.model;
  const std::string text = linuxcncExechonParameters(machine);
  EXPECT_EQ(valuesOf(text, "dB"), std::vector<double>{m.tripod.dB});
  EXPECT_EQ(valuesOf(text, "l12C"), std::vector<double>{m.tripod.l12C});
  EXPECT_EQ(valuesOf(text, "deltaA"), std::vector<double>{1.0});
  EXPECT_EQ(valuesOf(text, "length_offset"),
            (std::vector<double>{
                m.legs[0].length_offset, m.legs[1].length_offset, m.legs[2].length_offset}));
  EXPECT_EQ(valuesOf(text, "tool_length"), std::vector<double>{m.wrist.tool_length});
  const std::vector<double> R = valuesOf(text, "world_R_zoppi");
  ASSERT_EQ(R.size(), 9u);
  for (int i = 0; i < 9; ++i)
    EXPECT_EQ(R[static_cast<std::size_t>(i)], m.world_T_zoppi.linear()(i / 3, i % 3));
  const std::vector<double> a = valuesOf(text, "alpha_range_deg");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_NEAR(degToRad(a[0]), m.limits.alpha.min, test::kTolExact);
  EXPECT_EQ(valuesOf(text, "fk_max_iterations"),
            std::vector<double>{static_cast<double>(machine.fk.max_iterations)});
  EXPECT_EQ(valuesOf(text, "fk_tolerance"), std::vector<double>{machine.fk.tolerance});
}

TEST(LinuxcncExechon, OpenRangesAreInfinite) {
  const std::string text = linuxcncExechonParameters(loadExechonMachine("exechon-zoppi2010"));
  const std::vector<double> c = valuesOf(text, "c_range_deg");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_TRUE(std::isinf(c[0]) && c[0] < 0.0);
  EXPECT_TRUE(std::isinf(c[1]) && c[1] > 0.0);
  EXPECT_NE(text.find("alpha_range_deg -inf inf\n"), std::string::npos);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
