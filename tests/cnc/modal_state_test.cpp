// The coordinate chain machine = Rz(rotation)·(program + G92) + G5x + tool offset, its inverse,
// the targets of absolute and incremental moves, and the unit scale.
#include "pkm/cnc/modal_state.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

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
  const Axes back = s.toMachine(s.programPosition());
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(back[i], s.machine[i], kTolExact);
}

TEST(ModalState, RotationTurnsTheProgramAboutTheSystemOrigin) {
  MachineState s;
  s.g5x = {100, 0, 0, 0, 0, 0};
  s.g92 = {1, 0, 0, 0, 0, 0};
  s.tool_offset = {0, 0, 5, 0, 0, 0};
  s.rotation = 90.0;
  // Program (2, 0): + G92 = (3, 0), turned 90 degrees = (0, 3), + G5x = (100, 3), + tool Z.
  const Axes m = s.toMachine({2, 0, 1, 0, 0, 0});
  EXPECT_NEAR(m[0], 100.0, kTolExact);
  EXPECT_NEAR(m[1], 3.0, kTolExact);
  EXPECT_NEAR(m[2], 6.0, kTolExact);
  s.machine = m;
  EXPECT_NEAR(s.program(0), 2.0, kTolExact);
  EXPECT_NEAR(s.program(1), 0.0, kTolExact);
  // G90 X5 keeps the program Y; G91 X1 moves along the turned X axis.
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  const Axes a = s.target({5, kNaN, kNaN, kNaN, kNaN, kNaN});
  EXPECT_NEAR(a[0], 100.0, kTolExact);
  EXPECT_NEAR(a[1], 6.0, kTolExact);
  s.incremental = true;
  const Axes b = s.target({1, kNaN, kNaN, kNaN, kNaN, kNaN});
  EXPECT_NEAR(b[0], 100.0, kTolExact);
  EXPECT_NEAR(b[1], 4.0, kTolExact);
  EXPECT_EQ(b[2], m[2]);  // an axis without a word stays
}

TEST(ModalState, UnitScaleAppliesToLengthsOnly) {
  MachineState s;
  EXPECT_EQ(s.scale(), 1.0);
  s.inch = true;
  EXPECT_EQ(s.scale(), kMmPerInch);
  EXPECT_EQ(s.axisScale(2), kMmPerInch);
  EXPECT_EQ(s.axisScale(3), 1.0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
