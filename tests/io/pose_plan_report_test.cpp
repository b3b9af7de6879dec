// io::posePlanCsv / posePlanGcode / posePlanSummary / posePlanJson on a plan built by hand.
#include "pkm/io/pose_plan_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

PosePlanReport hexapodPlan() {
  PosePlanReport r;
  r.machine = "hx";
  r.index_label = "o2";
  r.index = calibration::ObservabilityIndex::kO2;
  r.plan.chosen = {3, 1};
  r.plan.index_value = 0.5;
  r.plan.random_baseline = 0.25;
  r.plan.condition_number = 100.0;
  r.plan.rank = 42;
  r.plan.swaps = 2;
  r.candidates = 10;
  r.parameters = 42;
  r.home.position = {0.0, 0.0, 200.0};
  kinematics::PoseRpy a, b;
  a.position = {1.5, -2.0, 210.0};
  a.rpy = {degToRad(90.0), 0.0, 0.0};
  b.position = {0.0, 0.0, 190.0};
  r.poses = {a, b};
  return r;
}

TEST(PosePlanReport, HexapodCsvAndProgram) {
  const PosePlanReport r = hexapodPlan();
  EXPECT_EQ(posePlanCsv(r), "pose,x,y,z,a,b,c\n0,1.5,-2,210,90,0,0\n1,0,0,190,0,0,0\n");
  const std::string g = posePlanGcode(r);
  EXPECT_EQ(g,
            "(pkm plan-poses: 2 calibration poses for hx by O2; measure at every M0)\n"
            "G21 G90 (absolute)\n"
            "G1 X0.0000 Y0.0000 Z200.0000 A0.0000 B0.0000 C0.0000 F1000.0 (home)\n"
            "N10 G1 X1.5000 Y-2.0000 Z210.0000 A90.0000 B0.0000 C0.0000\n"
            "M0 (measure pose 0)\n"
            "N20 G1 X0.0000 Y0.0000 Z190.0000 A0.0000 B0.0000 C0.0000\n"
            "M0 (measure pose 1)\n"
            "G1 X0.0000 Y0.0000 Z200.0000 A0.0000 B0.0000 C0.0000\nM2\n");
  EXPECT_EQ(posePlanSummary(r),
            "2 poses of 10 candidates by o2: O2 = 0.5 (random choice 0.25), condition number "
            "100, rank 42, 2 exchanges");
}

TEST(PosePlanReport, ExechonProgramUsesTheWristReadings) {
  PosePlanReport r = hexapodPlan();
  r.kind = "exechon";
  r.parameters = 26;
  r.plan.chosen = {0};
  r.points = {{{1.0, 2.0, 3.0}, {0.0, 0.0, -1.0}}};
  r.moves = {{{0.0, 0.0, -0.00001}, 0.0, 0.0}, {{1.0, 2.0, 3.0}, degToRad(10.0), degToRad(-5.0)}};
  EXPECT_EQ(posePlanCsv(r), "pose,x,y,z,i,j,k\n0,1,2,3,0,0,-1\n");
  const std::string g = posePlanGcode(r);
  EXPECT_THAT(g, HasSubstr("run with --orientation axes"));
  EXPECT_THAT(g,
              HasSubstr("G1 X0.0000 Y0.0000 Z0.0000 A0.0000 C0.0000 F1000.0 (home)\n"));  // no -0
  EXPECT_THAT(
      g, HasSubstr("N10 G1 X1.0000 Y2.0000 Z3.0000 A10.0000 C-5.0000\nM0 (measure point 0)\n"));
  EXPECT_THAT(posePlanSummary(r), HasSubstr("1 tracker points of 10 candidates"));
  EXPECT_THAT(posePlanSummary(r), HasSubstr("rank 42 of 26"));
}

TEST(PosePlanReport, JsonHoldsThePlanAndThePoses) {
  const nlohmann::json j = nlohmann::json::parse(posePlanJson(hexapodPlan()));
  EXPECT_EQ(j["kind"], "hexapod");
  EXPECT_EQ(j["index"], "O2");
  EXPECT_EQ(j["rank"], 42);
  EXPECT_EQ(j["chosen"], nlohmann::json::array({3, 1}));
  ASSERT_EQ(j["poses"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["poses"][0]["rpy_deg"][0].get<double>(), 90.0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
