#include "pkm/kinematics/exechon_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "kinematics/exechon_sample_models.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

TEST(ExechonModel, SampleModelsAreValid) {
  EXPECT_NO_THROW(test::zoppiTable1Model().validate());
  EXPECT_NO_THROW(test::biJinToyModel().validate());
  EXPECT_NO_THROW(test::machineModel().validate());
  EXPECT_EQ(test::zoppiTable1Model().characteristicLength(), 779.8);
}

TEST(ExechonModel, DefaultModelIsRejected) {
  EXPECT_THROW(ExechonModel().validate(), InvalidArgument);  // dB = 0, dA = dC
}

/// Expects validate() to throw with `needle` in the message after `edit`.
void expectInvalid(const std::function<void(ExechonModel&)>& edit, const std::string& needle) {
  ExechonModel m = test::machineModel();
  edit(m);
  try {
    m.validate();
    ADD_FAILURE() << "no exception for " << needle;
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(ExechonModel, ValidateNamesTheBadField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expectInvalid([&](ExechonModel& m) { m.tripod.hx = nan; }, "tripod geometry");
  expectInvalid([](ExechonModel& m) { m.tripod.dB = 0; }, "dB");
  expectInvalid([](ExechonModel& m) { m.tripod.dC = m.tripod.dA; }, "dA and dC");
  expectInvalid([](ExechonModel& m) { m.tripod.deltaC = 0; }, "branch signs");
  expectInvalid([](ExechonModel& m) { m.legs[2].min_reading = 1e4; }, "leg C: stroke");
  expectInvalid([&](ExechonModel& m) { m.legs[1].length_offset = nan; }, "leg B: length offset");
  expectInvalid([](ExechonModel& m) { m.limits.beta = {1, -1}; }, "limits.beta");
  expectInvalid([](ExechonModel& m) { m.wrist.a_axis = {0, 0, 1}; }, "perpendicular");
  expectInvalid([](ExechonModel& m) { m.wrist.c_axis.setZero(); }, "non-zero");
  expectInvalid([](ExechonModel& m) { m.wrist.a_sign = 2; }, "a_sign");
  expectInvalid([&](ExechonModel& m) { m.wrist.tool_length = nan; }, "wrist is not finite");
  expectInvalid([](ExechonModel& m) { m.max_condition = 1; }, "max_condition");
  expectInvalid([](ExechonModel& m) { m.world_T_zoppi.linear() *= 2; }, "rigid");
  expectInvalid([&](ExechonModel& m) { m.home.c = nan; }, "home is not finite");
}

TEST(ExechonModel, SingularHomeIsRejected) {
  // alpha = beta = 0, h = −hz puts the toy's wrist point (hx = 0) at O, on the base axis: r = 0 and
  // S does not determine e (J_S_e is singular).
  ExechonModel m = test::biJinToyModel();
  m.home.e = {0, 0, -m.tripod.hz};
  try {
    m.validate();
    ADD_FAILURE() << "singular home accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("singular at the home"), std::string::npos) << e.what();
  }
}

TEST(ExechonModel, AngleRangeMargin) {
  const AngleRange r{-1.0, 2.0};
  EXPECT_EQ(r.margin(0.5), 1.5);
  EXPECT_EQ(r.margin(-1.5), -0.5);
  EXPECT_EQ(r.margin(2.25), -0.25);
  EXPECT_EQ(AngleRange{}.margin(1e9), std::numeric_limits<double>::infinity());
}

TEST(ExechonModel, BranchIndexRoundTrips) {
  for (int i = 0; i < 16; ++i) {
    const ExechonBranch b = ExechonBranch::fromIndex(i);
    EXPECT_TRUE(b.isValid());
    EXPECT_EQ(b.index(), i);
  }
  EXPECT_EQ(ExechonBranch::fromIndex(0), (ExechonBranch{1, 1, 1, 1}));
  EXPECT_EQ(ExechonBranch::fromIndex(15), (ExechonBranch{-1, -1, -1, -1}));
  EXPECT_FALSE((ExechonBranch{0, 1, 1, 1}).isValid());
  EXPECT_THROW(static_cast<void>(ExechonBranch::fromIndex(-1)), InvalidArgument);
  ExechonTripodGeometry g;
  g.delta2B = -1;
  EXPECT_EQ(branchOf(g), (ExechonBranch{1, -1, 1, 1}));
}

TEST(ExechonModel, DataHoldsBaseJointsAndConfiguration) {
  const ExechonModel m = test::zoppiTable1Model();
  ExechonData data(m);
  EXPECT_EQ(data.zoppi_p_base[0], Eigen::Vector3d(0, m.tripod.dA, 0));
  EXPECT_EQ(data.zoppi_p_base[1], Eigen::Vector3d(m.tripod.dB, 0, 0));
  EXPECT_EQ(data.zoppi_p_base[2], Eigen::Vector3d(0, m.tripod.dC, 0));
  data.e = {1, 2, 3};
  data.c = 4;
  data.a = 5;
  const ExechonConfiguration c = configurationOf(data);
  EXPECT_EQ(c.e, data.e);
  EXPECT_EQ(c.c, 4);
  EXPECT_EQ(c.a, 5);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
