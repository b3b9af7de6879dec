// io::appendHexapodCheckRow / appendExechonCheckRow / drmCircleCsv: the fields of the check rows
// and the DRM table with and without a fit.
#include "pkm/io/kinematics_csv.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hexapod_data.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::size_t fields(const std::string& line) {
  return static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
}

TEST(KinematicsCsv, HexapodCheckRowHasAFieldPerColumn) {
  const HexapodMachine m = loadHexapodMachine("hexapod-default");
  kinematics::HexapodData data(m.model);
  std::string row;
  appendHexapodCheckRow(row, 7, kinematics::checkPose(m.model, data, m.model.home));
  EXPECT_THAT(row, StartsWith("7,ok,"));
  EXPECT_EQ(row.back(), '\n');  // no violation: the last field is empty
  EXPECT_EQ(fields(row), fields(hexapodCheckCsvHeader()));
}

TEST(KinematicsCsv, ExechonCheckRowOfAFailedSolveHasOnlyTheStatus) {
  kinematics::ExechonCheckResult c;
  c.solver_status = "unreachable";
  std::string row;
  appendExechonCheckRow(row, 3, c.status(), c);
  EXPECT_EQ(row, "3,unreachable,,,,,,,,,,\n");
  EXPECT_EQ(fields(row), fields(exechonCheckCsvHeader()));
  kinematics::ExechonCheckResult ok;
  ok.stroke_margin = {5.0, 2.0, INFINITY};
  ok.alpha_margin = std::numbers::pi / 180.0;  // 1 degree
  ok.beta_margin = ok.c_margin = ok.a_margin = INFINITY;
  ok.condition_number = 4.0;
  ok.condition_margin = 96.0;
  row.clear();
  appendExechonCheckRow(row, 0, "axis_limit", ok);
  EXPECT_EQ(row, "0,axis_limit,2,B,1,,,,0,4,96,\n");
}

TEST(KinematicsCsv, DrmTableWithItsFitOrItsFailure) {
  kinematics::DrmCircleResult r;
  r.theta = {0.0, std::numbers::pi};
  r.phi = {0.0, 0.0};
  r.coefficients = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const std::string ok = drmCircleCsv(r);
  EXPECT_THAT(ok, StartsWith("theta_deg,phi_drm_deg,fit_deg,residual_deg\n0,0,0,0\n180,0,0,0\n"));
  EXPECT_THAT(ok, HasSubstr("# status ok\n# fit phi(theta)"));
  EXPECT_THAT(ok, HasSubstr("# c5 0\n# max |phi_drm| 0 deg\n# max fit deviation 0 deg\n"));
  r.status = kinematics::ExechonIkStatus::kUnreachable;
  r.failed_index = 2;
  EXPECT_EQ(drmCircleCsv(r),
            "theta_deg,phi_drm_deg,fit_deg,residual_deg\n0,0,,\n180,0,,\n# status unreachable\n"
            "# failed at point 2\n");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
