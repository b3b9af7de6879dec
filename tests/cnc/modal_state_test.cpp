// The coordinate chain machine = program + G5x + G92 + tool offset, and the unit scale.
#include "pkm/cnc/modal_state.hpp"

#include <gtest/gtest.h>

#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace {

using pkm::test::kTolExact;

TEST(ModalState, StartUpModesAreRs274s) {
  const MachineState s;
  EXPECT_FALSE(s.inch);
  EXPECT_EQ(s.plane, Plane::kXY);
  EXPECT_FALSE(s.incremental);
  EXPECT_FALSE(s.ijk_absolute);
  EXPECT_TRUE(s.retract_to_r);  // G99
  EXPECT_EQ(s.motion, 800);     // G80
  EXPECT_EQ(s.coordinate_system, 1);
  EXPECT_EQ(s.feed, 0.0);
}

TEST(ModalState, ProgramCoordinatesRemoveEveryOffset) {
  MachineState s;
  s.machine = {10, 20, 30, 40, 50, 60};
  s.g5x = {1, 2, 3, 4, 5, 6};
  s.g92 = {0.5, 0, 0, 1, 0, 0};
  s.tool_offset = {0, 0, 12.9794, 0, 0, 0};
  EXPECT_NEAR(s.program(0), 8.5, kTolExact);
  EXPECT_NEAR(s.program(2), 30 - 3 - 12.9794, kTolExact);
  EXPECT_NEAR(s.program(3), 35, kTolExact);
  for (std::size_t i = 0; i < 6; ++i)
    EXPECT_NEAR(s.program(i) + s.offset(i), s.machine[i], kTolExact);
}

TEST(ModalState, UnitScaleAppliesToLengthsOnly) {
  MachineState s;
  EXPECT_EQ(s.scale(), 1.0);
  s.inch = true;
  EXPECT_EQ(s.scale(), kMmPerInch);
  EXPECT_EQ(s.axisScale(2), kMmPerInch);
  EXPECT_EQ(s.axisScale(3), 1.0);
}

}  // namespace
}  // namespace pkm::cnc
