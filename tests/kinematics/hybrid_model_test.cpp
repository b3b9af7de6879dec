#include "pkm/kinematics/hybrid_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pkm/core/error.hpp"
#include "support/hybrid_samples.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

using test::kTolExact;

/// Positions are a few thousand mm, so identities hold to kTolExact relative to this scale.
constexpr double kLengthScale = 1e4;

TEST(HybridModel, SampleModelsValidate) {
  EXPECT_NO_THROW(test::mxt700sLikeModel().validate());
  EXPECT_NO_THROW(test::offsetModel().validate());
  EXPECT_NO_THROW(HybridMachineModel{}.validate());  // unlimited strokes and volume
}

TEST(HybridModel, RejectsUnusableModels) {
  HybridMachineModel m = test::mxt700sLikeModel();
  m.x2_stroke = {10.0, -10.0};
  EXPECT_THROW(m.validate(), InvalidArgument);
  m = test::mxt700sLikeModel();
  m.y2_stroke.max = std::nan("");
  EXPECT_THROW(m.validate(), InvalidArgument);
  m = test::mxt700sLikeModel();
  m.pkm_min.z() = 400.0;  // above pkm_max.z
  EXPECT_THROW(m.validate(), InvalidArgument);
  m = test::mxt700sLikeModel();
  m.P_p_tcp0.y() = INFINITY;
  EXPECT_THROW(m.validate(), InvalidArgument);
  m = test::mxt700sLikeModel();
  m.Y2_p_work.x() = std::nan("");
  EXPECT_THROW(m.validate(), InvalidArgument);
}

TEST(HybridModel, NominalToolPositionIsTheSumOfTheAxes) {
  std::mt19937 rng(test::kSeed);
  const HybridMachineModel m = test::offsetModel();
  EXPECT_LT((m.workOffset() - (m.X2_p_P + m.P_p_tcp0 - m.Y2_p_work)).norm(), kTolExact);
  for (int k = 0; k < 50; ++k) {
    const HybridCommand c = test::randomCommand(rng, m);
    const Eigen::Vector3d expected(c.x2 + c.pkm.x(), c.pkm.y() - c.y2, c.pkm.z());
    EXPECT_LT((hybridNominalToolPosition(m, c) - m.workOffset() - expected).norm(),
              kTolExact * kLengthScale);
  }
  // Without offsets (seed 000), all axes at zero put the tool at the work origin.
  EXPECT_TRUE(hybridNominalToolPosition(test::mxt700sLikeModel(), HybridCommand{}).isZero(0.0));
}

TEST(HybridModel, CommandForToolInvertsTheNominalPosition) {
  std::mt19937 rng(test::kSeed);
  const HybridMachineModel m = test::offsetModel();
  for (int k = 0; k < 50; ++k) {
    const HybridCommand c = test::randomCommand(rng, m);
    const Eigen::Vector3d p = hybridNominalToolPosition(m, c);
    const HybridCommand back = hybridCommandForTool(m, p, c.x2, c.y2);
    EXPECT_EQ(back.x2, c.x2);
    EXPECT_EQ(back.y2, c.y2);
    EXPECT_LT((back.pkm - c.pkm).norm(), kTolExact * kLengthScale);
  }
}

TEST(HybridModel, CentredSplitPutsThePkmAtTheCentreOfItsVolume) {
  const HybridMachineModel m = test::mxt700sLikeModel();  // PKM volume centred at xP = yP = 0
  struct Case {
    Eigen::Vector3d target;
    double x2, y2;
    Eigen::Vector3d pkm;
    bool within;
  };
  const Case cases[] = {
      {{-2500.0, 300.0, 150.0},
       -2500.0,
       -300.0,
       {0.0, 0.0, 150.0},
       true},  // X2 and Y2 take x and y
      {{-2500.0, -300.0, 150.0},
       -2500.0,
       0.0,
       {0.0, -300.0, 150.0},
       true},  // y2 clamped: the PKM takes y
      {{-5000.0, 0.0, 0.0}, -4000.0, 0.0, {-1000.0, 0.0, 0.0}, false},  // out of reach
  };
  for (const Case& k : cases) {
    const HybridCommand c = hybridCommandCentred(m, k.target);
    EXPECT_NEAR(c.x2, k.x2, kTolExact * kLengthScale);
    EXPECT_NEAR(c.y2, k.y2, kTolExact * kLengthScale);
    EXPECT_LT((c.pkm - k.pkm).norm(), kTolExact * kLengthScale);
    EXPECT_EQ(hybridWithinLimits(m, c), k.within);
    EXPECT_LT((hybridNominalToolPosition(m, c) - k.target).norm(), kTolExact * kLengthScale);
  }
  EXPECT_THROW((void)hybridCommandCentred(m, Eigen::Vector3d(0.0, std::nan(""), 0.0)),
               InvalidArgument);
}

TEST(HybridModel, WithinLimitsIncludesTheEnds) {
  const HybridMachineModel m = test::mxt700sLikeModel();
  HybridCommand c;
  c.x2 = -4000.0;
  c.y2 = 0.0;
  c.pkm = m.pkm_max;
  EXPECT_TRUE(hybridWithinLimits(m, c));
  c.x2 = 1e-9;
  EXPECT_FALSE(hybridWithinLimits(m, c));
  c.x2 = -10.0;
  c.pkm.y() = std::nan("");
  EXPECT_FALSE(hybridWithinLimits(m, c));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
