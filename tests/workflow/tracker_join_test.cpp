// workflow::joinTrackerPoints end to end: a plan, a tracker's SpatialAnalyzer export of a machine
// whose geometry differs from the nominal, measured in the tracker's own frame with noise, in
// another order and with a pose missing, joined and calibrated: the held-out error falls to the
// noise. Plus the matching rules and the errors.
#include "pkm/workflow/tracker_join.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;
namespace kin = pkm::kinematics;

constexpr double kNoiseMm = 0.002;           ///< the tracker's noise per coordinate, 1 σ
constexpr double kHeldOutAfterLimit = 0.01;  ///< held-out RMS after calibration, mm
constexpr std::uint32_t kSeed = 20261126;

/// A plan of `n` random poses about home (±60 mm, ±5°), as `pkm plan-poses` writes it.
std::string plan(const kin::HexapodModel& m, int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::string t = "pose,x,y,z,a,b,c\n";
  for (int i = 0; i < n; ++i)
    t += fmt::format("{},{},{},{},{},{},{}\n",
                     i,
                     m.home.position.x() + 60 * d(rng),
                     m.home.position.y() + 60 * d(rng),
                     m.home.position.z() + 40 * d(rng),
                     5 * d(rng),
                     5 * d(rng),
                     5 * d(rng));
  return t;
}

/// What the tracker exports for `plan` on the true machine: the SMR at `smr` on the tool, in the
/// tracker's frame, with noise, rows shuffled, pose `skip` missed.
std::string trackerExport(const std::string& plan_text,
                          const kin::HexapodModel& nominal,
                          const kin::HexapodModel& truth,
                          const Eigen::Isometry3d& world_T_tracker,
                          const Eigen::Vector3d& smr,
                          int skip,
                          std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, kNoiseMm);
  kin::HexapodData dn(nominal), dt(truth);
  std::vector<std::string> rows;
  std::istringstream in(plan_text);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    double v[7];
    std::sscanf(line.c_str(),
                "%lf,%lf,%lf,%lf,%lf,%lf,%lf",
                &v[0],
                &v[1],
                &v[2],
                &v[3],
                &v[4],
                &v[5],
                &v[6]);
    if (static_cast<int>(v[0]) == skip) continue;
    kin::PoseRpy pose;
    pose.position = {v[1], v[2], v[3]};
    pose.rpy = Eigen::Vector3d(v[4], v[5], v[6]) * (M_PI / 180.0);
    const kin::StrutVector commanded = kin::inverseKinematics(nominal, dn, pose);
    EXPECT_TRUE(kin::forwardKinematics(truth, dt, commanded, pose).ok());
    const Eigen::Vector3d world_p = dt.pose.position + geometry::rotationFromRpy(dt.pose.rpy) * smr;
    Eigen::Vector3d p = world_T_tracker.inverse() * world_p;
    for (int k = 0; k < 3; ++k) p[k] += noise(rng);
    rows.push_back(fmt::format(
        "Tracker Poses P{} {:.5f} {:.5f} {:.5f}\n", static_cast<int>(v[0]), p[0], p[1], p[2]));
  }
  std::shuffle(rows.begin(), rows.end(), rng);
  std::string t = "// SA Version: 2024.1\n// Working Frame: A::Tracker\n";
  for (const std::string& r : rows) t += r;
  return t;
}

TEST(TrackerJoin, AJoinedExportCalibratesTheMachine) {
  std::mt19937 rng(kSeed);
  const kin::HexapodModel nominal = io::loadHexapodMachine("hexapod-default").model;
  kin::HexapodModel truth = nominal;
  truth.struts[0].world_p_base += Eigen::Vector3d(1.2, -0.8, 0.5);
  truth.struts[3].platform_p_joint += Eigen::Vector3d(-0.9, 1.0, 0.0);
  truth.struts[5].length_offset += 0.7;
  Eigen::Isometry3d world_T_tracker = Eigen::Isometry3d::Identity();
  world_T_tracker.linear() = geometry::rotationFromRpy({0.01, -0.02, 0.6});
  world_T_tracker.translation() = Eigen::Vector3d(1500, -200, 100);
  const Eigen::Vector3d smr(0, 60, 80);

  TrackerJoinRequest q;
  q.machine = "hexapod-default";
  q.smr_offset = smr;
  q.plan = {"plan.csv", plan(nominal, 80, rng)};
  q.points = {"sa.txt", trackerExport(q.plan.text, nominal, truth, world_T_tracker, smr, 7, rng)};
  const TrackerJoinResult fit = joinTrackerPoints(q);
  EXPECT_EQ(fit.rows, 79u);
  EXPECT_THAT(fit.notes.back(), HasSubstr("pose 7 (plan.csv:9): no point in sa.txt; left out"));
  EXPECT_THAT(fit.text, HasSubstr("# frame: tracker"));
  EXPECT_THAT(fit.text, HasSubstr("# smr offset mm: (0, 60, 80)"));
  TrackerJoinRequest h = q;
  h.plan = {"check.csv", plan(nominal, 25, rng)};
  h.points = {"check-sa.txt",
              trackerExport(h.plan.text, nominal, truth, world_T_tracker, smr, -1, rng)};
  const TrackerJoinResult check = joinTrackerPoints(h);

  HexapodCalibrationRequest c;
  c.machine = "hexapod-default";
  c.data = {{"joined.csv", fit.text}};
  c.holdout = {{"check-joined.csv", check.text}};
  c.out = test::scratchPath("tracker_join", "cal.json").string();
  c.force = true;
  const HexapodCalibrationResult r = calibrateHexapod(c);
  ASSERT_TRUE(r.report.holdout.has_value());
  EXPECT_LT(r.report.holdout->after.rms, kHeldOutAfterLimit);
  EXPECT_GT(r.report.holdout->before.rms, 10 * r.report.holdout->after.rms);
}

TEST(TrackerJoin, MatchingRulesAndErrors) {
  TrackerJoinRequest q;
  q.machine = "hexapod-default";
  q.plan = {"plan.csv", "pose,x,y,z,a,b,c\n0,0,0,200,0,0,0\n1,10,0,200,0,0,0\n"};
  q.points = {"sa.txt", "1 2 3\n4 5 6\n"};  // unnamed: in plan order
  EXPECT_EQ(joinTrackerPoints(q).rows, 2u);
  q.unit = "in";
  EXPECT_THAT(joinTrackerPoints(q).text, HasSubstr(",25.4,50.8,76.19"));
  q.unit.clear();
  auto error = [&](const std::string& points) {
    q.points = {"sa.txt", points};
    try {
      (void)joinTrackerPoints(q);
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error("1 2 3\n"), HasSubstr("sa.txt: 1 unnamed points for 2 planned poses"));
  EXPECT_THAT(error("P0 1 2 3\nP9 1 2 3\n"), HasSubstr("sa.txt:2: pose 9 is not in plan.csv"));
  EXPECT_THAT(error("P0 1 2 3\npose_000 1 2 3\n"),
              HasSubstr("sa.txt:2: a second point for pose 0 (first at line 1)"));
  EXPECT_THAT(error("Nest 1 2 3\n"), HasSubstr("target 'Nest' does not end with a pose number"));
  q.points = {"sa.txt", "P0 1 2 3\n"};
  q.frame = "machine";
  EXPECT_THROW((void)joinTrackerPoints(q), InvalidArgument);
  q.frame = "tracker";
  q.machine = "mxt700s-like";  // an Exechon
  EXPECT_THROW((void)joinTrackerPoints(q), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
