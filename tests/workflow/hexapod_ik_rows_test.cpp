#include "pkm/workflow/hexapod_ik_rows.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string_view>
#include <vector>

#include "pkm/core/units.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

/// Rows in chunks on the cores give, row by row, exactly what the one-pose functions give.
TEST(HexapodIkRows, EqualsTheOnePoseFunctionsOnEveryRow) {
  const kinematics::HexapodModel model = test::millingModel();
  std::mt19937 rng(7u);
  const std::size_t rows = 70000;  // above kParallelMinItems: chunks on every core
  std::vector<double> poses(6 * rows);
  for (std::size_t i = 0; i < rows; ++i) {
    const kinematics::PoseRpy p = test::randomPose(rng, model.home, 300.0, 0.6);
    for (int k = 0; k < 3; ++k) poses[6 * i + k] = p.position[k];
    for (int k = 0; k < 3; ++k) poses[6 * i + 3 + k] = radToDeg(p.rpy[k]);
  }
  std::vector<double> readings(6 * rows), checked(6 * rows);
  std::vector<std::string_view> status(rows);
  hexapodIkRows(model, poses, readings);
  hexapodIkRows(model, poses, checked, status);
  kinematics::HexapodData data(model);
  std::size_t not_ok = 0;
  for (std::size_t i = 0; i < rows; i += 997) {
    kinematics::PoseRpy p;
    p.position = {poses[6 * i], poses[6 * i + 1], poses[6 * i + 2]};
    p.rpy = {degToRad(poses[6 * i + 3]), degToRad(poses[6 * i + 4]), degToRad(poses[6 * i + 5])};
    const kinematics::StrutVector ik = kinematics::inverseKinematics(model, data, p);
    const kinematics::HexapodCheckResult c = kinematics::checkPose(model, data, p);
    for (int k = 0; k < 6; ++k) {
      ASSERT_EQ(readings[6 * i + k], ik[k]);
      ASSERT_EQ(checked[6 * i + k], c.readings[k]);
    }
    ASSERT_EQ(status[i], c.status());
    not_ok += c.status() == "ok" ? 0 : 1;
  }
  EXPECT_GT(not_ok, 0u);  // the poses reach beyond the limits: the statuses are exercised
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
