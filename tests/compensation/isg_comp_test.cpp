// ISG CSV (TwinCAT CNC TF5280) writer: exact text of positioning and straightness blocks, sign
// (+e), and limits.
#include "pkm/compensation/isg_comp.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "pkm/core/error.hpp"

namespace PKM_TEST_NS {

namespace comp = pkm::compensation;

TEST(IsgComp, PositioningAndStraightnessBlocksExactText) {
  const comp::AxisErrorTable x{"x", {0.0, 10.0, 20.5}, {0.02, 0.0, -0.001}, {0.0, -0.01, -0.003}};
  const comp::CrossAxisTable eyx{"X", "Y", {0.0, 10.0}, {0.001, -0.0025}};
  const std::vector<comp::IsgBlock> blocks{comp::isgBlockFromTable(x),
                                           comp::isgBlockFromTable(eyx)};
  EXPECT_EQ(comp::writeIsgCsv(blocks),
            "// positioning error of X (actual - commanded, mean of both directions), mm\n"
            "X EXX\n"
            "0 0.01\n"
            "10 -0.005\n"
            "20.5 -0.002\n"
            "#\n"
            "// straightness of X in Y (actual - nominal), mm\n"
            "X EYX\n"
            "0 0.001\n"
            "10 -0.0025\n");
}

TEST(IsgComp, Limits) {
  comp::AxisErrorTable a{"A", {0.0, 1.0}, {0.0, 0.0}, {0.0, 0.0}};
  EXPECT_THROW((void)comp::isgBlockFromTable(a), pkm::InvalidArgument);  // not X/Y/Z
  const comp::AxisErrorTable nan{
      "Z", {0.0, 1.0}, {0.0, std::numeric_limits<double>::quiet_NaN()}, {0.0, 0.0}};
  EXPECT_THROW((void)comp::isgBlockFromTable(nan), pkm::InvalidArgument);
  const comp::CrossAxisTable same{"X", "X", {0.0, 1.0}, {0.0, 0.0}};
  EXPECT_THROW((void)comp::isgBlockFromTable(same), pkm::InvalidArgument);
  comp::IsgBlock b{"", "X", {0.0, 0.0}, {{"EXX", {0.0, 0.0}}}};
  EXPECT_THROW(b.validate(), pkm::InvalidArgument);  // not increasing
  b.positions = {0.0, 1.0};
  b.columns[0].name = "exx";
  EXPECT_THROW(b.validate(), pkm::InvalidArgument);
  EXPECT_THROW((void)comp::writeIsgCsv({}), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
